"""The weak forms of the foil bearing, each declared once, and the coefficients that carry the
physics into them.

Scaled variables (Eshel-Elrod): X = x / (R eps^(1/3)), Z = z / (R eps^(1/3)) across the width,
H = h / (R eps^(2/3)), P = (p - p_a) R / T. Unknowns: the film pressure P (field "p") and the
web deflection W (field "w"); the web's gap is H_web = W + D(X) with the roller's departure
D = (|X| - beta/2)^2 / 2 outside the wrap, 0 inside, and the film's gap H = H_web + Delta(Z)
(Delta the groove depth on a grooved roller, :mod:`webfem.fem.grooves`; 0 on a land).

**Film** (:data:`FILM` + :data:`SINK`): Reynolds, compressible, with first-order slip and the
Darcy sink through the web (physics.md, divided by p_a):

    div(((1 + d P) H^3 + s H^2) grad P) = d((1 + d P) H)/dX + K (1 + ds P) P,

weak, with test function q: int (D P_X - C) q_X + D P_Z q_Z + K (1 + ds P) P q, where
D = (1 + d P) H_f^3 + s H_f^2 (Poiseuille conductance with slip) and C = (1 + d P) H_f
(Couette flux); H_f is the flow gap (:func:`flow_gap`): the mean local air gap over the
asperity heights E[(H - z)+] (air still flows through the roughness where the web rests on
it), or, with the roughness flow switched off, H floored smoothly (:func:`film_gap`). d = T / (R p_a) (0: the
incompressible limit), K = 12 k / (R t eps^(4/3)), s = 6 a lambda_a / (R eps^(2/3)), ds = d/2
for isothermal Darcy flow through the web, d for the paper's sink. P = 0 on the ends and the
web edges; dP/dZ = 0 on symmetry lines. In 1-D the Z terms are absent.

**Web** (:data:`WEB` + :data:`COUPLING`): the web's equilibrium (paper's Eq. 16), a membrane
with tension and, when Dn > 0, a beam:

    Pbar + Pc(H_web) = chi - W'' + Dn (H_web'''')

weak, with test function v: int W' v' + Dn (W'' - chi) v'' - (Pc - chi) v - Pbar v, where
chi = 1 in the wrap (the T/R term) and 0 outside, Dn = D / (T (R eps^(1/3))^2), Pc the asperity
contact pressure (:func:`contact_law`, on the lands only of a grooved roller: times the land
fraction) and Pbar the film pressure averaged over the width (1/width) int P dZ, which the
coupling form integrates over the film's points. W = 0 at both ends; bending acts on the
web's true curvature, so W'' = 0 there is natural.

Each form is data (:mod:`webfem.fem.weakform`): its residual terms and Jacobian blocks name
their coefficients, computed here by :func:`film_coefficients`, :func:`web_coefficients` and
:func:`coupling_coefficients` at the quadrature points. Adding a physics term is one line in a
declaration and one in its coefficients function; the scikit-fem forms and the vectorised
assembly are both generated from the declarations.
"""

from __future__ import annotations

import numpy as np

from ..physics.roughness import mean_excess, mean_gap, wet_share
from .weakform import Block, Term, WeakForm

__all__ = ["FILM", "SINK", "WEB", "COUPLING", "film_coefficients", "film_residual_coefficients",
           "film_jacobian_coefficients", "web_coefficients",
           "coupling_coefficients", "flow_gap", "film_gap", "contact_law", "departure",
           "in_wrap", "upwind_switch", "streamline_diffusion", "UPWIND_PE", "UPWIND_POWER"]

#: Reynolds' flux terms and their derivatives in P and in the web (dH/dW = 1).
FILM = WeakForm("film", ("p", "w"),
                terms=(Term("p", "dx", "flux_x"), Term("p", "dz", "flux_z")),
                blocks=(Block("p", "dx", "p", "dx", "jDX"), Block("p", "dx", "p", "val", "jX"),
                        Block("p", "dz", "p", "dz", "jD"), Block("p", "dz", "p", "val", "jZ"),
                        Block("p", "dx", "w", "val", "hX"),
                        Block("p", "dz", "w", "val", "hZ")))
#: The Darcy sink through the web, apart so it can be lumped (P1: nodal quadrature keeps the
#: film operator an M-matrix where the sink dominates, so the pressure cannot oscillate).
SINK = WeakForm("sink", ("p",), terms=(Term("p", "val", "sink"),),
                blocks=(Block("p", "val", "p", "val", "jS"),))
