"""Weak forms of the 2-D film: Reynolds over the wrap domain with edge leakage and the sink.

Scaled as in :mod:`webfem.fem.forms`, with Z = z / (R eps^(1/3)) across the width (the same
scale as X, so the operator stays isotropic; the web edges sit at Z = +-lambda):

    div(((1 + d P) H^3 + s H^2) grad P) = d((1 + d P) H)/dX + K (1 + ds P) P,

P = 0 on the ends X = X_s, X_e and on the web edges (paper's Eq. 19); with the half width
Z in [0, lambda], dP/dZ = 0 at Z = 0 (symmetry, natural). The gap comes from the 1-D web,
plus, on a grooved roller, the groove depth (:mod:`webfem.fem.grooves`):

    H(X, Z) = H_web(X) + Delta(Z),    Delta = depth in a groove, 0 on a land,

a field over the film's quadrature points; dH/dW is still 1, so the web coupling is
unchanged. The periodic cell of a wide grooved web (land centre to groove centre) has
dP/dZ = 0 on both sides and no edge condition. Weak residual with test function q:

    F_p = int ((1 + d P) H^3 + s H^2) grad P . grad q - (1 + d P) H q_X + K (1 + ds P) P q

(s: first-order slip, ds: the sink's compressibility; see :mod:`webfem.fem.forms`).

The forms take coefficient arrays at quadrature points (:func:`film_coefficients`), computed
once per assembly. The derivative with respect to the web goes through the transfer matrices
of :mod:`webfem.fem.transfer`.
"""

from __future__ import annotations

from skfem import BilinearForm, LinearForm

from .forms import film_gap

__all__ = ["film_coefficients", "film_residual", "film_jacobian"]


def film_coefficients(H, P, PX, PZ, prm, newton: bool = True) -> dict:
    """Arrays for :func:`film_residual` / :func:`film_jacobian` and the web coupling.

    ``H`` is the gap at the quadrature points (web gap plus groove depth) (floored smoothly at ``prm['floor']``, see
    :func:`webfem.fem.forms.film_gap`), ``P, PX, PZ`` the
    pressure and its gradient there. ``newton=False`` freezes rho = 1 + d P and H^3 (Picard).
    """
    d, K, s = prm["d"], prm["K"], prm.get("slip", 0.0)
    ds = prm.get("ds", d)
    Hf, above = film_gap(H, prm["floor"])
    rho, rho_s = 1.0 + d * P, 1.0 + ds * P
    Hf2 = Hf**2
    Hf3 = Hf2 * Hf
    diffusion = rho * Hf3 + s * Hf2           # Poiseuille conductance with slip
    dD = 3.0 * rho * Hf2 + 2.0 * s * Hf       # its derivative in H
    nt = 1.0 if newton else 0.0
    return {
        "D": diffusion,                       # diffusion coefficient
        "C": rho * Hf,                        # Couette flux
        "S": K * rho_s * P,                   # sink
        # dF/dP: D grad dp + dp (d Hf^3 grad P - d Hf e_X) + K (1 + 2 ds P) dp
        "jD": diffusion,
        "jX": nt * (d * Hf3 * PX - d * Hf),
        "jZ": nt * d * Hf3 * PZ,
        "jS": K * (rho_s + nt * ds * P),
        # dF/dH (to the web): (dD/dH grad P) . grad q - rho q_X
        "hX": above * (nt * dD * PX - rho),
        "hZ": above * nt * dD * PZ,
    }


@LinearForm
def film_residual(q, w):
    """F_p at the state whose coefficients and pressure field ``P`` are in ``w``."""
    P = w["P"]
    return (w["D"] * (P.grad[0] * q.grad[0] + P.grad[1] * q.grad[1]) - w["C"] * q.grad[0]
            + w["S"] * q)


@BilinearForm
def film_jacobian(dp, q, w):
    """dF_p/dP (exact, or Picard's frozen-coefficient operator)."""
    return (w["jD"] * (dp.grad[0] * q.grad[0] + dp.grad[1] * q.grad[1])
            + dp * (w["jX"] * q.grad[0] + w["jZ"] * q.grad[1]) + w["jS"] * dp * q)
