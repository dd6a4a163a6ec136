"""Friction between web and roller (paper's Eqs. 25-31) and Euler's belt formula.

mu = mu_c chi_c + mu_f chi_f, with mu_c the asperity friction (Eq. 29), mu_f = eta R U_s/(h T)
the viscous shear of the film (Eq. 30) and chi_c, chi_f the load shares of Eq. 13. The
effective coefficient of a roller is the average of mu(x) over the wrap. All functions
broadcast over numpy arrays.

Examples
--------
>>> round(float(delta_T_from_mu(0.3, 80.0, np.pi / 3)), 3)
29.529
>>> round(float(mu_from_delta_T(delta_T_from_mu(0.3, 80.0, np.pi / 3), 80.0, np.pi / 3)), 12)
0.3
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.special import exp1


@functools.lru_cache(maxsize=16)
def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """numpy's Gauss-Legendre points and weights on [-1, 1], computed once per ``n`` (an
    eigenvalue problem each time otherwise: most of the closed form's cost)."""
    g, w = np.polynomial.legendre.leggauss(n)
    g.flags.writeable = False
    w.flags.writeable = False
    return g, w

from .contact import (RESTING_SHARE, contact_gap, contact_pressure, load_ratio, regime_code,
                      resting_gap)
from .roughness import mean_gap, shear_factor

__all__ = ["friction_for", "jump_gaps", "load_friction", "wrap_average_loads", "SLIP_COEFFICIENT", "mu_asperity", "mu_film", "local_friction", "wrap_average_linear_gap",
           "wrap_average_numeric",
           "delta_T_from_mu", "mu_from_delta_T", "valley_shear_bound"]


def mu_boundary(U_s, mu_cc, C):
    """Boundary-lubrication asperity friction (2/pi) mu_cc atan(U_s / C) (Eq. 29, h < h_c)."""
    return 2.0 / np.pi * mu_cc * np.arctan(np.asarray(U_s, dtype=float) / C)


def mu_asperity(h, h_c, U_s, mu_cc, C, variant="paper"):
    """Asperity friction coefficient mu_c (Eq. 29).

    ``paper``: (2/pi) mu_cc atan(U_s/C) below h_c, mu_cc above (a jump at h_c).
    ``continuous``: (2/pi) mu_cc atan(U_s/C) at every gap.
    """
    mb = mu_boundary(U_s, mu_cc, C)
    if variant == "continuous":
        return np.broadcast_to(mb, np.broadcast(np.asarray(h), mb).shape).astype(float)
    return np.where(np.asarray(h) < h_c, mb, mu_cc + 0.0 * mb)


def mu_film(h, eta, R, U_s, T):
    """Viscous film friction mu_f = eta R U_s / (h T) (Eq. 30); infinite for h <= 0."""
    h = np.asarray(h, dtype=float)
    with np.errstate(divide="ignore"):
        return np.where(h > 0.0, eta * R * U_s / (np.where(h > 0.0, h, 1.0) * T), np.inf)


def local_friction(h, *, R, T, U_s, eta, E_b, sigma, t, mu_cc, C, variant="paper",
                   distribution="exponential", resting=False):
    """Local load shares and friction at gaps ``h`` [m].

    Returns a dict of arrays: ``chi_c``, ``mu_c``, ``mu_f``, ``mu`` and ``regime`` (codes of
    :data:`webfem.physics.contact.REGIMES`). Where chi_f = 0 the film term is dropped, so a
    landed web (h <= 0) has mu = mu_c. ``resting=True`` puts the edge of the boundary regime
    where contact carries :data:`~webfem.physics.contact.RESTING_SHARE` of T/R instead of
    exactly at h_c (for solved gaps, where a landed web sits at h_c within round-off).
    """
    h = np.asarray(h, dtype=float)
    p_bar = T / R
    h_c = (resting_gap(p_bar, E_b, sigma, t, distribution) if resting
           else contact_gap(p_bar, E_b, sigma, t, distribution))
    chi_c = load_ratio(h, p_bar, E_b, sigma, t, variant, distribution, h_edge=h_c)
    mu_c = mu_asperity(h, h_c, U_s, mu_cc, C, variant)
    mu_f = mu_film(h, eta, R, U_s, T)
    chi_f = 1.0 - chi_c
    film = np.where(chi_f > 0.0, mu_f, 0.0) * chi_f   # chi_f = 0 where mu_f is infinite
    return {"chi_c": chi_c, "mu_c": mu_c, "mu_f": mu_f, "mu": mu_c * chi_c + film,
            "regime": regime_code(h, h_c, sigma)}


