"""When a converged state is an answer: the admissibility test, and the input error for a case
whose converged answer on a fine mesh is still not admissible.

With asperity contact (the default), the web may rest on the roller with its surface
compressed: a negative gap h, the web's mean surface plane below the roller's crest, is
admissible while the compression stays below the web's thickness (physics.md, "Webs that
rest on the roller"; the contact law carries any load, so every tension has an
equilibrium). Without contact, a gap <= 0 is the web through the roller. Either way the
absolute film pressure must stay positive.
"""

from __future__ import annotations

import numpy as np

from ..case import Case
from ..errors import NoAdmissibleSolution
from ..fem.scaling import FoilParameters
from ..physics.contact import contact_gap
from .refine import minimum

__all__ = ["admissibility", "no_admissible_solution", "compression_limit", "through_thickness"]


def compression_limit(case: Case, prm: FoilParameters) -> float:
    """The lowest admissible gap [m]: minus the web's thickness with contact (its surface
    cannot be compressed through the web), 0 without."""
    return -case.web.thickness if prm.contact else 0.0


def admissibility(case: Case, problem, u, prm: FoilParameters) -> str | None:
    """Why a converged state is not an answer, or None when it is admissible: the gap above
    :func:`compression_limit` everywhere in the solved domain, finite, and the absolute film
    pressure positive."""
    X = problem.X
    H = problem.gap(u, prm, X)
    if not np.all(np.isfinite(H)):
        return "the gap is not finite"
    Hmin, Xmin = minimum(problem, u, prm)
    h_min, limit = Hmin * case.h_scale, compression_limit(case, prm)
    if h_min <= limit:
        where = f"at x = {Xmin * case.x_scale:.3g} m"
        if prm.contact:
            return (f"the web's surface is compressed by {-h_min:.3g} m {where}, through its "
                    f"thickness t = {case.web.thickness:g} m")
        return f"the gap reaches {h_min:.3g} m <= 0 {where} (asperity contact is off)"
    p_abs = case.air.ambient_pressure + problem.pressure(u, X) * case.p_bar
    if np.min(p_abs) <= 0.0:
        return f"the absolute film pressure reaches {np.min(p_abs):.3g} Pa <= 0"
    return None


def no_admissible_solution(case: Case, prm: FoilParameters, why: str, problem=None,
                           u=None) -> None:
    """The input error for a case whose state, converged on a fine mesh (``problem`` and
    ``u`` given), is still not admissible: the web compressed through its thickness, so the
    contact law's linear spring base no longer describes it (a web much softer across its
    thickness than the wrap pressure). Without ``problem`` (a coarse mesh): nothing to say
    yet, the driver tries finer meshes."""
    if problem is None or not prm.contact:
        return
    Hmin, Xmin = minimum(problem, u, prm)
    h_min = Hmin * case.h_scale
    if h_min > compression_limit(case, prm):
        return
    w = case.web
    raise NoAdmissibleSolution(
        f"no admissible solution: the wrap pressure T_eff/R = {case.p_bar:.4g} Pa would "
        f"compress the web's surface by {-h_min:.3g} m at x = {Xmin * case.x_scale:.4g} m, "
        f"through its thickness web.thickness = {w.thickness:g} m (thickness-direction "
        f"modulus web.modulus_thickness = {w.modulus_thickness:g} Pa): the asperity contact "
        "law does not hold there; a stiffer web or a lower web.tension is within it")


def through_thickness(case: Case, prm: FoilParameters) -> str | None:
    """Why a web resting on the roller would be compressed through its thickness, or None:
    the gap at which contact alone carries T_eff/R (the continued law) at or below minus the
    web's thickness. Where the film does not hold the web off the roller, no equilibrium of
    the model is admissible then."""
    if not prm.contact:
        return None
    w = case.web
    h_c = float(contact_gap(case.p_bar, w.modulus_thickness, case.sigma, w.thickness,
                            case.friction.distribution))
    if h_c > -w.thickness:
        return None
    return (f"the wrap pressure T_eff/R = {case.p_bar:.4g} Pa, carried by contact alone, "
            f"would compress the web's surface by {-h_c:.3g} m, through its thickness "
            f"web.thickness = {w.thickness:g} m (thickness-direction modulus "
            f"web.modulus_thickness = {w.modulus_thickness:g} Pa): the asperity contact law "
            "does not hold there; a stiffer web or a lower web.tension is within it")
