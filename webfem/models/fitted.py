"""Fitted model: a fit of webfem's own fe2d solutions in the dimensionless groups.

The fit (:mod:`webfem.models.fit_kernel`, coefficients in ``fitted_coefficients.npz``, made
by ``webfem fit build``) gives, from the eight groups of a smooth-roller case
(:mod:`webfem.models.fit_groups`), the scaled gap H and film pressure P at fixed positions
along the wrap and the smallest gap and where; the centre and smallest gaps and the contact
share are also fitted on their own, which the summary reports (measured more accurate than
the profile's; the share in arcsin(sqrt(share)),
:func:`webfem.models.fit_groups.share_to_fit`). The friction, the regimes, mu and delta_T
are computed from the profile with the physics functions the FE models use
(:func:`webfem.physics.friction.friction_for`, the contact law), so the friction constants
and the speeds add no dimensions to the fit.

Its domain is the box of groups the campaign sampled and the default full physics on a
smooth roller; outside it the model refuses (:class:`OutsideDomain`, naming the group, its
value and its range), and auto moves on. Its stated errors (``error_h_center``, ...) are the
95th percentile of the errors on a hold-out set never used in fitting, per region: the
predicted smallest gap over the roughness (flying, landing, resting) and the bending group
Dn (flexible < 1, 1-100, stiff > 100; :func:`region_of`).

Examples
--------
>>> from webfem import Case
>>> r = solve(Case())
>>> r["model"], r.summary.error_mu is not None
('fitted', True)
"""

from __future__ import annotations

import os
import time
from concurrent.futures import ThreadPoolExecutor
from functools import lru_cache
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from ..case import Case
from ..cores import usable_cores
from ..errors import NoAdmissibleSolution
from ..physics.contact import (REGIMES, contact_gap, contact_pressure, tail_gaussian_gaps,
                               tail_warning)
from ..physics.effects import MU_SCALE, included, traction_summaries
from ..physics.friction import friction_for
from ..physics.validity import answer_warnings
from ..result import Diagnostics, Fields, Result, refused
from ..summary import Summary
from . import fit_groups as fg
from . import fit_stated
from .fit_file import read_fit
from .fit_kernel import ONE_THREAD_FROM, STACKED, Kernel, Stack, blas_one_thread
from .options import FittedOptions

__all__ = ["solve", "solve_case", "solve_many", "predict", "read_profile", "read_profiles",
           "threads", "BLOCK",
           "OutsideDomain",
           "NAME", "region_of", "region_name",
           "COEFFICIENTS", "coefficients", "evaluator"]

NAME = "fitted"
COEFFICIENTS = Path(__file__).with_name("fitted_coefficients.npz")
QUANTITIES = ("h_center", "h_min", "mu", "contact_share")
#: The name a coefficients file gives the contact share's fitted variable
#: (:func:`webfem.models.fit_groups.share_to_fit`); a file without it fitted the share itself.
SHARE_VARIABLE = "arcsin-sqrt"


class OutsideDomain(NoAdmissibleSolution):
    """The case is outside the fitted model's domain (the message names the group)."""


@lru_cache(maxsize=4)
def coefficients(path: str | None = None) -> dict:
    """The shipped fit (or the one at ``path``): the kernel, the box, the stated-error
    table and what it was trained on.

    Raises
    ------
    webfem.errors.InputError
        ``path`` holds no fit (:func:`webfem.models.fit_file.read_fit` says what is
        wrong); :class:`~webfem.models.options.FittedOptions` reads it when the option is
        set, so every command refuses it before solving.
    """
    p = Path(path) if path else COEFFICIENTS
    if not p.is_file() and not path:
        raise NoAdmissibleSolution(f"the fitted model's coefficients {p} are missing: build "
                                   "them with `webfem fit build`")
    fit = read_fit(str(p))
    d, kernel, scalars = fit["arrays"], fit["kernel"], fit["scalars"]
    return {"kernel": kernel, "stack": evaluator(kernel, scalars), "lo": d["lo"],
            "hi": d["hi"], "edges": d["region_edges"], "errors": d["region_errors"],
            # a file from before the Dn bands states one error per gap region
            "dn_edges": d.get("dn_edges", np.empty(0)),
            # the share's variable (fit_groups.share_to_fit) where the file names it, else
            # the share itself, clipped (the files before it)
            "share_variable": str(d.get("share_variable", "share")),
            # the errors stated per point from the nearest hold-out points (fit_stated);
            # a file without them states its table's, per region
            "local": ({k: d[k] for k in fit_stated.KEYS}
                      if all(k in d for k in fit_stated.KEYS) else None),
            "physics": str(d["physics"]), "info": str(d["info"]), "scalars": scalars,
            "scalar_names": fit["scalar_names"],
            "holdout_points": len(d["holdout_values"]) if "holdout_values" in d else None}