def load_friction(h, p_c, *, p_bar, U_s, eta, mu_cc, C, h_edge, sigma, slip_length=0.0,
                  shear_p=0.0, land=1.0, groove_depth=0.0, roughness=None):
    """Friction from the solved loads (``friction.variant = "loads"``).

    The local traction on the web is the asperity friction on the contact pressure plus the
    film's shear, tau = mu_c p_c + eta U_s / (h + 2 a lambda) + tau_p, with mu_c =
    (2/pi) mu_cc atan(U_s/C) at every gap (no jump at h_c), ``slip_length`` = 2 a lambda
    (first-order slip lowers the Couette shear) and ``shear_p`` the pressure-driven part
    -(h/2) dp/dx; mu(x) = tau / p_bar with p_bar = T_eff/R. Unlike Eq. 28 the film's shear is
    not weighted by the film's share of the load: a film shears whatever it carries.

    A grooved roller (``land`` a/p_g < 1, ``groove_depth`` delta): ``p_c`` is the contact
    pressure on the lands, which acts on the land fraction only (the width average is
    land p_c), and the Couette shear is land eta U_s/(h + 2 a lambda) + (1 - land) eta U_s /
    (h + delta + 2 a lambda).

    ``roughness``: the asperity height density ("exponential" or "gaussian") when the air is
    sheared only where it wets the roller, over its local gap (``air.roughness_flow =
    "mean-gap"``): the Couette shear is then eta U_s E[1 / ((h - z) + 2 a lambda); z < h]
    (:func:`webfem.physics.roughness.shear_factor`), which tends to the smooth film's for
    h >> sigma and to zero as the web comes to rest, so mu tends to mu_c there; None: the
    smooth film's eta U_s / (h + 2 a lambda).

    Returns the arrays of :func:`local_friction` (``chi_c`` = min(p_c/p_bar, 1), ``mu_f`` the
    film's part tau_film/p_bar; ``regime`` by the gap against ``h_edge`` and 3 sigma).

    >>> out = load_friction(1e-3, 0.0, p_bar=1454.5, U_s=20.0, eta=1.81e-5, mu_cc=0.3,
    ...                     C=0.4, h_edge=4.9e-6, sigma=4e-6)
    >>> round(float(out["mu"]), 6)       # Couette shear eta U / h over p_bar
    0.000249
    """
    h = np.asarray(h, dtype=float)
    p_c = land * np.asarray(p_c, dtype=float)
    mu_c = mu_boundary(U_s, mu_cc, C) + 0.0 * h
    with np.errstate(divide="ignore"):
        if roughness is None:
            tau_f = np.where(h + slip_length > 0.0,
                             eta * U_s / np.where(h + slip_length > 0.0, h + slip_length, 1.0),
                             np.inf)
        else:
            tau_f = eta * U_s * shear_factor(h, sigma, slip_length, roughness)
        if land < 1.0:      # the grooves' part (computed only where there are grooves)
            groove = (eta * U_s / (h + groove_depth + slip_length) if roughness is None else
                      eta * U_s * shear_factor(h + groove_depth, sigma, slip_length,
                                               roughness))
            tau_f = land * tau_f + (1.0 - land) * groove
        tau_f = tau_f + shear_p
    mu_f = tau_f / p_bar
    return {"chi_c": np.minimum(p_c / p_bar, 1.0), "mu_c": mu_c, "mu_f": mu_f,
            "mu": mu_c * p_c / p_bar + mu_f, "regime": regime_code(h, h_edge, sigma)}