#: The web's membrane, bending and contact terms.
WEB = WeakForm("web", ("w",),
               terms=(Term("w", "dx", "dW"), Term("w", "dxx", "bend"),
                      Term("w", "val", "-load")),
               blocks=(Block("w", "dx", "w", "dx", 1.0), Block("w", "dxx", "w", "dxx", "Dn"),
                       Block("w", "val", "w", "val", "k_c")))
#: The film's load on the web, the width average of P, integrated over the film's points.
COUPLING = WeakForm("coupling", ("p", "w"), terms=(Term("w", "val", "-pbar"),),
                    blocks=(Block("w", "val", "p", "val", "-inv_width"),))


def departure(x, beta):
    """Scaled roller departure D(X) = (|X| - beta/2)^2 / 2 outside the wrap (Eq. 18)."""
    out = np.maximum(np.abs(x) - 0.5 * beta, 0.0)
    return 0.5 * out**2


def in_wrap(x, beta):
    """1 inside the wrap |X| < beta/2, 0 outside (the T/R term of Eq. 16)."""
    return (np.abs(x) < 0.5 * beta).astype(float)


def film_gap(H, floor):
    """Smooth maximum of H and ``floor``: f + ((H - f) + sqrt((H - f)^2 + f^2)) / 2, i.e. H
    where H >> f, f/2 + ... near it and f where H << f; returns it and its derivative."""
    d = H - floor
    root = np.sqrt(d * d + floor * floor)
    return floor + 0.5 * (d + root), 0.5 * (1.0 + d / root)


def contact_law(H, prm):
    """Scaled contact pressure Pc(H) = p_c R/T and stiffness -dPc/dH: (E_b/t) E[(z - H)+]
    scaled (:func:`webfem.physics.roughness.mean_excess`), Eq. 10 for the exponential
    heights (``prm['law']`` 0: Pc = c exp(-H/S) for H >= 0) and its Gaussian counterpart
    (``law`` 1), both continued past full asperity compression (H < 0: the web rests with its
    surface compressed; exponential: Pc = c (exp(H/S) - 2 H/S)). ``prm['contact']`` 0
    switches contact off."""
    on, c, S = prm["contact"], prm["c"], prm["S"]
    law = "gaussian" if prm.get("law", 0) == 1 else "exponential"
    # exponential: c = E_b sigma R / (2 t T), so (E_b/t) (R/T) h_scale = 2c/S; Gaussian: c
    k = on * (c if law == "gaussian" else 2.0 * c / S)
    with np.errstate(over="ignore"):   # a wild line-search trial: inf, then rejected
        return k * mean_excess(H, S, law), k * (1.0 - wet_share(H, S, law))


def flow_gap(H, prm):
    """The gap the air flows through and its derivative in H: with ``prm['flow']`` 1 the
    flow gap E[(H - z)+] over the asperity heights (:func:`webfem.physics.roughness.
    mean_gap`: positive by construction, H to within 2.5 % of S above 3 S), else H with the
    numerical floor of :func:`film_gap`."""
    Hf, wet = _flow_gap(H, prm)
    return Hf, wet(H) if callable(wet) else wet


def _flow_gap(H, prm):
    """:func:`flow_gap` with its derivative as a function of H where it costs a pass of its
    own (the roughness's wet share: a Jacobian's only)."""
    if prm.get("flow", 0):
        law = "gaussian" if prm.get("law", 0) == 1 else "exponential"
        return mean_gap(H, prm["S"], law), lambda h: wet_share(h, prm["S"], law)
    return film_gap(H, prm["floor"])


#: The cell Peclet number Pe = b h / (2 D) of the film's convection (b = d(Couette)/dP =
#: a d H_f the velocity at which the Couette flux carries the density 1 + d P, h the cell's
#: length along X, D the conductance) at which the streamline diffusion is half on. Chosen by
#: measurement: Galerkin P2 stays monotone to Pe ~ 2 for a layer, but films whose pressure
#: has no layer there are resolved at higher Pe: the bundled board case has Pe up to 5 on its
#: mesh and 10 on the error estimate's coarser one, and a threshold of 2 moved its h_min by
#: 5 % (its stated error 0.03 %), 10 its error estimate; at 30 it is unchanged to 1e-13.
#: Where the 1 mm board rests, Pe is 1e4-1e15, far above.
UPWIND_PE = 30.0
#: How fast it switches on: psi(t) = t^m / (1 + t^m), t = Pe / UPWIND_PE. The extra
#: diffusion is D Pe psi = D O(Pe^(m+1)) where Pe << UPWIND_PE: 3e-18 of D at Pe = 3, 3e-9 at
#: Pe = 10.
UPWIND_POWER = 16