#: The fewest hold-out points a fit states its errors from: with fewer, a percentile or a
#: neighbours' mean is one or two errors' luck (a 6-point campaign, 1 held out, stated h_min
#: 0.46 where its error was 2.5), so its answers state none (NaN) and auto never takes them.
MIN_HOLDOUT = 20


def unstated(fit: dict) -> str | None:
    """Why ``fit`` (:func:`coefficients`) states no errors, or None: fewer than
    :data:`MIN_HOLDOUT` hold-out points."""
    n = fit.get("holdout_points")
    if n is None or n >= MIN_HOLDOUT:
        return None
    return (f"the fit states no errors: its errors come from {n} hold-out point"
            f"{'' if n == 1 else 's'}, fewer than the {MIN_HOLDOUT} converged ones a statement "
            f"needs: `webfem fit build` holds out every fifth design point, so about "
            f"{5 * (MIN_HOLDOUT - n)} more converged --points")


#: The type the kernels' distances' product, radial function and weight products are
#: evaluated in (:class:`Stack`; the coordinates from the unit box's middle): the hold-out
#: answers move by up to 7.8e-5, 6.4e-5, 6.0e-6 and 3.6e-6 of webfem's error measures
#: (h_center, h_min, mu, contact share) against float64 throughout, 100,000 random points
#: of the box by up to 2.3e-4 (at most 1.5e-4 of their stated errors; the fitted
#: variables: the gaps' 3.9e-5, the pressures' 1.0e-3), under a thousandth of the stated
#: errors, mostly through the gaps' kernel, whose weights cancel (sum |w phi| is 680 times
#: |y| at the median); the stated errors are measured through it (docs/fit.md, "Speed").
RADIAL = np.float32


def evaluator(kernel, scalars=()) -> Stack | None:
    """The profile's kernel and the scalars' evaluated in one pass (:class:`Stack`, radial
    function in :data:`RADIAL`), or None where they are not :class:`Kernel` s of one
    kind the stack evaluates (comparisons of other methods)."""
    kernels = [kernel, *scalars]
    if all(isinstance(k, Kernel) for k in kernels) and len({k.kind for k in kernels}) == 1 \
            and kernel.kind in STACKED:
        return Stack(kernels, radial=RADIAL)
    return None


#: Points per block of :func:`predict`'s work: the block's arrays stay in cache, and the
#: blocks are shared among :func:`threads` threads (numpy's passes and BLAS release the GIL).
BLOCK = 2048


def threads() -> int:
    """How many threads :func:`predict` shares its blocks among: the cores this process
    may run on (at most 8)."""
    return min(usable_cores(), 8)


_POOLS: dict[tuple[int, int], ThreadPoolExecutor] = {}


def _pool(n: int) -> ThreadPoolExecutor:
    """A pool of ``n`` threads for this process (a forked child, e.g. a campaign's worker,
    makes its own: the parent's threads are not in it)."""
    key = (os.getpid(), n)
    if key not in _POOLS:
        _POOLS[key] = ThreadPoolExecutor(n, thread_name_prefix="webfem-fitted")
    return _POOLS[key]