def friction_for(case, h, resting: bool = False, p=None, dpdx=None) -> dict:
    """Local friction at gaps ``h`` [m] with every constant taken from ``case`` (a
    :class:`webfem.case.Case`) and its friction model (``case.friction_variant``): the
    paper's Eqs. 13, 28-30 (:func:`local_friction`, ``resting`` as there) or the solved
    loads (:func:`load_friction`, with the absolute film pressure ``p`` [Pa] for the slip
    length (default p_a) and the pressure gradient ``dpdx`` [Pa/m] (default 0))."""
    w = case.web
    if case.friction_variant == "loads":
        h = np.asarray(h, dtype=float)
        p_a = case.air.ambient_pressure
        p = p_a if p is None else np.asarray(p, float)
        density = case.friction.distribution
        rough = case.roughness_flow_model == "mean-gap"
        # through the roughness the shear's singularity at contact is cut off at the
        # molecular scale, 2 a lambda, whether or not the film carries slip flow
        slip = (2.0 * SLIP_COEFFICIENT * case.air.mean_free_path * p_a / p
                if case.slip_model == "first-order" or rough else 0.0)
        gap = mean_gap(h, case.sigma, density) if rough else h
        shear_p = 0.0 if dpdx is None else -0.5 * gap * np.asarray(dpdx, float)
        return load_friction(
            h, contact_pressure(h, w.modulus_thickness, case.sigma, w.thickness,
                                case.friction.distribution),
            p_bar=case.p_bar, U_s=case.U_slide, eta=case.air.viscosity,
            mu_cc=case.friction.mu_cc, C=case.friction.speed_constant,
            h_edge=resting_gap(case.p_bar, w.modulus_thickness, case.sigma, w.thickness,
                               case.friction.distribution, RESTING_SHARE if resting else 1.0),
            sigma=case.sigma, slip_length=slip, shear_p=shear_p, land=case.land_fraction,
            groove_depth=case.roller.groove_depth, roughness=density if rough else None)
    return local_friction(h, R=case.roller.radius, T=case.tension_eff, U_s=case.U_slide,
                          eta=case.air.viscosity, E_b=w.modulus_thickness,
                          sigma=case.sigma, t=w.thickness, mu_cc=case.friction.mu_cc,
                          C=case.friction.speed_constant, variant=case.friction_variant,
                          distribution=case.friction.distribution, resting=resting)


def jump_gaps(case, resting: bool = False) -> tuple[float, ...]:
    """The gaps [m] at which :func:`friction_for` (same ``case`` and ``resting``) jumps: the
    edge of the boundary regime (h_c, or where contact carries the resting share), 3 sigma
    and 0 (a landed web). ``mu`` jumps there with the paper's Eqs. 13 and 29 (``variant =
    "paper"``; chi_c drops from about 0.1 to 0 at 3 sigma); the regime codes jump there with
    every variant. A wrap average whose quadrature cells straddle one of them converges
    only at first order in the cell's length; splitting the cells where the gap crosses
    them makes it exact to the quadrature's order (:func:`webfem.models.readout.read_out`)."""
    w = case.web
    edge = float(resting_gap(case.p_bar, w.modulus_thickness, case.sigma, w.thickness,
                             case.friction.distribution, RESTING_SHARE if resting else 1.0))
    return tuple(sorted({0.0, edge, 3.0 * float(case.sigma)}))


#: Burgdorfer's first-order slip coefficient a (full accommodation of the air molecules).
SLIP_COEFFICIENT = 1.0


