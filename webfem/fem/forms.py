"""Weak forms of the infinitely wide foil bearing with permeation and asperity contact.

Scaled variables (Eshel-Elrod): X = x / (R eps^(1/3)), H = h / (R eps^(2/3)),
P = (p - p_a) R / T. Unknowns: film pressure P and web deflection W; the gap is
H = W + D(X) with the roller's departure D = (|X| - beta/2)^2 / 2 outside the wrap, 0 inside.

Reynolds, compressible, with first-order slip and the Darcy sink through the web (physics.md,
divided by p_a):

    (((1 + d P) H^3 + s H^2) P')' = ((1 + d P) H)' + K (1 + ds P) P,     P = 0 at both ends,

d = T / (R p_a) (0 for the incompressible limit), K = 12 k / (R t eps^(4/3)); s = 6 a
lambda_a / (R eps^(2/3)) Burgdorfer's slip term (0 without slip); ds = d/2 for isothermal
Darcy flow through the web (density (p + p_a)/2), d for the paper's sink (density p).

Web equilibrium (membrane with tension, beam with bending when Dn > 0):

    P + Pc(H) = chi - W'' + Dn (H'''' ),   Pc = c exp(-H / S),   W = 0 at both ends,

chi = 1 in the wrap (the T/R term) and 0 outside; Dn = D / (T (R eps^(1/3))^2);
c = E_b sigma R / (2 t T) and S = sigma / (R eps^(2/3)) scale Eq. 10's contact pressure.
Bending acts on the web's true curvature 1 - H'' (the web is flat when unloaded), which in the
weak form is Dn (W'' - chi) v'': couples at the wrap edges, and the natural end condition
W'' = 0 of Eq. 20.

Weak residuals (test functions q for P, v for W; boundary terms vanish by the conditions):

    F_p = int ((1 + d P) H^3 + s H^2) P' q' - (1 + d P) H q' + K (1 + ds P) P q
    F_w = int W' v' + Dn (W'' - chi) v'' - (P + Pc(H) - chi) v

and their exact Jacobian. The film uses a smooth maximum of H and a floor H_f (a fraction of
the roughness; :func:`film_gap`): where the web rests on its asperities air still seeps
through the roughness, and a film that vanished would make the Reynolds operator singular.

The state enters the forms through :func:`coefficients`, evaluated once per assembly at the
quadrature points and passed as keyword arguments of ``assemble``.
"""

from __future__ import annotations

import numpy as np
from scipy.special import erfc
from skfem import BilinearForm, LinearForm

__all__ = ["film_gap", "contact_law", "coefficients", "jacobian_coefficients", "residual", "jacobian", "sink_residual", "sink_jacobian", "departure", "in_wrap"]


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
    """Scaled contact pressure Pc(H) = p_c R/T and stiffness -dPc/dH (Eq. 10 or its Gaussian
    counterpart): ``prm['law']`` 0 exponential, Pc = c exp(-H/S); 1 Gaussian,
    Pc = c (S/sqrt(2 pi) exp(-H^2/(2 S^2)) - H/2 erfc(H/(S sqrt 2))). ``prm['contact']`` 0
    switches contact off."""
    on, c, S = prm["contact"], prm["c"], prm["S"]
    if prm.get("law", 0) == 1:
        e = erfc(H / (S * np.sqrt(2.0)))
        Pc = on * c * (S / np.sqrt(2.0 * np.pi) * np.exp(-0.5 * (H / S) ** 2) - 0.5 * H * e)
        return Pc, on * c * 0.5 * e
    with np.errstate(over="ignore"):   # a wild line-search trial: inf, then rejected
        Pc = on * c * np.exp(-H / S)
    return Pc, Pc / S