def _stack_of(fit: dict) -> Stack | None:
    """The fit's one-pass stack, or a new one where its kernels are not the stack's."""
    kernels = (fit["kernel"], *fit.get("scalars", ()))
    stack = fit.get("stack")
    if stack is None or len(stack.kernels) != len(kernels) or \
            any(a is not b for a, b in zip(stack.kernels, kernels)):
        # a fit whose kernels were swapped (a build's candidate) must not reuse the stack
        stack = evaluator(fit["kernel"], fit.get("scalars", ()))
    return stack


def predict(G: np.ndarray, fit: dict | None = None, *,
            n_threads: int | None = None) -> dict[str, np.ndarray]:
    """The scaled profile of groups ``G`` ((n, 8)): ``H`` and ``P`` (n, nodes), ``H_min``,
    ``s_min`` (position over the wrap, -1/2 entry) and ``region`` (index into the stated
    errors); and, where the fit has them (else None), the centre gap ``H_center`` and the
    contact ``share`` fitted on their own, ``H_min`` then also from its own fit (capped by
    the profile's smallest node). No domain check (:func:`fit_groups.outside_rows`).

    More than :data:`BLOCK` points are evaluated in blocks on ``n_threads`` threads
    (default :func:`threads`); each point's answer is computed alone (row by row), so it
    does not depend on the batch or the thread count (to rounding: tests/test_fitted.py)."""
    if n_threads is not None and (isinstance(n_threads, bool) or not isinstance(n_threads, int)
                                  or n_threads < 1):
        raise ValueError(f"n_threads = {n_threads!r} is out of range: an integer >= 1, or "
                         "None for one per core")
    fit = fit or coefficients()
    G = np.atleast_2d(np.asarray(G, float))
    stack = _stack_of(fit)
    n = len(G)
    if n <= BLOCK:
        if n < ONE_THREAD_FROM:
            return _predict(G, fit, stack)
        with blas_one_thread():
            return _predict(G, fit, stack)
    starts = range(0, n, BLOCK)
    n_threads = min(n_threads or threads(), len(starts))
    # every block writes its rows of the answer in place: concatenating the blocks' own
    # arrays afterwards cost 0.19 us a point (a second pass, and the new pages' faults)
    out = _answer(n, fit)
    # every block's BLAS on one thread: the blocks are the parallel work
    with blas_one_thread():
        if n_threads == 1:
            for i in starts:
                _predict(G[i:i + BLOCK], fit, stack, _rows(out, i))
        else:
            list(_pool(n_threads).map(
                lambda i: _predict(G[i:i + BLOCK], fit, stack, _rows(out, i)), starts))
    return out


def _answer(n: int, fit: dict) -> dict[str, np.ndarray | None]:
    """Empty arrays for :func:`predict`'s answer at ``n`` points (None where the fit has
    no such quantity)."""
    nodes, own = len(fg.NODES), bool(fit.get("scalar_names"))
    return {"H": np.empty((n, nodes)), "P": np.empty((n, nodes)), "H_min": np.empty(n),
            "s_min": np.empty(n), "region": np.empty(n, np.intp),
            "H_center": np.empty(n) if own else None, "share": np.empty(n) if own else None}


def _rows(out: dict, i: int) -> dict:
    """The block of :data:`BLOCK` rows from ``i`` of an answer, as views to fill."""
    return {k: None if a is None else a[i:i + BLOCK] for k, a in out.items()}