def valley_shear_bound(sigma, mean_free_path):
    """The most shear stress the air between the asperities exerts, at any gap, in units of
    eta U_s / sigma (exponential heights; physics.md, "Air through the roughness").

    The air wets the roller only where an asperity stays below it, over the local gap
    (h - z) + 2 a lambda, so the mean shear is tau(h) = E[eta U_s / ((h - z) + 2 a lambda);
    z < h]. It peaks just above contact (h about 0.15 sigma for the base web) at
    0.5 ln(sigma / (2 a lambda)) - 0.15 +- 0.3 (quadrature, sigma / (2 a lambda) from 3 to
    1e5: 0.68 to 5.47); 0.5 ln(1 + sigma / (2 a lambda)) + 0.3 lies above every peak, by at
    most 0.55. The cutoff is the molecular one, 2 a lambda with the mean free path at p_a,
    whether or not the model carries slip flow.

    >>> round(float(valley_shear_bound(4e-6, 65e-9)), 3)   # base web: peak 1.55
    2.029
    """
    cutoff = 2.0 * SLIP_COEFFICIENT * np.asarray(mean_free_path, float)
    with np.errstate(divide="ignore"):    # no cut-off (lambda = 0): no bound, inf
        return 0.5 * np.log1p(np.asarray(sigma, float) / cutoff) + 0.3


_EULER_GAMMA = 0.5772156649015329
# Taylor coefficients (-1)^(k+1) / (k k!) of E1(x) + gamma + ln(x), k = 1..30
_E1_SERIES = np.array([(-1.0) ** (k + 1) / (k * math.factorial(k))
                       for k in range(1, 31)])


def exp1_fast(x):
    """Exponential integral E1(x), x > 0, to about 1e-14 relative.

    The mixed regime only needs 0 < x <= 3, where a 30-term Taylor series in Horner form is
    about ten times faster than ``scipy.special.exp1``; larger arguments go to scipy.
    """
    x = np.asarray(x, dtype=float)
    small = x <= 3.0
    xs = np.where(small, x, 1.0)
    acc = np.full_like(xs, _E1_SERIES[-1])
    for coeff in _E1_SERIES[-2::-1]:
        acc *= xs
        acc += coeff
    with np.errstate(divide="ignore"):
        out = acc * xs - _EULER_GAMMA - np.log(xs)
    if not small.all():
        out = np.where(small, out, 0.0)
        out[~small] = exp1(x[~small])
    return out


