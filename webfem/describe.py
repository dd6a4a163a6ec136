"""The readable terminal summary of a :class:`webfem.result.Result`."""

from __future__ import annotations

import math

from .physics.contact import TAIL_SIGMAS, beyond_the_surface
from .physics.effects import margin_range, margin_verdict

__all__ = ["describe", "verdict", "idler_verdict", "small_text", "traction_text", "error_text", "resting_text",
           "contact_gap_text", "level_words", "regime_text"]

_NAMES = {"h_center": "h_center", "h_min": "h_min", "mu": "mu",
          "contact_share": "contact share"}


def error_text(s) -> str | None:
    """The stated errors of a summary on one line, or None where it states none:
    ``h_center 0.00032, h_min 4.1e-05, mu 0.0003, contact share 8.5e-05 (...)``: two digits
    (one rounded 1.62 to "2")."""
    # NaN: not stated (a fit with too few hold-out points), as None
    values = {q: v if (v := s.get(f"error_{q}")) is not None and v == v else None
              for q in _NAMES}
    if all(v is None for v in values.values()):
        return None
    parts = [f"{_NAMES[q]} {v:.2g}" for q, v in values.items() if v is not None]
    return ", ".join(parts) + (" (gaps against max(h, sigma), mu against max(|mu|, 0.1 mu_cc), "
                               "the contact share absolute)")


def resting_text(s) -> str | None:
    """Why a gap is below zero, or None where the web does not rest on the roller:
    ``the web rests on the asperities, pressed 2.25 um into them``.

    A nominal gap h < 0 is the web's mean surface plane below the roller's crest, its
    asperities and surface layer compressed by -h (docs/model.md, "Webs that rest on the
    roller"): an answer, but one a reader takes for an error unless it is said next to it.
    """
    depth = s.get("compression")
    if depth is None and s.get("h_min") is not None and s.h_min < 0:
        depth = -s.h_min
    if not s.get("resting") and not (depth and depth > 0):
        return None
    return (f"the web rests on the asperities, pressed {depth * 1e6:.3g} um into them: a gap "
            "below 0 is their compression")


def contact_gap_text(s) -> str:
    """What a negative contact gap h_c means, or "" where h_c >= 0."""
    if s.get("h_c") is None or s.h_c >= 0:
        return ""
    return (f" (below 0: contact alone carries T/R only with the web pressed "
            f"{-s.h_c * 1e6:.3g} um into the asperities)")


def level_words(h_c: float, sigma: float) -> tuple[str, str]:
    """What the levels h_c and 3 sigma mean for the paper's regime by the gap (boundary
    below h_c, mixed up to 3 sigma, fluid above; h_c wins where they cross), as
    ``(h_c's, 3 sigma's)``: where h_c lies above 3 sigma there is no mixed band and a gap
    between them is fluid only once it clears h_c.

    >>> level_words(4.94e-6, 4e-6)
    ('boundary below', 'fluid above')
    >>> level_words(2.2e-6, 0.2e-6)
    ('boundary below, fluid above', 'no mixed band: below h_c')
    """
    if h_c is not None and sigma is not None and h_c >= 3.0 * sigma:
        return "boundary below, fluid above", "no mixed band: below h_c"
    return "boundary below", "fluid above"


#: The contact load share a fluid regime's summary names (below it the words agree).
CONTACT_NOTED = 0.005


def regime_text(s, case=None) -> str:
    """The regime line of :func:`describe`: the levels, the paper's regime by the gap with
    its wrap shares, and, where they tell another story, what the contact model's load share
    says (a fluid regime by the gap whose asperities still carry load: the contact law's
    heights have no cut-off at 3 sigma)."""
    um = 1e6
    bands = ("boundary below h_c, mixed up to 3 sigma, fluid above"
             if level_words(s.h_c, s.sigma)[1] == "fluid above" else
             "h_c is above 3 sigma: boundary below h_c, fluid above, no mixed band")
    text = (f"  h_c = {s.h_c * um:.3f} um{contact_gap_text(s)}, 3 sigma = "
            f"{3 * s.sigma * um:.3f} um; regime {s.regime} by the gap (the paper's "
            f"classification: {bands}; wrap shares: boundary {s.share_boundary:.2f}, "
            f"mixed {s.share_mixed:.2f}, fluid {s.share_fluid:.2f})")
    share = s.get("contact_share")
    if s.regime == "fluid" and share is not None and share >= CONTACT_NOTED:
        follows = ("; mu follows this load share, not the regime"
                   if case is not None and case.friction_variant == "loads" else "")
        text += (f"\n  yet by the contact model the asperities carry {100 * share:.1f} % of "
                 f"the wrap load: its asperity heights have no cut-off at 3 sigma{follows}")
    return text



#: Below this a margin, a traction or mu_onset prints as "< 0.001": 1e-112 is no figure an
#: engineer reads, and the JSON keeps the number.
SMALL = 1e-3