def _predict(G: np.ndarray, fit: dict, stack: Stack | None,
             out: dict | None = None) -> dict[str, np.ndarray]:
    """:func:`predict` of one block of points, BLAS threads left to the caller; into
    ``out`` (views of the whole answer's rows, :func:`_rows`) where given."""
    out = _answer(len(G), fit) if out is None else out
    x = (fg.coordinates(G) - fit["lo"]) / (fit["hi"] - fit["lo"])
    n = len(fg.NODES)
    if stack is not None:    # the profile, then every scalar, side by side
        Y = stack.evaluate(x)
        scalars = ()
    else:
        Y, scalars = fit["kernel"](x), fit.get("scalars", ())
    S = G[:, fg.GROUPS.index("S")]
    H_c = S * np.log(G[:, fg.GROUPS.index("c")])
    # the fit is the remainder over the physical baseline in the fit's gap variable,
    # log((H - H_c) / S + FLOOR) (fit_groups.gap_to_fit; the baseline is never below H_c):
    # so the gap is H_c + S ((baseline's E + FLOOR) e^Y - FLOOR) = F e^Y + K, one exp, no
    # log, F and K the baseline's (fit_groups.baseline_factors)
    F, K, E_center, E_min = fg.baseline_factors(G)
    H = np.exp(Y[:, :n], out=out["H"])
    H *= F
    H += K[:, None]
    H_low = H.min(axis=1)
    out["P"][...] = Y[:, n:2 * n]
    if fit.get("scalar_names"):
        # the quantities fitted on their own, the gaps in a variable without a floor
        # (fit_groups.gap_to_asinh): measured better than the profile's values on the
        # hold-out set (docs/fit.md). They follow the profile's 2n + 2 columns where the
        # kernels run side by side (a Stack), else come from kernels of their own
        Ys = np.column_stack([Y[:, 2 * n + 2:]] + [k(x) for k in scalars])
        own = dict(zip(fit["scalar_names"], Ys.T))
        out["H_center"][...] = fg.asinh_to_gap(own["h_center"] + np.arcsinh(E_center), S, H_c)
        # capped by the profile's smallest node, as the profile's own minimum is
        np.minimum(fg.asinh_to_gap(own["h_min"] + np.arcsinh(E_min), S, H_c), H_low,
                   out=out["H_min"])
        if fit.get("share_variable") == SHARE_VARIABLE:
            fg.fit_to_share(own["contact_share"], out=out["share"])
        else:      # a file from before the transform: the share itself
            np.clip(own["contact_share"], 0.0, 1.0, out=out["share"])
    else:
        np.minimum(H_c + S * ((E_min + fg.FLOOR_SIGMAS) * np.exp(Y[:, 2 * n])
                              - fg.FLOOR_SIGMAS), H_low, out=out["H_min"])
    out["region"][...] = region_of(fit, out["H_min"] / S, G[:, fg.GROUPS.index("Dn")])
    np.clip(Y[:, 2 * n + 1], -0.5, 0.5, out=out["s_min"])
    return out


def region_of(fit: dict, ratio, Dn) -> np.ndarray:
    """The row of the stated-error table for a predicted smallest gap over sigma ``ratio``
    and a bending group ``Dn``: the gap region (``fit["edges"]``) times the number of Dn
    bands, plus the band (``fit["dn_edges"]``; none in a file from before them).

    >>> fit = {"edges": np.array([1.5, 4.0]), "dn_edges": np.array([1.0, 100.0])}
    >>> region_of(fit, np.array([0.5, 10.0, 10.0]), np.array([0.1, 0.1, 500.0])).tolist()
    [0, 6, 8]
    """
    dn_edges = fit.get("dn_edges", np.empty(0))
    return (np.searchsorted(fit["edges"], ratio) * (len(dn_edges) + 1)
            + np.searchsorted(dn_edges, Dn))


_REGION = ("resting (predicted h_min <= 1.5 sigma)", "landing (h_min 1.5-4 sigma)",
           "flying (h_min > 4 sigma)")


def region_name(fit: dict, region: int) -> str:
    """Words for row ``region`` of the stated-error table (:func:`region_of`).

    >>> fit = {"edges": np.array([1.5, 4.0]), "dn_edges": np.array([1.0, 100.0])}
    >>> region_name(fit, 8)
    'flying (h_min > 4 sigma), stiff web (bending group Dn > 100)'
    """
    dn_edges = fit.get("dn_edges", np.empty(0))
    gap, band = divmod(int(region), len(dn_edges) + 1)
    name = _REGION[gap] if len(fit["edges"]) == 2 else f"gap region {gap}"
    if len(dn_edges) == 2:
        name += (", flexible web (bending group Dn <= {0:g})",
                 ", bending group Dn {0:g}-{1:g}",
                 ", stiff web (bending group Dn > {1:g})")[band].format(*dn_edges)
    elif len(dn_edges):
        name += f", Dn band {band}"
    return name


