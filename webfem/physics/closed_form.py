"""The paper's closed-form gap (Eqs. 21-22): a fit to foil-bearing solutions plus permeation.

    h(x) = R eps^(2/3) (0.589 - 1.614/lambda + 1.764/lambda^2) - R kappa (1 + 2x/(RB)),
    h <= 0 -> 0,   eps = 6 eta U / T,  lambda = L/(2 R eps^(1/3)),
    kappa = k T B / (eta t R U),  beta = B / eps^(1/3)

stated valid for beta > 6 and lambda > 7. x runs from the inlet edge -RB/2 to the outlet
edge +RB/2, so the gap falls linearly along the wrap with slope -2 k T / (eta U R t).
All functions broadcast over numpy arrays.

Examples
--------
>>> eps = speed_parameter(1.81e-5, 40.0, 80.0)
>>> lam = width_parameter(0.035, 0.055, eps)
>>> round(float(gap_inlet(0.055, eps, lam)) * 1e6, 1)   # micrometres
33.3
"""

from __future__ import annotations

import numpy as np

__all__ = ["EQ21_COEFFS", "speed_parameter", "width_parameter", "wrap_parameter",
           "permeability_parameter", "width_factor", "gap_inlet", "gap", "eq21_valid"]

#: The fit coefficients of Eq. 21: H = a0 - a1/lambda + a2/lambda^2.
EQ21_COEFFS = (0.589, 1.614, 1.764)
#: Eq. 21's stated range: beta > BETA_MIN and lambda > LAMBDA_MIN.
BETA_MIN, LAMBDA_MIN = 6.0, 7.0


def speed_parameter(eta, U, T):
    """eps = 6 eta U / T (Eq. 22); U is the entrainment speed U_r + U_w."""
    return 6.0 * np.asarray(eta, float) * U / T


def width_parameter(L, R, eps):
    """lambda = L / (2 R eps^(1/3)) (Eq. 22)."""
    return np.asarray(L, float) / (2.0 * R * np.cbrt(eps))


def wrap_parameter(B, eps):
    """beta = B / eps^(1/3) (Eq. 22), B in radians."""
    return np.asarray(B, float) / np.cbrt(eps)


def permeability_parameter(k, T, B, eta, t, R, U):
    """kappa = k T B / (eta t R U) (Eq. 22)."""
    return np.asarray(k, float) * T * B / (eta * t * R * U)


def width_factor(lam):
    """The width fit 0.589 - 1.614/lambda + 1.764/lambda^2 of Eq. 21 (impermeable H)."""
    a0, a1, a2 = EQ21_COEFFS
    lam = np.asarray(lam, float)
    return a0 - a1 / lam + a2 / lam**2


def gap_inlet(R, eps, lam):
    """Unclamped Eq. 21 gap at the inlet edge x = -RB/2 [m] (the kappa term vanishes there)."""
    return R * np.cbrt(eps) ** 2 * width_factor(lam)


def gap(x, R, B, eps, lam, kappa, clamp=True):
    """Eq. 21 gap at arc positions x [m] in the wrap, clamped at 0 unless ``clamp=False``."""
    h = gap_inlet(R, eps, lam) - R * kappa * (1.0 + 2.0 * np.asarray(x, float) / (R * B))
    return np.maximum(h, 0.0) if clamp else h


def eq21_valid(beta, lam):
    """True where Eq. 21 is inside its stated range (beta > 6 and lambda > 7)."""
    return (np.asarray(beta) > BETA_MIN) & (np.asarray(lam) > LAMBDA_MIN)
