"""Where the film is thin: the adaptive refinement rule, the wrap's quadrature samples and the
search for the smallest gap (shared by the 1-D and 2-D models)."""

from __future__ import annotations

import numpy as np
from numpy.polynomial.legendre import leggauss

from ..fem import forms

__all__ = ["adapted_nodes", "minimum", "wrap_samples"]


def minimum(problem, u, prm) -> tuple[float, float]:
    """Smallest scaled gap in the domain and where: nodal search refined inside the
    adjacent cells."""
    Hn = problem.gap(u, prm, problem.X)
    i = int(np.argmin(Hn))
    lo, hi = problem.X[max(i - 1, 0)], problem.X[min(i + 1, len(problem.X) - 1)]
    Xs = np.linspace(lo, hi, 81)
    Hs = problem.gap(u, prm, Xs)
    j = int(np.argmin(Hs))
    return float(Hs[j]), float(Xs[j])


def wrap_samples(X: np.ndarray, beta: float, n: int = 8, cuts=()):
    """Gauss points and weights over the wrap cells (nodes sit on the wrap edges), the cells
    split at ``cuts`` (points inside the wrap where the integrand jumps)."""
    e = 0.5 * beta
    inner = X[(X >= -e - 1e-12) & (X <= e + 1e-12)]
    cuts = np.asarray(cuts, float).ravel()
    cuts = cuts[(cuts > inner[0]) & (cuts < inner[-1])]
    if cuts.size:
        inner = np.unique(np.concatenate([inner, cuts]))
    g, gw = leggauss(n)
    a, b = inner[:-1, None], inner[1:, None]
    pts = 0.5 * (a + b) + 0.5 * (b - a) * g[None, :]
    wts = 0.5 * (b - a) * gw[None, :]
    return pts.ravel(), wts.ravel()


def adapted_nodes(problem, u, prm, ratio, min_cell, max_cells=4000):
    """Bisect cells longer than ``ratio`` times the local film or contact length, or None.

    Where the film is thin the sink and the contact springs make boundary layers far
    shorter than the entry-zone scale: the film's reaction length sqrt(H^3 / K), the
    contact length sqrt(S / (c exp(-H/S))) of the web on its asperities and, for a beam, the
    length (Dn / k_c)^(1/4) over which a web bends into its asperities (a beam on an elastic
    foundation of stiffness k_c). No refinement past ``max_cells`` cells.
    """
    X = problem.X
    H_true = problem.gap(u, prm, X)
    # films thinner than the roughness carry nothing the asperities do not: resolve to S
    H = np.maximum(H_true, max(prm.floor, prm.S if prm.contact else 0.0))
    Hc = np.minimum(H[1:], H[:-1])
    scale = np.full(Hc.shape, np.inf)
    if prm.K > 0:
        scale = np.minimum(scale, np.sqrt(Hc**3 / prm.K))
    if prm.contact:
        kc = forms.contact_law(Hc, prm.as_form_args())[1]
        with np.errstate(all="ignore"):
            scale = np.minimum(scale, 1.0 / np.sqrt(kc))
            if prm.Dn > 0:
                # where the web is pressed into its asperities the foundation is as stiff
                # as the contact law at the true gap, not at the film's floor
                k_true = forms.contact_law(np.minimum(H_true[1:], H_true[:-1]),
                                           prm.as_form_args())[1]
                scale = np.minimum(scale, (prm.Dn / np.maximum(kc, k_true)) ** 0.25)
    dx = np.diff(X)
    mark = (dx > ratio * scale) & (dx > 2.0 * min_cell)
    if not mark.any() or X.size + mark.sum() > max_cells:
        return None
    return np.sort(np.concatenate([X, 0.5 * (X[1:] + X[:-1])[mark]]))