def _stacked(v: dict[str, np.ndarray]) -> SimpleNamespace:
    """Cases as (n, 1) columns under the names a :class:`Case` gives them, for the physics
    functions (which broadcast): the fit's physics switches (:data:`fit_groups.FIT_PHYSICS`,
    the only ones it answers for) on a smooth roller."""
    c = {k: a[:, None] for k, a in v.items()}
    ns, phys = SimpleNamespace, fg.FIT_PHYSICS
    return ns(friction_variant=phys["friction.variant"], slip_model=phys["air.slip"],
              roughness_flow_model=phys["air.roughness_flow"],
              air=ns(ambient_pressure=c["p_a"], mean_free_path=c["mfp"], viscosity=c["eta"]),
              friction=ns(distribution=phys["friction.distribution"], mu_cc=c["mu_cc"],
                          speed_constant=c["C"]),
              web=ns(modulus_thickness=c["E_b"], thickness=c["t"]),
              roller=ns(groove_depth=0.0), land_fraction=1.0,
              sigma=c["sigma"], p_bar=c["p_bar"], U_slide=c["U_slide"])


def read_profiles(v: dict[str, np.ndarray], H, P, H_min, s_min, H_center=None,
                  share=None) -> dict[str, np.ndarray]:
    """Gaps, friction, regimes and contact share of many cases (their
    :func:`fit_groups.case_columns` ``v``) from their scaled profiles (rows of ``H``, ``P``),
    with the FE models' physics functions evaluated on arrays (readout.py does the same on
    the FE solution): one value per case (``regime`` as the index into REGIMES), and the gap
    ``h``, the local friction ``loc``, the absolute pressure ``p`` and its gradient ``dpdx``
    along the wrap, a row per case. ``H_center`` (scaled) and ``share``: the centre gap and
    the contact share where they were fitted on their own (:func:`predict`), instead of the
    profile's."""
    case = _stacked(v)
    hs, xs, pb, beta = (v[k][:, None] for k in ("h_scale", "x_scale", "p_bar", "beta"))
    p_a = case.air.ambient_pressure
    h = H * hs
    # a fitted suction may overshoot below vacuum, where the slip length has no meaning
    p = np.maximum(p_a + P * pb, 0.1 * p_a)
    dpdx = np.gradient(P, fg.NODES, axis=1) / beta * pb / xs
    loc = friction_for(case, h, resting=True, p=p, dpdx=dpdx)
    W = fg.WEIGHTS
    Pc = contact_pressure(h, case.web.modulus_thickness, case.sigma, case.web.thickness,
                          case.friction.distribution) / pb
    # a share of the load: a fitted suction may make the film's part nearly cancel contact's
    if share is None:
        share = np.clip(np.sum(W * Pc, axis=1) / np.maximum(np.sum(W * (P + Pc), axis=1),
                                                            1e-300), 0.0, 1.0)
    shares = np.stack([np.sum(W * (loc["regime"] == k), axis=1) for k in range(3)], axis=1)
    c = len(fg.NODES) // 2
    h_min = H_min * hs[:, 0]
    h_center = h[:, c] if H_center is None else H_center * hs[:, 0]
    return {"h_center": h_center, "h_inlet": h[:, 0], "h_outlet": h[:, -1], "h_min": h_min,
            "x_min": s_min * beta[:, 0] * xs[:, 0], "mu": np.sum(W * loc["mu"], axis=1),
            "contact_share": share, "share_boundary": shares[:, 0],
            "share_mixed": shares[:, 1], "share_fluid": shares[:, 2],
            "regime": np.argmax(shares, axis=1), "h": h, "loc": loc, "p": p, "dpdx": dpdx,
            "compression": np.maximum(0.0, -np.minimum(h.min(axis=1), h_min))}


