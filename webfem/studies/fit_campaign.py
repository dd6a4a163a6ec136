"""The fitted model's training campaign: a space-filling design in the groups, solved by fe2d.

The design is a scrambled Sobol sequence (:mod:`scipy.stats.qmc`) in the fit's coordinates
over :data:`~webfem.models.fit_groups.DOMAIN`; its prefix of any length is space-filling, so
a campaign can stop anywhere and the fit uses what is solved. Every fifth point (n % 5 == 4)
is held out: never used in fitting, it states the fit's error. Each point becomes a real
case with those groups (:func:`case_of_groups`: a held web, newsprint's friction constants,
every other number chosen to realise the groups within the keys' valid ranges) and is
solved by fe2d with its default mesh error target (1e-3, well below the fit's). The rows go
to a resumable CSV (:func:`webfem.sweeps.keyed.run_points`): re-running the same command
continues where it stopped. The points may be solved in local processes or on a Dask
cluster: each is a cold solve of its own case, so the rows do not depend on where or in
which order they were solved.

Examples
--------
>>> from webfem.models.fit_groups import groups_of, DOMAIN
>>> g = {k: (lo * hi) ** 0.5 if lo > 0 else 1.0 for k, (lo, hi) in DOMAIN.items()}
>>> back = groups_of(case_of_groups(g))
>>> all(abs(back[k] / g[k] - 1) < 1e-9 for k in g)
True
"""

from __future__ import annotations

import math
import time
from functools import lru_cache, partial

import numpy as np

from ..case import Case
from ..errors import InputError
from ..models.fit_groups import GROUPS, KB_FLOOR, NODES, box, coordinates
from ..models.registry import make_options, model_spec
from ..sweeps.keyed import run_points
from .time_limit import TimeLimit, time_limit

__all__ = ["design", "case_of_groups", "solve_point", "solve_design_point", "run", "recheck",
           "extra_holdout", "EXTRA_SEED", "COLUMNS", "HOLD_OUT_EVERY", "time_limit",
           "TimeLimit"]

#: Every this many points one is held out (n % HOLD_OUT_EVERY == HOLD_OUT_EVERY - 1).
HOLD_OUT_EVERY = 5
#: The fe2d summary values each row keeps besides the profile.
KEPT = ("h_center", "h_inlet", "h_outlet", "h_min", "x_min", "mu", "contact_share",
        "share_boundary", "share_mixed", "share_fluid", "error_h_center", "error_h_min",
        "error_mu", "error_contact_share", "h_scale", "x_scale", "p_bar")
COLUMNS = (("n", "holdout") + tuple(f"g_{g}" for g in GROUPS) + ("converged", "seconds")
           + KEPT + tuple(f"H{j}" for j in range(len(NODES)))
           + tuple(f"P{j}" for j in range(len(NODES))) + ("message",))
#: The friction constants and air of every campaign case (newsprint's; they do not enter
#: the scaled film problem, only the friction computed from it).
_BASE = {"web.speed": 0.0, "air.viscosity": 1.81e-5, "friction.roughness": "web",
         "roller.roughness": 0.0, "web.density": 700.0}
#: Target surface speed [m/s] of a campaign case (any would do: only the groups matter).
_SPEED = 10.0


def design(n: int, seed: int = 24) -> np.ndarray:
    """The first ``n`` points of the scrambled Sobol design, as groups ((n, 8), GROUPS
    order). Kb below KB_FLOOR's bottom end is an impermeable web (0)."""
    from scipy.stats import qmc
    lo, hi = box()
    lo = lo.copy()
    kb = GROUPS.index("Kb")
    lo[kb] -= 0.3    # a share of the design (0.3 of the axis's length) at Kb = 0 exactly
    m = max(int(math.ceil(math.log2(max(n, 2)))), 1)
    u = qmc.Sobol(len(GROUPS), scramble=True, seed=seed).random_base2(m)[:n]
    x = lo + u * (hi - lo)
    G = 10.0 ** x
    G[:, kb] = np.maximum(10.0 ** x[:, kb] - KB_FLOOR, 0.0)
    return G


