"""The three studies of docs/studies.md: convergence, speed against accuracy, stability.

Run: ``make studies`` or ``webfem study report cases/base.toml --out docs [--quick]``. The
full studies take about 15-25 minutes on 2 cores; ``quick`` runs the reduced versions the
tests use. Computes only; :func:`webfem.io.studies.write` writes each study's files and
``studies.md``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable, ClassVar

from ..case import Case
from . import convergence, pareto, stability

__all__ = ["StudiesReport", "run"]


@dataclass(frozen=True)
class StudiesReport:
    """The three studies of one case and how long they took together."""

    kind: ClassVar[str] = "report"
    convergence: convergence.ConvergenceStudy
    pareto: pareto.ParetoStudy
    stability: stability.StabilityStudy
    seconds: float
    quick: bool = False


def run(case: Case, quick: bool = False,
        progress: Callable[[str], None] | None = None) -> StudiesReport:
    """Run the convergence, pareto and stability studies of ``case`` in turn."""
    t0 = time.perf_counter()
    conv = convergence.run(case, quick, progress)
    par = pareto.run(case, quick, progress=progress)
    stab = stability.run(case, quick, progress)
    return StudiesReport(conv, par, stab, time.perf_counter() - t0, quick)