def wrap_average_linear_gap(h_in, h_out, *, R, T, U_s, eta, E_b, sigma, t, mu_cc, C,
                            variant="paper", distribution="exponential"):
    """Exact wrap average of mu for a gap linear in x from ``h_in`` to ``h_out`` (clamped >= 0).

    The Eq. 21 gap is linear along the wrap, so the average is an exact integral over h:
    constants in the boundary regime, exponentials and the exponential integral E1 in the
    mixed regime, logarithms in the fluid regime. Also returns the wrap shares of the three
    regimes. Infinite where h_c <= 0 and the film thins to zero (contact cannot carry T/R).

    The Gaussian height density (``distribution="gaussian"``) has no such closed form; its
    average is integrated numerically (:func:`wrap_average_numeric`).

    Returns
    -------
    dict with ``mu`` and ``share_boundary``, ``share_mixed``, ``share_fluid``.
    """
    if distribution != "exponential":
        return wrap_average_numeric(h_in, h_out, R=R, T=T, U_s=U_s, eta=eta, E_b=E_b,
                                    sigma=sigma, t=t, mu_cc=mu_cc, C=C, variant=variant,
                                    distribution=distribution)
    h_in, h_out = np.broadcast_arrays(np.asarray(h_in, float), np.asarray(h_out, float))
    p_bar = T / R
    c = E_b * sigma / (2.0 * t * p_bar)          # chi_c = c exp(-h/sigma) in the mixed regime
    h_c = sigma * np.log(c)
    A = eta * R * U_s / T                         # mu_f = A / h
    mb = mu_boundary(U_s, mu_cc, C)
    mu_mixed_c = mb if variant == "continuous" else mu_cc
    hb = np.maximum(h_c, 0.0)                     # boundary below hb (a landed web included)
    top = np.inf if variant == "continuous" else 3.0 * sigma   # mixed regime ends here

    span = h_in - h_out
    flat = span <= 0.0                            # impermeable web: uniform gap
    lo, hi = np.maximum(h_out, 0.0), np.maximum(h_in, 0.0)
    length = np.where(flat, 1.0, span)

    def measure(a, b):  # length of [a, b] inside [lo, hi]
        return np.maximum(np.minimum(b, hi) - np.maximum(a, lo), 0.0)

    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        # boundary: h in [0, hb), plus the landed part of the wrap (h_lin < 0)
        landed = np.clip(-h_out, 0.0, np.where(flat, 0.0, span))
        I = mb * (measure(0.0, hb) + landed)
        # mixed: h in [hb, top]
        a = np.maximum(np.maximum(hb, lo), 0.0)
        b = np.minimum(top, hi)
        ok = b > a
        a_, b_ = np.where(ok, a, 1.0), np.where(ok, b, 1.0)
        ea, eb = np.exp(-a_ / sigma), np.exp(-b_ / sigma)
        mixed = (mu_mixed_c * c * sigma * (ea - eb)
                 + A * (np.log(b_ / a_) - c * (exp1_fast(a_ / sigma) - exp1_fast(b_ / sigma))))
        I = I + np.where(ok, mixed, 0.0)
        # fluid: h above top
        a = np.maximum(np.maximum(top, hb), lo)
        ok = hi > a
        a_, b_ = np.where(ok, a, 1.0), np.where(ok, hi, 1.0)
        I = I + np.where(ok, A * np.log(b_ / a_), 0.0)
        mu = I / length

    def frac_below(v):  # share of a sloped wrap where the linear gap is below v
        return np.clip((v - h_out) / np.where(flat, 1.0, span), 0.0, 1.0)

    # uniform gap: evaluate mu pointwise (the integral above has zero length)
    point = local_friction(np.maximum(h_in, 0.0), R=R, T=T, U_s=U_s, eta=eta, E_b=E_b,
                           sigma=sigma, t=t, mu_cc=mu_cc, C=C, variant=variant)["mu"]
    mu = np.where(flat, point, mu)
    s_b = np.where(flat, (h_in < hb) | (h_in <= 0.0), frac_below(hb)) * 1.0
    s_m = np.maximum(np.where(flat, h_in <= 3 * sigma, frac_below(np.maximum(3 * sigma, hb)))
                     - s_b, 0.0)
    return {"mu": mu, "share_boundary": s_b, "share_mixed": s_m,
            "share_fluid": np.maximum(1.0 - s_b - s_m, 0.0)}


def wrap_average_numeric(h_in, h_out, *, R, T, U_s, eta, E_b, sigma, t, mu_cc, C,
                         variant="paper", distribution="exponential", n=48):
    """Wrap average of mu for a linear gap by Gauss-Legendre quadrature (``n`` points on each
    piece between the regime boundaries h = 0, h_c and 3 sigma, so the jumps sit on piece ends).

    The film term mu_f ~ 1/h makes the average infinite where the film thins to 0 without
    contact taking the load (h_c <= 0), as in the exact formula.
    """
    h_in, h_out = np.broadcast_arrays(np.asarray(h_in, float), np.asarray(h_out, float))
    h_c = contact_gap(T / R, E_b, sigma, t, distribution)
    span = h_out - h_in
    flat = np.abs(span) < 1e-300
    cuts = [np.zeros_like(h_in), np.ones_like(h_in)]
    for level in (0.0, h_c, 3.0 * sigma):
        with np.errstate(divide="ignore", invalid="ignore"):
            s_cut = np.where(flat, 0.0, (level - h_in) / np.where(flat, 1.0, span))
        cuts.append(np.clip(s_cut, 0.0, 1.0))
    cuts = np.sort(np.stack(cuts), axis=0)
    g, gw = gauss_legendre(n)
    total = np.zeros_like(h_in)
    shares = np.zeros((3,) + h_in.shape)
    for a, b in zip(cuts[:-1], cuts[1:]):
        s = 0.5 * (a + b)[..., None] + 0.5 * (b - a)[..., None] * g
        wts = 0.5 * (b - a)[..., None] * gw
        h = np.maximum(h_in[..., None] + span[..., None] * s, 0.0)
        loc = local_friction(h, R=R, T=T, U_s=U_s, eta=eta, E_b=E_b, sigma=sigma, t=t,
                             mu_cc=mu_cc, C=C, variant=variant, distribution=distribution)
        total += np.sum(loc["mu"] * wts, axis=-1)
        for k in range(3):
            shares[k] += np.sum((loc["regime"] == k) * wts, axis=-1)
    return {"mu": total, "share_boundary": shares[0], "share_mixed": shares[1],
            "share_fluid": shares[2]}


