"""Closed-form model: the paper's Eq. 21 gap with its contact and friction model.

The cheapest model in webfem (about a microsecond per operating point). Because the Eq. 21
gap is linear along the wrap, the wrap-averaged friction is integrated exactly
(:func:`webfem.physics.friction.wrap_average_linear_gap`), not by quadrature.

Where it has no answer
----------------------
Eq. 21 is a fit with a contact and friction model beside it; some operating points give
numbers that are not an answer. :func:`evaluate` marks them (``no_answer``, a code into
:data:`NO_ANSWER`, 0 where there is an answer), judged on the unclamped Eq. 21 gap
h(x) from h_inlet down to h_outlet, in this order:

``thin-film``
    the film scale R eps^(2/3) is above R/100: Reynolds' thin-film equation does not hold
    (:func:`webfem.physics.validity.thin_film_check`);
``gap``
    a gap the answer states, Eq. 21's h_inlet or the contact gap h_c where the web rests on
    its asperities, is above R/100 (e.g. asperities a metre tall);
``landed``
    Eq. 21's h <= 0 over the whole wrap, from edge to edge: no film is left to speak of;
``mu``
    the wrap-averaged mu is not finite, or above mu_cc by more than the air between the
    asperities can add (:func:`mu_bound`: mu_cc + c eta U_s / (sigma T_eff/R), c = 2.03
    for the base web). The asperities' friction is at most mu_cc; the air in the valleys
    between them shears at most about 1.55 eta U_s / sigma there
    (:func:`~webfem.physics.friction.valley_shear_bound`; physics.md). Only the Couette
    shear eta U_s / (h + 2 a lambda) at a resting gap h_c far below sigma goes further,
    where it no longer holds (a contact law near its limit: T/R close to E_b sigma / (2 t)).
    A mu a little above mu_cc is an answer: boundary friction near mu_cc plus the real drag
    of the air (the base web at T = 120 N/m and 9 m/s: 0.301);
``compressed``
    the resting web's stated gap would compress its surface through its thickness (h_min <=
    -t): a web far softer across its thickness than the wrap pressure, outside the contact
    law.

A partly landed wrap is an answer (the paper's): where Eq. 21 puts h <= h_c the web rests on
its asperities, boundary lubrication with mu = (2/pi) mu_cc atan(U_s/C). So the base case
swept down to 0.5 m/s keeps its boundary-lubrication mu (0.17 there) though Eq. 21 lands all
but the first 0.2 % of the wrap. With the friction from the loads (every effect, the
default) the stated gaps are those of the resting web there, max(h_Eq21, h_c), as the FE
models find them; h_c < 0 where T_eff/R exceeds what the asperities carry at h = 0 (E_b sigma
/ (2 t)): the web rests with its surface compressed (``resting``, ``compression``;
physics.md, "Webs that rest on the roller"). With the paper's physics the gaps are Eq. 21's,
clamped at 0 as printed.

Where there is no answer, :func:`solve_case` raises
:class:`~webfem.errors.NoAdmissibleSolution` (exit 2 on the command line) naming the reason,
or with ``raise_on_failure=False`` returns the result with ``converged = False``, the reason
in ``solver_message`` and first in ``warnings``, the computed numbers NaN (null in JSON) and
no fields; :func:`solve_many` (sweeps) returns every point that way, as sweeps keep any
point no model can answer. :func:`no_answer` reads a result.

Examples
--------
>>> from webfem import Case
>>> r = solve(Case())
>>> r["model"], r["regime"]
('closed-form', 'boundary')
"""

from __future__ import annotations

import time

import numpy as np

from ..case import Case
from ..physics import closed_form as cf
from ..physics.contact import (REGIMES, contact_gap, contact_pressure, regime_code,
                               tail_gaussian_gaps, tail_warning)
from ..physics.effects import CLOSED_FORM_CARRIES, included, left_out, traction_summary
from ..errors import NoAdmissibleSolution
from ..physics.friction import (SLIP_COEFFICIENT, delta_T_from_mu, friction_for,
                                gauss_legendre, wrap_average_linear_gap,
                                wrap_average_loads)
from ..physics.validity import (answer_warnings, grooves_refused,
                                thin_film_check)
from ..result import Diagnostics, Fields, Result, Summary
from .closed_refusal import NO_ANSWER, mu_bound, no_answer, no_answer_codes, no_answer_reason
from .model_error import closed_form_errors
from .options import ClosedFormOptions

__all__ = ["evaluate", "case_arrays", "solve", "solve_case", "solve_many", "no_answer",
           "NO_ANSWER", "NAME"]

