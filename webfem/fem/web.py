"""Weak forms of the web alone (cubic Hermite on a line), loaded by a film solved elsewhere.

Scaled as in :mod:`webfem.fem.forms`: the web equilibrium (paper's Eq. 16)

    Pbar + Pc(H) = chi - W'' + Dn (H''''),     W = 0 at both ends,

with Pbar the width-averaged film pressure. On a grooved roller the asperities touch the
lands only: Pc is the width average land Pc(H) (land = a/p_g, the land fraction). These forms hold every term except Pbar, which
the 2-D model adds through its transfer matrices (:mod:`webfem.fem.transfer`):

    F_w = int W' v' + Dn (W'' - chi) v'' - (Pc(H) - chi) v   [ - int Pbar v ]
"""

from __future__ import annotations

from skfem import BilinearForm, LinearForm

from .forms import contact_law, departure, in_wrap

__all__ = ["web_coefficients", "web_residual", "web_jacobian"]


def web_coefficients(x, W, prm) -> dict:
    """Contact load and stiffness and the wrap indicator at quadrature points x."""
    H = W + departure(x, prm["beta"])
    Pc, kc = contact_law(H, prm)
    land = prm.get("land", 1.0)             # grooved roller: contact on the lands only
    Pc, kc = land * Pc, land * kc
    chi = in_wrap(x, prm["beta"])
    return {"chi": chi, "load": Pc - chi, "k_c": kc}


@LinearForm
def web_residual(v, w):
    """F_w without the film pressure term."""
    W = w["W"]
    return (W.grad[0] * v.grad[0] + w["Dn"] * (W.hess[0, 0] - w["chi"]) * v.hess[0, 0]
            - w["load"] * v)


@BilinearForm
def web_jacobian(dw, v, w):
    """Derivative of :func:`web_residual`."""
    return dw.grad[0] * v.grad[0] + w["Dn"] * dw.hess[0, 0] * v.hess[0, 0] + w["k_c"] * dw * v
