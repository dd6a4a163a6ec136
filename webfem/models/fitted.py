"""Fitted model: a fit of webfem's own fe2d solutions in the dimensionless groups.

The fit (:mod:`webfem.models.fit_kernel`, coefficients in ``fitted_coefficients.npz``, made
by ``webfem fit build``) gives, from the eight groups of a smooth-roller case
(:mod:`webfem.models.fit_groups`), the scaled gap H and film pressure P at fixed positions
along the wrap and the smallest gap and where. The friction, the regimes, the contact share,
mu and delta_T are then computed from that profile with the physics functions the FE models
use (:func:`webfem.physics.friction.friction_for`, the contact law), so the friction
constants and the speeds add no dimensions to the fit.

Its domain is the box of groups the campaign sampled and the default full physics on a
smooth roller; outside it the model refuses (:class:`OutsideDomain`, naming the group, its
value and its range), and auto moves on. Its stated errors (``error_h_center``, ...) are the
95th percentile of the errors on a hold-out set never used in fitting, per region of the
predicted smallest gap over the roughness (flying, landing, resting).

Examples
--------
>>> from webfem import Case
>>> r = solve(Case())
>>> r["model"], r.summary.error_mu is not None
('fitted', True)
"""

from __future__ import annotations

import time
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..case import Case
from ..errors import NoAdmissibleSolution
from ..physics.contact import REGIMES, contact_gap, contact_pressure
from ..physics.effects import included, traction_summary
from ..physics.friction import friction_for
from ..result import Diagnostics, Fields, Result, Summary
from . import fit_groups as fg
from .fit_kernel import Kernel
from .options import FittedOptions

__all__ = ["solve", "solve_case", "solve_many", "predict", "read_profile", "OutsideDomain",
           "NAME",
           "COEFFICIENTS", "coefficients"]

NAME = "fitted"
COEFFICIENTS = Path(__file__).with_name("fitted_coefficients.npz")
QUANTITIES = ("h_center", "h_min", "mu", "contact_share")


class OutsideDomain(NoAdmissibleSolution):
    """The case is outside the fitted model's domain (the message names the group)."""


@lru_cache(maxsize=4)
def coefficients(path: str | None = None) -> dict:
    """The shipped fit (or the one at ``path``): the kernel, the box, the stated-error
    table and what it was trained on."""
    p = Path(path) if path else COEFFICIENTS
    if not p.is_file():
        raise NoAdmissibleSolution(f"the fitted model's coefficients {p} are missing: build "
                                   "them with `webfem fit build`")
    with np.load(p, allow_pickle=False) as data:
        d = {k: data[k] for k in data.files}
    return {"kernel": Kernel.from_arrays(d, "k"), "lo": d["lo"], "hi": d["hi"],
            "edges": d["region_edges"], "errors": d["region_errors"],
            "physics": str(d["physics"]), "info": str(d["info"])}


def predict(G: np.ndarray, fit: dict | None = None) -> dict[str, np.ndarray]:
    """The scaled profile of groups ``G`` ((n, 8)): ``H`` and ``P`` (n, nodes), ``H_min``,
    ``s_min`` (position over the wrap, -1/2 entry) and ``region`` (index into the stated
    errors). No domain check (:func:`fit_groups.outside_rows`)."""
    fit = fit or coefficients()
    x = (fg.coordinates(G) - fit["lo"]) / (fit["hi"] - fit["lo"])
    Y = fit["kernel"](x)
    n = len(fg.NODES)
    G = np.asarray(G, float)
    S = G[:, fg.GROUPS.index("S")][:, None]
    H_c = S * np.log(G[:, fg.GROUPS.index("c")])[:, None]
    base, base_min = fg.baseline(G)
    # the fit is the remainder over the physical baseline, in the fit's gap variable
    y_nodes = Y[:, :n] + fg.gap_to_fit(base, S, H_c)
    y_min = Y[:, 2 * n] + fg.gap_to_fit(base_min, S[:, 0], H_c[:, 0])
    H = fg.fit_to_gap(y_nodes, S, H_c)
    H_min = np.minimum(fg.fit_to_gap(y_min, S[:, 0], H_c[:, 0]), H.min(axis=1))
    region = np.searchsorted(fit["edges"], H_min / S[:, 0])
    return {"H": H, "P": Y[:, n:2 * n], "H_min": H_min,
            "s_min": np.clip(Y[:, 2 * n + 1], -0.5, 0.5), "region": region}


def read_profile(case: Case, H, P, H_min, s_min) -> dict:
    """Gaps, friction, regimes and contact share of one case from its scaled profile, with
    the FE models' physics functions (readout.py does the same on the FE solution)."""
    hs, xs, pb = case.h_scale, case.x_scale, case.p_bar
    h = H * hs
    # a fitted suction may overshoot below vacuum, where the slip length has no meaning
    p = np.maximum(case.air.ambient_pressure + P * pb, 0.1 * case.air.ambient_pressure)
    dpdx = np.gradient(P, fg.NODES * case.beta) * pb / xs
    loc = friction_for(case, h, resting=True, p=p, dpdx=dpdx)
    W = fg.WEIGHTS
    w = case.web
    Pc = contact_pressure(h, w.modulus_thickness, case.sigma, w.thickness,
                          case.friction.distribution) / pb
    # a share of the load: a fitted suction may make the film's part nearly cancel contact's
    share = float(np.clip(np.sum(W * Pc) / max(np.sum(W * (P + Pc)), 1e-300), 0.0, 1.0))
    mu = float(np.sum(W * loc["mu"]))
    shares = [float(np.sum(W * (loc["regime"] == k))) for k in range(3)]
    c = len(fg.NODES) // 2
    return {"h_center": h[c], "h_inlet": h[0], "h_outlet": h[-1], "h_min": H_min * hs,
            "x_min": s_min * case.beta * xs, "mu": mu, "contact_share": share,
            "share_boundary": shares[0], "share_mixed": shares[1], "share_fluid": shares[2],
            "regime": REGIMES[int(np.argmax(shares))], "h": h, "loc": loc,
            "compression": max(0.0, -min(float(h.min()), H_min * hs))}