def delta_T_from_mu(mu, T, B):
    """Tension increase a roller can carry before slip, dT = T (exp(mu B) - 1) [N/m] (Eq. 31)."""
    return T * np.expm1(np.asarray(mu, dtype=float) * B)


def mu_from_delta_T(delta_T, T, B):
    """Friction coefficient from a measured tension increase, mu = ln(1 + dT/T) / B (Eq. 31)."""
    return np.log1p(np.asarray(delta_T, dtype=float) / T) / B


def wrap_average_loads(h_in, h_out, *, R, T, U_s, eta, E_b, sigma, t, mu_cc, C,
                       distribution="exponential", slip_length=0.0, n=32, roughness=False):
    """Wrap average of the "loads" friction (:func:`load_friction`, no pressure-gradient
    shear) over a linear gap from ``h_in`` to ``h_out``, for the closed form.

    Where the linear gap falls below h_c the web rests on its asperities at h_c (as the FE
    models find; h_c < 0 where the web rests compressed), so the gap is taken as
    max(h, h_c) there; Gauss-Legendre quadrature with ``n`` points on each piece between h_c
    and 3 sigma. ``roughness``: the film's shear through the roughness (:func:`load_friction`).
    Arrays broadcast over operating points.
    """
    arrays = np.broadcast_arrays(*(np.asarray(v, float) for v in
                                   (h_in, h_out, R, T, U_s, eta, E_b, sigma, t, mu_cc, C,
                                    slip_length)))
    h_in, h_out, R, T, U_s, eta, E_b, sigma, t, mu_cc, C, slip_length = \
        (a[..., None] for a in arrays)
    p_bar = T / R
    h_c = contact_gap(p_bar, E_b, sigma, t, distribution)
    span = h_out - h_in
    flat = np.abs(span) < 1e-300
    cuts = [np.zeros_like(h_in), np.ones_like(h_in)]
    for level in (h_c, 3.0 * sigma):
        with np.errstate(divide="ignore", invalid="ignore"):
            cuts.append(np.clip(np.where(flat, 0.0, (level - h_in) / np.where(flat, 1.0, span)),
                                0.0, 1.0))
    cuts = np.sort(np.concatenate(cuts, axis=-1), axis=-1)
    g, gw = gauss_legendre(n)
    total = np.zeros(h_in.shape[:-1])
    shares = np.zeros((3,) + total.shape)
    for j in range(cuts.shape[-1] - 1):
        a, b = cuts[..., j:j + 1], cuts[..., j + 1:j + 2]
        s = 0.5 * (a + b) + 0.5 * (b - a) * g
        wts = 0.5 * (b - a) * gw
        h_line = h_in + span * s
        h = np.maximum(h_line, h_c)
        loc = load_friction(h, contact_pressure(h, E_b, sigma, t, distribution), p_bar=p_bar,
                            U_s=U_s, eta=eta, mu_cc=mu_cc, C=C, h_edge=h_c, sigma=sigma,
                            slip_length=slip_length,
                            roughness=distribution if roughness else None)
        total += np.sum(loc["mu"] * wts, axis=-1)
        regime = regime_code(h_line, h_c, sigma)   # landed by Eq. 21: boundary
        for k in range(3):
            shares[k] += np.sum((regime == k) * wts, axis=-1)
    return {"mu": total, "share_boundary": shares[0], "share_mixed": shares[1],
            "share_fluid": shares[2]}
