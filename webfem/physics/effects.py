"""The effects beyond the paper's rig: which a case includes, the key that switches each
off, and what the closed form cannot carry; and the idler slip check.

Each effect is a named, switchable part of the model (physics.md, "Beyond the paper"):

=====================  ===============================  ====================================
effect                 on when                          off with
=====================  ===============================  ====================================
inertia                the web moves (U_w > 0)          ``web.density = 0``
bending                D > 0 (default E_m t^3/12)       ``web.bending_stiffness = 0``
slip                   ``air.slip = "first-order"``     ``air.slip = "none"``
isothermal-permeation  k > 0, ``web.permeation =        ``web.permeation = "paper"``
                       "isothermal"``
load-friction          ``friction.variant = "loads"``   ``friction.variant = "paper"``
roughness-flow         ``air.roughness_flow =           ``air.roughness_flow = "none"``
                       "mean-gap"``
spans                  ``wrap.ends = "span"``: the web  ``wrap.ends = "held"`` (at the
                       held at the neighbouring         entry and exit zones' ends, Eq. 20)
                       rollers, ``wrap.span`` away
=====================  ===============================  ====================================

``model.physics = "paper"`` switches them all off at once (an explicit D stays).

Examples
--------
>>> from webfem import Case
>>> included(Case())
('bending', 'slip', 'isothermal-permeation', 'load-friction', 'roughness-flow', 'spans')
>>> included(Case().updated({"model.physics": "paper"}))
()
"""

from __future__ import annotations

import math

import numpy as np

from .friction import delta_T_from_mu

__all__ = ["MU_SCALE", "margin_range", "margin_verdict", "EFFECTS", "SWITCH_OFF",
           "CLOSED_FORM_CARRIES", "included", "left_out", "idler_check", "idler_torque",
           "states_load",
           "traction_summary", "traction_summaries"]

#: Every effect, in the order tables list them.
EFFECTS = ("inertia", "bending", "slip", "isothermal-permeation", "load-friction",
           "roughness-flow", "spans")
#: The case keys that switch each effect off.
SWITCH_OFF = {"inertia": {"web.density": 0.0}, "bending": {"web.bending_stiffness": 0.0},
              "slip": {"air.slip": "none"}, "isothermal-permeation": {"web.permeation": "paper"},
              "load-friction": {"friction.variant": "paper"},
              "roughness-flow": {"air.roughness_flow": "none"},
              "spans": {"wrap.ends": "held"}}
#: What the closed form carries: T_eff (inertia), the friction from the loads on its Eq. 21
#: gap (contact and Couette shear with slip; no pressure-gradient shear) and, of the
#: roughness flow, the shear of the air through the roughness (Eq. 21's gap has no flow term).
CLOSED_FORM_CARRIES = ("inertia", "load-friction", "roughness-flow")


def included(case) -> tuple[str, ...]:
    """The effects ``case`` asks for (the FE models carry them all)."""
    on = {"inertia": case.web_inertia > 0.0, "bending": case.bending_used > 0.0,
          "slip": case.slip_model == "first-order",
          "isothermal-permeation": (case.permeation_model == "isothermal"
                                    and case.web.permeability > 0.0),
          "load-friction": case.friction_variant == "loads",
          "roughness-flow": case.roughness_flow_model == "mean-gap",
          "spans": case.span_used is not None}
    return tuple(name for name in EFFECTS if on[name])


def left_out(case) -> tuple[str, ...]:
    """The effects ``case`` asks for that the closed form cannot carry."""
    return tuple(e for e in included(case) if e not in CLOSED_FORM_CARRIES)


def idler_check(case, mu_onset: float) -> dict:
    """Traction an undriven roller needs against what it can carry (physics.md, "Will an
    idler slip?").

    delta_T_required = |M_d + J a / R| / (R L) [N/m]: the bearing and seal drag and the
    roller's angular acceleration per unit web width (:func:`idler_torque`: a line slowing
    down, a < 0, has the roller's inertia helping the drag). delta_T_available =
    T_eff (exp(mu_onset B) - 1) with ``mu_onset`` the friction coefficient at the onset of
    slip (small sliding speed: the boundary friction of Eq. 29 vanishes there, so the caller
    states it, e.g. mu_cc times the contact share of the wrap load). Returns the keys
    ``delta_T_required``, ``delta_T_available``, ``slip_margin`` (available / required) and
    ``mu_onset``, all None when the case states no drag torque and no acceleration.

    >>> from webfem import Case
    >>> c = Case().updated({"roller.drag_torque": 0.02, "roller.speed": 20.0,
    ...                     "web.speed": 20.0})
    >>> out = idler_check(c, 0.3)
    >>> round(out["delta_T_required"], 3), round(out["slip_margin"], 2)
    (10.39, 2.2)
    """
    R, L = case.roller.radius, case.web.width
    if not states_load(case):
        return dict(delta_T_required=None, delta_T_available=None, slip_margin=None,
                    mu_onset=None)
    required = idler_torque(case) / (R * L)
    available = case.tension_eff * math.expm1(mu_onset * case.B)
    # drag and inertia cancel exactly: the web need carry nothing, any traction holds
    margin = available / required if required > 0.0 else math.inf
    return dict(delta_T_required=required, delta_T_available=available,
                slip_margin=margin, mu_onset=mu_onset)


