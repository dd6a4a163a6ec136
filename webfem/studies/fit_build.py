"""Fitting the fitted model from a campaign's rows, measuring it on the hold-out set and
writing the coefficients file.

The outputs fitted per design point are the gap variable log((H_j - H_c)/S + 2)
(:func:`webfem.models.fit_groups.gap_to_fit`: its change is the gap's relative change where
the web flies far above its roughness and the absolute change in units of sigma where it
rests, as webfem measures gap errors, and the fitted gap never falls more than 2 sigma below
the contact gap) at the wrap nodes less that of the physical baseline
(:func:`webfem.models.fit_groups.baseline`), the film pressure P_j, the same variable of
H_min less its baseline's, and the minimum's position. The interpolant (:class:`webfem.models.fit_kernel.Kernel`)
is a Gaussian-process mean with an anisotropic Matern-5/2 kernel on the remainder over the
baseline (no trend: far from the data it returns to the baseline, which measured best); its
length scales and nugget minimise the leave-one-out error (closed form) of a fixed draw of
:data:`HYPER_POINTS` training points. Besides the profile, the centre gap, the smallest gap
(in :func:`webfem.models.fit_groups.gap_to_asinh`, which has no floor, less their
baseline's) and the contact share are fitted on their own (:func:`scalar_targets`), each
with its own length scales: measured better than the profile's values on the hold-out set
(docs/fit.md). The fit is then compressed for speed: each kernel keeps :data:`CENTRES`
of the training points as centres, chosen by pivoted Cholesky (:func:`select_centres`), with
weights fitted to all of them (subset of regressors, :func:`sor_weights`; same length scales
and nugget). :func:`holdout_errors` evaluates the model, as users get it, on the hold-out
rows against their fe2d answers; the stated error per region is the 95th percentile there.

Examples
--------
>>> import numpy as np
>>> x = np.linspace(0, 1, 12)[:, None]
>>> k = fit_kernel(x, np.sin(3 * x), restarts=0)
>>> float(abs(k(np.array([[0.5]]))[0, 0] - np.sin(1.5))) < 1e-2
True
"""

from __future__ import annotations

import numpy as np

from ..models import fit_groups as fg
from ..models.fit_kernel import KINDS, Kernel, blas_one_thread, thin_plate
from ..models.fit_stated import unit_of_groups
from ..models.readout import error_scale

__all__ = ["targets", "scalar_targets", "fit_kernel", "hyperparameters", "select_centres",
           "sor_weights", "holdout_errors", "REGION_EDGES", "DN_EDGES", "QUANTILE", "SCALARS",
           "CENTRES", "KIND", "restate", "local_arrays", "LOCAL_METRIC"]