def coefficients(x, P, dP, W, prm, sink: bool = True, geometry=None) -> dict:
    """Coefficient arrays of the residual and Jacobian at quadrature points.

    Computed once per assembly (the forms below only multiply them with basis functions:
    scikit-fem calls a form once per pair of basis functions). ``prm`` holds
    ``beta, d, K, Dn, c, S, contact, floor``. ``sink=False`` leaves the Darcy sink out (it
    is then assembled apart with nodal quadrature, :func:`sink_residual`). ``geometry``:
    ``(departure(x, beta), in_wrap(x, beta))`` when the caller keeps them (they depend on
    the mesh only).
    """
    D, chi = geometry if geometry is not None else (departure(x, prm["beta"]),
                                                    in_wrap(x, prm["beta"]))
    H = W + D
    Hf, above = film_gap(H, prm["floor"])
    d, s = prm["d"], prm.get("slip", 0.0)
    ds = prm.get("ds", d)
    rho, rho_s = 1.0 + d * P, 1.0 + ds * P
    Pc, kc = contact_law(H, prm)
    Hf2 = Hf**2
    Hf3 = Hf2 * Hf
    diffusion = rho * Hf3 + s * Hf2                 # Poiseuille conductance with slip
    return {
        "flux": diffusion * dP - rho * Hf,          # F_p = flux q'
        "load": P + Pc - chi,                       # F_w = W'v' + Dn (W'' - chi) v'' - load v
        "chi": chi,
        "a_p": d * Hf3 * dP - d * Hf,               # d flux / dP (through rho)
        "a_dp": diffusion,                          # d flux / dP'
        "a_w": -above * rho,                        # d flux / dW (through the Couette flux)
        "a_w3": above * (3.0 * rho * Hf2 + 2.0 * s * Hf) * dP,  # d flux / dW (conductance)
        "k_c": kc,                                  # -d load / dW (contact stiffness)
        "sink": prm["K"] * rho_s * P if sink else 0.0,         # F_p += sink q
        "a_sink": prm["K"] * rho_s if sink else 0.0,
        "a_sink_p": prm["K"] * ds * P if sink else 0.0,
    }


@LinearForm
def residual(q, v, w):
    """F_p(q) + F_w(v) at the state whose :func:`coefficients` and ``W`` are in ``w``."""
    W = w["W"]
    return (w["flux"] * q.grad[0] + w["sink"] * q + W.grad[0] * v.grad[0]
            + w["Dn"] * (W.hess[0, 0] - w["chi"]) * v.hess[0, 0] - w["load"] * v)


def jacobian_coefficients(coef: dict, newton: bool = True) -> dict:
    """The arrays :func:`jacobian` multiplies, from :func:`coefficients`.

    ``newton=True``: the exact derivative. ``newton=False``: the Picard operator, with the
    film's coefficients rho = 1 + d P and H^3 frozen at the current state (the asperity
    contact stays linearised: it is local and stiff).
    """
    nt = 1.0 if newton else 0.0
    return {"j_p": nt * coef["a_p"], "j_dp": coef["a_dp"], "j_w": coef["a_w"] + nt * coef["a_w3"],
            "j_sink": coef["a_sink"] + nt * coef["a_sink_p"], "k_c": coef["k_c"]}


@BilinearForm
def jacobian(dp, dw, q, v, w):
    """Derivative of :func:`residual` in the direction (dp, dw), with the coefficient arrays
    of :func:`jacobian_coefficients` (exact, or Picard's frozen-coefficient operator)."""
    return ((w["j_p"] * dp + w["j_dp"] * dp.grad[0] + w["j_w"] * dw) * q.grad[0]
            + w["j_sink"] * dp * q + dw.grad[0] * v.grad[0]
            + w["Dn"] * dw.hess[0, 0] * v.hess[0, 0] + w["k_c"] * dw * v - dp * v)


@LinearForm
def sink_residual(q, v, w):
    """The Darcy sink K (1 + ds P) P q of F_p, kept apart so it can be lumped (nodal
    quadrature); ``w["d"]`` carries ds.

    With P1 pressure and nodal quadrature the film operator for a given gap is an M-matrix,
    so the pressure cannot oscillate where the film is thin and the sink dominates (a landed
    web: reaction-to-diffusion ratio K dx^2 / H^3 of order 100 at 10 m/s on newsprint).
    """
    P = w["P"]
    return w["K"] * (1.0 + w["d"] * P) * P * q


@BilinearForm
def sink_jacobian(dp, dw, q, v, w):
    """Derivative of :func:`sink_residual` (Picard, ``newton = 0``: rho frozen)."""
    return w["K"] * (1.0 + (1.0 + w["newton"]) * w["d"] * w["P"]) * dp * q