def case_of_groups(g: dict[str, float]) -> Case:
    """A held-web case whose groups are ``g`` (dict by :data:`GROUPS`): eps^(1/3) small
    enough for a thin film and a wrap <= 180 deg, T, R and p_a from d and the speed, then
    the web's numbers from the other groups."""
    beta, lam, d = g["beta"], g["lam"], g["d"]
    e3 = min(0.05, 2.5 / beta)                 # eps^(1/3): B = beta e3 <= 2.5 rad
    eps = e3**3
    eta = _BASE["air.viscosity"]
    L_max = 4.0 / (2.0 * e3 * lam)            # R that keeps the width <= 4 m
    U = _SPEED
    for _ in range(4):
        T = 6.0 * eta * U / eps
        # R p_a = T / d; the base atmosphere where the radius allows it
        R = max(min(max(T / (d * 101325.0), 0.01), 2.0, L_max), 0.0011 / (2.0 * e3 * lam))
        p_a = T / (d * R)
        if 2e3 <= p_a <= 5e6:
            break
        U = min(U * (5e5 / p_a), 300.0)      # the speed moves T, hence p_a, into range
    h_s, x_s = R * eps ** (2 / 3), R * e3
    sigma = g["S"] * h_s
    # thickness: E_b = 2 c t T / (sigma R) and k = K R t eps^(4/3) / 12 within range
    K = g["Kb"] / beta
    # E_b about 1 MPa; no thicker than R/10 (t/(2R) = 0.05, inside THICK_WEB_LIMIT): the
    # groups hold E_b t and D, not t itself
    t = min(max(1e6 * sigma * R / (2.0 * g["c"] * T), 1e-6), 1e-2, 0.1 * R)
    if K > 0.0:      # and a permeability k <= 1e-9 m^2
        t = max(min(t, 1.2e-8 / (K * R * eps ** (4 / 3))), 1e-6)
    E_b = 2.0 * g["c"] * t * T / (sigma * R)
    return Case().updated({
        **_BASE, "roller.radius": R, "roller.speed": U, "web.tension": T,
        "air.ambient_pressure": p_a, "web.width": 2.0 * R * e3 * lam,
        "wrap.angle_deg": math.degrees(beta * e3), "web.thickness": t,
        "web.roughness": sigma, "web.modulus_thickness": E_b,
        "web.permeability": K * R * t * eps ** (4 / 3) / 12.0,
        "web.bending_stiffness": g["Dn"] * T * x_s**2,
        "air.mean_free_path": g["slip"] * h_s / 6.0})


def profile_of(result) -> tuple[np.ndarray, np.ndarray]:
    """The scaled gap H and film pressure P of an FE result at :data:`NODES` of the wrap
    (linear interpolation of the node fields, which are far finer than the nodes)."""
    case = result.case
    X = result.fields.x / case.x_scale
    at = NODES * case.beta
    H = np.interp(at, X, result.fields.h) / case.h_scale
    P = np.interp(at, X, result.fields.p_rel) / case.p_bar
    return H, P