def small_text(value: float, spec: str = ".2g") -> str:
    """``value`` formatted by ``spec``, or ``< 0.001`` where it is positive and below
    :data:`SMALL` (0 stays 0).

    >>> small_text(7.93e-112), small_text(0.0), small_text(1.234, ".3g"), small_text(2e-3)
    ('< 0.001', '0', '1.23', '0.002')
    """
    if value is not None and 0.0 < value < SMALL:
        return f"< {SMALL:g}"
    return format(value, spec)


def idler_verdict(s, case=None) -> tuple[str, str] | None:
    """The idler's answer from a summary, as ``(word, sentence)``: the word ``holds``,
    ``unsure``, ``slips`` or ``not judged``, the sentence with the traction needed and
    available; None where the case states no idler load. One text for ``webfem solve``
    (:func:`verdict`) and the report's headline and warnings.

    With the ``case``, ``unsure`` where mu's stated error puts the margin on both sides of
    1 (:func:`webfem.physics.effects.margin_range`), or where a margin above 1 rests on
    asperities the exponential law puts beyond :data:`~webfem.physics.contact.TAIL_SIGMAS`
    sigma (:func:`~webfem.physics.contact.beyond_the_surface`). The check is at the onset of slip,
    U_r = U_w. Where the case's speeds differ the web already slides on the roller, which is
    then driven (or slipping), not an idler turning with the web, and its film is not an
    idler's: the sentence says so, and words what an idler would do from the second solve
    at U_r = U_w that supplied the margin (``idler_basis``), or that this solve cannot judge
    it.
    """
    if s.get("delta_T_required") is None:
        return None
    sliding = case is not None and case.U_slide != 0.0
    if case is not None and case.web.speed <= 0.0:
        return "not judged", ("idler check: not judged; the web stands still, so this roller "
                              "is no idler turning with it (an idler's check needs "
                              "web.speed > 0)")
    need = f"needs {small_text(s.delta_T_required, '.3g')} N/m"
    margin = s.get("slip_margin")
    if not sliding and (margin is None or math.isnan(margin)):
        return "not judged", ("idler check: not judged; this solve has no answer to judge "
                              f"it by ({need})")
    if sliding:
        basis = s.get("idler_basis")
        head = (f"idler check at the onset of slip (U_r = U_w; here the web slides at U_s = "
                f"{case.U_slide:.4g} m/s, so this roller is driven or already slipping, not "
                "an idler turning with the web")
        if s.slip_margin is None:
            why = (basis or "this solve's film is not an idler's (an idler turns with the "
                   "web and entrains other air): `webfem solve` with roller.speed = "
                   "web.speed, or `webfem idler`, judges it")
            return "not judged", f"{head}): not judged; {why} ({need})"
        head += f"; from {basis}" if basis else ""
        head += "): an idler would "
    else:
        head = "idler "
    error = s.get("error_mu_onset") if sliding else s.get("error_mu")
    carry = (f"can carry {small_text(s.delta_T_available, '.3g')} N/m at mu_onset "
             f"{small_text(s.mu_onset, '.3g')}")
    if case is not None and error is not None:
        low, high = margin_range(case, s.delta_T_required, s.mu_onset, error)
        if margin_verdict(low, high) == "unsure":
            return "unsure", (f"{head}{'be ' if sliding else ''}unsure: margin "
                              f"{small_text(s.slip_margin)}, but mu's stated error allows "
                              f"{small_text(low)} to {small_text(high)} ({need}, {carry}); "
                              "a finer model decides")
    share = s.get("idler_contact_share") if sliding else s.contact_share
    if (s.slip_margin >= 1.0 and case is not None
            and beyond_the_surface(case, s.h_c, share)):
        # the margin rests on asperities the exponential law puts above any real surface
        return "unsure", (f"{head}{'be ' if sliding else ''}unsure: margin "
                          f"{small_text(s.slip_margin)} ({need}, {carry}), but only by the "
                          f"exponential heights' tail: h_c = {s.h_c / s.sigma:.3g} sigma, "
                          f"beyond {TAIL_SIGMAS:g} sigma where no surface has asperities "
                          "(see the warning); friction.distribution = \"gaussian\" decides")
    if s.slip_margin >= 1.0:
        return "holds", (f"{head}{'hold' if sliding else 'holds'} with margin "
                         f"{s.slip_margin:.2g} ({need}, {carry})")
    return "slips", (f"{head}{'slip' if sliding else 'slips'}: {need}, can carry "
                     f"{small_text(s.delta_T_available, '.3g')} N/m (margin "
                     f"{small_text(s.slip_margin)}, mu_onset {small_text(s.mu_onset, '.3g')})")


def verdict(s, case=None) -> str:
    """The idler's one-line answer for the terminal (:func:`idler_verdict`), indented."""
    said = idler_verdict(s, case)
    return "" if said is None else "  " + said[1]


def traction_text(s, case) -> str:
    """What the headline mu and delta_T are: the onset traction where nothing slides, the
    traction at the sliding speed where a moving web slides (the two differ, see
    docs/model.md, "Traction at a slip and at the onset of slip"); "" in the paper's rig."""
    if s.mu_film is not None:
        return (": the traction available at the onset of slip (nothing slides, U_s = 0; "
                "mu_onset = mu_cc x contact share)")
    if case.web.speed > 0.0 and case.U_slide > 0.0:
        return (f": the traction at the sliding speed U_s = {case.U_slide:.4g} m/s (Eq. 29's "
                "boundary friction (2/pi) mu_cc atan(U_s/C) falls to 0 with U_s; the traction "
                "available at the onset of slip, mu_cc x contact share, is another number: "
                "docs/model.md)")
    return ""


