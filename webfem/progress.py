"""Progress of long solves: the solvers say where they are; a front end, if any, shows it.

The iterative solvers (:func:`webfem.fem.newton.newton`, :func:`webfem.fem.picard.picard`)
call :func:`report` once per iteration, and the FE driver and the models name what they are
doing with :func:`stage` (the 1-D start of fe2d, the solve on each mesh, the refinement
rounds, continuation steps; stages nest). Without a reporter both cost one context-variable
read, so the solvers call them unconditionally. A front end installs one with
:func:`reporting`: the command line's live line on a terminal (:class:`webfem.cli.common.
Ticker`), or any callable in a notebook. A context variable, not a global, so threads and
asyncio tasks each see their own reporter (none unless they install one).

:func:`iterations_left` extrapolates a residual history to the tolerance: the estimate of
time left that the command line shows.

Examples
--------
>>> seen = []
>>> with reporting(seen.append), stage("demo"):
...     report("newton", 1, 1e-3, 1e-9)
>>> seen
[Step(stage=('demo',), solver='newton', iteration=1, residual=0.001, tol=1e-09)]
>>> report("newton", 2, 1e-6, 1e-9)   # no reporter: nothing happens
>>> iterations_left([1e-1, 1e-2, 1e-4], 1e-9)   # quadratic: 1e-8, then 1e-16
2
"""

from __future__ import annotations

import math
from contextvars import ContextVar
from typing import Callable, NamedTuple

__all__ = ["Step", "report", "stage", "reporting", "iterations_left"]


class Step(NamedTuple):
    """One iteration as reported: the stages it runs in (outermost first), the solver
    (``"newton"`` or ``"picard"``), the iteration (0: the start), the residual norm the
    solver tests and its tolerance."""

    stage: tuple[str, ...]
    solver: str
    iteration: int
    residual: float
    tol: float


_REPORTER: ContextVar[Callable[[Step], None] | None] = ContextVar("webfem_reporter",
                                                                   default=None)
_STAGE: ContextVar[tuple[str, ...]] = ContextVar("webfem_stage", default=())


def report(solver: str, iteration: int, residual: float, tol: float) -> None:
    """Tell the reporter, if one is installed, that ``solver`` reached ``iteration`` with
    ``residual`` (towards ``tol``); nothing otherwise."""
    reporter = _REPORTER.get()
    if reporter is not None:
        reporter(Step(_STAGE.get(), solver, iteration, float(residual), float(tol)))


class stage:
    """``with stage("refinement round 1"):`` names what the solves inside are part of; nested
    stages add to the outer ones. Without a reporter it records nothing."""

    __slots__ = ("name", "_token")

    def __init__(self, name: str):
        self.name = name
        self._token = None

    def __enter__(self) -> "stage":
        if _REPORTER.get() is not None:
            self._token = _STAGE.set(_STAGE.get() + (self.name,))
        return self

    def __exit__(self, *exc) -> None:
        if self._token is not None:
            _STAGE.reset(self._token)
            self._token = None


class reporting:
    """``with reporting(callback):`` sends every :class:`Step` reported inside to
    ``callback`` (called in the solving thread, so it should be quick); ``None`` silences
    an outer reporter."""

    __slots__ = ("callback", "_tokens")

    def __init__(self, callback: Callable[[Step], None] | None):
        self.callback = callback
        self._tokens = None

    def __enter__(self) -> "reporting":
        self._tokens = (_REPORTER.set(self.callback), _STAGE.set(()))
        return self

    def __exit__(self, *exc) -> None:
        reporter, stages = self._tokens
        _STAGE.reset(stages)
        _REPORTER.reset(reporter)


def iterations_left(residuals, tol: float, order: float | None = None) -> int | None:
    """Iterations until the residual falls to ``tol``, extrapolated from ``residuals`` (one
    solve's, oldest first): an estimate, not a promise.

    The last step's decrease ``d = log(r_k / r_k-1)`` is carried forward, each later step
    ``p`` times the one before in log r: exact for ``r_k+1 = C r_k^p``. The order ``p`` is
    ``order`` when given (1 for a linearly converging fixed point), else the observed one,
    ``d / log(r_k-1 / r_k-2)``, kept within [1, 2] (Newton's range). With ``order=1`` the
    decrease is averaged over the last five steps (Picard's rate is noisy). None when there
    is no rate to extrapolate: fewer than two residuals, or the last step did not lower the
    residual (a damped or stalling phase).
    """
    r = [float(v) for v in residuals if v is not None and math.isfinite(v) and v > 0.0]
    if not r:
        return None
    if r[-1] <= tol:
        return 0
    if len(r) < 2 or not tol > 0.0:
        return None
    if order is not None and order <= 1.0:
        back = min(len(r) - 1, 5)
        d, p = math.log(r[-1] / r[-1 - back]) / back, 1.0
    else:
        d = math.log(r[-1] / r[-2])
        p = order
        if p is None:
            before = math.log(r[-2] / r[-3]) if len(r) >= 3 else 0.0
            p = min(max(d / before, 1.0), 2.0) if before < 0.0 else 1.0
    if not d < 0.0:
        return None
    gap = math.log(tol / r[-1])          # < 0: how far the residual still has to fall
    if p == 1.0:
        return math.ceil(gap / d - 1e-9)
    n, total = 0, 0.0
    while total > gap and n < 1000:
        d *= p
        total += d
        n += 1
    return n