#: Regions of the predicted H_min / S: resting (< 1.5), landing, flying (> 4).
REGION_EDGES = np.array([1.5, 4.0])
#: Bands of the bending group Dn inside each of those regions (flexible <= 1, 1-100, stiff
#: > 100): the stated error is per (region, band) cell. Measured on the 321 hold-out points
#: of the 1642-point campaign, the 95th percentiles of a flying web's h_min error are 0.39,
#: 0.59 and 5.4 in the three bands: one table per gap region stated 1.02 for all three, a
#: fifth of a stiff web's true error and 2.6 times a flexible one's.
DN_EDGES = np.array([1.0, 100.0])
#: The gap columns' remainders are clipped to +-CLIP before fitting: a few points whose web
#: is pressed far below its contact gap (the floor) or flies far above the baseline would
#: otherwise set the kernel's length scales for all (measured: the 90th percentile of the
#: h_center error 0.85 -> 0.52 on the training set's own 1-in-4 check).
CLIP = 2.0
#: The stated error is this quantile of the region's hold-out errors.
QUANTILE = 95.0
#: The quantities fitted on their own besides the profile (:func:`scalar_targets`), and
#: how they share kernels (indices into SCALARS; each kernel has its own length scales):
#: the two gaps share one, the contact share has its own (chosen by a 4-fold check inside
#: the training rows: sharing measured better for the gaps, worse for the share).
SCALARS = ("h_center", "h_min", "contact_share")
SCALAR_KERNELS = ((0, 1), (2,))
#: The scalar gaps' remainders (:func:`webfem.models.fit_groups.gap_to_asinh`) are clipped
#: to +-SCALAR_CLIP: wide enough for a stiff web resting far below the baseline (e^4 = 55
#: times), narrow enough that the few extreme points do not set the length scales.
SCALAR_CLIP = 4.0
#: The length scales and nugget are chosen on this many training points (a fixed draw):
#: on the 1220 training points of the held-ends campaign the leave-one-out on all of them
#: took 5 minutes and measured no better on the hold-out set (docs/fit.md).
HYPER_POINTS = 450
#: Centres kept by the compressed fit (:func:`select_centres`, weights fitted to every
#: training point: :func:`sor_weights`): the profile's kernel, then each of
#: :data:`SCALAR_KERNELS`'. Chosen on the held-ends campaign's hold-out set (docs/fit.md,
#: "Speed"): 200 / 400 / 300 of its 1220 points kept every hold-out median and 95th
#: percentile within the bootstrap's noise of the full fit, at a quarter of the
#: evaluation's work; 200 for the gaps raised the flying points' 95th percentile in h_min
#: by half, 100-200 for the contact share doubled its median. Kept unchanged for the
#: 1286 points of the spans campaign, where the build report's full fit measured the same
#: within noise. A campaign with fewer training points keeps them all; ``webfem fit
#: build`` reports the full fit's hold-out errors beside.
CENTRES = (200, 400, 300)
#: The kernels' radial function (:data:`webfem.models.fit_kernel.KINDS`; every function
#: below takes ``kind``, default this). The Gaussian and the rational-quadratic (cauchy)
#: evaluate 1.3 times as fast but measured a little worse on the hold-out set (medians
#: 10-25 % higher in the gaps, within the bootstrap's noise; docs/fit.md, "Speed").
KIND = "matern52"


def targets(rows) -> np.ndarray:
    """The fitted outputs of campaign rows (see the module text)."""
    n = len(fg.NODES)
    out = []
    G = np.array([[r[f"g_{g}"] for g in fg.GROUPS] for r in rows], float)
    base, base_min = fg.baseline(G)
    for i, r in enumerate(rows):
        S = r["g_S"]
        H_c = S * np.log(r["g_c"])
        H = np.array([r[f"H{j}"] for j in range(n)])
        P = np.array([r[f"P{j}"] for j in range(n)])
        Hmin = r["h_min"] / r["h_scale"]
        s_min = r["x_min"] / (r["x_scale"] * r["g_beta"])
        out.append(np.concatenate([fg.gap_to_fit(H, S, H_c) - fg.gap_to_fit(base[i], S, H_c),
                                   P, [fg.gap_to_fit(Hmin, S, H_c)
                                       - fg.gap_to_fit(base_min[i], S, H_c), s_min]]))
    return np.array(out)