def solve_point(n: int, g: dict[str, float], *, timeout: float | None = 120.0,
                options=None) -> dict:
    """The row of design point ``n`` with groups ``g``: fe2d's summary values, the
    profile at :data:`NODES`, or ``converged = False`` and the message."""
    row = {c: None for c in COLUMNS}
    row.update(n=n, holdout=int(n % HOLD_OUT_EVERY == HOLD_OUT_EVERY - 1),
               **{f"g_{k}": float(g[k]) for k in GROUPS}, converged=False, message="")
    t0 = time.perf_counter()
    limit = None
    try:
        case = case_of_groups(g)
        opts = make_options("fe2d", options)
        spec = model_spec("fe2d")
        with time_limit(timeout) as limit:
            r = spec.solve(case, opts, raise_on_failure=False)
    except Exception as err:   # noqa: BLE001 - the expected failures, or the time limit's
        if limit is not None and limit.expired:    # whatever the error became on its way
            message = f"TimeoutError: {limit.message}"
        elif isinstance(err, (InputError, TimeoutError, ArithmeticError, RuntimeError,
                              ValueError)):
            message = f"{type(err).__name__}: {err}"
        else:
            raise
        row.update(seconds=time.perf_counter() - t0, message=message)
        return row
    row["seconds"] = time.perf_counter() - t0
    s = r.summary
    if not s.converged:
        row["message"] = s.solver_message or "did not converge"
        return row
    H, P = profile_of(r)
    row.update({k: s.get(k) for k in KEPT if k not in ("h_scale", "x_scale", "p_bar")},
               h_scale=case.h_scale, x_scale=case.x_scale, p_bar=case.p_bar,
               converged=True, **{f"H{j}": float(v) for j, v in enumerate(H)},
               **{f"P{j}": float(v) for j, v in enumerate(P)})
    return row


#: fe2d's options in the campaign: the default mesh without its error estimate (the
#: estimate's second and finer meshes cost 2-5x; on a sample of the design the default
#: mesh's change on refinement was <= 3e-3 in every quantity, far below the fit's error).
FE2D_OPTIONS = {"estimate": False}


def run(out_csv, n: int, *, seed: int = 24, timeout: float | None = 120.0,
        options=None, progress=None, workers: int = 1, dask: str | None = None,
        retry_failed: bool = False) -> list[dict]:
    """Solve (or resume) the first ``n`` design points into ``out_csv``; returns the rows.

    Points that fail are kept (each is solved from cold: a re-run would repeat it) unless
    ``retry_failed``: then they are solved again (with a longer ``timeout``, or after a
    change to the solver that keeps the campaign's signature: a new webfem version starts
    the table afresh). ``options``: fe2d's (default :data:`FE2D_OPTIONS`). ``workers`` local
    processes, or a Dask cluster (``dask``: ``"local"`` with ``workers`` processes, or a
    scheduler's address), as :func:`webfem.sweeps.keyed.run_points` runs them: every point
    is a cold solve of its own case, so the rows are those of a serial run (the CSV in
    design order at the end); ``timeout`` limits each point in its worker."""
    options = dict(FE2D_OPTIONS if options is None else options)
    _check_points(n)
    from .. import __version__
    # not the number of points: the design's first n points are those of any longer one,
    # so a run with more points extends the campaign (it used to start the table afresh)
    sig = {"table": "fit-campaign", "parameter": "groups", "model": "fe2d",
           "design": "scrambled Sobol prefix", "seed": seed, "webfem": __version__,
           "options": options, "domain": [[float(a), float(b)] for a, b in zip(*box())]}
    # the key is the design index: the same seed gives the same point
    return run_points(out_csv, sig, COLUMNS,
                      ("n",), [(float(i),) for i in range(n)],
                      partial(solve_design_point, points=n, seed=seed, timeout=timeout,
                              options=options),
                      progress=progress, keep_failures=not retry_failed, workers=workers,
                      dask=dask)


def _check_points(n) -> None:
    """Refuse a number of design points that is not an integer 1-100000, naming it."""
    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= 100_000:
        raise InputError(f"points = {n!r} is out of range: must be an integer 1-100000")


def solve_design_point(i: int, *, points: int, seed: int, timeout: float | None,
                       options) -> dict:
    """The row of design point ``i`` of the first ``points`` (:func:`solve_point`): a
    module function, so a worker process or a Dask worker can be sent it; each computes
    the design once (a point's task carries its index, not the design)."""
    G = _design(points, seed)
    return solve_point(i, dict(zip(GROUPS, G[i])), timeout=timeout, options=options)