NAME = "closed-form"
#: Points along the wrap in the fields of a single solve (for charts and VTU).
N_FIELD_POINTS = 201
def case_arrays(cases) -> dict[str, np.ndarray]:
    """Stack cases into the keyword arrays :func:`evaluate` takes."""
    get = {
        "R": lambda c: c.roller.radius, "U_r": lambda c: c.roller.speed,
        "U_w": lambda c: c.web.speed, "L": lambda c: c.web.width, "T": lambda c: c.tension_eff,
        "B": lambda c: c.B, "k": lambda c: c.web.permeability, "t": lambda c: c.web.thickness,
        "eta": lambda c: c.air.viscosity, "E_b": lambda c: c.web.modulus_thickness,
        "sigma": lambda c: c.sigma, "mu_cc": lambda c: c.friction.mu_cc,
        "C": lambda c: c.friction.speed_constant,
        # through the roughness the shear is cut off at 2 a lambda with or without slip flow
        "slip_length": lambda c: (2.0 * SLIP_COEFFICIENT * c.air.mean_free_path
                                  if c.slip_model == "first-order"
                                  or c.roughness_flow_model == "mean-gap" else 0.0),
        "mean_free_path": lambda c: c.air.mean_free_path,
    }
    return {k: np.array([f(c) for c in cases], dtype=float) for k, f in get.items()}


def evaluate(*, R, U_r, U_w, L, T, B, k, t, eta, E_b, sigma, mu_cc, C, variant="paper",
             distribution="exponential", slip_length=0.0, mean_free_path=65e-9,
             roughness=False):
    """Closed-form gaps and traction at many operating points at once (arrays broadcast).

    Parameters are SI (B in radians). Returns a dict of arrays with the gap keys ``h_inlet``,
    ``h_center``, ``h_outlet``, ``h_min`` [m], ``mu``, ``delta_T`` [N/m], ``lambda``, ``beta``,
    ``eq21_valid``, ``h_c`` [m], the regime shares and ``regime_code`` (index into
    :data:`webfem.physics.contact.REGIMES`). ``T`` is the effective tension T_eff;
    ``variant="loads"`` averages the friction from the loads (with the slip length 2 a lambda
    in the film's shear) numerically, the others exactly. ``mu`` and ``delta_T`` are the
    traction at the stated speeds (the film's drag alone where nothing slides; the summary
    then reports the onset traction, :func:`webfem.physics.effects.traction_summary`).
    ``no_answer`` is 0 where the closed form has an answer, else the index into
    :data:`NO_ANSWER` of why not (see the module text); the arrays keep the numbers there
    for inspection, never to be read as an answer (a result's summary makes them NaN:
    :func:`summary_from_arrays`). ``mean_free_path`` [m] (at p_a) sets the
    bound on mu (:func:`mu_bound`); ``roughness``: the film's shear through the roughness
    (``air.roughness_flow = "mean-gap"``). With ``variant="loads"`` the gaps are the resting
    web's where Eq. 21 lands it, max(h, h_c); ``resting`` and ``compression`` say where that
    is below the roller's crest.
    """
    U = np.asarray(U_r, float) + U_w
    U_s = np.abs(np.asarray(U_r, float) - U_w)
    eps = cf.speed_parameter(eta, U, T)
    lam = cf.width_parameter(L, R, eps)
    beta = cf.wrap_parameter(B, eps)
    kappa = cf.permeability_parameter(k, T, B, eta, t, R, U)
    h_in = cf.gap_inlet(R, eps, lam)
    h_out = h_in - 2.0 * R * kappa
    if variant == "loads":
        avg = wrap_average_loads(h_in, h_out, R=R, T=T, U_s=U_s, eta=eta, E_b=E_b,
                                 sigma=sigma, t=t, mu_cc=mu_cc, C=C, distribution=distribution,
                                 slip_length=slip_length, roughness=roughness)
    else:
        avg = wrap_average_linear_gap(h_in, h_out, R=R, T=T, U_s=U_s, eta=eta, E_b=E_b,
                                      sigma=sigma, t=t, mu_cc=mu_cc, C=C, variant=variant,
                                      distribution=distribution)
    shares = np.stack([avg["share_boundary"], avg["share_mixed"], avg["share_fluid"]])
    h_c = contact_gap(T / R, E_b, sigma, t, distribution)
    # where Eq. 21 lands the web: at rest on its asperities (friction from the loads), or
    # clamped at 0 as the paper prints it
    rest = h_c if variant == "loads" else 0.0
    h_center = np.maximum(h_in - R * kappa, rest)
    h_min = np.maximum(h_out, rest)
    code = no_answer_codes(R=R, eps=eps, h_in=h_in, h_out=h_out, h_c=h_c, mu=avg["mu"],
                           mu_max=mu_bound(mu_cc, eta, U_s, sigma, T / R, mean_free_path),
                           h_min=h_min, t=t)
    return {"no_answer": code,
        "contact_share": _contact_share(h_in, h_out, h_c, T / R, E_b, sigma, t, distribution),
        "h_inlet": np.maximum(h_in, rest), "h_center": h_center,
        "h_outlet": h_min, "h_min": h_min,
        "resting": h_min < 0.0, "compression": np.maximum(-h_min, 0.0),
        "mu": avg["mu"], "delta_T": delta_T_from_mu(avg["mu"], T, B),
        "lambda": lam, "beta": beta, "eq21_valid": cf.eq21_valid(beta, lam),
        "eps": eps, "kappa": kappa, "h_c": h_c,
        "share_boundary": avg["share_boundary"], "share_mixed": avg["share_mixed"],
        "share_fluid": avg["share_fluid"], "regime_code": np.argmax(shares, axis=0),
    }


