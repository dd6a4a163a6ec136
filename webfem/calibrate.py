"""Calibration of the friction constants mu_cc and C (and optionally sigma) from measurements.

The paper says its constants "should be determined experimentally by the standard test".
Given measured rows (roller speed, tension, wrap and the measured tension increase dT or
friction coefficient mu, plus any other case key as a column), the constants are fitted by
nonlinear least squares through the chosen model and Euler's belt formula (Eq. 31), in the
measured quantity. The gap of each row is solved once (friction does not feed back on the gap
unless sigma is fitted, which re-solves the FE gaps at every trial sigma).

Confidence intervals come from the linearised covariance s^2 (J^T J)^-1 with s^2 the residual
variance, and Student's t with n - p degrees of freedom. Every constant is positive, so its
interval is stated in log space too (``interval95``: p exp(-+t se/p), the same
linearisation in ln p, which never reaches below 0); where the linear one (``ci95``, the
half width) would reach below 0 the constant is not determined by the data and a note says
so (a 5-row newsprint rig fitted C = 0.19 +- 1.56 m/s). A constant the data cannot identify
(the predictions do not change with it, or change only together with another constant, e.g.
C without rows at several sliding speeds within a few C) is reported with no interval and a
note saying why.

Examples
--------
>>> from webfem import Case
>>> paper = Case().updated({"model.physics": "paper"})    # rows of the paper's closed form
>>> rows = [{"roller.speed": u, "mu": m} for u, m in zip([2.0, 8.0, 20.0, 30.0, 40.0],
...         [0.267, 0.2703, 0.1771, 0.0672, 0.0207])]
>>> fit = calibrate(rows, paper, model="closed-form")
>>> round(fit.estimates["mu_cc"], 2), fit["estimates"] == fit.estimates
(0.3, True)
"""

from __future__ import annotations

import csv
import dataclasses
import difflib
import math
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares
from scipy.stats import t as student_t

from .api import solve
from .case import Case, valid_keys
from .effects import answered_by
from .errors import InputError, ValidityWarning
from .keys import key_meta
from .models.closed import case_arrays, evaluate
from .models.registry import make_options
from .physics.friction import delta_T_from_mu, friction_for
from .units import to_si

__all__ = ["Calibration", "read_measurements", "calibrate", "COLUMN_ALIASES"]

#: Short column names accepted in measurement files, and the case keys they set.
COLUMN_ALIASES = {"roller_speed": "roller.speed", "speed": "roller.speed",
                  "tension": "web.tension", "wrap_deg": "wrap.angle_deg",
                  "width": "web.width", "radius": "roller.radius", "web_speed": "web.speed"}
#: The measured quantities a row may carry (one of them, the same in every row).
MEASURED = {"delta_T": "tension increase before slip [N/m]", "mu": "friction coefficient [-]"}
#: The constants' units in notes (SI).
_UNITS = {"mu_cc": "", "speed_constant": " m/s", "sigma": " m"}
#: How to make the data identify each constant.
_HINTS = {"mu_cc": "rows where asperity contact carries load (low speeds)",
          "speed_constant": "rows at several sliding speeds U_s = |U_r - U_w| within a few C, "
                            "in boundary or mixed lubrication (Eq. 29's (2/pi) mu_cc "
                            "atan(U_s/C) is flat where U_s >> C: rows at more high speeds do "
                            "not help)",
          "sigma": "rows in mixed lubrication at several speeds or tensions"}


