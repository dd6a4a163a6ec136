"""Traction loss: the roller speed above which the friction coefficient stays below a threshold.

mu(U_r) rises from the boundary-lubrication value at low speed, peaks, and falls as air lifts
the web (the paper's Stribeck-like curve). The traction-loss speed is where it falls through
``mu_min`` after the peak: found on a logarithmic scan of roller speeds (walked with
:func:`webfem.api.solve_along`, each FE point started from the previous one, up to the first
speed where mu is below ``mu_min`` after having reached it) and refined by Brent's method
inside the bracketing interval (the solves: :mod:`webfem.loss_scan`).

Examples
--------
>>> from webfem import Case
>>> out = traction_loss_speed(Case(), 0.1, "closed-form")
>>> round(out.speed, 1), out.model, out["speed"] == out.speed
(28.2, 'closed-form', True)
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from .case import Case
from .errors import ConvergenceError, InputError
from .keys import key_meta
from .line_speed import at_speed, ratio_text, speed_ratio, top_speed
from .loss_scan import crossing, refine, scan
from .models.options import Options
from .models.registry import make_options, model_spec

__all__ = ["TractionLoss", "traction_loss_speed", "traction_loss_table", "mu_curve",
           "fitted_speed_range", "chart_parameters",
           "CHART_PARAMETERS", "SPEED_RANGE", "CHART_POINTS"]

#: Roller speeds [m/s] a traction-loss scan spans unless told otherwise.
SPEED_RANGE = (0.5, 100.0)
#: Values per parameter in the traction-loss chart.
CHART_POINTS = 5


@dataclass(frozen=True)
class TractionLoss:
    """The answer of :func:`traction_loss_speed`.

    ``speed`` [m/s] is None when mu never reaches ``mu_min`` in the scanned range or never
    falls below it; ``bracket`` the scan interval holding the crossing; ``mu_peak`` and
    ``speed_peak`` the largest mu of the scan's speeds and where; ``scanned`` the lowest and
    highest scan speed solved (the scan stops at its first crossing unless asked for the
    full range); ``evaluations`` the number of solves; ``message`` says what was found (and
    where the scan stopped). ``out["speed"]`` reads a field too.
    ``model_used``: the model that answered at the speed found (else at the peak): auto's
    choice there, or ``model`` itself; ``models_used``: every model that answered a solve
    of the search, in the order first used. ``web_speed_ratio``: U_w/U_r kept at every
    scanned speed (:mod:`webfem.line_speed`; None: the roller at rest, the web speed kept).
    ``scan_limit``: why the speeds above ``scanned[1]`` could not be scanned where the
    scan's range ends below the one asked (None where it covered it, or where the scan
    stopped at its crossing below that end, which the speeds above cannot move): the line
    itself is not
    possible above it (T_eff <= 0, a film thicker than R/100:
    :func:`webfem.line_speed.top_speed`) or the model has no answer at the next scan speed
    (:class:`webfem.loss_scan.Refused`). With ``speed`` None it bounds the answer: mu stays
    on its side of ``mu_min`` up to ``scanned[1]``, what lies above is not known.
    ``speed_interval``: the speeds [m/s] between which mu's stated error band reaches
    ``mu_min`` (:func:`speed_interval`): the first where mu less its stated error falls to
    it, the first where mu plus its stated error does; an end is None where the solved
    speeds do not show it (a stated error missing, the band reaching mu_min at the peak, or
    above the last speed solved). ``error_speed``: the larger distance from ``speed`` to
    an end, relative to ``speed`` (None where an end is not known); it holds Brent's
    tolerance too, ``speed`` being the root find's answer, within ``xtol`` of the crossing.
    """

    speed: float | None
    model: str
    mu_min: float
    mu_peak: float
    speed_peak: float
    bracket: tuple[float, float] | None
    evaluations: int
    message: str
    model_used: str | None = None
    models_used: tuple[str, ...] = ()
    scanned: tuple[float, float] | None = None
    web_speed_ratio: float | None = None
    scan_limit: str | None = None
    speed_interval: tuple[float | None, float | None] | None = None
    error_speed: float | None = None

    def answered(self) -> str:
        """``fe2d``, or for auto ``auto: fe2d`` (``auto: fe2d; the scan also used fe1d``)."""
        if self.model_used in (None, self.model):
            return self.model
        others = [m for m in self.models_used if m != self.model_used]
        return (f"{self.model}: {self.model_used}"
                + (f"; the scan also used {', '.join(others)}" if others else ""))

    def __getitem__(self, key: str):
        if not isinstance(key, str) or key not in self.keys():
            raise KeyError(key)
        return getattr(self, key)

    def keys(self) -> list[str]:
        return [f.name for f in dataclasses.fields(self)]

    def to_dict(self) -> dict:
        """JSON-safe: the bracket as a list, non-finite numbers as None."""
        out = {}
        for key in self.keys():
            value = getattr(self, key)
            if isinstance(value, tuple):
                value = list(value)
            elif isinstance(value, float) and not math.isfinite(value):
                value = None
            out[key] = value
        return out


def _used(result) -> str:
    """The model that answered ``result`` (auto's choice, or the model itself)."""
    return result["model_used"] or result["model"]


def traction_loss_speed(case: Case, mu_min: float, model: str = "auto",
                        speed_range=SPEED_RANGE, n_scan: int = 24, xtol: float = 1e-3,
                        options: Options | dict | None = None, workers: int = 1,
                        full_scan: bool = False, **values) -> TractionLoss:
    """Roller speed [m/s] at which the wrap-averaged mu falls below ``mu_min`` (after its peak).

    The scan walks up the speeds and stops at the first one where mu is below ``mu_min``
    after having reached it (the speeds above cannot move that crossing); the root find
    refines it between that speed and the one before. ``full_scan`` solves every speed of
    the range: the peak is then the whole range's and the crossing the first after it (the
    same answer unless mu rises above ``mu_min`` again at a higher speed, and higher than
    before).

    Parameters
    ----------
    case : Case
        The operating point; its roller speed U_r is scanned with the web following at the
        case's ratio U_w/U_r (:func:`webfem.line_speed.at_speed`: the line moves; the
        paper's rig, web at rest, stays at rest).
    mu_min : float
        Friction threshold, > 0.
    model : str
        A model of :data:`webfem.models.registry.MODELS`.
    speed_range : (float, float)
        Roller speeds scanned, 0 <= low < high [m/s]; a web whose speed rises with the
        roller's is scanned only below the speed at which it can no longer be held on the
        roller (:func:`webfem.line_speed.top_speed`; the message says so).
    n_scan : int
        Points of the logarithmic scan (at least 3).
    xtol : float
        Brent's tolerance relative to the bracket's low end.
    options, **values
        The model's options (an options object, a dict or keywords).
    workers : int
        Local processes for the scan (1 to 256; default 1). An FE scan walks its speeds in
        two runs, each with continuation and each stopping at a crossing of its own: the
        lowest :data:`webfem.loss_scan.LOW_SHARE` of them, then the rest from a cold start;
        with ``workers`` > 1 a worker process walks the second run while this one walks the
        first, and refines its crossing at once (used where it is the scan's first). The
        answer is the same to the bit with any ``workers`` (more than 2 are not used).
    full_scan : bool
        Solve every speed of the range, not stopping at the first crossing.

    Returns
    -------
    TractionLoss
    """
    try:
        threshold = float(mu_min)
    except (TypeError, ValueError):
        threshold = math.nan
    if isinstance(mu_min, bool) or not (math.isfinite(threshold) and threshold > 0.0):
        raise InputError(f"mu_min = {mu_min!r} is out of range: must be a finite number > 0")
    mu_min = threshold
    try:
        lo, hi = (float(v) for v in speed_range)
    except (TypeError, ValueError):
        raise InputError(f"speed range = {speed_range!r} is not valid: need two speeds "
                         "0 <= low < high [m/s]") from None
    if not (math.isfinite(hi) and 0.0 <= lo < hi):
        raise InputError(f"speed range = {speed_range!r} is not valid: need 0 <= low < high "
                         "(finite) [m/s]")
    top = key_meta("roller.speed")["hi"]
    if hi > top:   # refused here, not at the first scanned speed above it
        raise InputError(f"speed range = {speed_range!r} is out of range: the high end must "
                         f"be <= {top:g} m/s, the roller speeds a case allows (roller.speed)")
    if isinstance(n_scan, bool) or not isinstance(n_scan, int) or not 3 <= n_scan <= 10_000:
        raise InputError(f"n_scan = {n_scan!r} is out of range: must be an integer from 3 "
                         "to 10000")
    from .sweeps.workers import check_workers

    check_workers(workers)
    if not isinstance(full_scan, bool):
        raise InputError(f"full_scan = {full_scan!r} is not valid: must be True or False")
    opts = make_options(model, options, **values)
    note = capped = ""
    limit = None
    top, why = top_speed(case, hi)
    if why:   # the line flies off the roller or out of the thin-film bound above ``top``
        if top <= lo:
            raise InputError(f"speed range = {speed_range!r} is out of range: at U_r = "
                             f"{max(lo, 1e-3):g} m/s ({ratio_text(case)}) {why}")
        hi = top
        limit = f"above U_r = {top:.4g} m/s {why}"
        capped = f" (the scan ends at U_r = {top:.4g} m/s, the last possible speed: {limit})"
    if model == "fitted":       # scan the speeds its domain holds (it refuses the others)
        lo_in, hi_in = fitted_speed_range(case, max(lo, 1e-3), hi)
        if (lo_in, hi_in) != (max(lo, 1e-3), hi):
            note += (f" (the fitted model's domain limits the scan to {lo_in:.4g}..{hi_in:.4g}"
                    " m/s)")
        lo, hi = lo_in, hi_in
    speeds = np.geomspace(max(lo, 1e-3), hi, n_scan)
    results, solved, refined, ended = scan(case, speeds, model, opts, workers=workers,
                                           stop=None if full_scan else mu_min, xtol=xtol)
    # a stopped scan's results end at its first crossing: the search below finds it again
    # (every speed between mu's first reaching mu_min and it is at or above mu_min)
    mu = np.array([r["mu"] for r in results], float)
    i_peak = int(np.nanargmax(mu))
    used = list(dict.fromkeys(_used(r) for r in results))
    found = dict(model=model, mu_min=float(mu_min), mu_peak=float(mu[i_peak]),
                 speed_peak=float(speeds[i_peak]), evaluations=solved, bracket=None,
                 speed=None, model_used=_used(results[i_peak]), models_used=tuple(used),
                 scanned=(float(speeds[0]), float(speeds[len(results) - 1])),
                 web_speed_ratio=speed_ratio(case), scan_limit=limit)
    last = float(speeds[len(results) - 1])
    if isinstance(ended, ConvergenceError) and crossing(mu, mu_min) is None:
        # a failed solve is no answer about the speeds above it, but those below stand
        side = ("reaches it and does not fall below it" if mu[i_peak] >= mu_min
                else "stays below")
        raise ConvergenceError(f"{ended}; below it, at {lo:.4g}..{last:.4g} m/s, mu {side} "
                               f"(mu_min = {mu_min:g}; peak {mu[i_peak]:.4g} at "
                               f"{speeds[i_peak]:.3g} m/s; {ratio_text(case)})",
                               ended.result, ended.history)
    if ended is not None:
        # the model refused the next speed (or, in a full scan past its crossing, failed
        # there): the answer is the speeds below it, said so
        found["scan_limit"] = (" ".join(str(ended).split())
                               if isinstance(ended, ConvergenceError)
                               else f"at U_r = {ended.speed:.4g} m/s, {ended.reason}")
        note = (f" (the scan ends at U_r = {last:.4g} m/s, the last speed answered: "
                f"{found['scan_limit']}){note}")
    elif len(results) < n_scan:
        found["scan_limit"] = None   # stopped at its crossing: the speeds above are not needed
        note = f" (the scan stopped at {last:.4g} m/s, its first speed below it){note}"
    else:   # the scan reached its top: say why that is below the range asked for
        note = f"{capped}{note}"
    note = f"{note}; {ratio_text(case)}"
    if mu[i_peak] < mu_min:
        return TractionLoss(**found, message=(
            f"mu stays below {mu_min:g} at every speed in {lo:.4g}..{last:.4g} m/s (peak "
            f"{mu[i_peak]:.4g} at {speeds[i_peak]:.3g} m/s){note}"))
    after = np.nonzero(mu[i_peak:] < mu_min)[0]
    if after.size == 0:
        return TractionLoss(**found, message=f"mu stays above {mu_min:g} up to {last:.4g} m/s"
                                          f"{note}")
    j = i_peak + int(after[0])
    a, b = float(speeds[j - 1]), float(speeds[j])
    if refined is not None and refined[0] == (a, b):   # a worker's, while the scan went on
        speed, cache = refined[1:]
    else:
        speed, cache = refine(case, model, opts, a, b, results[j - 1], results[j], mu_min,
                              xtol)
        found["evaluations"] += len(cache) - 2
    speed = interpolated_crossing(cache, mu_min, speed)
    at = cache[min(cache, key=lambda v: abs(v - speed))]
    used += [m for m in dict.fromkeys(_used(r) for r in cache.values()) if m not in used]
    found.update(speed=speed, bracket=(a, b), model_used=_used(at), models_used=tuple(used))
    low, high = speed_interval(list(results) + list(cache.values()), mu_min,
                               float(speeds[i_peak]))
    error = interval_error(low, high, speed)
    found.update(speed_interval=(low, high), error_speed=error)
    return TractionLoss(**found, message=f"mu falls below {mu_min:g} at U_r = {speed:.4g} m/s"
                                      f" ({interval_text(low, high, error)}){note}")


def interval_error(low: float | None, high: float | None, speed: float) -> float | None:
    """``error_speed``: the larger distance from ``speed`` to an end of its stated interval,
    relative to it (None without both ends)."""
    if low is None or high is None:
        return None
    return max(abs(speed - low), abs(high - speed)) / speed


def interpolated_crossing(cache: dict, mu_min: float, speed: float) -> float:
    """The crossing of mu through ``mu_min`` interpolated linearly between the root find's
    two solved speeds nearest to Brent's answer ``speed`` on either side of it (``cache``:
    result by speed): a speed inside the interval mu's stated error band gives
    (:func:`speed_interval`), where Brent's own tolerance (1e-3 of the bracket) is up to 20
    times wider than that band on fe2d. ``speed`` itself where the two do not straddle
    ``mu_min``."""
    below = [u for u in cache if u <= speed and cache[u]["mu"] >= mu_min]
    above = [u for u in cache if u >= speed and cache[u]["mu"] < mu_min]
    if not below or not above:
        return speed
    a, b = max(below), min(above)
    ga, gb = cache[a]["mu"] - mu_min, cache[b]["mu"] - mu_min
    return a if ga == gb else a + (b - a) * ga / (ga - gb)


def interval_text(low: float | None, high: float | None, error: float | None) -> str:
    """The stated interval of a traction-loss speed in words, for its message (``error``:
    :func:`interval_error`)."""
    if error is not None:
        # enough digits that the interval's ends differ where the error is small
        digits = max(4, 2 + math.ceil(-math.log10(max(error, 1e-12))))
        return (f"stated interval {low:.{digits}g}..{high:.{digits}g} m/s, where mu's stated "
                f"error band reaches mu_min; error {error:.2g}")
    start = f"{low:.4g} m/s" if low is not None else "the peak"
    end = (f"{high:.4g} m/s" if high is not None else "above the last speed solved (the "
           "scan stops at its crossing; --full-scan solves the speeds above)")
    return (f"no stated error: within mu's stated error, mu may reach mu_min anywhere from "
            f"{start} to {end}")


def speed_interval(results, mu_min: float, after: float) -> tuple[float | None, float | None]:
    """Where mu's stated error band reaches ``mu_min`` after the peak speed ``after``: the
    first speed at which mu - e falls to ``mu_min`` and the first at which mu + e does, e
    being mu's stated error in absolute terms (``error_mu`` times its scale,
    :func:`webfem.models.readout.error_scale`), each interpolated linearly between the
    solved speeds ``results`` (results of any order). An end is None where they do not show
    it: a result without a stated error on the way, the band's low side at or below
    ``mu_min`` already at the peak (the loss may come earlier than any speed solved after
    it), or the band's high side still above ``mu_min`` at the last speed solved.

    >>> import webfem
    >>> rs = [webfem.solve(Case().updated({"roller.speed": u}), model="closed-form")
    ...       for u in (10.0, 20.0, 30.0, 40.0)]
    >>> low, high = speed_interval(rs, 0.1, 10.0)   # Eq. 21's mu band (errors 0.4-2) at 0.1
    >>> round(low, 1), round(high, 1)
    (15.1, 37.2)
    """
    from .models.readout import error_scale

    points = []
    for r in sorted(results, key=lambda r: r.case.roller.speed):
        u, mu = r.case.roller.speed, r["mu"]
        if u < after:
            continue
        try:
            error = r["error_mu"]
        except KeyError:
            error = None
        if error is None or not math.isfinite(error):
            points.append((u, mu, math.nan))
            continue
        points.append((u, mu, error * error_scale(r.case, "mu", mu)))

    def first_below(sign: float) -> float | None:
        prev = None
        for u, mu, e in points:
            g = mu + sign * e - mu_min
            if not math.isfinite(g):
                return None
            if g <= 0.0:
                if prev is None:
                    return None
                u0, g0 = prev
                return u0 + (u - u0) * g0 / (g0 - g)
            prev = (u, g)
        return None

    return first_below(-1.0), first_below(+1.0)


def fitted_speed_range(case: Case, lo: float, hi: float, n: int = 400) -> tuple[float, float]:
    """The roller speeds of ``lo..hi`` [m/s] the fitted model answers at: the longest run of
    a logarithmic grid of ``n`` speeds inside its domain (its groups move with the speed;
    a speed where the case itself is impossible counts as outside). Raises
    :class:`~webfem.models.fitted.OutsideDomain` naming why when no speed is inside.

    >>> lo, hi = fitted_speed_range(Case(), 0.5, 100.0)
    >>> 0.5 < lo < 2.0, hi == 100.0
    (True, True)
    """
    from .models import fit_groups as fg
    from .models.fitted import OutsideDomain

    why = fg.physics_refusal(case)
    if why:
        raise OutsideDomain(f"no fitted answer: {why}")
    grid = np.geomspace(lo, hi, n)
    cases, where = _cases_at(case, grid)
    inside = np.zeros(n, bool)
    if cases:
        rows = fg.outside_rows(fg.groups_of_columns(fg.case_columns(cases)))
        inside[np.array(where)[rows < 0]] = True
    best, start = (0, 0), None
    for j, ok in enumerate(np.append(inside, False)):
        if ok and start is None:
            start = j
        elif not ok and start is not None:
            best = max(best, (j - start, start))
            start = None
    length, first = best
    if length == 0:
        probe = fg.outside(cases[0]) if cases else "no possible case"
        raise OutsideDomain(f"no fitted answer at any roller speed in {lo:g}..{hi:g} m/s "
                            f"(at {grid[where[0]] if cases else lo:g} m/s: {probe})")
    return float(grid[first]), float(grid[first + length - 1])


def _cases_at(case: Case, speeds) -> tuple[list[Case], list[int]]:
    """The line of ``case`` at each of ``speeds`` (:func:`webfem.line_speed.at_speed`) that
    is a case at all, and the indices of those speeds."""
    cases, where = [], []
    for j, u in enumerate(speeds):
        try:
            cases.append(at_speed(case, float(u)))
            where.append(j)
        except InputError:      # the web cannot be held on the roller at that speed
            pass
    return cases, where


def mu_curve(case: Case, model: str, speeds, options: Options | dict | None = None
             ) -> tuple[np.ndarray, np.ndarray]:
    """mu against roller speed: ``(speeds, mu)``, walked with continuation (the web at the
    case's ratio U_w/U_r, :func:`webfem.line_speed.at_speed`); a point without an answer (not
    converged, a case the model does not hold at that speed, a speed at which the web cannot
    be held, outside the fitted model's domain) is NaN: a gap in a chart's line, not the end
    of the chart.

    >>> u, mu = mu_curve(Case(), "closed-form", [2.0, 30.0])
    >>> bool(mu[0] > mu[1])   # air lifts the web: traction falls with speed
    True
    """
    from .api import solve_many

    speeds = np.asarray(speeds, float)
    # a web flown off the roller is no case (left out); a film too thick for the thin-film
    # model is refused by the solve (kept unconverged): both NaN
    cases, where = _cases_at(case, speeds)
    mu = np.full(len(speeds), np.nan)
    if model == "fitted":       # outside its domain (which moves with the speed): NaN
        from .models import fit_groups as fg
        from .models.fitted import solve_many as fitted_many
        inside = [k for k, c in enumerate(cases) if fg.outside(c) is None]
        if inside:
            mu[np.array(where)[inside]] = [r["mu"] for r in fitted_many(
                [cases[k] for k in inside], make_options(model, options))]
        return speeds, mu
    # solve_many keeps a refused point (its film too thick at that speed, say) as unconverged
    results = solve_many(cases, model, make_options(model, options))
    mu[where] = [r["mu"] if r["converged"] else np.nan for r in results]
    return speeds, mu


#: The paper's operating parameters and the ranges the traction-loss chart spans:
#: (case key, axis label, (low, high)).
CHART_PARAMETERS = (("web.tension", "T [N/m]", (40.0, 120.0)),
                    ("wrap.angle_deg", "B [deg]", (20.0, 120.0)),
                    ("web.width", "L [m]", (0.02, 0.2)),
                    ("roller.radius", "R [m]", (0.035, 0.1)))


#: How far a chart's range reaches either side of a case value outside the paper's range:
#: from the value / SPAN to the value * SPAN (a factor, so a 1.2 m web and a 20 mm one get
#: ranges alike in shape).
SPAN = 2.0


def chart_parameters(case: Case) -> tuple:
    """:data:`CHART_PARAMETERS` with ranges that hold ``case``'s values: the paper's range
    where it holds the case's value (the paper's rig and cases near it chart as the paper
    did), else the value / :data:`SPAN` to the value * SPAN, inside the key's valid range
    (a wrap angle stays below 360 deg).

    >>> [r for _, _, r in chart_parameters(Case())] == [r for _, _, r in CHART_PARAMETERS]
    True
    >>> chart_parameters(Case().updated({"web.tension": 300.0}))[0][2]
    (150.0, 600.0)
    """
    out = []
    for key, label, (a, b) in CHART_PARAMETERS:
        value = float(case.get(key))
        if not a <= value <= b:
            meta = key_meta(key)
            lo, hi = meta["lo"], meta["hi"]
            # an open end is kept out by a hair: the key refuses the end itself
            lo = lo * 1.001 if meta["lo_open"] else lo
            hi = hi * 0.999 if meta["hi_open"] else hi
            a, b = max(value / SPAN, lo), min(value * SPAN, hi)
        out.append((key, label, (float(a), float(b))))
    return tuple(out)


def _options_for(model: str, options):
    """``options`` belong to the FE model of a comparison: an options object reaches the
    model of its type only, a dict every model but the closed form."""
    if options is None:
        return None
    if isinstance(options, Options):
        return options if type(options) is model_spec(model).options else None
    return None if model == "closed-form" else options


def traction_loss_table(case: Case, mu_min: float, models=("auto",),
                        n: int = CHART_POINTS,
                        n_scan: int = 16, progress=None, options=None, workers: int = 1,
                        parameters=None, speed_range=SPEED_RANGE, **values) -> list[dict]:
    """Traction-loss speed against each of ``parameters`` (default
    :func:`chart_parameters` of ``case``; the others at the case's values), ``n`` values
    each, one row per model and value: ``model``, ``parameter``, ``value``, ``speed``
    (None: no loss in range, or no answer), ``mu_peak``, ``evaluations`` and ``skipped``:
    None, or why the point has no answer (its case is not one the model holds, e.g. a film
    too thick for the thin-film model at a low tension, or a solve that did not converge):
    a point without an answer does not end the table. ``speed_range``: the roller speeds
    each search scans [m/s].

    ``options`` (or keywords): the FE model's options; the closed form takes its defaults.
    ``workers`` > 1 runs the searches in that many local processes: each search is the same
    serial scan and root find, so the rows are the same, in the same order (to rounding: a
    warm process reuses cached meshes and orderings).
    """
    from .sweeps.workers import check_workers

    check_workers(workers)
    options = dict(values) if values and options is None else options
    parameters = chart_parameters(case) if parameters is None else parameters
    tasks = [(case, mu_min, model, key, float(value), n_scan, _options_for(model, options),
              tuple(speed_range))
             for model in models for key, _, (a, b) in parameters
             for value in np.linspace(a, b, n)]
    rows: list = [None] * len(tasks)
    done = 0

    def record(i, row):
        nonlocal done
        rows[i] = row
        done += 1
        if progress:
            progress(done, len(tasks))

    if workers == 1:
        for i, args in enumerate(tasks):
            record(i, _table_row(*args))
        return rows
    from .sweeps.workers import Processes

    pool = Processes(min(workers, len(tasks)))
    try:
        pool.run(list(enumerate(tasks)), record, task=_table_row)
    finally:
        pool.close()
    return rows


def _table_row(case: Case, mu_min: float, model: str, key: str, value: float, n_scan: int,
               options, speed_range=SPEED_RANGE) -> dict:
    """One row of :func:`traction_loss_table` (a worker's task): a point the model cannot
    answer is a row saying why, not an error (one impossible point of a chart must not
    cost the others)."""
    from .errors import ConvergenceError

    try:
        out = traction_loss_speed(case.updated({key: value}), mu_min, model, n_scan=n_scan,
                                  options=options, speed_range=speed_range)
    except (InputError, ConvergenceError) as err:   # the fitted model's OutsideDomain too
        return {"model": model, "parameter": key, "value": value, "speed": None,
                "mu_peak": None, "evaluations": 0, "skipped": " ".join(str(err).split())}
    return {"model": model, "parameter": key, "value": value, "speed": out.speed,
            "mu_peak": out.mu_peak, "evaluations": out.evaluations, "skipped": None}
