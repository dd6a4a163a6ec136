"""When a converged state is an answer: the admissibility test, and the input error for a case
that admits no admissible solution at all.
"""

from __future__ import annotations

import numpy as np

from ..case import Case
from ..errors import NoAdmissibleSolution
from ..fem import forms
from ..fem.scaling import FoilParameters
from ..physics.validity import contact_overload
from .refine import minimum

__all__ = ["admissibility", "no_admissible_solution"]


def admissibility(case: Case, problem, u, prm: FoilParameters) -> str | None:
    """Why a converged state is not an answer, or None when it is admissible: the gap must
    be positive everywhere in the solved domain (with contact the web rests on its
    asperities, never through them) and the absolute film pressure positive."""
    X = problem.X
    H = problem.gap(u, prm, X)
    if not np.all(np.isfinite(H)):
        return "the gap is not finite"
    Hmin, Xmin = minimum(problem, u, prm)
    if Hmin <= 0.0:
        return (f"the gap reaches {Hmin * case.h_scale:.3g} m <= 0 at x = "
                f"{Xmin * case.x_scale:.3g} m")
    p_abs = case.air.ambient_pressure + problem.pressure(u, X) * case.p_bar
    if np.min(p_abs) <= 0.0:
        return f"the absolute film pressure reaches {np.min(p_abs):.3g} Pa <= 0"
    return None


def no_admissible_solution(case: Case, prm: FoilParameters, why: str, problem=None,
                           u=None) -> None:
    """An input error when the case admits no solution with a positive gap: the web lands
    and the contact law cannot carry T/R at any h >= 0, or (``problem`` and ``u`` given: a
    mesh-converged state) the web is pressed through its asperities somewhere because the
    load there exceeds what contact carries at h = 0."""
    overload = contact_overload(case) if prm.contact else None
    if overload:
        raise NoAdmissibleSolution(f"no admissible solution: the web lands ({why}) and "
                                   f"{overload}")
    if problem is None or not prm.contact:
        return
    Hmin, Xmin = minimum(problem, u, prm)
    if Hmin > 0.0:
        return
    w = case.web
    p0 = prm.c * case.p_bar if prm.law == 0 else float(
        forms.contact_law(np.array([0.0]), prm.as_form_args())[0][0] * case.p_bar)
    suction = float(np.min(problem.pressure(u, problem.X))) * case.p_bar
    cause = (f"the film's suction ({-suction:.3g} Pa below ambient where the web lifts off) "
             "pulls it" if suction < -case.p_bar else "the web is pressed")
    bend = (f" with bending stiffness D = {case.bending_used:.3g} N m"
            if case.bending_used > 0 else "")
    raise NoAdmissibleSolution(
        f"no admissible solution: {cause} through its asperities at x = "
        f"{Xmin * case.x_scale:.4g} m{bend}: the contact pressure needed exceeds what the "
        f"{case.friction.distribution} contact law carries at h = 0 ({p0:.4g} Pa, E_b sigma/"
        f"(2t) for the exponential law); a stiffer or rougher web (web.modulus_thickness = "
        f"{w.modulus_thickness:g} Pa, web.roughness = {w.roughness:g} m) or a lower "
        f"web.tension keeps it on its asperities")
