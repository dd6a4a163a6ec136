"""Asperity contact between a rough web and a roller (paper's Eqs. 2, 10-13).

Rigid asperities with exponential height density phi(z) = exp(-z/sigma) / (2 sigma) sit on a
linear-spring base of stiffness E_b / t. All functions broadcast over numpy arrays.

Examples
--------
>>> round(float(contact_gap(80 / 0.055, 175e3, 4e-6, 70e-6)) * 1e6, 3)   # h_c in micrometres
4.939
"""

from __future__ import annotations

import numpy as np

__all__ = ["contact_pressure", "contact_pressure_derivative", "contact_gap", "load_ratio",
           "REGIMES", "regime_code"]

#: Regime names by code: 0 boundary (h < h_c), 1 mixed (h_c <= h <= 3 sigma), 2 fluid film.
REGIMES = ("boundary", "mixed", "fluid")


def contact_pressure(h, E_b, sigma, t):
    """Mean asperity contact pressure p_c = E_b sigma / (2 t) exp(-h / sigma) [Pa] (Eq. 10).

    Eq. 8 as printed integrates (h - z); the load is positive for (z - h), which gives Eq. 10.
    """
    return E_b * sigma / (2.0 * t) * np.exp(-np.asarray(h, dtype=float) / sigma)


def contact_pressure_derivative(h, E_b, sigma, t):
    """d p_c / d h [Pa/m]."""
    return -contact_pressure(h, E_b, sigma, t) / sigma


def contact_gap(p_bar, E_b, sigma, t):
    """Gap h_c at which contact alone carries the wrap pressure p_bar = T/R [m] (Eq. 11)."""
    return sigma * np.log(E_b * sigma / (2.0 * t * np.asarray(p_bar, dtype=float)))


def load_ratio(h, p_bar, E_b, sigma, t, variant="paper"):
    """Share chi_c of the wrap load carried by asperity contact (Eq. 13); chi_f = 1 - chi_c.

    ``variant="paper"``: 1 below h_c, p_c/p_bar up to 3 sigma, 0 above (jumps at 3 sigma).
    ``variant="continuous"``: min(1, p_c/p_bar) for every h (no cut at 3 sigma).
    A landed web (h <= 0) is in full contact in both.
    """
    h = np.asarray(h, dtype=float)
    ratio = np.minimum(contact_pressure(h, E_b, sigma, t) / p_bar, 1.0)
    if variant == "continuous":
        chi = ratio
    elif variant == "paper":
        h_c = contact_gap(p_bar, E_b, sigma, t)
        chi = np.where(h < h_c, 1.0, np.where(h <= 3.0 * sigma, ratio, 0.0))
    else:
        raise ValueError(f"variant = {variant!r} is not valid: must be 'paper' or 'continuous'")
    return np.where(h <= 0.0, 1.0, chi)


def regime_code(h, h_c, sigma):
    """0 boundary (h < h_c or landed), 1 mixed (h_c <= h <= 3 sigma), 2 fluid (h > 3 sigma)."""
    h = np.asarray(h, dtype=float)
    return np.where((h < h_c) | (h <= 0.0), 0, np.where(h <= 3.0 * sigma, 1, 2))
