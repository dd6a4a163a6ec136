"""When the closed form has no answer: the reasons, their codes and their messages.

:func:`no_answer_codes` gives each operating point of :func:`webfem.models.closed.evaluate`
the first reason that applies (:data:`NO_ANSWER`; 0: an answer), :func:`no_answer_reason` its
message naming the parameter, its value and what helps, and :func:`no_answer` reads a result.
The reasons and their order are stated in :mod:`webfem.models.closed`'s module text.
"""

from __future__ import annotations

import numpy as np

from ..case import Case
from ..physics.friction import valley_shear_bound
from ..physics.validity import THIN_FILM_RATIO, thin_film_message

__all__ = ["NO_ANSWER", "mu_bound", "no_answer_codes", "no_answer", "no_answer_reason"]

#: Why the closed form has no answer, by the code :func:`evaluate` returns as ``no_answer``
#: (0: an answer); the module text says what each means.
NO_ANSWER = ("", "thin-film", "gap", "landed", "mu", "compressed")
def mu_bound(mu_cc, eta, U_s, sigma, p_bar, mean_free_path):
    """The largest traction coefficient the closed form may state: the asperities' mu_cc
    plus the most the air between them can add where the web rests on them,
    :func:`~webfem.physics.friction.valley_shear_bound` eta U_s / sigma (about 2 eta U_s /
    sigma for the base web), over p_bar = T_eff/R. Only the Couette shear eta U_s / (h + 2 a
    lambda) at a resting gap h_c far below sigma goes further: the symptom of a contact law
    near its limit (T/R close to E_b sigma/(2t)), not a traction. A film flying over the
    whole wrap (h > 3 sigma) stays below the bound by itself (eta U_s / h < eta U_s /
    (3 sigma)), whatever mu_cc.

    >>> round(float(mu_bound(0.3, 1.81e-5, 20.0, 4e-6, 250.0 / 0.055, 65e-9)), 4)
    0.3404
    """
    return mu_cc + (valley_shear_bound(sigma, mean_free_path) * eta * U_s
                    / (sigma * p_bar))


def no_answer_codes(*, R, eps, h_in, h_out, h_c, mu, mu_max, h_min=None, t=None):
    """The :data:`NO_ANSWER` code of each point (0: an answer), the first reason that
    applies in the order of the module text; ``h_in`` and ``h_out`` are the unclamped Eq. 21
    gaps at the wrap edges (h_out <= h_in: permeation only lowers the gap); ``h_min`` the
    stated (resting) minimum gap and ``t`` the web's thickness."""
    limit = THIN_FILM_RATIO * np.asarray(R, float)
    mu = np.asarray(mu, float)
    through = (np.asarray(h_min, float) <= -np.asarray(t, float) if t is not None
               else np.zeros(np.shape(mu), bool))
    with np.errstate(invalid="ignore"):
        reasons = {                     # in the order they are judged
            "thin-film": np.asarray(R, float) * np.cbrt(eps) ** 2 > limit,
            "gap": np.maximum(h_in, h_c) > limit,
            "landed": h_in <= 0.0,
            "compressed": through,
            "mu": ~np.isfinite(mu) | (mu > mu_max),
        }
    return np.select(list(reasons.values()), [NO_ANSWER.index(k) for k in reasons], 0)


def no_answer(result) -> str | None:
    """Why the closed form has no answer at ``result``'s operating point (its
    ``solver_message``), or None when it has one. A result of :func:`webfem.models.closed.solve_many`, or of
    :func:`webfem.models.closed.solve_case` with ``raise_on_failure=False``, may carry no answer: ``converged``
    is then False. A model choosing among others (auto) tests this before using it.

    >>> from webfem import Case
    >>> from webfem.models.closed import solve, solve_many
    >>> no_answer(solve(Case())) is None
    True
    >>> r = solve_many([Case().updated({"web.tension": 0.01})])[0]
    >>> r["converged"], no_answer(r)[:30]
    (False, 'web.tension = 0.01 N/m with U ')
    """
    if result["converged"]:
        return None
    return result["solver_message"] or "no closed-form answer"


