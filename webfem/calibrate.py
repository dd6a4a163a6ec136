"""Calibration of the friction constants mu_cc and C (and optionally sigma) from measurements.

The paper says its constants "should be determined experimentally by the standard test".
Given measured rows (roller speed, tension, wrap and the measured tension increase dT or
friction coefficient mu, plus any other case key as a column), the constants are fitted by
nonlinear least squares through the chosen model and Euler's belt formula (Eq. 31), in the
measured quantity. The gap of each row is solved once (friction does not feed back on the gap
unless sigma is fitted, which re-solves the FE gaps at every trial sigma).

Confidence intervals come from the linearised covariance s^2 (J^T J)^-1 with s^2 the residual
variance, and Student's t with n - p degrees of freedom.

Examples
--------
>>> import numpy as np
>>> from webfem import Case
>>> rows = [{"roller.speed": u, "mu": m} for u, m in zip([2.0, 8.0, 20.0, 30.0, 40.0],
...         [0.267, 0.2703, 0.1771, 0.0672, 0.0207])]
>>> fit = calibrate(rows, Case())
>>> round(fit["estimates"]["mu_cc"], 2)
0.3
"""

from __future__ import annotations

import csv
import warnings
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares
from scipy.stats import t as student_t

from .api import solve
from .case import Case, CaseError, valid_keys
from .errors import ValidityWarning
from .models.closed import case_arrays, evaluate
from .physics.friction import delta_T_from_mu, local_friction

__all__ = ["read_measurements", "calibrate", "COLUMN_ALIASES"]

#: Short column names accepted in measurement files, and the case keys they set.
COLUMN_ALIASES = {"roller_speed": "roller.speed", "speed": "roller.speed",
                  "tension": "web.tension", "wrap_deg": "wrap.angle_deg",
                  "width": "web.width", "radius": "roller.radius", "web_speed": "web.speed"}


def read_measurements(path) -> list[dict]:
    """Rows of a measurement CSV: case keys (dotted or the short aliases of
    :data:`COLUMN_ALIASES`) and one measured column, ``delta_T`` [N/m] or ``mu``."""
    path = Path(path)
    if not path.is_file():
        raise CaseError(f"measurement file '{path}' does not exist")
    with path.open(newline="") as fh:
        reader = csv.DictReader(row for row in fh if not row.lstrip().startswith("#"))
        rows = []
        for i, raw in enumerate(reader, start=2):
            row = {}
            for k, v in raw.items():
                key = COLUMN_ALIASES.get(k.strip(), k.strip())
                if key not in valid_keys() and key not in ("delta_T", "mu"):
                    raise CaseError(f"{path}: unknown column '{k}'; use case keys (e.g. "
                                    "roller.speed), the aliases " + ", ".join(COLUMN_ALIASES)
                                    + ", and delta_T or mu")
                try:
                    row[key] = float(v)
                except (TypeError, ValueError):
                    raise CaseError(f"{path}, line {i}: column '{k}' = {v!r} is not a number")
            rows.append(row)
    if not rows:
        raise CaseError(f"{path}: no measurement rows")
    return rows


def _wrap_samples(result) -> tuple[np.ndarray, np.ndarray]:
    """Gap at the wrap's quadrature points and weights summing to 1, for any model."""
    if "wrap_h" in result.diagnostics:
        return result.diagnostics["wrap_h"], result.diagnostics["wrap_w"]
    # closed form: the gap is linear; a fine Gauss rule over its fields is ample
    x, h = result.fields["x"], result.fields["h"]
    g, w = np.polynomial.legendre.leggauss(400)
    s = 0.5 * (g + 1.0) * (x[-1] - x[0]) + x[0]
    return np.interp(s, x, h), 0.5 * w


def calibrate(rows: list[dict], case: Case, model: str = "closed-form",
              fit_sigma: bool = False, x0=None, **options) -> dict:
    """Fit mu_cc, C (and sigma) to measured rows; see the module docstring.

    Returns a dict: ``estimates``, ``stderr``, ``ci95`` (half widths), ``measured`` (name),
    ``observed``, ``predicted``, ``residuals``, ``rms``, ``dof``, ``model``, ``cases``.
    """
    measured = {"delta_T", "mu"} & set(rows[0])
    if len(measured) != 1 or any(set(r) & {"delta_T", "mu"} != measured for r in rows):
        raise CaseError("each measurement row needs exactly one of delta_T or mu, the same in "
                        "every row")
    measured = measured.pop()
    names = ["mu_cc", "speed_constant"] + (["sigma"] if fit_sigma else [])
    if len(rows) <= len(names):
        raise CaseError(f"{len(rows)} rows cannot fit {len(names)} constants: need more rows")
    cases = [case.updated({k: v for k, v in r.items() if k not in ("delta_T", "mu")})
             for r in rows]
    obs = np.array([r[measured] for r in rows])
    web_sigma = case.web.roughness
    gaps: dict = {}

    def gap_samples(sigma):
        key = round(float(sigma), 15)
        if key not in gaps:
            out = []
            for c in cases:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", ValidityWarning)
                    r = solve(c.updated({"web.roughness": sigma}), model=model, **options)
                out.append(_wrap_samples(r))
            gaps[key] = out
        return gaps[key]

    def predict(p):
        mu_cc, C = p[0], p[1]
        sigma = p[2] if fit_sigma else web_sigma
        if model == "closed-form":
            arr = case_arrays([c.updated({"web.roughness": sigma}) for c in cases])
            arr.update(mu_cc=mu_cc, C=C)
            mu = evaluate(**arr, variant=case.friction.variant,
                          distribution=case.friction.distribution)["mu"]
        else:
            mu = np.empty(len(cases))
            for i, (c, (h, w)) in enumerate(zip(cases, gap_samples(sigma))):
                loc = local_friction(h, R=c.roller.radius, T=c.web.tension, U_s=c.U_slide,
                                     eta=c.air.viscosity, E_b=c.web.modulus_thickness,
                                     sigma=sigma, t=c.web.thickness, mu_cc=mu_cc, C=C,
                                     variant=c.friction.variant,
                                     distribution=c.friction.distribution)
                mu[i] = np.sum(loc["mu"] * w)
        if measured == "mu":
            return mu
        return np.array([delta_T_from_mu(m, c.web.tension, c.B) for m, c in zip(mu, cases)])

    start = np.array(x0 if x0 is not None else
                     [case.friction.mu_cc, case.friction.speed_constant]
                     + ([web_sigma] if fit_sigma else []), float)
    scale = np.abs(start) + 1e-12
    fit = least_squares(lambda q: predict(q * scale) - obs, start / scale,
                        bounds=(np.full(start.size, 1e-9), np.full(start.size, np.inf)),
                        x_scale="jac", diff_step=1e-6)
    p = fit.x * scale
    res = predict(p) - obs
    dof = len(obs) - len(p)
    s2 = float(res @ res) / dof
    J = fit.jac / scale                      # d residual / d p
    try:
        cov = s2 * np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        cov = np.full((len(p), len(p)), np.inf)
    se = np.sqrt(np.maximum(np.diag(cov), 0.0))
    half = student_t.ppf(0.975, dof) * se
    return {"model": model, "measured": measured,
            "estimates": dict(zip(names, map(float, p))),
            "stderr": dict(zip(names, map(float, se))),
            "ci95": dict(zip(names, map(float, half))),
            "observed": obs, "predicted": obs + res, "residuals": res,
            "rms": float(np.sqrt(np.mean(res**2))), "dof": dof, "cases": cases,
            "converged": bool(fit.success), "message": fit.message}