@dataclass(frozen=True)
class Calibration:
    """The answer of :func:`calibrate`.

    ``estimates``, ``stderr`` and ``ci95`` (half widths of the 95 % intervals) map each
    constant's name to a number; ``stderr`` and ``ci95`` are None for a constant the data
    cannot identify (``identified`` False; ``notes`` says why). ``observed``,
    ``predicted``, ``residuals`` per row in the ``measured`` quantity; ``cases`` the rows'
    cases. ``interval95``: each constant's 95 % interval in log space (the constants are
    positive); :meth:`determined` says whether the data bound a constant away from 0. ``fit["estimates"]`` reads a field too.
    """

    model: str
    measured: str
    estimates: dict
    stderr: dict
    ci95: dict
    identified: dict
    observed: np.ndarray
    predicted: np.ndarray
    residuals: np.ndarray
    rms: float
    dof: int
    converged: bool
    message: str
    cases: tuple
    notes: tuple = ()
    #: The model that answered each row (auto chooses per row, once: see :func:`calibrate`).
    models_used: tuple = ()
    #: Each constant's 95 % interval ``(low, high)`` in log space, p exp(-+t se/p): positive
    #: as the constant is (None where ``ci95`` is None).
    interval95: dict = dataclasses.field(default_factory=dict)

    def determined(self, name: str) -> bool:
        """Whether the data bound ``name`` away from 0: identified, and its linear 95 %
        interval (estimate +- ``ci95``) stays above 0."""
        half = self.ci95.get(name)
        return half is not None and half < self.estimates[name]

    def __getitem__(self, key: str):
        if not isinstance(key, str) or key not in {f.name for f in dataclasses.fields(self)}:
            raise KeyError(key)
        return getattr(self, key)

    def to_dict(self) -> dict:
        """The JSON object of ``webfem calibrate --json``: strict JSON values (a non-finite
        number becomes None and gets a line in ``notes``)."""
        notes = list(self.notes)

        def plain(value, where):
            if isinstance(value, dict):
                return {k: plain(v, f"{where}.{k}") for k, v in value.items()}
            if isinstance(value, (list, tuple, np.ndarray)):
                return [plain(v, f"{where}[{i}]") for i, v in enumerate(value)]
            if isinstance(value, (bool, np.bool_)):
                return bool(value)
            if isinstance(value, (int, np.integer)):
                return int(value)
            if isinstance(value, (float, np.floating)):
                if not math.isfinite(value):
                    notes.append(f"{where} = {float(value)} is not finite: written as null")
                    return None
                return float(value)
            return value

        keys = ("model", "measured", "estimates", "stderr", "ci95", "identified", "rms",
                "dof", "converged", "message", "observed", "predicted", "residuals",
                "models_used", "interval95")
        out = {k: plain(getattr(self, k), k) for k in keys}
        # whether the data bound each constant away from 0 (:meth:`determined`): where not,
        # its estimate is where the fit stopped, not a measurement
        out["determined"] = {n: self.determined(n) for n in self.estimates}
        out["notes"] = notes
        return out


def _column(name: str, path: Path) -> str:
    """The case key or measured quantity a column header means."""
    key = COLUMN_ALIASES.get(name, name)
    if key in valid_keys() or key in MEASURED:
        return key
    valid = list(COLUMN_ALIASES) + valid_keys() + list(MEASURED)
    close = difflib.get_close_matches(name, valid, n=1, cutoff=0.6)
    hint = (f"did you mean '{close[0]}'?" if close else
            "use case keys (e.g. roller.speed), the aliases " + ", ".join(COLUMN_ALIASES)
            + ", and delta_T or mu")
    raise InputError(f"{path}: unknown column '{name}'; {hint}")


def _check_measured(key: str, value: float, where: str) -> None:
    if not math.isfinite(value):
        raise InputError(f"{where}: {key} = {value!r} is not finite: a measured "
                         f"{MEASURED[key]} must be a finite number >= 0")
    if value < 0.0:
        raise InputError(f"{where}: {key} = {value!r} is negative: a measured "
                         f"{MEASURED[key]} must be >= 0")


def _cell_value(name: str, key: str, cell: str, where: str) -> float:
    """A cell's value in SI: a number, or for a case key a number with a unit ("2 m/s",
    "120 deg"), read as the case files read it; measured columns take plain numbers."""
    try:
        return float(cell)
    except ValueError:
        pass
    if key in MEASURED:
        raise InputError(f"{where}: column '{name}' = {cell.strip()!r} is not a number "
                         f"(a measured {MEASURED[key]}: give the number alone)")
    try:
        return to_si(key, cell.strip(), key_meta(key)["unit"])
    except InputError as err:
        raise InputError(f"{where}: column '{name}': {err}") from None