def states_load(case) -> bool:
    """Whether ``case`` states an idler load: a drag torque, or an inertia with a line
    acceleration (whatever their sum)."""
    r = case.roller
    return r.drag_torque > 0.0 or r.inertia * case.web.acceleration != 0.0


def idler_torque(case) -> float:
    """The torque the web must put on an idler, |M_d + J a / R| [N m] (:func:`idler_check`).

    The roller's equation: J alpha = R F - M_d, with F = delta_T L the web's pull on its
    surface (the tension difference across the wrap) and alpha = a / R while it turns with
    the line (no slip). So R F = M_d + J a / R: a line speeding up (a > 0) adds the inertia
    to the drag; one slowing down (a < 0) has the roller's inertia helping the drag, and
    where J |a| / R exceeds M_d the web must brake the roller instead, F < 0. Friction
    carries either sign, so the traction needed is the magnitude.

    >>> from webfem import Case
    >>> c = Case().updated({"roller.drag_torque": 0.05, "roller.inertia": 0.006})
    >>> [round(idler_torque(c.updated({"web.acceleration": a})), 4) for a in (5.0, -5.0)]
    [0.5955, 0.4955]
    """
    r = case.roller
    return abs(r.drag_torque + r.inertia * case.web.acceleration / r.radius)


def traction_summary(case, mu: float, contact_share: float) -> dict:
    """The traction keys of every model's summary: ``mu``, ``delta_T``, ``mu_film``,
    ``delta_T_film`` and the idler keys of :func:`idler_check`.

    Parameters
    ----------
    case : Case
        The operating point.
    mu : float
        The wrap-averaged friction coefficient at the stated speeds (what the model computed
        from the film and the contact).
    contact_share : float
        The share of the wrap load that asperity contact carries (0 to 1).

    Returns
    -------
    dict
        Where something slides (U_s = |U_r - U_w| > 0): ``mu`` as given, ``delta_T`` =
        T_eff (exp(mu B) - 1), ``mu_film`` and ``delta_T_film`` None; of the idler keys only
        ``delta_T_required`` (the roller's load): this film is not an idler's (an idler
        turns with the web, U_r = U_w, and entrains other air), so ``mu_onset``,
        ``delta_T_available`` and ``slip_margin`` are None
        (:func:`webfem.idler.idler_at_web_speed` solves the idler's own film). Where nothing slides
        (U_s = 0: an idler turning with the web) the traction at the stated speeds is only
        the film's pressure-driven drag, tiny and of either sign; a belt-formula measurement
        (pull the web until the roller slips) reads the traction available at the onset of
        slip instead. So there ``mu`` = ``mu_onset`` = mu_cc x ``contact_share`` (the
        asperities hold with the static mu_cc on the load they carry, the film with nothing)
        and ``delta_T`` = ``delta_T_available`` = T_eff (exp(mu_onset B) - 1), given even when
        the case states no idler load; the film's own drag goes to ``mu_film`` and
        ``delta_T_film``.

    Examples
    --------
    >>> from webfem import Case
    >>> idler = Case().updated({"roller.speed": 10.0, "web.speed": 10.0})
    >>> out = traction_summary(idler, -2e-4, 0.5)
    >>> round(out["mu"], 3), out["mu"] == out["mu_onset"], out["mu_film"]
    (0.15, True, -0.0002)
    >>> traction_summary(Case(), 0.137, 0.9)["mu_film"] is None
    True
    """
    T, B = case.tension_eff, case.B
    mu_onset = case.friction.mu_cc * contact_share
    idler = idler_check(case, mu_onset)
    delta_T = float(delta_T_from_mu(mu, T, B))
    if case.U_slide != 0.0:
        idler.update(dict.fromkeys(_FILM_IDLER_KEYS))
        return dict(mu=mu, delta_T=delta_T, mu_film=None, delta_T_film=None, **idler)
    available = T * math.expm1(mu_onset * B)
    idler.update(mu_onset=mu_onset, delta_T_available=available)
    return dict(mu=mu_onset, delta_T=available, mu_film=mu, delta_T_film=delta_T, **idler)


_IDLER_KEYS = ("delta_T_required", "delta_T_available", "slip_margin", "mu_onset")
#: The idler keys read from the film: where the web slides (U_s > 0) this film is not an
#: idler's (U_r = U_w entrains other air), so they are None; delta_T_required is the
#: roller's load and stands (:func:`webfem.idler.idler_at_web_speed` solves the idler's film).
_FILM_IDLER_KEYS = ("delta_T_available", "slip_margin", "mu_onset")


