"""Eq. 21 against the converged 2-D solution over the width parameter lambda = 7 ... 100.

For the case at a roller speed where the web flies (fluid film everywhere; 40 m/s for the
base case), the web width sets lambda; the 2-D central gap on the default mesh and on one
refinement (their difference is the discretisation error estimate) is compared with Eq. 21,
for the case's permeable web (newsprint, k = 5e-15 m^2) and for an impermeable web (which
isolates Eq. 21's width fit from its permeation term).

Run: ``webfem study lambda-table cases/base.toml --out docs`` (about a minute). Computes
only; :func:`webfem.io.studies.write` writes the CSV, chart and markdown.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Callable, ClassVar

from ..api import solve
from ..case import Case
from ..errors import ValidityWarning
from ..line_speed import at_speed

__all__ = ["LAMBDAS", "QUICK_LAMBDAS", "PERMEABILITIES", "LambdaTable", "run"]

LAMBDAS = (7.0, 10.0, 15.0, 20.0, 30.0, 50.0, 70.0, 100.0)
QUICK_LAMBDAS = (10.0, 50.0)
#: Web permeabilities compared [m^2]: the paper's newsprint and an impermeable web.
PERMEABILITIES = (5e-15, 0.0)


@dataclass(frozen=True)
class LambdaTable:
    """Eq. 21's central gap against the 2-D solution per web permeability and lambda.

    Attributes
    ----------
    speed : float
        Roller speed of every point [m/s].
    rows : tuple of dict
        ``permeability``, ``lambda``, ``beta``, ``width_m``, ``h_center_fe2d_um`` (level 1),
        ``fe2d_mesh_error_pct`` (level 0 against 1), ``h_center_eq21_um``,
        ``eq21_error_pct`` and ``h_center_fe1d_um`` (the infinitely wide film).
    quick : bool
        The reduced table.
    """

    kind: ClassVar[str] = "lambda-table"
    speed: float
    rows: tuple
    quick: bool = False


def run(case: Case, speed: float = 40.0, lambdas=None, quick: bool = False,
        progress: Callable[[str], None] | None = None) -> LambdaTable:
    """Solve the closed form, fe2d (levels 0 and 1) and fe1d at each lambda of ``lambdas``
    (default :data:`LAMBDAS`, or :data:`QUICK_LAMBDAS` with ``quick``) for each of
    :data:`PERMEABILITIES`, at roller speed ``speed``. ``progress`` receives one line of
    text per point."""
    lambdas = tuple(lambdas if lambdas is not None else (QUICK_LAMBDAS if quick else LAMBDAS))
    rows = []
    for k in PERMEABILITIES:
        base = at_speed(case, speed).updated({"web.permeability": k})   # the line moves
        for lam in lambdas:
            width = lam * 2.0 * base.x_scale
            point = base.updated({"web.width": width})
            with warnings.catch_warnings():   # Eq. 21's limits are what the table measures
                warnings.simplefilter("ignore", ValidityWarning)
                cf = solve(point, model="closed-form")
            r0 = solve(point, model="fe2d", estimate=False, adapt_settle=False)  # levels: own meshes
            r1 = solve(point, model="fe2d", level=1, estimate=False, adapt_settle=False)
            err = (cf["h_center"] / r1["h_center"] - 1.0) * 100.0
            rows.append({"permeability": k, "lambda": point.lam, "beta": point.beta,
                         "width_m": width, "h_center_fe2d_um": r1["h_center"] * 1e6,
                         "fe2d_mesh_error_pct": abs(r0["h_center"] / r1["h_center"] - 1) * 100,
                         "h_center_eq21_um": cf["h_center"] * 1e6, "eq21_error_pct": err,
                         "h_center_fe1d_um": solve(point, model="fe1d", estimate=False)["h_center"] * 1e6})
            if progress:
                progress(f"k = {k:g}, lambda = {point.lam:6.1f}: fe2d "
                         f"{r1['h_center'] * 1e6:7.3f} um, Eq. 21 "
                         f"{cf['h_center'] * 1e6:7.3f} um ({err:+.1f} %)")
    return LambdaTable(float(speed), tuple(rows), quick)