def _contact_share(h_in, h_out, h_c, p_bar, E_b, sigma, t, distribution, n=24):
    """Wrap average of the load share min(p_c/p_bar, 1) that asperity contact carries on the
    linear gap, the web resting at h_c where Eq. 21 lands it.

    Exponential heights: p_c(h)/p_bar = exp(-(h - h_c)/sigma) above h_c, integrated exactly
    over the linear gap while h_c >= 0; otherwise (Gaussian heights, or a web resting
    compressed) Gauss-Legendre with ``n`` points.
    """
    if distribution == "exponential" and np.all(np.asarray(h_c) >= 0.0):
        h_in, h_out, h_c, sigma = np.broadcast_arrays(*(np.asarray(v, float) for v in
                                                        (h_in, h_out, h_c, sigma)))
        lo, hi = np.minimum(h_in, h_out), np.maximum(h_in, h_out)
        span = hi - lo
        edge = np.maximum(h_c, 0.0)
        a = np.clip(edge, lo, hi)                 # the part of the gap below the edge: 1
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            tail = sigma * (np.exp(-(a - h_c) / sigma) - np.exp(-(hi - h_c) / sigma))
            share = np.where(span > 0.0, ((a - lo) + tail) / np.where(span > 0.0, span, 1.0),
                             np.minimum(np.exp(-(np.maximum(lo, edge) - h_c) / sigma), 1.0))
        return share
    g, gw = gauss_legendre(n)
    s = 0.5 * (g + 1.0)
    h_in, h_out, h_c, p_bar = (np.asarray(v, float)[..., None] for v in
                               np.broadcast_arrays(h_in, h_out, h_c, p_bar))
    h = np.maximum(h_in + (h_out - h_in) * s, h_c)
    pc = contact_pressure(h, np.asarray(E_b)[..., None] if np.ndim(E_b) else E_b,
                          np.asarray(sigma)[..., None] if np.ndim(sigma) else sigma,
                          np.asarray(t)[..., None] if np.ndim(t) else t, distribution)
    return np.sum(np.minimum(pc / p_bar, 1.0) * 0.5 * gw, axis=-1)


def _warnings(case: Case, summary: dict, gaussian_gap=None) -> list[str]:
    out = []
    missing = left_out(case)
    if missing:
        out.append("the closed form leaves out " + ", ".join(missing)
                   + f" (bending D = {case.bending_used:.3g} N m)" * ("bending" in missing)
                   + "; the FE models carry them")
    if not summary["eq21_valid"]:
        out.append(f"outside Eq. 21's stated range: beta = {summary['beta']:.3g} (needs > 6), "
                   f"lambda = {summary['lambda']:.3g} (needs > 7); use an FE model")
    landed = summary["h_outlet"] <= max(summary["h_c"], 0.0) * (1.0 + 1e-12)
    if landed and case.friction_variant == "loads":
        out.append("Eq. 21's gap falls below h_c in the wrap: the web rests on its asperities "
                   "there, at h_c" + (" with its surface compressed (h_c < 0)"
                                      if summary["h_c"] < 0.0 else ""))
    elif landed and summary["h_outlet"] <= 0.0:
        # the paper's own contact model would carry T/R at h_c, where the FE models rest the
        # web; the paper prints Eq. 21 clamped at 0, which the stated gap errors include
        out.append("Eq. 21 gap reaches 0 in the wrap: the web lands on the roller there "
                   "(clamped h <= 0 -> 0, as the paper prints it; its friction counts the web "
                   "resting on its asperities wherever h <= h_c, and the FE models rest it at "
                   f"h_c = {summary['h_c'] * 1e6:.3g} um)")
    elif landed:
        out.append("Eq. 21's gap falls below h_c in the wrap: its friction counts the web "
                   "resting on its asperities there (boundary) while the gaps stay Eq. 21's, "
                   "as the paper prints them; the FE models rest it at h_c = "
                   f"{summary['h_c'] * 1e6:.3g} um")
    tail = tail_warning(case, summary["h_c"], summary["contact_share"], gaussian_gap)
    out.extend(answer_warnings(case, summary["h_min"], tail))
    return out