def no_answer_reason(code: int, case: Case, s: dict) -> str:
    """The message of :data:`NO_ANSWER` code ``code`` for ``case`` (summary values ``s``):
    what is wrong, the parameter and its value against its valid range, and what helps."""
    R = case.roller.radius
    limit = THIN_FILM_RATIO * R
    reason = NO_ANSWER[code]
    if reason == "thin-film":
        return thin_film_message(case) or "the film is thicker than R/100"
    if reason == "gap":
        if s["h_c"] > limit:
            w, f = case.web, case.friction
            keys = (f"web.roughness = {w.roughness:g} m"
                    + (f", roller.roughness = {case.roller.roughness:g} m, friction.roughness"
                       " = composite" if f.roughness == "composite" else ""))
            # the moving web's inertia lowers the load, so h_c rises with the line's speed
            load = ("T/R" if case.web_inertia <= 0.0 else
                    f"T_eff/R (T_eff = {case.tension_eff:.3g} N/m after the moving web's "
                    "inertia)")
            # as many digits as it takes for the two to differ (0.000375 against 0.000375)
            digits = next((d for d in range(3, 10)
                           if f"{s['h_c']:.{d}g}" != f"{limit:.{d}g}"), 10)
            return (f"the contact gap h_c = {s['h_c']:.{digits}g} m, where the asperities "
                    f"alone carry {load}, is more than R/100 = {limit:.{digits}g} m "
                    f"(roller.radius = {R:g} "
                    f"m; valid: h_c < R/100): the roughness sigma = {case.sigma:.3g} m "
                    f"({keys}) is far too coarse for a thin film on this roller; lower it")
        return (f"Eq. 21's inlet gap h_inlet = {s['h_inlet']:.3g} m is more than R/100 = "
                f"{limit:.2g} m (roller.radius = {R:g} m; lambda = {s['lambda']:.3g}, "
                "web.width is narrow against the film's entry length): the thin-film model "
                "does not hold; raise web.tension or lower the speeds")
    if reason == "landed":
        return (f"Eq. 21's gap is <= 0 over the whole wrap (h_inlet = {s['h_inlet']:.3g} m "
                f"at U = {case.U:g} m/s): no film is left to describe; raise the speeds")
    if reason == "compressed":
        w = case.web
        return (f"the wrap pressure T_eff/R = {case.p_bar:.4g} Pa would compress the web's "
                f"surface by {-s['h_min']:.3g} m, through its thickness web.thickness = "
                f"{w.thickness:g} m (thickness-direction modulus web.modulus_thickness = "
                f"{w.modulus_thickness:g} Pa): the asperity contact law does not hold there; "
                "a stiffer web or a lower web.tension is within it")
    if not np.isfinite(s["mu"]):
        if case.friction_variant != "loads":
            return ("the wrap-averaged mu is not finite: the paper's friction (Eqs. 28-30) "
                    f"weights the film's eta U_s / h by the film's share of the load, which "
                    f"stays above 0 as h -> 0 where contact cannot carry T/R at h = 0 (h_c = "
                    f"{s['h_c']:.3g} m <= 0) and Eq. 21 lands the web: use friction.variant = "
                    "loads (the friction from the solved loads)")
        if case.roughness_flow_model == "none":
            return ("the wrap-averaged mu is not finite: the Eq. 21 gap closes where the "
                    "Couette shear has no floor (air.roughness_flow = none); use the default "
                    "roughness flow or fe1d or fe2d")
        # only what the case states can be named, never a key it left at its default
        return (f"the wrap-averaged mu is not finite (h_c = {s['h_c']:.3g} m, Eq. 21's "
                f"outlet gap {s['h_outlet']:.3g} m): use fe1d or fe2d")
    mu_cc = case.friction.mu_cc
    top = mu_bound(mu_cc, case.air.viscosity, case.U_slide, case.sigma, case.p_bar,
                   case.air.mean_free_path)
    peak = valley_shear_bound(case.sigma, case.air.mean_free_path)
    return (f"the wrap-averaged mu = {s['mu']:.3g} is above what the asperities (friction."
            f"mu_cc = {mu_cc:g}) and the air between them (at most about "
            f"{peak:.2g} eta U_s / sigma) can carry: valid mu <= {top:.3g}; "
            f"the Couette shear over Eq. 21's resting gap h_c = {s['h_c']:.3g} m, well below "
            f"the roughness sigma = {case.sigma:.3g} m (U_s = {case.U_slide:g} m/s), is the "
            "contact law near its limit, not a traction: lower web.tension or raise "
            "web.modulus_thickness or web.roughness")