def read_profile(case: Case, H, P, H_min, s_min, H_center=None, share=None) -> dict:
    """:func:`read_profiles` of one case: its numbers, its regime's name, and ``h`` and
    ``loc`` along the wrap."""
    out = read_profiles(fg.case_columns([case]), np.atleast_2d(H), np.atleast_2d(P),
                        np.atleast_1d(H_min), np.atleast_1d(s_min),
                        *(None if a is None else np.atleast_1d(a) for a in (H_center, share)))
    one = {k: a[0] for k, a in out.items() if k != "loc"}
    one.update(regime=REGIMES[int(one["regime"])], loc={k: a[0] for k, a in out["loc"].items()})
    return one


#: How the fitted model answers (the results' ``diagnostics.method``).
METHOD = ("fit of fe2d solutions (Matern-5/2 kernels, subset-of-regressors GP mean) + "
          "Eqs. 10-13, 28-31 on its profile")


def stated_errors(G: np.ndarray, pr: dict, fit: dict) -> np.ndarray:
    """The stated errors (n, 4; :data:`QUANTITIES`) at groups ``G`` with predictions ``pr``
    (:func:`predict`): from the nearest hold-out points where the fit has them
    (:mod:`webfem.models.fit_stated`), else the table's row of each point's region."""
    if unstated(fit):
        return np.full((len(G), len(QUANTITIES)), np.nan)
    local = fit.get("local")
    if local is None:
        return fit["errors"][pr["region"]]
    x = fit_stated.unit_of_groups(G, fit["lo"], fit["hi"])
    coords = fit_stated.coordinates(x, pr["H_min"] / G[:, fg.GROUPS.index("S")],
                                    pr["share"])
    return fit_stated.stated(coords, local)