def upwind_switch(t):
    """psi(t) = t^m / (1 + t^m), m = :data:`UPWIND_POWER`, evaluated without overflow (the
    cell Peclet number reaches 1e15 where a web rests deep on its asperities), and
    m psi (1 - psi), which is t dpsi/dt. t <= 0 (a vanishing or negative conductance: only a
    wild trial state) counts as infinite: psi = 1.

    >>> [round(float(v), 6) for v in upwind_switch(np.array([0.1, 1.0, 1e15]))[0]]
    [0.0, 0.5, 1.0]
    """
    t = np.asarray(t, float)
    m = UPWIND_POWER
    with np.errstate(divide="ignore", over="ignore"):
        t = np.where(t > 0.0, t, np.inf)
        small = t < 1.0
        tm = np.where(small, t, 1.0 / t) ** m     # <= 1: no overflow either way
        psi = np.where(small, tm / (1.0 + tm), 1.0 / (1.0 + tm))
    return psi, m * psi * (1.0 - psi)


def streamline_diffusion(Hf, D, hx, prm):
    """The film's streamline diffusion nu along X at points in cells of length ``hx`` with
    flow gap ``Hf`` and conductance ``D``, and its derivatives in D and in Hf (at fixed D):
    ``(nu, nu_D, nu_Hf)``.

    nu = (b h / 2) psi(Pe / UPWIND_PE), b = a d H_f the velocity at which the Couette flux
    carries the density 1 + d P, Pe = b h / (2 D) the cell Peclet number. Where the web rests
    deep on its asperities (the flow gap ~ e^-26 S: 1 mm board on the base roller) Pe
    reaches 1e7-1e15 and the Galerkin pressure oscillates from node to node (below vacuum);
    there nu -> b h / 2, full upwinding, which brings the effective Peclet number down to
    1. Where Pe is small (every flying film: Pe <= 0.6 on the bundled cases; the bundled
    board, resting 0.6 sigma deep: Pe <= 5) nu is D O((Pe / UPWIND_PE)^16) Pe: it changes
    nothing and keeps the discretisation's order (tests/test_upwind.py)."""
    nu, parts = _streamline(Hf, D, hx, prm)
    return (nu,) + _streamline_derivatives(parts)


def _streamline(Hf, D, hx, prm):
    """:func:`streamline_diffusion`'s nu, and what its derivatives are made of (for
    :func:`_streamline_derivatives`, asked for only where a Jacobian is)."""
    a, d = prm.get("couette", 1.0), prm["d"]
    D = np.asarray(D, float)
    ok = D > 0.0
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        inv = np.where(ok, 1.0 / np.where(ok, D, 1.0), 0.0)
    bh2 = 0.5 * a * d * hx                        # b h / 2 per unit flow gap
    psi, dpsi = upwind_switch(bh2 * Hf * inv / UPWIND_PE)
    return bh2 * Hf * psi, (Hf, inv, bh2, ok, psi, dpsi)


def _streamline_derivatives(parts):
    """:func:`streamline_diffusion`'s ``(nu_D, nu_Hf)`` from :func:`_streamline`'s parts."""
    Hf, inv, bh2, ok, psi, dpsi = parts
    dpsi = np.where(ok, dpsi, 0.0)
    # t = bh2 Hf / (D UPWIND_PE): dpsi/dD = -(t dpsi/dt) / D, dpsi/dHf = (t dpsi/dt) / Hf;
    # where full upwinding is reached (dpsi = 0) nu no longer depends on D, even where 1/D
    # overflows (a denormal conductance: inf x 0 made the Jacobian NaN)
    with np.errstate(invalid="ignore", over="ignore"):
        nu_D = np.where(dpsi > 0.0, -(bh2 * Hf * inv) * dpsi, 0.0)
    return nu_D, bh2 * (psi + dpsi)


def film_coefficients(H, P, PX, PZ, prm, newton: bool = True, hx=None) -> dict:
    """The coefficients of :data:`FILM` and :data:`SINK` at quadrature points: the film's
    gap ``H`` there (web gap plus groove depth), the pressure ``P`` and its gradient ``PX``,
    ``PZ`` (0 in 1-D). ``newton=False`` gives Picard's operator instead of the exact
    Jacobian: rho = 1 + d P and H^3 frozen at the state.

    ``hx``: the length along X of the cell each point lies in; with it the X flux gets the
    streamline diffusion of :func:`streamline_diffusion`, which vanishes to high order where
    the cell Peclet number is small. None (the default): no streamline
    diffusion (the manufactured solutions, the sink's own part).

    :func:`film_residual_coefficients` then :func:`film_jacobian_coefficients`: the same
    numbers, the residual's alone where no Jacobian is asked for."""
    out, parts = film_residual_coefficients(H, P, PX, PZ, prm, hx)
    out.update(film_jacobian_coefficients(parts, newton))
    return out


