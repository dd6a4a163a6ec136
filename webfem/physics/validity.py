"""Where the models' physics holds: the thin-film bound, the slip-flow warning, and the
longest wrap the FE meshes resolve.

Examples
--------
>>> from webfem import Case
>>> thin_film_check(Case())          # the base case: h ~ 1e-3 R, fine
>>> thin_film_check(Case().updated({"web.tension": 1e-6}))
Traceback (most recent call last):
...
webfem.errors.NoAdmissibleSolution: web.tension = 1e-06 N/m with U = 20 m/s and air.viscosity = 1.81e-05 Pa s gives a film R eps^(2/3) = 9.22 m thick, more than R/100 = 0.00055 m: the thin-film (Reynolds) model does not hold; raise web.tension or lower the speeds or air.viscosity
"""

from __future__ import annotations

from ..errors import NoAdmissibleSolution

__all__ = ["MEAN_FREE_PATH", "THIN_FILM_RATIO", "BETA_MAX", "thin_film_check",
           "THICK_WEB_RATIO", "THICK_WEB_LIMIT", "COMPRESSION_RATIO", "thick_web_warning",
           "thin_film_message",
           "wrap_length_check", "slip_warning", "smooth_roller_warning", "answer_warnings"]

#: Mean free path of air at 101325 Pa and 23 C [m]; it scales as 1/p_a.
MEAN_FREE_PATH = 68e-9
#: The film scale R eps^(2/3) must stay below this fraction of R: Reynolds' thin-film
#: equation and the parabolic roller departure x^2/(2R) assume h << R.
THIN_FILM_RATIO = 0.01
#: Longest wrap, in units of the entry length R eps^(1/3), that the FE meshes resolve
#: (about BETA_MAX/2 cells before refinement).
BETA_MAX = 5000.0


def thin_film_message(case) -> str | None:
    """Why the thin-film model does not hold for ``case`` (its film scale R eps^(2/3) above
    :data:`THIN_FILM_RATIO` R), or None when it holds. The closed form's vectorised path
    flags a point with this text where :func:`thin_film_check` would raise."""
    R = case.roller.radius
    if case.h_scale <= THIN_FILM_RATIO * R:
        return None
    # a moving web spends rho_w t U_w^2 of its tension turning: say so when that is the cause
    inertia = (f" (T_eff = {case.tension_eff:.3g} N/m after the moving web's inertia)"
               if case.web_inertia > 0.0 else "")
    return (f"web.tension = {case.web.tension:g} N/m{inertia} with U = {case.U:g} m/s and "
            f"air.viscosity = {case.air.viscosity:g} Pa s gives a film R eps^(2/3) = "
            f"{case.h_scale:.3g} m thick, more than R/100 = {THIN_FILM_RATIO * R:.2g} m: the "
            "thin-film (Reynolds) model does not hold; raise web.tension or lower the speeds "
            "or air.viscosity")


def thin_film_check(case) -> None:
    """Raise :class:`NoAdmissibleSolution` (an :class:`InputError`) when the film scale
    R eps^(2/3) exceeds :data:`THIN_FILM_RATIO` R (the thin-film model does not hold)."""
    message = thin_film_message(case)
    if message:
        raise NoAdmissibleSolution(message)


def wrap_length_check(case) -> None:
    """Raise :class:`InputError` when the wrap is longer than :data:`BETA_MAX` entry lengths
    (very low speed: the FE mesh would need too many cells; the web rests on its asperities
    there, which the closed form describes)."""
    if case.beta > BETA_MAX:
        raise NoAdmissibleSolution(
            f"roller.speed = {case.roller.speed:g} m/s (U = {case.U:.3g} m/s) makes the wrap "
            f"beta = {case.beta:.4g} entry lengths long, beyond the FE models' limit "
            f"{BETA_MAX:g}: the air film is negligible there (boundary lubrication); use "
            "model = 'closed-form' or a higher speed")


def slip_warning(case, h_min: float) -> str | None:
    """The slip-flow warning when the minimum gap is below 10 mean free paths, else None.

    What it warns of follows the case's slip model (``case.slip_model``): without slip the
    continuum Reynolds equation overestimates the film pressure there; with first-order slip
    (the default) the correction is included, but beyond Kn = lambda/h_min = 0.1 it departs
    from the Boltzmann flow (Fukui-Kaneko) by more than the few per cent of the correction
    measured at the base case's Kn 0.003-0.03, an error the stated ones do not include."""
    mfp = MEAN_FREE_PATH * 101325.0 / case.air.ambient_pressure
    if not 0.0 < h_min < 10.0 * mfp:
        return None
    said = (f"h_min = {h_min:.3g} m is below 10 mean free paths of air ({10 * mfp:.3g} m; "
            f"Kn = {mfp / h_min:.2g}): ")
    if case.slip_model == "none":
        return said + ("slip flow, where the continuum Reynolds equation overestimates the "
                       "film pressure (air.slip = \"first-order\" includes the slip)")
    return said + ("slip flow beyond Kn 0.1, where the first-order slip webfem includes "
                   "departs from the Boltzmann flow: the film near h_min carries a model "
                   "error the stated errors leave out")