def read_measurements(path) -> list[dict]:
    """Rows of a measurement CSV (UTF-8): case keys (dotted or the short aliases of
    :data:`COLUMN_ALIASES`) and one measured column, ``delta_T`` [N/m] or ``mu``. A case
    key's cell is a number in SI units or a number with a unit (``2 m/s``, ``120 deg``).

    Lines starting with ``#`` are comments. Each bad cell is an :class:`InputError` naming
    the file, line and column: unknown columns (with the closest valid name), text where a
    number belongs, non-finite values, negative measurements.
    """
    path = Path(path)
    if not path.exists():
        raise InputError(f"measurement file '{path}' does not exist")
    if not path.is_file():
        raise InputError(f"measurement file '{path}' is not a file")
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as err:
        raise InputError(f"{path}: not UTF-8 text (byte {err.object[err.start]:#04x} at "
                         f"offset {err.start}); save the file as UTF-8 CSV") from None
    lines = [(i, line) for i, line in enumerate(text.splitlines(), start=1)
             if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise InputError(f"{path}: no header and no measurement rows")
    reader = csv.reader(line for _, line in lines)
    header = [h.strip() for h in next(reader)]
    keys = [_column(h, path) for h in header]
    for key in set(keys):
        names = [h for h, k in zip(header, keys) if k == key]
        if len(names) > 1:
            raise InputError(f"{path}: columns {' and '.join(map(repr, names))} both set "
                             f"{key}: keep one")
    rows = []
    for (line_no, _), cells in zip(lines[1:], reader):
        where = f"{path}, line {line_no}"
        if len(cells) != len(header):
            raise InputError(f"{where}: {len(cells)} values for {len(header)} columns "
                             f"({', '.join(header)})")
        row = {}
        for name, key, cell in zip(header, keys, cells):
            value = _cell_value(name, key, cell, where)
            if key in MEASURED:
                _check_measured(key, value, where)
            elif not math.isfinite(value):
                raise InputError(f"{where}: column '{name}' = {cell.strip()!r} is not finite")
            row[key] = value
        rows.append(row)
    if not rows:
        raise InputError(f"{path}: no measurement rows")
    return rows


def _wrap_samples(result) -> tuple:
    """Gap at the wrap's quadrature points, weights summing to 1, whether the gap was
    solved (FE: the web rests on its asperities, :func:`friction_for`'s ``resting``), and
    the film pressure and its gradient there (None for the closed form)."""
    d = result.diagnostics
    if "wrap_h" in d:
        return d["wrap_h"], d["wrap_w"], True, d.get("wrap_p"), d.get("wrap_dpdx")
    # closed form: the gap is linear; a fine Gauss rule over its fields is ample
    x, h = result.fields["x"], result.fields["h"]
    g, w = np.polynomial.legendre.leggauss(400)
    s = 0.5 * (g + 1.0) * (x[-1] - x[0]) + x[0]
    return np.interp(s, x, h), 0.5 * w, False, None, None


def _identifiability(J: np.ndarray, p: np.ndarray, obs: np.ndarray, names) -> dict:
    """Which constants the data identify, from the Jacobian at the fit.

    Relative sensitivities S_j = p_j dr/dp_j: a column below 1e-7 of the data's size is flat
    (the predictions do not depend on that constant); among the others, columns whose
    normalised directions leave a singular value below 1e-6 of the largest are
    rank-deficient (the constants act only together). Both thresholds sit orders of
    magnitude above the finite-difference noise of the Jacobian (about 1e-10).
    """
    S = J * p
    norms = np.linalg.norm(S, axis=0)
    scale = max(float(np.linalg.norm(obs)), 1e-300)
    why = {}
    live = []
    for j, name in enumerate(names):
        if norms[j] <= 1e-7 * scale:
            why[name] = (f"{name} cannot be identified: the predictions do not change with "
                         f"it; add {_HINTS[name]}")
        else:
            live.append(j)
    if len(live) > 1:
        U, s, Vt = np.linalg.svd(S[:, live] / norms[live], full_matrices=False)
        if s[-1] <= 1e-6 * s[0]:
            involved = [names[live[i]] for i in np.nonzero(np.abs(Vt[-1]) > 0.1)[0]]
            for name in involved:
                others = " and ".join(n for n in involved if n != name)
                why[name] = (f"{name} cannot be identified: the predictions change with it "
                             f"only together with {others}; add {_HINTS[name]}")
    return why


def calibrate(rows: list[dict], case: Case, model: str = "auto",
              fit_sigma: bool = False, x0=None, options=None, **values) -> Calibration:
    """Fit mu_cc, C (and sigma) to measured rows; see the module docstring.

    Parameters
    ----------
    rows : list of dict
        Case keys (dotted) and exactly one measured key, ``delta_T`` or ``mu`` (finite,
        >= 0), the same in every row; more rows than constants.
    case : Case
        Everything the rows leave out.
    model : str
        The model whose gaps the friction is evaluated on.
    fit_sigma : bool
        Also fit the web roughness sigma.
    x0 : sequence, optional
        Start values (default: the case's constants).
    options, **values
        The model's options.

    Returns
    -------
    Calibration
    """
    if not rows:
        raise InputError("no measurement rows")
    measured = set(MEASURED) & set(rows[0])
    if len(measured) != 1 or any(set(r) & set(MEASURED) != measured for r in rows):
        raise InputError("each measurement row needs exactly one of delta_T or mu, the same "
                         "in every row")
    measured = measured.pop()
    names = ["mu_cc", "speed_constant"] + (["sigma"] if fit_sigma else [])
    if len(rows) <= len(names):
        raise InputError(f"{len(rows)} rows cannot fit {len(names)} constants: need more rows")
    cases = []
    for i, r in enumerate(rows, start=1):
        value = r[measured]
        if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
            raise InputError(f"measurement row {i}: {measured} = {value!r} is not a number")
        _check_measured(measured, float(value), f"measurement row {i}")
        try:
            cases.append(case.updated({k: v for k, v in r.items() if k not in MEASURED}))
        except InputError as err:
            raise InputError(f"measurement row {i}: {err}") from None
    obs = np.array([float(r[measured]) for r in rows])
    web_sigma = case.web.roughness
    gaps: dict = {}
    # auto chooses a row's model at the first sigma; later sigmas (--fit-sigma) keep it, so
    # the fit's objective never jumps where auto would change its mind
    chosen: list = []
    base_options = make_options(model, options, **values)

    def gap_samples(sigma):
        key = round(float(sigma), 15)
        if key not in gaps:
            out = []
            for i, c in enumerate(cases):
                # a row's first solve asks for ``model``; later ones the model that answered
                name, opts = chosen[i] if len(chosen) > i else (model, base_options)
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", ValidityWarning)
                    r = solve(c.updated({"web.roughness": sigma}), model=name, options=opts)
                if len(chosen) <= i:
                    chosen.append(answered_by(r, model, base_options))
                out.append(_wrap_samples(r))
            gaps[key] = out
        return gaps[key]

    def predict(p):
        mu_cc, C = p[0], p[1]
        sigma = p[2] if fit_sigma else web_sigma
        if model == "closed-form":
            arr = case_arrays([c.updated({"web.roughness": sigma}) for c in cases])
            arr.update(mu_cc=mu_cc, C=C)
            mu = evaluate(**arr, variant=case.friction_variant,
                          distribution=case.friction.distribution,
                          roughness=case.roughness_flow_model == "mean-gap")["mu"]
        else:
            mu = np.empty(len(cases))
            for i, (c, (h, w, resting, p, dpdx)) in enumerate(zip(cases,
                                                                  gap_samples(sigma))):
                c = c.updated({"web.roughness": sigma, "friction.mu_cc": mu_cc,
                               "friction.speed_constant": C})
                mu[i] = np.sum(friction_for(c, h, resting, p, dpdx)["mu"] * w)
        if measured == "mu":
            return np.asarray(mu, float)
        return np.array([delta_T_from_mu(m, c.tension_eff, c.B) for m, c in zip(mu, cases)])

    start = np.array(x0 if x0 is not None else
                     [case.friction.mu_cc, case.friction.speed_constant]
                     + ([web_sigma] if fit_sigma else []), float)
    if start.shape != (len(names),) or not np.all(np.isfinite(start) & (start > 0)):
        raise InputError(f"x0 = {x0!r} is not valid: must be {len(names)} finite numbers > 0 "
                         f"({', '.join(names)})")
    bad = np.nonzero(~np.isfinite(predict(start)))[0]
    if bad.size:
        raise InputError(f"the {model} model predicts no finite {measured} for measurement "
                         f"rows {', '.join(str(i + 1) for i in bad)} (e.g. contact cannot "
                         "carry T/R there): check those rows' case values")
    scale = np.abs(start)
    fit = least_squares(lambda q: predict(q * scale) - obs, start / scale,
                        bounds=(np.full(start.size, 1e-9), np.full(start.size, np.inf)),
                        x_scale="jac", diff_step=1e-6)
    p = fit.x * scale
    res = predict(p) - obs
    dof = len(obs) - len(p)
    s2 = float(res @ res) / dof
    J = fit.jac / scale                      # d residual / d p
    why = _identifiability(J, p, obs, names)
    notes = [why[n] for n in names if n in why]
    keep = [j for j, n in enumerate(names) if n not in why]
    se = dict.fromkeys(names)
    half = dict.fromkeys(names)
    if keep:
        cov = s2 * np.linalg.pinv(J[:, keep].T @ J[:, keep])
        t95 = float(student_t.ppf(0.975, dof))
        for j, v in zip(keep, np.sqrt(np.maximum(np.diag(cov), 0.0))):
            se[names[j]], half[names[j]] = float(v), t95 * float(v)
    interval = dict.fromkeys(names)
    for j in keep:
        name, v = names[j], float(p[j])
        # ln p +- t se / p; an estimate pressed to the fit's bound (v -> 1e-9 of its scale)
        # has no log-space interval to speak of: 0 to infinity, not an overflow
        z = half[name] / v if v > 0.0 else math.inf
        spread = math.exp(z) if z < 700.0 else math.inf
        interval[name] = (v / spread, v * spread) if math.isfinite(spread) else (0.0, math.inf)
        if half[name] >= v:
            low, high = interval[name]
            unit = _UNITS[name]
            span = (f"in log space it spans {low:.2g} to {high:.2g}{unit}, a factor "
                    f"{spread:.2g} either way" if math.isfinite(spread) else
                    "in log space it spans 0 to infinity (the estimate sits at the fit's "
                    "lower bound)")
            notes.append(f"{name} is not determined by these data: its linear 95 % interval "
                         f"({v:.2g} +- {half[name]:.2g}{unit}) reaches below 0, and {span}; "
                         f"add {_HINTS[name]}")
    if s2 == 0.0 and keep:
        notes.append("the fit is exact (zero residuals): the intervals are 0 because the "
                     "data show no scatter, not because the constants are known exactly")
    return Calibration(
        model=model, measured=measured, estimates=dict(zip(names, map(float, p))),
        stderr=se, ci95=half, identified={n: n not in why for n in names},
        observed=obs, predicted=obs + res, residuals=res,
        rms=float(np.sqrt(np.mean(res**2))), dof=dof, converged=bool(fit.success),
        message=str(fit.message), cases=tuple(cases), notes=tuple(notes),
        models_used=tuple(name for name, _ in chosen) if chosen else (model,) * len(cases),
        interval95=interval)