#: The summary's computed numbers, NaN where the closed form has no answer (the case's own
#: groups, lambda, beta, eps, kappa, T_eff, stay: they say where the point is).
NO_ANSWER_NAN = ("h_center", "h_inlet", "h_outlet", "h_min", "mu", "delta_T", "h_c",
                 "share_boundary", "share_mixed", "share_fluid", "contact_share",
                 "compression", "mu_onset", "mu_film", "delta_T_film", "delta_T_available",
                 "slip_margin")


def summary_from_arrays(values: dict, i: int, case: Case, elapsed: float,
                        gaussian_gap=None) -> Summary:
    """The :class:`~webfem.result.Summary` of point ``i`` of :func:`evaluate`'s output;
    where the closed form has no answer, ``converged`` is False, ``solver_message`` and the
    first of the ``warnings`` say why (see the module text), the computed numbers
    (:data:`NO_ANSWER_NAN`) are NaN and ``regime`` is ``"none"``, as
    :func:`webfem.result.refused` gives the other models'. ``gaussian_gap``: the point's
    Gaussian h_c for the tail warning where a batch solved it
    (:func:`~webfem.physics.contact.tail_gaussian_gaps`)."""
    s = {key: (np.asarray(v)[i] if np.ndim(v) else v) for key, v in values.items()}
    s = {k: (v.item() if hasattr(v, "item") else v) for k, v in s.items()}
    code = int(s.pop("no_answer"))
    # mu and delta_T as the belt formula would measure them (the onset traction where
    # nothing slides), with the idler check
    s.update(traction_summary(case, s["mu"], s["contact_share"]))
    s.update(model=NAME, regime=REGIMES[int(s.pop("regime_code"))], converged=code == 0,
             iterations=0, n_dofs=0, residual=0.0, solve_time_s=elapsed,
             sigma=case.sigma, U=case.U, U_slide=case.U_slide, T_eff=case.tension_eff,
             bending_stiffness_used=0.0,
             effects=tuple(e for e in included(case) if e in CLOSED_FORM_CARRIES))
    s["warnings"] = _warnings(case, s, gaussian_gap)
    if code:
        # the reason reads from the traction at the stated speeds, which it judged
        s["solver_message"] = no_answer_reason(
            code, case, {**s, "mu": s["mu_film"] if s["mu_film"] is not None else s["mu"]})
        # the reason first (what a reader acts on), and no number that could be read as an
        # answer: NaN (null in JSON), as webfem.result.refused gives every model's
        s["warnings"].insert(0, "no closed-form answer: " + s["solver_message"])
        s.update({k: float("nan") for k in NO_ANSWER_NAN if s.get(k) is not None},
                 regime="none", residual=float("nan"), resting=None)
    else:
        s.update({f"error_{q}": e for q, e in closed_form_errors(case, s).items()},
                 error_basis=ERROR_BASIS)
    return Summary.from_mapping(s)


#: How the closed form's stated errors are obtained (:mod:`webfem.models.model_error`).
ERROR_BASIS = ("model: Eq. 21's fit against the wide-web gap 0.643 R eps^(2/3) with "
               "1.48/lambda edge leakage, Eshel-Elrod's exit constriction and the contact "
               "gathered there, the web resting at h_c where Eq. 21's film has no air left "
               "(its gap <= 0), the pressure-driven shear and the bending it leaves out (the "
               "gap lowered by up to 0.035 h_scale per sqrt(Dn), the wrap ends' line loads "
               "sqrt(D T)/R on the asperities) (doubled); no mesh")


def evaluate_case(case: Case) -> int:
    """The :data:`NO_ANSWER` code of ``case`` (0: the closed form has an answer)."""
    values = evaluate(**case_arrays([case]), variant=case.friction_variant,
                      distribution=case.friction.distribution,
                      roughness=case.roughness_flow_model == "mean-gap")
    return int(np.asarray(values["no_answer"]).ravel()[0])