def above_mu_cc_text(s, case) -> str:
    """Why a mu above the dry-friction constant mu_cc is an answer ("" when it is not
    above): mu is the traction per unit wrap load T_eff/R, and both parts can exceed what
    the asperities give at the wrap load (README, "Closed form": a mu a little above mu_cc
    is an answer)."""
    mu_cc = case.friction.mu_cc
    if not (s.mu is not None and s.mu > mu_cc):
        return ""
    return (f"  mu is above friction.mu_cc = {mu_cc:g}: mu is the traction over the wrap "
            "load T_eff/R; the air sheared between the asperities adds its drag to the "
            "boundary friction, and the asperities may carry more than T_eff/R where the "
            "film's pressure is below ambient or the web's bending presses the wrap's ends")


def judged_text(s) -> str:
    """``largest stated error 0.00031 <= 0.01 (every quantity judged)`` for auto's choice."""
    what = "every quantity judged" if s.quantity == "all" else f"{s.quantity} judged"
    if s.estimated_error is None:
        return f"error not estimated; {what}"
    sign = "<=" if s.estimated_error <= s.tolerance else ">"
    return f"largest stated error {s.estimated_error:.2g} {sign} {s.tolerance:g}, {what}"


def describe(result) -> str:
    """Several lines: the operating point, Eq. 21's range, the gaps, the regime, mu and
    delta_T, how the numbers were obtained, and every warning."""
    s, c = result.summary, result.case
    um = 1e6
    lines = [
        f"webfem {s.model}: R = {c.roller.radius:g} m, L = {c.web.width:g} m, "
        f"T = {c.web.tension:g} N/m, B = {c.wrap.angle_deg:g} deg, "
        f"U_r = {c.roller.speed:g} m/s, U_w = {c.web.speed:g} m/s",
        f"  lambda = {s.lambda_:.3g}, beta = {s.beta:.3g}, Eq. 21 range "
        + ("met" if s.eq21_valid else "NOT met (beta > 6 and lambda > 7)"),
        f"  gap: inlet {s.h_inlet * um:.3f} um, centre {s.h_center * um:.3f} um, "
        f"outlet {s.h_outlet * um:.3f} um, minimum {s.h_min * um:.3f} um"
        + (f" ({resting_text(s)})" if resting_text(s) else ""),
        regime_text(s, c),
        f"  mu = {s.mu:.4f}, tension increase before slip delta_T = {s.delta_T:.3f} N/m"
        + traction_text(s, c),
        *([above] if (above := above_mu_cc_text(s, c)) else []),
        *([f"  the film's own drag at these speeds (its pressure-driven shear): mu_film = "
           f"{s.mu_film:.4f}, delta_T_film = {s.delta_T_film:.3f} N/m"]
          if s.mu_film is not None else []),
        f"  converged = {s.converged}, iterations = {s.iterations}, "
        f"n_dofs = {s.n_dofs}, time = {s.solve_time_s * 1e3:.3f} ms",
    ]
    if s.solver_message and (not s.converged or any(
            why in s.solver_message for why in ("rounding floor", "balanced stopping"))):
        # converged above the tolerance (at the residual's rounding floor, or stopped where
        # the algebraic error is negligible) or not at all: the residual printed below is
        # not the tolerance's, so the reason goes beside it
        lines.append(f"  solver: {s.solver_message}")
    errors = error_text(s)
    failed = any(w.startswith("no mesh error estimate") for w in s.warnings)
    lines.append(f"  stated error: {errors}; {s.error_basis}" if errors else
                 "  stated error: none (no mesh error estimate could be made: the warning "
                 "below says why; treat the answer as unverified)" if failed else
                 f"  stated error: none ({s.error_basis})" if s.error_basis else
                 "  stated error: none (no estimate was made)")
    if s.mesh is not None:
        lines.append(f"  {s.method or ''} on {s.mesh}; residual {s.residual:.2e}; contact "
                     f"carries {100 * (s.contact_share or 0.0):.1f} % of the wrap load")
    if s.groove_domain is not None:
        lines.append(f"  grooved roller: land fraction {s.land_fraction:.3f}; asperities carry "
                     f"{100 * (s.contact_share_lands or 0.0):.1f} % of the lands' load; "
                     f"{s.groove_domain}")
    if s.why is not None:
        lines.append(f"  model used: {s.model_used} ({judged_text(s)}): {s.why}")
    lines.append(f"  physics: T_eff = {s.T_eff:.4g} N/m, D = {s.bending_stiffness_used:.3g} N m; "
                 "effects: " + (", ".join(s.effects) or "none (the paper's model)"))
    if s.delta_T_required is not None:
        lines.append(verdict(s, c))
    for w in s.warnings:
        lines.append(f"  warning: {w}")
    return "\n".join(lines)
