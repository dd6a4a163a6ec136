"""The live progress display of the command line: one line on stderr, rewritten in place, only
when stderr is a terminal and ``--quiet`` was not given: counted work with the time left
(:class:`Progress`), and a solve's stage, iteration and residual against its tolerance with
an estimate of the time until it converges (:class:`Ticker`, :func:`progress_line`).
"""

from __future__ import annotations

import shutil
import sys
import threading
import time

from ..progress import iterations_left, reporting

__all__ = ["Progress", "Ticker", "progress_line"]


def _live(quiet: bool) -> bool:
    return not quiet and sys.stderr.isatty()


class Progress:
    """Progress of counted work on stderr with the time left, as one live line; silent with
    ``quiet`` or when stderr is not a terminal (logs and pipes stay clean)."""

    def __init__(self, quiet: bool = False, what: str = "points"):
        self.t0 = time.perf_counter()
        self.on = _live(quiet)
        self.what = what

    def __call__(self, done: int, total: int) -> None:
        if not self.on:
            return
        elapsed = time.perf_counter() - self.t0
        left = elapsed / max(done, 1) * (total - done)
        end = "\n" if done == total else "\r"
        print(f"  {done}/{total} {self.what}, {_clock(elapsed)} elapsed, about "
              f"{_clock(left)} left   ", end=end, file=sys.stderr, flush=True)


def _clock(seconds: float) -> str:
    seconds = int(round(seconds))
    return f"{seconds // 60}:{seconds % 60:02d}" if seconds >= 60 else f"{seconds} s"


def _time_left(track) -> float | None:
    """Seconds until the solve of ``track`` reaches its tolerance: the iterations
    :func:`webfem.progress.iterations_left` extrapolates from its residuals (Picard: at its
    mean linear rate; Newton: at its observed order) times the mean time per iteration so
    far. None while there is no rate to extrapolate."""
    step, points = track
    if len(points) < 2 or points[-1][2] <= points[0][2]:
        return None
    n = iterations_left([r for _, r, _ in points], step.tol,
                        order=1.0 if step.solver == "picard" else None)
    if n is None:
        return None
    per = (points[-1][0] - points[0][0]) / (points[-1][2] - points[0][2])
    return n * per


def progress_line(text: str, elapsed: float, track=None, expected: float | None = None,
                  width: int | None = None) -> str:
    """The live line of :class:`Ticker`: ``text``, the time elapsed and, when the solvers
    report (``track``: the last :class:`webfem.progress.Step` and ``(time, residual,
    iteration)`` of its solve), the stages, the iteration, its residual against the
    tolerance and the estimated time left until that solve converges (:func:`_time_left`);
    else the time left of ``expected`` seconds, if given. At most ``width`` characters (a
    wrapped line cannot be redrawn in place): the outer stages, then ``text``, then the
    stage are left out until it fits, and then it is cut.

    >>> from webfem.progress import Step
    >>> step = Step(("fe2d start", "fe1d newton"), "newton", 2, 1e-4, 1e-9)
    >>> line = progress_line("solving", 75.0, (step, ((0.0, 1e-1, 0), (1.0, 1e-2, 1),
    ...                                              (2.0, 1e-4, 2))))
    >>> line.split(" | ")  # doctest: +NORMALIZE_WHITESPACE
    ['  solving: 1:15', 'fe2d start > fe1d newton', 'newton 2: residual 1.0e-04 -> 1e-09,
     about 2 s left (estimate)']
    """
    if track is None:
        line = f"  {text}: {_clock(elapsed)} elapsed" + (
            f", about {_clock(max(expected - elapsed, 0.0))} left" if expected else "")
        return _cut(line, width)
    step = track[0]
    now = f"{step.solver} {step.iteration}: residual {step.residual:.1e} -> {step.tol:.0e}"
    left = _time_left(track)
    if step.residual <= step.tol:
        now += ", converged"
    elif left is not None:
        now += (", under 1 s" if left < 1.0 else f", about {_clock(left)}") + \
            " left (estimate)"
    # on a narrow terminal, in turn: the outer stages, the text, the stage go; then the end
    clock = _clock(elapsed)
    for first, where in ((f"  {text}: {clock}", step.stage),
                         (f"  {text}: {clock}", step.stage[-1:]),
                         (f"  {clock}", step.stage[-1:]), (f"  {clock}", ())):
        line = " | ".join([first] + ([" > ".join(where)] if where else []) + [now])
        if width is None or len(line) <= width:
            break
    return _cut(line, width)


def _cut(line: str, width: int | None) -> str:
    """``line`` cut to ``width`` characters (a wrapped line cannot be redrawn in place)."""
    if width is not None and len(line) > width:
        line = line[:max(width - 3, 0)] + "..."
    return line


class Ticker:
    """``with Ticker("solving with fe2d"):`` shows a live stderr line while a call of unknown
    length runs, and clears it after: the time elapsed and what the solvers report through
    :mod:`webfem.progress` (the stage, the iteration, the residual against its tolerance and
    an estimate of the time to converge; see :func:`progress_line`), or, before any report,
    the time left of ``expected`` seconds when given. Silent with ``quiet`` or when stderr
    is not a terminal; the solvers then report to no one."""

    def __init__(self, text: str, quiet: bool = False, expected: float | None = None,
                 after: float = 1.0):
        self.text, self.expected, self.after = text, expected, after
        self.on = _live(quiet)
        self._stop = threading.Event()
        self._thread = None
        self._width = 0
        self._reporting = None
        #: (last Step, ((time, residual, iteration), ...) of its solve), replaced whole so
        #: the drawing thread always reads a consistent pair
        self.track = None

    def record(self, step) -> None:
        """A :class:`webfem.progress.Step` from the solving thread: a later iteration of the
        same solve is added to its track, anything else starts a new one. A Newton solve
        inside a Picard iteration's stage (the staggered scheme's sub-solves) is not shown:
        the Picard iteration is what converges."""
        now = time.perf_counter()
        point = (now, step.residual, step.iteration)
        last = self.track
        if last is not None:
            prev, points = last
            same = prev.stage == step.stage
            if same and step.solver == "newton" and prev.solver == "picard":
                return
            if same and step.solver == prev.solver and step.iteration > prev.iteration:
                self.track = (step, points[-7:] + (point,))
                return
        self.track = (step, (point,))

    def _line(self, elapsed: float) -> str:
        columns = shutil.get_terminal_size((100, 24)).columns
        return progress_line(self.text, elapsed, self.track, self.expected, columns - 1)

    def _run(self) -> None:
        t0 = time.perf_counter()
        if self._stop.wait(self.after):   # quick calls show nothing
            return
        while True:
            line = self._line(time.perf_counter() - t0)
            self._width = max(self._width, len(line))
            print(line.ljust(self._width), end="\r", file=sys.stderr, flush=True)
            if self._stop.wait(0.5):
                return

    def __enter__(self) -> "Ticker":
        if self.on:
            self._reporting = reporting(self.record)
            self._reporting.__enter__()
            self._thread = threading.Thread(target=self._run, daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        if self._reporting is not None:
            self._reporting.__exit__(*exc)
            self._reporting = None
        if self._thread is not None:
            self._stop.set()
            self._thread.join()
            if self._width:
                print(" " * self._width, end="\r", file=sys.stderr, flush=True)