@lru_cache(maxsize=2)
def _design(n: int, seed: int) -> np.ndarray:
    """:func:`design`, once per process (read only)."""
    G = design(n, seed)
    G.flags.writeable = False
    return G


def recheck(out_csv, n: int, *, seed: int = 24, timeout: float | None = 120.0,
            options=None, progress=None, workers: int = 1, dask=None) -> list[dict]:
    """Solve (or resume) the hold-out points among the first ``n`` design points again,
    with the current fe2d and physics, into ``out_csv``; returns the rows. For a fit trained
    on rows of an earlier physics (as the fit shipped until its retraining was: the web held
    at the zones' ends, before ``wrap.ends = "span"`` became the default): its stated errors are then measured against
    what fe2d answers now (:func:`webfem.studies.fit_build.build`'s ``holdout_csv``).
    Points that fail are solved again on a re-run; ``workers`` and ``dask`` as :func:`run`."""
    options = dict(FE2D_OPTIONS if options is None else options)
    _check_points(n)
    idx = [i for i in range(n) if i % HOLD_OUT_EVERY == HOLD_OUT_EVERY - 1]
    from .. import __version__
    sig = {"table": "fit-holdout-recheck", "parameter": "groups", "model": "fe2d",
           "design": "scrambled Sobol prefix", "seed": seed, "webfem": __version__,
           "options": options, "physics": "default (wrap.ends = span, 1 m)"}
    # keyed by the design index, as the campaign's rows are
    return run_points(out_csv, sig, COLUMNS, ("n",), [(float(i),) for i in idx],
                      partial(_solve_held_out, held=tuple(idx), points=n, seed=seed,
                              timeout=timeout, options=options),
                      progress=progress, workers=workers, dask=dask)


#: The seed of the extra hold-out design (:func:`extra_holdout`): neither the campaign's
#: (24) nor the fresh points' check (2024, benchmarks/bench_fitted.py).
EXTRA_SEED = 7


def extra_holdout(out_csv, n: int, *, seed: int = EXTRA_SEED, timeout: float | None = 120.0,
                  options=None, progress=None, workers: int = 1, dask=None) -> list[dict]:
    """Solve (or resume) the first ``n`` points of a design of another seed into
    ``out_csv``, every one held out; returns the rows. The campaign's own hold-out points
    share their design with the points the fit's variants were compared on
    (docs/fit.md), so their errors may be optimistic; these were never seen by any choice,
    and join them in stating the errors (:func:`webfem.studies.fit_build.build`'s
    ``extra_csv``). Resumable and parallel as :func:`run`; points that failed are solved
    again on a re-run, as :func:`recheck`'s are (the shipped table's point 180, timed out
    at 60 s on a loaded machine, answered when solved again)."""
    options = dict(FE2D_OPTIONS if options is None else options)
    _check_points(n)
    from .. import __version__
    sig = {"table": "fit-extra-holdout", "parameter": "groups", "model": "fe2d",
           "design": "scrambled Sobol prefix", "seed": seed, "webfem": __version__,
           "options": options, "domain": [[float(a), float(b)] for a, b in zip(*box())]}
    return run_points(out_csv, sig, COLUMNS, ("n",), [(float(i),) for i in range(n)],
                      partial(_solve_extra, points=n, seed=seed, timeout=timeout,
                              options=options),
                      progress=progress, workers=workers, dask=dask)


def _solve_extra(i: int, **kw) -> dict:
    """The row of point ``i`` of the extra hold-out design, held out."""
    return {**solve_design_point(i, **kw), "holdout": 1}


def _solve_held_out(k: int, *, held: tuple, **kw) -> dict:
    """The row of the ``k``-th hold-out point (:func:`solve_design_point`)."""
    return solve_design_point(held[k], **kw)


def coordinates_of_rows(rows) -> np.ndarray:
    """The fit's coordinates of campaign rows."""
    return coordinates(np.array([[r[f"g_{g}"] for g in GROUPS] for r in rows], float))
