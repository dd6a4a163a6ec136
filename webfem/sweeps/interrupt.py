"""What a sweep says when it is interrupted, and the quiet its clean-up needs.

A terminal's Ctrl-C and ``timeout -s INT`` may deliver SIGINT twice (``timeout`` signals the
command and then its process group): the second one used to land in the sweep's clean-up,
replacing the :class:`SweepInterrupted` that counts the saved points by a bare
``KeyboardInterrupt`` ("webfem: interrupted", no count). :func:`hold_interrupts` ignores
SIGINT while the files are closed and the lock released.
"""

from __future__ import annotations

import signal
import threading
from pathlib import Path
from typing import Callable

__all__ = ["SweepInterrupted", "hold_interrupts", "saved_count"]


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during a resumable run: the files are closed and the lock released; ``saved``
    of ``total`` ``what`` (points, designs, geometries) are in ``csv_path`` and the same
    call continues from there."""

    def __init__(self, saved: int, total: int, csv_path: Path, what: str = "points"):
        super().__init__(f"interrupted: {saved} of {total} {what} saved in {csv_path}; "
                         "run the same command to continue")
        self.saved, self.total, self.csv_path = saved, total, Path(csv_path)
        self.what = what


def hold_interrupts() -> Callable[[], None]:
    """Ignore SIGINT from now (the run is stopping already); returns the function that
    puts the previous handler back. Outside the main thread nothing changes."""
    if threading.current_thread() is not threading.main_thread():
        return lambda: None
    try:
        old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    except (ValueError, OSError):
        return lambda: None

    def restore() -> None:
        if old is not None:     # None: a handler not installed from Python, left as it is
            signal.signal(signal.SIGINT, old)
    return restore


def saved_count(err: BaseException | None) -> str | None:
    """What the interruption in ``err``'s chain (itself, its cause or context) counted,
    ``"interrupted: 3 of 60 points saved in PATH; run the same command to continue"``, or
    None: an interruption that came on top of a :class:`SweepInterrupted` still reports
    what it counted. Any exception with ``saved``, ``total`` and ``csv_path`` (and
    optionally ``what``) counts."""
    seen = set()
    while err is not None and id(err) not in seen:
        saved, total, path = (getattr(err, k, None) for k in ("saved", "total", "csv_path"))
        if saved is not None and total is not None and path is not None:
            return (f"interrupted: {saved} of {total} {getattr(err, 'what', 'points')} "
                    f"saved in {path}; run the same command to continue")
        seen.add(id(err))
        err = err.__cause__ or err.__context__
    return None