def _summary(case: Case, values: dict, errors: np.ndarray, elapsed: float,
             info: str) -> Summary:
    s = {k: v for k, v in values.items() if k not in ("h", "loc")}
    s.update(traction_summary(case, s["mu"], s["contact_share"]))
    s.update(model=NAME, converged=True, iterations=0, n_dofs=0, residual=0.0,
             solve_time_s=elapsed, sigma=case.sigma, U=case.U, U_slide=case.U_slide,
             T_eff=case.tension_eff, bending_stiffness_used=case.bending_used,
             effects=tuple(included(case)), eps=case.eps, kappa=case.kappa,
             beta=case.beta, eq21_valid=bool(case.beta > 6 and case.lam > 7),
             h_c=float(contact_gap(case.p_bar, case.web.modulus_thickness, case.sigma,
                                   case.web.thickness, case.friction.distribution)),
             resting=bool(s["compression"] > 0.0), method="fit", land_fraction=1.0,
             error_basis=info, **{"lambda": case.lam},
             **{f"error_{q}": float(e) for q, e in zip(QUANTITIES, errors)})
    return Summary.from_mapping(s)


def _checked_groups(case: Case) -> dict[str, float]:
    """The groups of ``case``, or :class:`OutsideDomain` naming why it has none."""
    why = fg.physics_refusal(case)
    g = None if why else fg.groups_of(case)
    why = why or fg.outside(case, g)
    if why:
        raise OutsideDomain(f"no fitted answer: {why}")
    return g


def solve_case(case: Case, options: FittedOptions, *, initial: Result | None = None,
               raise_on_failure: bool = True) -> Result:
    """The fitted answer for one case, with its gap and friction along the wrap as fields.
    Outside the domain it raises :class:`OutsideDomain` (``raise_on_failure`` is accepted
    for the registry's common signature; a refusal is never returned as an answer)."""
    t0 = time.perf_counter()
    g = _checked_groups(case)
    fit = coefficients(options.coefficients)
    pr = predict(fg.group_array(g), fit)
    values = read_profile(case, pr["H"][0], pr["P"][0], pr["H_min"][0], pr["s_min"][0])
    elapsed = time.perf_counter() - t0
    summary = _summary(case, values, fit["errors"][pr["region"][0]], elapsed,
                       _basis(fit, pr["region"][0]))
    x = fg.NODES * case.beta * case.x_scale
    fields = Fields(x=x, h=values["h"], **values["loc"])
    return Result(case, summary, fields, Diagnostics(method="fit of fe2d solutions "
                                                     "(Matern-5/2 GP mean) + Eqs. 10-13, "
                                                     "28-31 on its profile", options=options))


_REGION = ("resting (predicted h_min < 1.5 sigma)", "landing (h_min 1.5-4 sigma)",
           "flying (h_min > 4 sigma)")


def _basis(fit: dict, region: int) -> str:
    name = _REGION[region] if len(fit["edges"]) == 2 else f"region {region}"
    return (f"fit: 95th percentile of the hold-out errors against fe2d in its region, "
            f"{name}; {fit['info']}")


def solve(case: Case, options: FittedOptions | None = None, **values) -> Result:
    """:func:`solve_case` with the options as keywords."""
    options = options.replace(**values) if options is not None else \
        FittedOptions.from_mapping(values)
    return solve_case(case, options)


def solve_many(cases, options: FittedOptions | None = None) -> list[Result]:
    """Many cases in one vectorised evaluation of the fit (summaries and the wrap profile).
    A case outside the domain is an :class:`OutsideDomain` error naming it."""
    cases = list(cases)
    options = options or FittedOptions()
    t0 = time.perf_counter()
    groups = []
    for i, c in enumerate(cases):
        try:
            groups.append(_checked_groups(c))
        except OutsideDomain as err:
            raise OutsideDomain(f"case {i}: {err}") from None
    fit = coefficients(options.coefficients)
    G = np.vstack([fg.group_array(g) for g in groups])
    pr = predict(G, fit)
    elapsed = (time.perf_counter() - t0) / max(len(cases), 1)
    out = []
    for i, c in enumerate(cases):
        v = read_profile(c, pr["H"][i], pr["P"][i], pr["H_min"][i], pr["s_min"][i])
        s = _summary(c, v, fit["errors"][pr["region"][i]], elapsed,
                     _basis(fit, pr["region"][i]))
        out.append(Result(c, s, Fields(x=fg.NODES * c.beta * c.x_scale, h=v["h"])))
    return out