def scalar_targets(rows) -> np.ndarray:
    """The :data:`SCALARS` of campaign rows as fitted: the centre and smallest gaps in
    :func:`~webfem.models.fit_groups.gap_to_asinh` less their baseline's, the contact share
    (a share of the load, a function of the groups alone) in its arcsine transform
    (:func:`~webfem.models.fit_groups.share_to_fit`)."""
    G = np.array([[r[f"g_{g}"] for g in fg.GROUPS] for r in rows], float)
    base, base_min = fg.baseline(G)
    S = G[:, fg.GROUPS.index("S")]
    H_c = S * np.log(G[:, fg.GROUPS.index("c")])
    hs = np.array([r["h_scale"] for r in rows], float)
    centre = np.array([r["h_center"] for r in rows], float) / hs
    low = np.array([r["h_min"] for r in rows], float) / hs
    return np.column_stack([
        fg.gap_to_asinh(centre, S, H_c) - fg.gap_to_asinh(base[:, len(fg.NODES) // 2], S, H_c),
        fg.gap_to_asinh(low, S, H_c) - fg.gap_to_asinh(base_min, S, H_c),
        fg.share_to_fit([r["contact_share"] for r in rows])])


def _loo(x, y, log_scales, log_nugget, kind=None):
    """Leave-one-out residuals (closed form) of the GP mean with these parameters."""
    K = KINDS[kind or KIND](x, x, np.exp(log_scales)) + np.exp(log_nugget) * np.eye(len(x))
    Ki = np.linalg.inv(K)
    return (Ki @ y) / np.diag(Ki)[:, None]


def hyperparameters(x: np.ndarray, res: np.ndarray, *, weights=None, restarts: int = 2,
                    seed: int = 0, hyper_points: int | None = None,
                    kind: str | None = None) -> tuple[np.ndarray, float]:
    """The length scales and nugget of the kernel minimising the weighted leave-one-out
    error (closed form) of the residuals ``res`` (n, k) at unit-box points ``x``, on
    ``hyper_points`` of them (a fixed draw by ``seed``; each leave-one-out costs an n x n
    inverse) or all."""
    from scipy.optimize import minimize
    w = np.ones(res.shape[1]) if weights is None else np.asarray(weights, float)
    m = x.shape[1]
    sub = np.arange(len(x))
    if hyper_points is not None and hyper_points < len(x):
        sub = np.sort(np.random.default_rng(seed).choice(len(x), hyper_points,
                                                         replace=False))

    def cost(theta):
        try:
            e = _loo(x[sub], res[sub], theta[:m], theta[m], kind)
        except np.linalg.LinAlgError:
            return 1e10
        return float(np.mean(e * e * w))

    rng = np.random.default_rng(seed)
    best = None
    for k in range(restarts + 1):
        start = np.concatenate([np.log(np.full(m, 0.5) if k == 0 else
                                       rng.uniform(0.1, 2.0, m)), [np.log(1e-4)]])
        opt = minimize(cost, start, method="L-BFGS-B",
                       bounds=[(np.log(0.02), np.log(50.0))] * m + [(np.log(1e-8), 0.0)],
                       options={"maxiter": 200})
        if best is None or opt.fun < best.fun:
            best = opt
    return np.exp(best.x[:m]), float(np.exp(best.x[m]))


def select_centres(x: np.ndarray, scales: np.ndarray, m: int,
                   kind: str | None = None) -> np.ndarray:
    """Indices of ``m`` rows of ``x`` chosen as centres by pivoted Cholesky on the kernel
    matrix: each next centre is the point the chosen ones' span predicts worst (largest
    remaining variance), so they spread evenly in the kernel's own metric; deterministic.
    Fewer where the chosen ones already span every point to rounding (repeated points)."""
    n = len(x)
    m = min(m, n)
    K = KINDS[kind or KIND](x, x, scales)
    d = np.diag(K).copy()
    d0 = float(d.max())
    L = np.zeros((m, n))
    chosen = []
    for j in range(m):
        i = int(np.argmax(d))
        if d[i] <= 1e-12 * d0:
            break      # the points left are spanned to rounding: another would divide by ~0
        chosen.append(i)
        L[j] = (K[i] - L[:j, i] @ L[:j]) / np.sqrt(d[i])
        d -= L[j] ** 2
        d[chosen] = -np.inf
    return np.array(chosen)


def sor_weights(x: np.ndarray, res: np.ndarray, scales: np.ndarray, nugget: float,
                idx: np.ndarray, kind: str | None = None) -> np.ndarray:
    """The subset-of-regressors weights at the centres ``x[idx]``, fitted to all points:
    min |K_nm a - res|^2 + nugget a' K_mm a (the GP mean's weights when idx is every
    point), by least squares on the stacked system (K_mm's Cholesky factor)."""
    Knm = KINDS[kind or KIND](x, x[idx], scales)
    Kmm = Knm[idx]
    L = np.linalg.cholesky(Kmm + 1e-10 * np.eye(len(idx)))
    A = np.vstack([Knm, np.sqrt(nugget) * L.T])
    b = np.vstack([res, np.zeros((len(idx), res.shape[1]))])
    return np.linalg.lstsq(A, b, rcond=None)[0]


def _standardised(y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Outputs ``y`` less their mean, over their spread (as :func:`fit_kernel` fits them),
    with that mean and spread."""
    y_mean, y_std = y.mean(0), np.maximum(y.std(0), 1e-12)
    return (y - y_mean) / y_std, y_mean, y_std


def fit_kernel(x: np.ndarray, y: np.ndarray, *, weights=None, restarts: int = 2,
               seed: int = 0, trend: bool = True, hyper_points: int | None = None,
               centres: int | None = None, hyper=None, kind: str | None = None) -> Kernel:
    """The interpolant of outputs ``y`` (n, k) at unit-box points ``x`` (n, m): linear trend
    by least squares, then the kernel's length scales and nugget minimising the weighted
    leave-one-out error of the trend's residuals (:func:`hyperparameters`; ``hyper``:
    given instead, as (scales, nugget)). ``hyper_points``: choose them on that many of the
    points, then solve for the weights on all of them. ``centres``: keep that many
    centres (:func:`select_centres`), their weights fitted to all the points
    (:func:`sor_weights`); None keeps every point (the GP mean). ``kind``: the radial
    function (:data:`KIND` by default)."""
    kind = kind or KIND
    if kind not in KINDS:
        raise ValueError(f"kind = {kind!r} is not a radial function: one of {sorted(KINDS)}")
    ys, y_mean, y_std = _standardised(y)
    A = np.hstack([np.ones((len(x), 1)), x])
    if trend:
        trend, *_ = np.linalg.lstsq(A, ys, rcond=None)
    else:    # the mean alone: far from the data the fit returns to the baseline's
        trend = np.zeros((A.shape[1], ys.shape[1]))
    res = ys - A @ trend
    scales, nugget = hyper if hyper is not None else hyperparameters(
        x, res, weights=weights, restarts=restarts, seed=seed, hyper_points=hyper_points,
        kind=kind)
    if centres is None or centres >= len(x):
        K = KINDS[kind](x, x, scales) + nugget * np.eye(len(x))
        return Kernel(centres=x, scales=scales, trend=trend, weights=np.linalg.solve(K, res),
                      y_mean=y_mean, y_std=y_std, kind=kind)
    idx = select_centres(x, scales, centres, kind)
    return Kernel(centres=x[idx], scales=scales, trend=trend,
                  weights=sor_weights(x, res, scales, nugget, idx, kind), y_mean=y_mean,
                  y_std=y_std, kind=kind)


def fit_thin_plate(x: np.ndarray, y: np.ndarray, scales: np.ndarray,
                   smoothing: float = 0.0) -> Kernel:
    """The thin-plate spline interpolant with a linear polynomial (the augmented system),
    distances scaled by ``scales`` (e.g. the GP's length scales: an anisotropic spline)."""
    y_mean, y_std = y.mean(0), np.maximum(y.std(0), 1e-12)
    ys = (y - y_mean) / y_std
    n, m = x.shape
    A = np.hstack([np.ones((n, 1)), x])
    M = np.zeros((n + m + 1, n + m + 1))
    M[:n, :n] = thin_plate(x, x, scales) + smoothing * np.eye(n)
    M[:n, n:] = A
    M[n:, :n] = A.T
    sol = np.linalg.solve(M, np.vstack([ys, np.zeros((m + 1, ys.shape[1]))]))
    return Kernel(centres=x, scales=np.asarray(scales, float), trend=sol[n:],
                  weights=sol[:n], y_mean=y_mean, y_std=y_std, kind="thin-plate")


#: Groups as unit-box coordinates (the benchmarks call it ``fb.unit``).
unit = unit_of_groups


#: The suffix of :func:`holdout_errors`' keys measured against the smaller of the
#: reference's and the fitted answer's scales.
EITHER = "@either"


def holdout_errors(rows, fit: dict) -> dict[str, np.ndarray]:
    """Per hold-out row, the fitted model's error in each quantity against the row's fe2d
    answer (webfem's error measures, :func:`webfem.models.readout.error_scale` of the fe2d
    answer; the same against the smaller of its and the fitted answer's scales under
    ``q + EITHER``), and the row's predicted region."""
    from ..models.fitted import QUANTITIES, predict, read_profile
    from .fit_campaign import case_of_groups
    G = np.array([[r[f"g_{g}"] for g in fg.GROUPS] for r in rows], float)
    pr = predict(G, fit)
    errs = {q: np.empty(len(rows)) for q in QUANTITIES}
    either = {q: np.empty(len(rows)) for q in QUANTITIES}
    for i, r in enumerate(rows):
        case = case_of_groups(dict(zip(fg.GROUPS, G[i])))
        v = read_profile(case, pr["H"][i], pr["P"][i], pr["H_min"][i], pr["s_min"][i],
                         *(None if pr.get(k) is None else pr[k][i]
                           for k in ("H_center", "share")))
        for q in QUANTITIES:
            # the scale of the fe2d answer: the error is the fit's, against the reference
            scale = error_scale(case, q, r[q])
            errs[q][i] = abs(v[q] - r[q]) / scale
            # and against the smaller of its and the fitted answer's: a user judges the
            # answer on its own value (readout.errors_between), which for mu or h_min
            # below the reference's makes the error larger
            either[q][i] = abs(v[q] - r[q]) / min(scale, error_scale(case, q, v[q]))
    errs["region"] = pr["region"]
    errs.update({f"{q}{EITHER}": a for q, a in either.items()})
    return errs


def region_errors(errs: dict,
                  n_regions: int = (len(REGION_EDGES) + 1) * (len(DN_EDGES) + 1)) -> np.ndarray:
    """The stated error table (region x quantity; a region is a cell of the predicted
    H_min / S's :data:`REGION_EDGES` and Dn's :data:`DN_EDGES`, :func:`webfem.models.fitted.
    region_of`): the :data:`QUANTILE` of the hold-out errors in each region; a region with
    fewer than 5 hold-out points takes the largest of all the quantile's regions' and the
    whole set's."""
    from ..models.fitted import QUANTITIES
    table = np.empty((n_regions, len(QUANTITIES)))
    overall = [np.percentile(errs[q], QUANTILE) for q in QUANTITIES]
    for k in range(n_regions):
        m = errs["region"] == k
        for j, q in enumerate(QUANTITIES):
            table[k, j] = np.percentile(errs[q][m], QUANTILE) if m.sum() >= 5 else np.inf
    for j in range(len(QUANTITIES)):
        col = table[:, j]
        col[~np.isfinite(col)] = max(overall[j], np.max(col[np.isfinite(col)], initial=0.0))
    return table


#: The neighbour search's metric per quantity (h_center, h_min, mu, contact share) for the
#: errors stated per point (:mod:`webfem.models.fit_stated`): a row of
#: :func:`local_arrays`' scales, 0 the gaps' kernel's length scales, 1 the share's (each
#: with 1 for the two predicted coordinates). Chosen on the hold-out set split in two
#: (``benchmarks/fit_stated_check.py holdout``): the share's scales for all four state
#: errors within the split's noise of each quantity's own kernel's (h_min's smaller, mu's
#: and h_center's up to 10 % larger, by their geometric mean) in one search, where two
#: cost 0.04 s more of CPU on 10,000 points.
LOCAL_METRIC = (1, 1, 1, 1)


def local_arrays(G: np.ndarray, errs: dict, fit: dict) -> dict:
    """The ``local_*`` arrays of a coefficients file (:mod:`webfem.models.fit_stated`)
    from hold-out groups ``G`` and their errors ``errs`` (:func:`holdout_errors`) under
    ``fit``: each measured against the smaller of the reference's and the fitted answer's
    scales, so that the statement bounds the error however it is measured (on fresh points
    mu's, against the answer's scale, exceeded the table's statement on 15-27 %)."""
    from ..models import fit_stated as fs
    from ..models.fitted import QUANTITIES, predict
    pr = predict(G, fit)
    coords = fs.coordinates(unit(G, fit["lo"], fit["hi"]),
                            pr["H_min"] / G[:, fg.GROUPS.index("S")], pr["share"])
    scales = np.array([np.r_[k.scales, 1.0, 1.0] for k in fit["scalars"]])
    return fs.calibrate(coords, np.column_stack([errs[q + EITHER] for q in QUANTITIES]),
                        scales, LOCAL_METRIC)


def restate(npz, out_npz=None) -> np.ndarray:
    """The stated-error table of the coefficients file ``npz`` measured again from its own
    hold-out rows through today's evaluation (:func:`webfem.models.fitted.predict`), every
    other array kept, written to ``out_npz`` (default: ``npz`` itself); returns the table.

    For a change of the evaluation's rounding (the float32 products, docs/fit.md, "Speed"):
    :func:`build` would refit the kernels too, and its leave-one-out search is the same bit
    for bit only on the same machine (another CPU's BLAS ends it elsewhere)."""
    from ..models.fitted import QUANTITIES, coefficients
    with np.load(npz, allow_pickle=False) as data:
        arrays = {k: data[k] for k in data.files}
    fit = coefficients.__wrapped__(str(npz))         # the file as it is now, not a cached one
    rows = [{**{f"g_{g}": v for g, v in zip(fg.GROUPS, G)}, **dict(zip(QUANTITIES, V))}
            for G, V in zip(arrays["holdout_groups"], arrays["holdout_values"])]
    errs = holdout_errors(rows, fit)
    table = region_errors(errs, n_regions=len(arrays["region_errors"]))
    arrays["region_errors"] = table
    if len(fit.get("scalars", ())) == 2 and len(rows) > 1:
        # the errors stated per point, measured again with the table
        arrays.update(local_arrays(arrays["holdout_groups"], errs, fit))
    np.savez_compressed(npz if out_npz is None else out_npz, **arrays)
    return table


def build(campaign_csv, out_npz, *, restarts: int = 2, holdout_csv=None,
          extra_csv=None, kind: str | None = None) -> dict:
    """Fit the converged training rows of ``campaign_csv``, state the errors from its
    hold-out rows (or from the converged rows of ``holdout_csv``: the same points solved
    again with the current physics, :func:`webfem.studies.fit_campaign.recheck`), joined by
    the converged rows of ``extra_csv`` (points of another design, all held out:
    :func:`webfem.studies.fit_campaign.extra_holdout`), and write the coefficients to
    ``out_npz``; returns a report (sizes, the hold-out error distribution per quantity, the
    stated table). ``kind``: the kernels' radial function (:data:`KIND` by default; other
    kinds for comparisons)."""
    import datetime
    from pathlib import Path
    from .. import __version__
    from ..case import Case
    from ..errors import InputError
    from ..models.fitted import QUANTITIES, SHARE_VARIABLE
    from ..sweeps.table import read_table, typed
    # in design order: the fit (the draw of HYPER_POINTS, the kernels' centres) must not
    # depend on the order rows finished in, which an interrupted parallel run leaves
    rows = sorted((r for r in typed(read_table(campaign_csv).rows) if r["converged"]),
                  key=lambda r: r["n"])
    train = [r for r in rows if not r["holdout"]]
    hold = [r for r in rows if r["holdout"]]
    rechecked = holdout_csv is not None
    if rechecked:
        hold = sorted((r for r in typed(read_table(holdout_csv).rows) if r["converged"]),
                      key=lambda r: r["n"])
    extra_rows = [] if extra_csv is None else sorted(
        (r for r in typed(read_table(extra_csv).rows) if r["converged"]), key=lambda r: r["n"])
    own_hold = len(hold)
    hold = hold + extra_rows
    if len(train) < 4 or len(hold) < 1:
        raise InputError(f"{campaign_csv}: {len(train)} converged training and {len(hold)} "
                         "hold-out rows; the fit needs at least 4 and 1")
    lo, hi = fg.box()
    lo = lo.copy()
    lo[fg.GROUPS.index("Kb")] -= 0.3       # the design's share at Kb = 0 (fit_campaign)
    G = np.array([[r[f"g_{g}"] for g in fg.GROUPS] for r in train], float)
    y = targets(train)
    gaps = np.r_[np.arange(len(fg.NODES)), 2 * len(fg.NODES)]
    y[:, gaps] = np.clip(y[:, gaps], -CLIP, CLIP)
    x = unit(G, lo, hi)
    ys = scalar_targets(train)
    ys[:, :2] = np.clip(ys[:, :2], -SCALAR_CLIP, SCALAR_CLIP)
    # on one BLAS thread: the optimiser's path, hence the coefficients, then do not depend
    # on the machine's thread count (the rebuild is bit for bit), and on a loaded machine
    # one thread is the faster
    outputs = [y] + [ys[:, list(cols)] for cols in SCALAR_KERNELS]
    with blas_one_thread():
        hyper = [hyperparameters(x, _standardised(t)[0], restarts=restarts,
                                 hyper_points=HYPER_POINTS, kind=kind) for t in outputs]
        kernel, *scalars = (fit_kernel(x, t, trend=False, hyper=h, centres=m, kind=kind)
                            for t, h, m in zip(outputs, hyper, CENTRES))
        # the full fit (every training point a centre) on the same length scales: the
        # report states what the compression costs on this campaign's hold-out set
        full, *full_scalars = (fit_kernel(x, t, trend=False, hyper=h, kind=kind)
                               for t, h in zip(outputs, hyper))
    span = Case().span_used
    ends = f"wrap.ends = span, {span:g} m" if span else "wrap.ends = held"
    if rechecked:
        # the training rows may come from an earlier physics: the errors are today's
        info = (f"trained on {len(train)} fe2d solutions of an earlier campaign; errors "
                f"stated from {own_hold} hold-out points solved again with webfem "
                f"{__version__}'s default physics ({ends}, smooth roller)")
    else:
        info = (f"trained on {len(train)} fe2d solutions (webfem {__version__}, default full "
                f"physics: {ends}; smooth roller), {own_hold} held out")
    if extra_rows:
        info += (f"; the errors stated from these and {len(extra_rows)} points of another "
                 "design, all held out")
    kept = " / ".join(str(len(k.centres)) for k in (kernel, *scalars))
    info += f"; kernels of {kept} centres; {datetime.date.today().isoformat()}"
    fit = {"kernel": kernel, "lo": lo, "hi": hi, "edges": REGION_EDGES, "dn_edges": DN_EDGES,
           "scalars": scalars, "share_variable": SHARE_VARIABLE,
           "scalar_names": tuple(SCALARS[c] for cols in SCALAR_KERNELS for c in cols)}
    errs = holdout_errors(hold, fit)
    table = region_errors(errs)
    G_hold = np.array([[r[f"g_{g}"] for g in fg.GROUPS] for r in hold], float)
    # per point from its nearest hold-out points; a campaign with one hold-out point has
    # no neighbours to state from: its table alone
    local = local_arrays(G_hold, errs, fit) if len(hold) > 1 else {}
    errs_full = holdout_errors(hold, {**fit, "kernel": full, "scalars": full_scalars})
    Path(out_npz).parent.mkdir(parents=True, exist_ok=True)
    extra = {}
    for j, k in enumerate(scalars):
        extra.update(k.arrays(f"s{j}"))
    np.savez_compressed(out_npz, **kernel.arrays("k"), **extra,
                        scalar_names=np.array(fit["scalar_names"]), lo=lo, hi=hi,
                        region_edges=REGION_EDGES, dn_edges=DN_EDGES, region_errors=table,
                        share_variable=np.array(SHARE_VARIABLE),
                        physics=np.array(f"webfem {__version__}"), info=np.array(info),
                        holdout_groups=G_hold, **local,
                        holdout_values=np.array([[r[q] for q in QUANTITIES] for r in hold]),
                        holdout_seconds=np.array([r["seconds"] for r in hold]))
    def pct(e):
        return {q: np.percentile(e[q], [50, 90, 95, 100]).tolist() for q in QUANTITIES}
    return {"train": len(train), "holdout": len(hold), "failed": sum(
        1 for r in typed(read_table(campaign_csv).rows) if not r["converged"]),
        "holdout_rechecked": rechecked, "holdout_extra": len(extra_rows),
        "percentiles_50_90_95_max": pct(errs), "stated": table.tolist(),
        "centres": [len(k.centres) for k in (kernel, *scalars)],
        "full_fit_percentiles_50_90_95_max": pct(errs_full),
        "regions": np.bincount(errs["region"], minlength=len(table)).tolist(), "info": info}
