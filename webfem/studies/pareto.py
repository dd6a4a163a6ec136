"""Speed against accuracy: every method's time per solve against its error.

Methods: the closed form; the fitted model (a fit of fe2d solutions); the 1-D FE model at
several mesh levels (Newton, and Picard at the default mesh); the 2-D FE model at several
levels and both element orders (Newton, and Picard at the default mesh). Time: median of
``repeats`` warm solves. Error: relative to the finest 2-D solution (Q2, two levels above
the default), in the central gap, the minimum gap and the wrap-averaged mu. The Pareto
front: the methods no other method beats in both time and the mu error.

The fitted model answers only inside its domain and for the default physics it was trained
on. Where it refuses the case only for its physics switches (e.g. the paper's physics, as
the docs' chart is drawn), its row is the same case with the default physics, against the
finest 2-D solution of that case, named ``fitted (default physics)`` and left off the
front (its error is measured against another reference).

Computes only; :func:`webfem.io.studies.write` writes the CSV, chart and markdown.
"""

from __future__ import annotations

import statistics
import time
import warnings
from dataclasses import dataclass
from typing import Callable, ClassVar

from ..api import solve
from ..case import Case
from ..errors import ValidityWarning

__all__ = ["QUANTITIES", "ParetoStudy", "methods", "pareto_front", "run"]

QUANTITIES = ("h_center", "h_min", "mu")


@dataclass(frozen=True)
class ParetoStudy:
    """What the speed-against-accuracy study found.

    Attributes
    ----------
    case : Case
        The case solved.
    rows : tuple of dict
        Per method: ``method``, ``model``, ``time_s`` (median), ``iterations``, ``n_dofs``,
        ``error_h_center``, ``error_h_min``, ``error_mu`` (relative to the reference) and
        ``pareto_mu`` (on the front of time against the mu error).
    reference_level : int
        Mesh level of the fe2d Q2 reference.
    reference_dofs : int
        Its number of unknowns.
    repeats : int
        Solves per method (the time is their median).
    quick : bool
        The reduced study.
    """

    kind: ClassVar[str] = "pareto"
    case: Case
    rows: tuple
    reference_level: int
    reference_dofs: int
    repeats: int
    quick: bool = False

    def row(self, method: str) -> dict:
        """The row of the named method, e.g. ``"closed form"``."""
        return next(r for r in self.rows if r["method"] == method)


def methods(quick: bool = False) -> list[tuple[str, str, dict]]:
    """``(name, model, options)`` of every method timed. The rows named by a mesh level
    solve on that level's mesh alone (no error estimate, which would refine further); the
    "default" rows are what a user gets: the default mesh with its error estimate."""
    fixed = {"estimate": False, "adapt_settle": False}
    lv1 = (0, 1) if quick else (0, 1, 2)
    out = [("closed form", "closed-form", {}), ("fitted", "fitted", {})]
    out += [(f"fe1d P2 level {lv}", "fe1d", {"level": lv, **fixed}) for lv in lv1]
    out += [("fe1d P1 level 0", "fe1d", {"order": 1, **fixed}),
            ("fe1d Picard", "fe1d", {"method": "picard", **fixed})]
    out += [("fe2d Q2 level 0", "fe2d", dict(fixed)),
            ("fe2d Q1 level 0", "fe2d", {"order": 1, **fixed}),
            ("fe2d Q1 level 1", "fe2d", {"order": 1, "level": 1, **fixed}),
            ("fe2d default", "fe2d", {})]
    if not quick:
        out += [("fe2d Q2 level 1", "fe2d", {"level": 1, **fixed}),
                ("fe2d Picard", "fe2d", {"method": "picard", **fixed})]
    return out


def pareto_front(points) -> list[int]:
    """Indices of the points no other point beats in both coordinates (lower is better).

    Examples
    --------
    >>> pareto_front([(1.0, 1.0), (2.0, 0.5), (3.0, 0.6), (0.5, 2.0)])
    [0, 1, 3]
    """
    front = []
    for i, (t, e) in enumerate(points):
        if not any((t2 <= t and e2 <= e) and (t2 < t or e2 < e)
                   for j, (t2, e2) in enumerate(points) if j != i):
            front.append(i)
    return front


def run(case: Case, quick: bool = False, repeats: int = 3,
        progress: Callable[[str], None] | None = None) -> ParetoStudy:
    """Time and compare every method of :func:`methods` (``quick``: fewer methods and a
    reference one level coarser). ``progress`` receives one line of text per method."""
    with warnings.catch_warnings():   # the errors measure what the warnings say
        warnings.simplefilter("ignore", ValidityWarning)
        level = 1 if quick else 2
        ref = solve(case, model="fe2d", level=level, estimate=False)
        if progress:
            progress(f"reference fe2d Q2 level {level}: {ref['n_dofs']} unknowns")
        rows = []
        for name, model, opts in methods(quick):
            on, against = case, ref
            if model == "fitted":
                on, name = _fitted_case(case, name)
                if on is None:
                    if progress:
                        progress(f"fitted: no row ({name})")
                    continue
                if on is not case:
                    against = solve(on, model="fe2d", level=level, estimate=False)
            times, r = [], None
            for _ in range(repeats):
                t0 = time.perf_counter()
                r = solve(on, model=model, **opts)
                times.append(time.perf_counter() - t0)
            row = {"method": name, "model": model, "time_s": statistics.median(times),
                   "iterations": r["iterations"], "n_dofs": r["n_dofs"],
                   "same_case": on is case}
            for q in QUANTITIES:
                row[f"error_{q}"] = abs(r[q] / against[q] - 1.0)
            rows.append(row)
            if progress:
                progress(f"{name}: {row['time_s'] * 1e3:.1f} ms, mu error {row['error_mu']:.2e}")
    same = [i for i, r in enumerate(rows) if r["same_case"]]
    front = [same[i] for i in pareto_front([(rows[j]["time_s"], max(rows[j]["error_mu"], 1e-16))
                                            for j in same])]
    rows = [dict(r, pareto_mu=i in front) for i, r in enumerate(rows)]
    return ParetoStudy(case, tuple(rows), level, int(ref["n_dofs"]), repeats, quick)


def _fitted_case(case: Case, name: str) -> tuple[Case | None, str]:
    """The case the fitted model's row is measured on, and the row's name: ``case`` itself
    inside its domain; the case with the fit's physics switches (the defaults) where only
    those are refused, named so; else None and why."""
    from ..models import fit_groups as fg
    if fg.outside(case) is None:
        return case, name
    if fg.physics_refusal(case) is not None and not case.grooved:
        other = case.updated(fg.FIT_PHYSICS)
        if fg.outside(other) is None:
            return other, f"{name} (default physics)"
    return None, fg.outside(case)