def _results(cases: list[Case], v: dict[str, np.ndarray], pr: dict, fit: dict,
             options: FittedOptions, G: np.ndarray) -> list[Result]:
    """The results of ``cases`` (their columns ``v``, groups ``G`` and predicted profiles
    ``pr``): everything evaluated on arrays, then one summary and one set of fields (rows
    of the arrays) per case; ``solve_time_s`` is left 0 for the caller."""
    r = read_profiles(v, pr["H"], pr["P"], pr["H_min"], pr["s_min"], pr.get("H_center"),
                      pr.get("share"))
    traction = traction_summaries(cases, r["mu"], r["contact_share"])
    errors = stated_errors(G, pr, fit)
    lam, beta = v["lam"], v["beta"]
    per_case = {k: r[k] for k in ("h_center", "h_inlet", "h_outlet", "h_min", "x_min",
                                  "contact_share", "share_boundary", "share_mixed",
                                  "share_fluid", "compression")}
    per_case.update(
        sigma=v["sigma"], U=v["U"], U_slide=v["U_slide"], T_eff=v["T_eff"],
        bending_stiffness_used=v["D"], eps=v["eps"], kappa=v["kappa"], beta=beta,
        lambda_=lam, eq21_valid=(beta > 6) & (lam > 7), resting=r["compression"] > 0.0,
        h_c=contact_gap(v["p_bar"], v["E_b"], v["sigma"], v["t"],
                        fg.FIT_PHYSICS["friction.distribution"]),
        **{f"error_{q}": errors[:, j] for j, q in enumerate(QUANTITIES)})
    # where nothing slides mu is mu_cc x the contact share: its stated error is the share's
    # carried through, not the cell's mu error (measured on the campaign's sliding cases)
    idle = v["U_slide"] == 0.0
    if np.any(idle):
        carried = onset_error(v["mu_cc"] * r["contact_share"], v["mu_cc"],
                              per_case["error_contact_share"])
        per_case["error_mu"] = np.where(idle, carried, per_case["error_mu"])
    names = list(per_case)
    columns = [np.asarray(per_case[k]).tolist() for k in names]
    regimes = [REGIMES[k] for k in r["regime"].tolist()]
    basis = [_basis(fit, k) for k in range(len(fit["errors"]))]
    fixed = dict(model=NAME, converged=True, iterations=0, n_dofs=0, residual=0.0,
                 solve_time_s=0.0, method="fit", land_fraction=1.0)
    # the effects included: with the fit's physics switches fixed, they vary only with
    # whether the web moves, bends and breathes, so ask once per combination
    kinds = list(zip((v["inertia"] > 0).tolist(), (v["D"] > 0).tolist(),
                     (v["k"] > 0).tolist()))
    first = {}
    for i, kind in enumerate(kinds):
        first.setdefault(kind, i)
    effects = {kind: included(cases[i]) for kind, i in first.items()}
    x = fg.NODES[None, :] * beta[:, None] * v["x_scale"][:, None]
    h, loc = r["h"], r["loc"]
    # the tail warnings' Gaussian h_c in one vectorised solve, not one per case
    gaussian = tail_gaussian_gaps(cases, per_case["h_c"], per_case["contact_share"])
    none_stated = unstated(fit)
    out = []
    for i, (case, row, tr, regime, region, kind) in enumerate(zip(
            cases, zip(*columns), traction, regimes, pr["region"].tolist(), kinds)):
        values = dict(zip(names, row))
        tail = tail_warning(case, values.get("h_c"), values.get("contact_share"),
                            gaussian[i])
        summary = Summary(**values, **tr, **fixed, regime=regime, effects=effects[kind],
                          warnings=tuple(answer_warnings(case, values["h_min"], tail))
                          + ((none_stated,) if none_stated else ()),
                          error_basis=basis[region] + (ONSET_BASIS if idle[i] else ""))
        fields = Fields(x=x[i], h=h[i], chi_c=loc["chi_c"][i], mu_c=loc["mu_c"][i],
                        mu_f=loc["mu_f"][i], mu=loc["mu"][i], regime=loc["regime"][i])
        # the wrap quadrature, as the FE models give it: calibration re-evaluates the
        # friction there with other constants (webfem.calibrate)
        diagnostics = Diagnostics(method=METHOD, options=options, wrap_h=h[i],
                                  wrap_w=fg.WEIGHTS, wrap_p=r["p"][i],
                                  wrap_dpdx=r["dpdx"][i])
        out.append(Result(case, summary, fields, diagnostics))
    return out


#: What :data:`Summary.error_basis` adds where nothing slides (:func:`onset_error`).
ONSET_BASIS = ("; mu where nothing slides (U_s = 0: mu = mu_cc x contact share, the "
               "traction at the onset of slip): the contact share's stated error carried "
               "through, not the region's mu error, which the campaign measured on sliding "
               "webs")


def onset_error(mu, mu_cc, share_error):
    """The stated error of mu where nothing slides, from the contact share's.

    There mu = mu_cc x contact share (:func:`webfem.physics.effects.traction_summary`), so
    a share off by at most ``share_error`` (absolute) puts mu off by at most A = mu_cc x
    ``share_error``. mu's error is measured against the larger of the true |mu| and
    :data:`webfem.models.readout.MU_SCALE` mu_cc (:func:`webfem.models.readout.
    error_scale`), and the true |mu| is at least |mu| - A: the bound is A / max(|mu| - A,
    MU_SCALE mu_cc). Why: the hold-out's mu errors were measured on the campaign's
    cases, whose web stands while the roller turns (everything slides); on idlers, where
    mu is the contact share's alone, they understated it up to 12 times (the bundled idler at
    12.4 m/s: mu 0.078 against fe2d's 0.0063, true error 2.4, stated 0.2; this bound 2.7).

    >>> round(float(onset_error(0.0784, 0.3, 0.27)), 2)
    2.7
    >>> round(float(onset_error(0.3, 0.3, 0.1)), 2)      # mostly contact: a smaller bound
    0.11
    """
    A = np.asarray(mu_cc, float) * np.asarray(share_error, float)
    return A / np.maximum(np.abs(np.asarray(mu, float)) - A, MU_SCALE * np.asarray(mu_cc, float))


