"""Traction loss: the roller speed above which the friction coefficient stays below a threshold.

mu(U_r) rises from the boundary-lubrication value at low speed, peaks, and falls as air lifts
the web (the paper's Stribeck-like curve). The traction-loss speed is where it falls through
``mu_min`` after the peak: found on a logarithmic scan of roller speeds (each FE point started
from the previous one) and refined by Brent's method inside the bracketing interval.

Examples
--------
>>> from webfem import Case
>>> out = traction_loss_speed(Case(), 0.1)
>>> round(out["speed"], 1), out["model"]
(26.3, 'closed-form')
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy.optimize import brentq

from .api import solve
from .case import Case, CaseError
from .errors import ConvergenceError, ValidityWarning

__all__ = ["traction_loss_speed"]


def _mu(case: Case, speed: float, model: str, options: dict, initial=None):
    c = case.updated({"roller.speed": float(speed)})
    extra = {"initial": initial} if initial is not None else {}
    try:
        with warnings.catch_warnings():   # a scan crosses validity ranges on purpose
            warnings.simplefilter("ignore", ValidityWarning)
            r = solve(c, model=model, **extra, **options)
    except ConvergenceError as err:
        raise ConvergenceError(f"traction-loss search: the {model} solve at U_r = {speed:.4g} "
                               f"m/s did not converge", err.result, err.history) from None
    return r


def traction_loss_speed(case: Case, mu_min: float, model: str = "closed-form",
                        speed_range=(0.5, 100.0), n_scan: int = 24, xtol: float = 1e-3,
                        **options) -> dict:
    """Roller speed [m/s] at which the wrap-averaged mu falls below ``mu_min`` (after its peak).

    Returns a dict with ``speed`` (None if mu never falls below ``mu_min`` in ``speed_range``
    or never reaches it), ``model``, ``mu_min``, ``mu_peak``, ``speed_peak``, ``bracket``,
    ``evaluations`` (number of solves) and ``message``. The web speed is the case's.
    """
    if not 0.0 < mu_min:
        raise CaseError(f"mu_min = {mu_min!r} is out of range: must be > 0")
    lo, hi = speed_range
    if not 0.0 <= lo < hi:
        raise CaseError(f"speed range = {speed_range!r} is not valid: need 0 <= low < high")
    fe = model != "closed-form"
    speeds = np.geomspace(max(lo, 1e-3), hi, n_scan)
    results, prev = [], None
    for u in speeds:
        prev = _mu(case, u, model, options, prev if fe else None)
        results.append(prev)
    mu = np.array([r["mu"] for r in results])
    i_peak = int(np.nanargmax(mu))
    out = {"model": model, "mu_min": mu_min, "mu_peak": float(mu[i_peak]),
           "speed_peak": float(speeds[i_peak]), "evaluations": n_scan, "bracket": None,
           "speed": None}
    if mu[i_peak] < mu_min:
        out["message"] = (f"mu stays below {mu_min:g} at every speed in {lo:g}..{hi:g} m/s "
                          f"(peak {mu[i_peak]:.4g} at {speeds[i_peak]:.3g} m/s)")
        return out
    after = np.nonzero(mu[i_peak:] < mu_min)[0]
    if after.size == 0:
        out["message"] = f"mu stays above {mu_min:g} up to {hi:g} m/s"
        return out
    j = i_peak + int(after[0])
    a, b = speeds[j - 1], speeds[j]
    cache = {a: results[j - 1]}

    def f(u):
        nearest = cache[min(cache, key=lambda v: abs(v - u))]
        r = _mu(case, u, model, options, nearest if fe else None)
        cache[u] = r
        out["evaluations"] += 1
        return r["mu"] - mu_min

    speed = brentq(f, a, b, xtol=xtol * a, rtol=1e-10)
    out.update(speed=float(speed), bracket=(float(a), float(b)),
               message=f"mu falls below {mu_min:g} at U_r = {speed:.4g} m/s")
    return out


#: The paper's operating parameters and the ranges the traction-loss chart spans.
CHART_PARAMETERS = (("web.tension", "T [N/m]", (40.0, 120.0)),
                    ("wrap.angle_deg", "B [deg]", (20.0, 120.0)),
                    ("web.width", "L [m]", (0.02, 0.2)),
                    ("roller.radius", "R [m]", (0.035, 0.1)))


def traction_loss_table(case: Case, mu_min: float, models=("closed-form",), n: int = 5,
                        n_scan: int = 16, progress=None, **options) -> list[dict]:
    """Traction-loss speed against each operating parameter (others at the case's values)."""
    rows = []
    total = len(models) * len(CHART_PARAMETERS) * n
    for model in models:
        for key, _, (a, b) in CHART_PARAMETERS:
            for value in np.linspace(a, b, n):
                out = traction_loss_speed(case.updated({key: float(value)}), mu_min, model,
                                          n_scan=n_scan, **(options if model != "closed-form"
                                                            else {}))
                rows.append({"model": model, "parameter": key, "value": float(value),
                             "speed": out["speed"], "mu_peak": out["mu_peak"],
                             "evaluations": out["evaluations"]})
                if progress:
                    progress(len(rows), total)
    return rows
