"""Convergence study: mesh refinement of the FE models and Eq. 21 against the converged 2-D gap.

1. For the case: uniform refinement (every cell bisected per level, the adaptive refinement
   off so the sequence is nested) of the 1-D model (P1, P2 pressure) and the 2-D model
   (Q1, Q2): central gap, minimum gap and mu per level, the observed order from the last three
   levels and the Richardson-extrapolated value with its error estimate.
2. Eq. 21's central gap against the 2-D solution over a grid of lambda and beta (web width
   and wrap angle varied at the case's speed), inside and outside Eq. 21's stated range.

Computes only; :func:`webfem.io.studies.write` writes the CSV files, chart and markdown.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Callable, ClassVar

import numpy as np

from ..api import solve
from ..case import Case
from ..errors import ValidityWarning

__all__ = ["QUANTITIES", "SEQUENCES", "ConvergenceStudy", "richardson", "refinement",
           "summarise", "eq21_grid", "run"]

QUANTITIES = ("h_center", "h_min", "mu")
#: (model, element order) of each refinement sequence.
SEQUENCES = (("fe1d", 1), ("fe1d", 2), ("fe2d", 1), ("fe2d", 2))


@dataclass(frozen=True)
class ConvergenceStudy:
    """What the convergence study found.

    Attributes
    ----------
    case : Case
        The case refined.
    refinement : tuple of dict
        Per (model, order, level): ``n_dofs``, ``time_s`` and each of :data:`QUANTITIES`.
    summary : tuple of dict
        Per (model, order, quantity): ``observed_order``, ``richardson`` (extrapolated
        value), ``error_estimate``, ``relative_error_finest``, ``relative_error_coarsest``.
    eq21 : tuple of dict
        Per (lambda, beta): the 2-D and Eq. 21 central gap and mu, their errors in %.
    quick : bool
        The reduced study (fewer levels and grid points).
    """

    kind: ClassVar[str] = "convergence"
    case: Case
    refinement: tuple
    summary: tuple
    eq21: tuple
    quick: bool = False

    def order(self, model: str, order: int, quantity: str) -> dict:
        """The summary row of one sequence and quantity, e.g. ``("fe2d", 2, "h_center")``."""
        return next(s for s in self.summary if s["model"] == model and s["order"] == order
                    and s["quantity"] == quantity)


def richardson(values):
    """Observed order from the last three values of a refinement-by-2 sequence, the
    extrapolated value and the error estimate of the finest value (NaN order when the
    sequence is not monotone).

    Examples
    --------
    >>> p, ext, err = richardson([1 + 1 / 4, 1 + 1 / 16, 1 + 1 / 64])
    >>> round(p, 12), round(ext, 12)
    (2.0, 1.0)
    """
    v = np.asarray(values, float)
    d1, d2 = v[-2] - v[-3], v[-1] - v[-2]
    if d1 == 0 or d2 == 0 or d1 * d2 < 0:
        return math.nan, float(v[-1]), abs(d2)
    p = math.log2(abs(d1 / d2))
    ext = v[-1] + d2 / (2**p - 1)
    return p, float(ext), abs(ext - v[-1])


def refinement(case: Case, levels=(0, 1, 2, 3), levels2d=(0, 1, 2),
               progress: Callable[[str], None] | None = None) -> list[dict]:
    """Uniform refinement rows of every sequence of :data:`SEQUENCES`."""
    rows = []
    for model, order in SEQUENCES:
        seq = levels if model == "fe1d" else levels2d
        res = [solve(case, model=model, level=lv, order=order, adapt=0, estimate=False)
               for lv in seq]
        for lv, r in zip(seq, res):
            rows.append({"model": model, "order": order, "level": lv, "n_dofs": r["n_dofs"],
                         "time_s": r["solve_time_s"],
                         **{q: r[q] for q in QUANTITIES}})
        if progress:
            progress(f"{model} order {order}: levels {list(seq)} done")
    return rows


def summarise(rows) -> list[dict]:
    """Observed order and Richardson value per sequence and quantity."""
    out = []
    for model, order in SEQUENCES:
        sel = [r for r in rows if r["model"] == model and r["order"] == order]
        for q in QUANTITIES:
            p, ext, err = richardson([r[q] for r in sel])
            out.append({"model": model, "order": order, "quantity": q, "observed_order": p,
                        "richardson": ext, "error_estimate": err,
                        "relative_error_finest": err / abs(ext) if ext else math.nan,
                        "relative_error_coarsest": abs(sel[0][q] - ext) / abs(ext)})
    return out


def eq21_grid(case: Case, lambdas=(3.0, 5.0, 7.0, 10.0, 20.0, 50.0),
              betas=(3.0, 6.0, 10.0, 20.0, 40.0),
              progress: Callable[[str], None] | None = None) -> list[dict]:
    """Eq. 21 against the 2-D model over lambda (web width) and beta (wrap angle)."""
    rows = []
    cube = case.eps ** (1 / 3)
    for beta in betas:
        angle = math.degrees(beta * cube)
        if not 0 < angle < 360:
            continue
        for lam in lambdas:
            c = case.updated({"wrap.angle_deg": angle,
                              "web.width": lam * 2 * case.roller.radius * cube})
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)   # the range is mapped
                cf = solve(c, model="closed-form")
                fe = solve(c, model="fe2d")
            rows.append({"lambda": lam, "beta": beta, "eq21_valid": cf["eq21_valid"],
                         "h_center_fe2d": fe["h_center"], "h_center_eq21": cf["h_center"],
                         "gap_error_pct": 100 * (cf["h_center"] / fe["h_center"] - 1),
                         "mu_fe2d": fe["mu"], "mu_eq21": cf["mu"],
                         "mu_error_pct": 100 * (cf["mu"] / fe["mu"] - 1)})
        if progress:
            progress(f"beta = {beta:g}: {len(lambdas)} widths done")
    return rows


def run(case: Case, quick: bool = False,
        progress: Callable[[str], None] | None = None) -> ConvergenceStudy:
    """Run the study (``quick``: levels 0-2 and a 2 x 2 grid, about a minute; else about
    ten). ``progress`` receives one line of text per finished sequence or grid row."""
    if quick:
        rows = refinement(case, (0, 1, 2), (0, 1, 2), progress)
        grid = eq21_grid(case, (5.0, 10.0), (6.0, 20.0), progress)
    else:
        rows = refinement(case, progress=progress)
        grid = eq21_grid(case, progress=progress)
    return ConvergenceStudy(case, tuple(rows), tuple(summarise(rows)), tuple(grid), quick)