def _checked_columns(cases: list[Case], many: bool) -> tuple[dict, np.ndarray, dict]:
    """The columns and groups of ``cases`` and why each case outside the domain has no
    answer (``{index: message}``: its physics switches, or the first group outside and its
    range). A single case (``many`` False) outside raises :class:`OutsideDomain`."""
    refusals = {i: why for i, c in enumerate(cases) if (why := fg.physics_refusal(c))}
    v = fg.case_columns(cases)
    G = fg.groups_of_columns(v)
    bad = fg.outside_rows(G)
    for i in np.flatnonzero(bad >= 0):
        refusals.setdefault(int(i), fg.outside_text(int(bad[i]), G[i, bad[i]]))
    refusals = {i: f"no fitted answer: {why}" for i, why in sorted(refusals.items())}
    if refusals and not many:
        raise OutsideDomain(next(iter(refusals.values())))
    return v, G, refusals


def _timed(results: list[Result], seconds: float) -> list[Result]:
    """``results`` with their ``solve_time_s`` set (their summaries are new, not yet seen
    by anyone: set in place rather than copied, which would cost as much as making them)."""
    for r in results:
        object.__setattr__(r.summary, "solve_time_s", seconds)
    return results


def solve_case(case: Case, options: FittedOptions, *, initial: Result | None = None,
               raise_on_failure: bool = True) -> Result:
    """The fitted answer for one case, with its gap and friction along the wrap as fields
    (:func:`solve_many` of one case). Outside the domain it raises :class:`OutsideDomain`
    (``raise_on_failure`` is accepted for the registry's common signature; a refusal is
    never returned as an answer)."""
    t0 = time.perf_counter()
    v, G, _ = _checked_columns([case], many=False)
    fit = coefficients(options.coefficients)
    res = _results([case], v, predict(G, fit), fit, options, G)
    return _timed(res, time.perf_counter() - t0)[0]


def _basis(fit: dict, region: int) -> str:
    if none := unstated(fit):
        return f"fit: {none}; {fit['info']}"
    local = fit.get("local")
    if local is None:
        return (f"fit: 95th percentile of the hold-out errors against fe2d in its region, "
                f"{region_name(fit, region)}; {fit['info']}")
    return (f"fit: the mean error against fe2d of the {int(local['local_k'])} hold-out "
            "points nearest it (in the groups and its predicted smallest gap and contact "
            "share), scaled to the hold-out's 95th percentile (docs/fit.md, \"Stated errors "
            f"per point\"); its region {region_name(fit, region)}; {fit['info']}")


def solve(case: Case, options: FittedOptions | None = None, **values) -> Result:
    """:func:`solve_case` with the options as keywords."""
    options = options.replace(**values) if options is not None else \
        FittedOptions.from_mapping(values)
    return solve_case(case, options)


def solve_many(cases, options: FittedOptions | None = None) -> list[Result]:
    """Many cases in one vectorised evaluation: the fit, the friction read-out and the
    traction on arrays, then one result per case, each the same as :func:`solve_case`'s
    (``solve_time_s``: the batch's time per case). A case outside the domain is kept in
    its place, not answered (:func:`webfem.result.refused`: ``converged`` False, why in
    ``solver_message`` and ``warnings``), as every model's many-point call keeps it."""
    cases = list(cases)
    if not cases:
        return []
    options = options or FittedOptions()
    t0 = time.perf_counter()
    v, G, refusals = _checked_columns(cases, many=True)
    fit = coefficients(options.coefficients)
    keep = [i for i in range(len(cases)) if i not in refusals]
    if refusals and keep:
        v, G = {k: a[keep] for k, a in v.items()}, G[keep]
    answers = iter(_results([cases[i] for i in keep], v, predict(G, fit), fit, options, G)
                   if keep else [])
    res = [refused(c, NAME, refusals[i]) if i in refusals else next(answers)
           for i, c in enumerate(cases)]
    return _timed(res, (time.perf_counter() - t0) / len(cases))