def traction_summaries(cases, mu, contact_share) -> list[dict]:
    """:func:`traction_summary` of many cases at once: the same numbers (to rounding), with
    the belt formula's exponentials evaluated on arrays (``mu`` and ``contact_share``: one
    value per case). For the vectorised models (:func:`webfem.models.fitted.solve_many`).

    >>> from webfem import Case
    >>> cases = [Case(), Case().updated({"roller.speed": 10.0, "web.speed": 10.0})]
    >>> many = traction_summaries(cases, [0.137, -2e-4], [0.9, 0.5])
    >>> [round(many[i]["delta_T"] - traction_summary(c, m, s)["delta_T"], 12)
    ...  for i, (c, m, s) in enumerate(zip(cases, [0.137, -2e-4], [0.9, 0.5]))]
    [0.0, 0.0]
    """
    rows = np.array([(c.tension_eff, c.B, c.friction.mu_cc, c.U_slide, idler_torque(c),
                      c.roller.radius, c.web.width, states_load(c)) for c in cases],
                    float).reshape(-1, 8)
    T, B, mu_cc, U_s, torque, R, L, loaded = rows.T
    mu = np.asarray(mu, float)
    mu_onset = mu_cc * np.asarray(contact_share, float)
    delta_T = delta_T_from_mu(mu, T, B)
    available = T * np.expm1(mu_onset * B)
    with np.errstate(divide="ignore", invalid="ignore"):
        required = torque / (R * L)
        margin = np.where(required > 0.0, available / required, np.inf)
    cols = [v.tolist() for v in (mu, delta_T, mu_onset, available, required, margin, U_s,
                                 loaded)]
    out = []
    for m, dT, onset, avail, req, marg, us, load in zip(*cols):
        idler = (dict(delta_T_required=req, delta_T_available=avail, slip_margin=marg,
                      mu_onset=onset) if load else dict.fromkeys(_IDLER_KEYS))
        if us != 0.0:
            idler.update(dict.fromkeys(_FILM_IDLER_KEYS))
            out.append(dict(mu=m, delta_T=dT, mu_film=None, delta_T_film=None, **idler))
        else:
            idler.update(mu_onset=onset, delta_T_available=avail)
            out.append(dict(mu=onset, delta_T=avail, mu_film=m, delta_T_film=dT, **idler))
    return out


#: mu's error is relative to mu, or to this fraction of mu_cc where mu is smaller (where
#: nothing slides mu is about 0, and a relative error of a near-zero value means nothing).
MU_SCALE = 0.1


def margin_range(case, required: float, mu: float, error_mu: float | None):
    """The slip margin's range ``(low, high)`` that mu's stated error allows: the available
    tension increase T_eff (exp(mu B) - 1) at mu -/+ the error (``error_mu`` relative to
    the larger of |mu| and :data:`MU_SCALE` mu_cc; mu at least 0),
    over the ``required`` one [N/m]. Without a stated error, the margin itself both ways;
    infinite where nothing is required (the drag and the inertia cancel: 0.05 N m against
    0.006 kg m^2 x -0.5 m/s^2 / 0.06 m).

    >>> import math
    >>> from webfem import Case
    >>> c = Case().updated({"roller.speed": 10.0, "web.speed": 10.0})
    >>> lo, hi = margin_range(c, 1.0, 0.1, 0.5)
    >>> [round(v / (c.tension_eff * math.expm1(m * c.B)), 12) for v, m in ((lo, 0.05), (hi, 0.15))]
    [1.0, 1.0]
    """
    if not required > 0.0:      # drag and inertia cancel: nothing to carry, nothing to slip
        return math.inf, math.inf
    T, B = case.tension_eff, case.B
    margin = T * math.expm1(max(mu, 0.0) * B) / required
    if error_mu is None or not math.isfinite(error_mu) or not math.isfinite(margin):
        return margin, margin
    d = error_mu * max(abs(mu), MU_SCALE * case.friction.mu_cc)
    return (T * math.expm1(max(mu - d, 0.0) * B) / required,
            T * math.expm1(max(mu + d, 0.0) * B) / required)


def margin_verdict(low: float, high: float) -> str:
    """``holds`` where the slip margin's whole stated range (:func:`margin_range`) is at or
    above 1, ``SLIPS`` where all of it is below 1, else ``unsure``.

    >>> margin_verdict(1.2, 1.5), margin_verdict(0.2, 0.9), margin_verdict(0.8, 1.3)
    ('holds', 'SLIPS', 'unsure')
    """
    return "holds" if low >= 1.0 else "SLIPS" if high < 1.0 else "unsure"
