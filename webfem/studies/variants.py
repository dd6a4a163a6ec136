"""How much the friction model's options move mu for a case.

The paper's Eqs. 13 and 29 jump at h = 3 sigma and h = h_c (``friction.variant = "paper"``);
the continuous variant removes the jumps. The paper's exponential asperity heights (Eq. 2)
against the Gaussian of Eq. 1 (``friction.distribution``). Four combinations, mu against
roller speed, closed form and an FE model (each speed continued from the previous one).

Run: ``webfem study variants cases/base.toml --out docs/figures [--model fe2d] [--num 24]``.
Computes only; :func:`webfem.io.studies.write` writes the chart and markdown.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, ClassVar

import numpy as np

from ..api import solve_along
from ..case import Case
from ..line_speed import at_speed

__all__ = ["COMBOS", "VariantsStudy", "run"]

#: (friction.variant, friction.distribution) of each curve.
COMBOS = (("paper", "exponential"), ("continuous", "exponential"), ("paper", "gaussian"),
          ("continuous", "gaussian"))


@dataclass(frozen=True)
class VariantsStudy:
    """mu against roller speed per friction option and model.

    Attributes
    ----------
    model : str
        The FE model beside the closed form.
    speeds : tuple of float
        Roller speeds [m/s] (geometric, 0.5 to 40).
    mu : dict
        ``(variant, distribution, model) -> tuple of mu`` per speed (NaN where the solve did
        not converge), in the order of :data:`COMBOS`, closed form first.
    failed : int
        Points that did not converge.
    quick : bool
        The reduced study.
    """

    kind: ClassVar[str] = "variants"
    model: str
    speeds: tuple
    mu: dict
    failed: int = 0
    quick: bool = False

    def picks(self) -> list[int]:
        """Indices of the speeds the table shows (about six, evenly spread)."""
        step = max(len(self.speeds) // 6, 1)
        return [i for i in range(len(self.speeds)) if i % step == 0]


def run(case: Case, model: str = "fe2d", num: int | None = None, quick: bool = False,
        progress: Callable[[str], None] | None = None, workers: int = 1) -> VariantsStudy:
    """Solve the four friction options of :data:`COMBOS` over ``num`` roller speeds (default
    24, or 6 with ``quick``) with the closed form and ``model``. ``progress`` receives one
    line of text per curve. ``workers`` > 1 solves the curves in that many local processes
    (each curve is the same continuation path: the same values, to rounding)."""
    from ..sweeps.workers import check_workers

    check_workers(workers)
    num = num if num is not None else (6 if quick else 24)
    speeds = np.geomspace(0.5, 40.0, num)
    tasks = [(case.updated({"friction.variant": variant, "friction.distribution": dist}),
              tuple(float(u) for u in speeds), m)
             for variant, dist in COMBOS for m in ("closed-form", model)]
    curves: dict = {}

    def record(i, mu):
        variant, dist = COMBOS[i // 2]
        curves[i] = mu
        if progress:
            progress(f"{variant:10s} {dist:11s} {tasks[i][2]:11s} done")

    if workers == 1:
        for i, args in enumerate(tasks):
            record(i, _curve(*args))
    else:
        from ..sweeps.workers import Processes

        pool = Processes(min(workers, len(tasks)))
        try:
            pool.run(list(enumerate(tasks)), record, task=_curve)
        finally:
            pool.close()
    data = {COMBOS[i // 2] + (tasks[i][2],): curves[i] for i in range(len(tasks))}
    failed = sum(math.isnan(v) for mu in data.values() for v in mu)
    return VariantsStudy(model, tuple(float(u) for u in speeds), data, failed, quick)


def _curve(base: Case, speeds: tuple, model: str) -> tuple:
    """mu along ``speeds`` with continuation (NaN where a solve did not converge)."""
    cases = [at_speed(base, u) for u in speeds]   # the line moves (webfem.line_speed)
    return tuple(float(r["mu"]) if r["converged"] else math.nan
                 for r in solve_along(cases, model))