def solve_case(case: Case, options: ClosedFormOptions, *, initial: Result | None = None,
               raise_on_failure: bool = True) -> Result:
    """Closed-form solution of one case, with fields along the wrap for charts and VTU
    (``options.n_points`` points). ``initial`` is accepted for the registry's common
    signature and not used: the closed form needs no start. A grooved roller is refused.

    Where the closed form has no answer (module text) it raises
    :class:`~webfem.errors.NoAdmissibleSolution` naming the reason, or with
    ``raise_on_failure=False`` returns the result with ``converged = False``, the reason
    in ``solver_message`` (:func:`no_answer`) and first in ``warnings``, its computed
    numbers NaN and no fields: never to be read as an answer.
    """
    grooves_refused(case, "the closed form")
    if raise_on_failure:
        thin_film_check(case)
    t0 = time.perf_counter()
    values = evaluate(**case_arrays([case]), variant=case.friction_variant,
                      distribution=case.friction.distribution,
                      roughness=case.roughness_flow_model == "mean-gap")
    elapsed = time.perf_counter() - t0
    summary = summary_from_arrays(values, 0, case, elapsed)
    if not summary.converged:
        if raise_on_failure:
            raise NoAdmissibleSolution(f"no admissible closed-form answer: "
                                       f"{summary.solver_message}")
        empty = np.empty(0)     # no answer, no profile (its gaps are NaN)
        return Result(case, summary, Fields(x=empty, h=empty),
                      Diagnostics(reason=summary.solver_message, options=options))
    R, B = case.roller.radius, case.B
    x = np.linspace(-R * B / 2, R * B / 2, options.n_points)
    h = cf.gap(x, R, B, case.eps, case.lam, case.kappa)
    # with friction from the loads the web rests on its asperities where Eq. 21 lands it
    loads = case.friction_variant == "loads"
    if loads:   # where Eq. 21 lands the web it rests on its asperities: boundary
        h = np.maximum(cf.gap(x, R, B, case.eps, case.lam, case.kappa, clamp=False),
                       summary.h_c)
    local = friction_for(case, h)
    if loads:
        local["regime"] = regime_code(h, summary.h_c, case.sigma)
    fields = Fields(x=x, h=h, **local)
    return Result(case, summary, fields,
                  Diagnostics(method="Eq. 21 + Eqs. 10-13, 28-31, exact average",
                              options=options))


def solve(case: Case, options: ClosedFormOptions | None = None, **values) -> Result:
    """Closed-form solution of one case (see :func:`solve_case`); options as keywords
    (``n_points``); any other name is an error naming it."""
    options = options.replace(**values) if options is not None else \
        ClosedFormOptions.from_mapping(values)
    return solve_case(case, options)


def solve_many(cases) -> list[Result]:
    """Solve many cases in one vectorised evaluation (summaries only, no fields). A point
    where the closed form has no answer is returned with ``converged = False``, the reason
    in ``solver_message`` (what :func:`solve_case` would raise) and first in ``warnings``,
    its computed numbers NaN, as sweeps keep it."""
    cases = list(cases)
    for c in cases:
        grooves_refused(c, "the closed form")
    out: list[Result | None] = [None] * len(cases)
    def kind(c):
        return c.friction_variant, c.friction.distribution, c.roughness_flow_model
    for variant, distribution, flow in {kind(c) for c in cases}:
        idx = [i for i, c in enumerate(cases) if kind(c) == (variant, distribution, flow)]
        t0 = time.perf_counter()
        values = evaluate(**case_arrays([cases[i] for i in idx]), variant=variant,
                          distribution=distribution, roughness=flow == "mean-gap")
        # the tail warnings' Gaussian h_c in one vectorised solve, not one per point
        gaussian = tail_gaussian_gaps([cases[i] for i in idx], values["h_c"],
                                      values["contact_share"])
        elapsed = (time.perf_counter() - t0) / len(idx)
        for j, i in enumerate(idx):
            # summaries only: the fields are the wrap endpoints of the linear Eq. 21 gap
            # (none where there is no answer)
            s = summary_from_arrays(values, j, cases[i], elapsed, gaussian[j])
            half = cases[i].roller.radius * cases[i].B / 2 if s.converged else None
            out[i] = Result(cases[i], s, Fields(x=np.array([-half, half]),
                                                h=np.array([s.h_inlet, s.h_outlet]))
                            if half is not None else Fields(x=np.empty(0), h=np.empty(0)))
    return out  # type: ignore[return-value]
