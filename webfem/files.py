"""Files that appear whole or not at all, with the user's permissions.

Every output (CSV, sidecar, VTU, PVD) is written to a hidden temporary file beside its target,
named ``.NAME.tmp-PID`` so it never looks like a result, then given the mode a plain
``open()`` would have given it (``0o666 & ~umask``, 0644 by default; ``mkstemp``'s 0600
would hide it from colleagues) and renamed onto the target. An exception, Ctrl-C included,
removes the temporary file.

Examples
--------
>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> write_text(folder / "a.txt", "hello\\n").read_text()
'hello\\n'
>>> sorted(p.name for p in folder.iterdir())
['a.txt']
"""

from __future__ import annotations

import os
import re
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator

__all__ = ["file_mode", "temp_path", "replacing", "write_text", "remove_stale_temps",
           "pid_alive"]


def _umask() -> int:
    try:   # Linux >= 4.7 shows it without changing it (os.umask is process-wide: racy)
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def file_mode() -> int:
    """The mode a new file gets from ``open()``: ``0o666 & ~umask``."""
    return 0o666 & ~_umask()


def temp_path(path: str | Path) -> Path:
    """The hidden temporary name of ``path`` for this process: ``.NAME.tmp-PID``."""
    path = Path(path)
    return path.with_name(f".{path.name}.tmp-{os.getpid()}")


@contextmanager
def replacing(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path to write; on success it becomes ``path`` (mode from the
    umask, atomic rename), on any exception it is removed and ``path`` is left as it was."""
    path = Path(path)
    tmp = temp_path(path)
    try:
        yield tmp
        os.chmod(tmp, file_mode())
        os.replace(tmp, path)
    finally:
        try:
            tmp.unlink()
        except FileNotFoundError:
            pass


def write_text(path: str | Path, text: str, *, fsync: bool = False) -> Path:
    """Write ``text`` to ``path`` atomically (UTF-8); returns ``path``."""
    path = Path(path)
    with replacing(path) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="") as fh:
            fh.write(text)
            if fsync:
                fh.flush()
                os.fsync(fh.fileno())
    return path


def pid_alive(pid: int, since: float | None = None) -> bool:
    """True if process ``pid`` runs on this host (a zombie counts as ended); with ``since``
    (epoch seconds), a process started after that moment is a reused pid: False."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:   # someone else's process: alive
        pass
    except (OverflowError, ValueError):
        return False
    try:
        with open(f"/proc/{pid}/stat") as fh:
            stat = fh.read()
        fields = stat[stat.rindex(")") + 2:].split()
        if fields[0] in ("Z", "X"):
            return False
        if since is not None:
            with open("/proc/stat") as fh:
                btime = next(int(line.split()[1]) for line in fh if line.startswith("btime"))
            started = btime + int(fields[19]) / os.sysconf("SC_CLK_TCK")
            if started > since + 2.0:   # clock ticks and boot time are coarse
                return False
    except (OSError, ValueError, IndexError, StopIteration):
        pass   # no /proc: trust os.kill
    return True


_TEMP = re.compile(r"\.tmp-(\d+)$")


def remove_stale_temps(folder: str | Path, prefix: str) -> None:
    """Remove ``.PREFIX*.tmp-PID`` files in ``folder`` left by processes that were killed."""
    try:
        names = os.listdir(folder)
    except OSError:
        return
    for name in names:
        match = _TEMP.search(name)
        if (match and name.startswith("." + prefix) and int(match.group(1)) != os.getpid()
                and not pid_alive(int(match.group(1)))):
            try:
                os.unlink(Path(folder) / name)
            except OSError:
                pass