def film_residual_coefficients(H, P, PX, PZ, prm, hx=None) -> tuple[dict, tuple]:
    """The residual's coefficients of :data:`FILM` and :data:`SINK` (``flux_x``, ``flux_z``,
    ``sink``; arguments as :func:`film_coefficients`') and what the Jacobian's are made of,
    for :func:`film_jacobian_coefficients`. Why apart: Newton's line search and chord steps
    ask for residuals at states whose Jacobian is never assembled (10 of the 15 2-D states
    of the base case's cold solve), and the Jacobian's coefficients were about half of the
    work."""
    d, K, s = prm["d"], prm["K"], prm.get("slip", 0.0)
    ds = prm.get("ds", d)
    # the Couette (entrainment) flux scaled by a (1: the physics; below 1 only on the way to
    # a resting web, :func:`webfem.fem.continuation.film_strength`: a = 0 has P = 0)
    a = prm.get("couette", 1.0)
    Hf, wet = _flow_gap(H, prm)
    rho, rho_s = 1.0 + d * P, 1.0 + ds * P
    Hf2 = Hf**2
    Hf3 = Hf2 * Hf
    diffusion = rho * Hf3 + s * Hf2           # Poiseuille conductance with slip
    nu, upwind = 0.0, None
    if hx is not None and a * d > 0.0:
        nu, upwind = _streamline(Hf, diffusion, hx, prm)
    diffusion_x = diffusion + nu
    out = {
        "flux_x": diffusion_x * PX - a * rho * Hf,  # Poiseuille minus Couette along X
        "flux_z": diffusion * PZ,
        "sink": K * rho_s * P,
    }
    return out, (H, P, PX, PZ, prm, Hf, wet, rho, rho_s, Hf2, Hf3, diffusion, diffusion_x,
                 upwind)


def film_jacobian_coefficients(parts, newton: bool = True) -> dict:
    """The Jacobian's coefficients of :data:`FILM` and :data:`SINK` from the ``parts`` of
    :func:`film_residual_coefficients` (``newton`` as :func:`film_coefficients`')."""
    (H, P, PX, PZ, prm, Hf, wet, rho, rho_s, Hf2, Hf3, diffusion, diffusion_x,
     upwind) = parts
    d, s = prm["d"], prm.get("slip", 0.0)
    ds, a, K = prm.get("ds", d), prm.get("couette", 1.0), prm["K"]
    above = wet(H) if callable(wet) else wet
    dD = 3.0 * rho * Hf2 + 2.0 * s * Hf       # the conductance's derivative in H
    nt = 1.0 if newton else 0.0
    nu_P, nu_H = 0.0, 0.0
    if upwind is not None:
        nu_D, nu_Hf = _streamline_derivatives(upwind)
        nu_P = nu_D * d * Hf3                     # dnu/dP through D
        nu_H = nu_Hf + nu_D * dD                  # dnu/dHf, directly and through D
    return {
        # dF/dP: D grad dp + dp (d Hf^3 grad P - d Hf e_X) + K (1 + 2 ds P) dp, with the
        # streamline diffusion in the X flux
        "jD": diffusion,
        "jDX": diffusion_x,
        "jX": nt * ((d * Hf3 + nu_P) * PX - a * d * Hf),
        "jZ": nt * d * Hf3 * PZ,
        "jS": K * (rho_s + nt * ds * P),
        # dF/dH, which is dF/dW: (dD/dH grad P) . grad q - rho q_X
        "hX": above * (nt * (dD + nu_H) * PX - a * rho),
        "hZ": above * nt * dD * PZ,
    }


def web_coefficients(x, W, dW, ddW, prm, geometry=None) -> dict:
    """The coefficients of :data:`WEB` at quadrature points x: the web deflection ``W`` and
    its first two X-derivatives there. ``geometry``: ``(departure(x, beta), in_wrap(x,
    beta))`` when the caller keeps them (they depend on the mesh only). On a grooved roller
    the asperities touch the lands only (``prm['land']``, the land fraction)."""
    D, chi = geometry if geometry is not None else (departure(x, prm["beta"]),
                                                    in_wrap(x, prm["beta"]))
    Pc, kc = contact_law(W + D, prm)
    land = prm.get("land", 1.0)
    return {"dW": dW, "bend": prm["Dn"] * (ddW - chi), "load": land * Pc - chi,
            "k_c": land * kc, "Dn": prm["Dn"], "chi": chi}


def coupling_coefficients(P, width: float) -> dict:
    """The coefficients of :data:`COUPLING`: the film pressure at the film's points over the
    width it is averaged on (1 in 1-D)."""
    return {"pbar": P / width, "inv_width": 1.0 / width}