#: The case keys of a grooved roller.
GROOVE_KEYS = ("roller.groove_pitch", "roller.groove_width", "roller.groove_depth")


def smooth_roller_warning(case) -> str | None:
    """The warning of a roller given a groove pitch or depth but no groove width: it is
    solved smooth (a width of 0 means no grooves, as in a sweep of the width from 0), which
    the answer must say; None otherwise."""
    r = case.roller
    if case.grooved or (r.groove_pitch == 0.0 and r.groove_depth == 0.0):
        return None
    given = [f"roller.{k} = {getattr(r, k):g} m" for k in ("groove_pitch", "groove_depth")
             if getattr(r, k) > 0.0]
    return (f"{' and '.join(given)} set, but roller.groove_width = 0: the roller is solved "
            "smooth (grooves need a width > 0 and < the pitch, and a depth > 0)")


def answer_warnings(case, h_min: float, tail: str | None = None) -> list[str]:
    """The warnings every model's answer carries where they apply, in this order: slip flow
    (:func:`slip_warning`), the exponential heights' tail (``tail``, the caller's
    :func:`webfem.physics.contact.tail_warning`), a thick web (:func:`thick_web_warning`)
    and a groove geometry without a width (:func:`smooth_roller_warning`)."""
    return [w for w in (slip_warning(case, h_min), tail, thick_web_warning(case, h_min),
                        smooth_roller_warning(case)) if w]


def groove_keys_text(case) -> str:
    """The groove keys of ``case`` as messages show them: ``roller.groove_pitch = 0.00127,
    roller.groove_width = 0.00025, roller.groove_depth = 0.00025 m``."""
    r = case.roller
    return (f"roller.groove_pitch = {r.groove_pitch:g}, roller.groove_width = "
            f"{r.groove_width:g}, roller.groove_depth = {r.groove_depth:g} m")


def grooves_text(case, model: str) -> str | None:
    """Why ``model`` (as messages name it) cannot solve ``case``: a grooved roller, which only
    the 2-D film model (fe2d) solves; None for a smooth roller."""
    if not case.grooved:
        return None
    return (f"{model} cannot solve a grooved roller ({groove_keys_text(case)}): use model "
            "fe2d or auto, or set roller.groove_width = 0 for a smooth roller")


def grooves_refused(case, model: str) -> None:
    """An :class:`~webfem.errors.InputError` when ``case`` has a grooved roller
    (:func:`grooves_text`)."""
    text = grooves_text(case, model)
    if text:
        from ..errors import InputError
        raise InputError(text)


#: Largest t/(2R) the thin-web geometry takes without a warning: the web's mid-plane runs on
#: radius R + t/2 while the model puts its tension at the film's surface on radius R, so the
#: wrap pressure T/R is off by about t/(2R), and the web's outer fibre is strained by t/(2R)
#: in bending (1 %: the geometry then errs by more than 1 %).
THICK_WEB_RATIO = 0.01
#: Largest t/(2R) webfem solves at all: beyond it the web's outer fibre would be strained by
#: more than 10 % in bending and the thin-web wrap pressure T/R is off by as much (a stated
#: choice: no paper, film or foil bends that far elastically).
THICK_WEB_LIMIT = 0.1
#: Largest through-thickness compression, as a share of the web's thickness, the contact
#: law's linear spring base E_b/t is taken to describe without a warning (a stated choice:
#: the law is linear in the compression and has no hardening as the web densifies).
COMPRESSION_RATIO = 0.1


def thick_web_warning(case, h_min) -> str | None:
    """Where the thin-web assumptions fail: the web thick against the roller (t/(2R) above
    :data:`THICK_WEB_RATIO`) or its surface compressed by more than
    :data:`COMPRESSION_RATIO` of its thickness (``h_min`` [m] the stated minimum gap, below
    0 where the web rests compressed). None where both hold."""
    t, R = case.web.thickness, case.roller.radius
    parts = []
    if t / (2.0 * R) > THICK_WEB_RATIO:
        parts.append(f"web.thickness / (2 roller.radius) = {t / (2.0 * R):.2g} (t = {t:g} m, "
                     f"R = {R:g} m): the web bends to an outer-fibre strain of "
                     f"{100 * t / (2.0 * R):.2g} % and its mid-plane runs on radius R + t/2, "
                     "which the thin-web model (tension at the film's surface, wrap pressure "
                     "T/R) leaves out: its wrap pressure is off by about that share")
    if h_min is not None and h_min < 0.0 and -h_min > COMPRESSION_RATIO * t:
        parts.append(f"the web's surface is compressed by {-h_min:.3g} m, "
                     f"{100 * -h_min / t:.0f} % of its thickness web.thickness = {t:g} m: "
                     "the contact law's linear spring base E_b/t has no hardening as the web "
                     f"densifies (taken to hold below {100 * COMPRESSION_RATIO:.0f} %)")
    return "; ".join(parts) + "; the answer is outside the model's assumptions" if parts else None
