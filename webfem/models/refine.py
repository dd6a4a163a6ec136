"""Where the film is thin: the adaptive refinement rule, the wrap's quadrature samples and the
search for the smallest gap (shared by the 1-D and 2-D models); and where a mesh misses a
solution in hand (:func:`interpolation_weights`: the 2-D mesh decided from the 1-D
solution)."""

from __future__ import annotations

import numpy as np
from numpy.polynomial.legendre import leggauss

from ..fem import forms

__all__ = ["adapted_nodes", "minimum", "wrap_samples", "interpolation_weights",
           "interpolated_nodes", "FLAT_GAP"]

#: A cell lies where the web is flat when its gap changes by less than this times sigma
#: across it and its two neighbours (:func:`adapted_nodes` with ``flat``).
FLAT_GAP = 0.01


def minimum(problem, u, prm) -> tuple[float, float]:
    """Smallest scaled gap in the domain and where: nodal search refined inside the
    adjacent cells. The last state's answer is kept on the problem (a pure function of its
    arguments): a solved state is asked for its minimum by its read-out, the admissibility
    check and the driver's resting test in turn (on the base case's 24-point speed sweep
    62 of its 211 calls find it kept, 124 of 1,312 gap evaluations fewer)."""
    kept = getattr(problem, "_minimum", None)
    if kept is not None and kept[1] is prm and kept[0].shape == np.shape(u) \
            and np.array_equal(kept[0], u):
        return kept[2]
    Hn = problem.gap(u, prm, problem.X)
    i = int(np.argmin(Hn))
    lo, hi = problem.X[max(i - 1, 0)], problem.X[min(i + 1, len(problem.X) - 1)]
    Xs = np.linspace(lo, hi, 81)
    Hs = problem.gap(u, prm, Xs)
    j = int(np.argmin(Hs))
    out = float(Hs[j]), float(Xs[j])
    try:
        problem._minimum = (np.array(u, float, copy=True), prm, out)
    except AttributeError:      # a problem without a __dict__: nothing kept
        pass
    return out


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


def adapted_nodes(problem, u, prm, ratio, min_cell, max_cells=4000, flat=1.0,
                  flat_gap=FLAT_GAP):
    """Bisect cells longer than ``ratio`` times the local film or contact length, or None.

    Where the film is thin the sink and the contact springs make boundary layers far
    shorter than the entry-zone scale: the film's reaction length sqrt(H^3 / K), the
    contact length sqrt(S / (c exp(-H/S))) of the web on its asperities and, for a beam, the
    length (Dn / k_c)^(1/4) over which a web bends into its asperities (a beam on an elastic
    foundation of stiffness k_c). No refinement past ``max_cells`` cells.

    ``flat``: where the web lies flat on its asperities (the gap changes by less than
    :data:`FLAT_GAP` sigma across a cell and its neighbours) cells are bisected only past
    ``flat`` times ``ratio`` those lengths: nothing varies there on them (fe2d's 4, whose
    error estimate decides the rest; below 5 m/s the base case's web rests on a uniform
    film over the whole wrap, and the rule bisected all of it). ``flat_gap``: that change's
    bound in sigma (a continued point's is wider: a hysteresis, see :data:`webfem.models.
    fe2d.FLAT_KEPT`).
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
    S = prm.S if prm.contact else 0.0
    if flat != 1.0 and S > 0.0:
        change = np.abs(np.diff(H_true)) / S
        near = np.maximum(change, np.maximum(np.r_[change[1:], 0.0], np.r_[0.0, change[:-1]]))
        ratio = np.where(near < flat_gap, flat * ratio, ratio)
    return _bisected(X, np.diff(X) > ratio * scale, min_cell, max_cells)


def _bisected(X, mark, min_cell, max_cells):
    """``X`` with the ``mark`` ed cells halved where their halves stay longer than
    ``min_cell``; None where none is left to halve or ``X`` would pass ``max_cells``."""
    mark = mark & (np.diff(X) > 2.0 * min_cell)
    if not mark.any() or X.size + mark.sum() > max_cells:
        return None
    return np.sort(np.concatenate([X, 0.5 * (X[1:] + X[:-1])[mark]]))


def _hermite_misfit(X, W, t):
    """|cubic Hermite interpolant - W| at the fractions ``t`` of each cell of ``X``, from the
    values and slopes of ``W`` at the nodes (differences of second order over steps 1e-3 of
    the shorter neighbouring cell long, one-sided at the ends: the web's values carry
    relative noise of about 1e-8, far below what steps that long see). Returns the misfits
    (cell, fraction), the points and W there."""
    dx = np.diff(X)
    n = X.size
    d = 1e-3 * np.minimum(np.concatenate([dx[:1], dx]), np.concatenate([dx, dx[-1:]]))
    # central differences inside; at the ends W(x), W(x +- d), W(x +- 2d), inwards
    s = np.ones(n)
    s[-1] = -1.0
    v = W(np.concatenate([X, np.maximum(X - d, X[0]), np.minimum(X + d, X[-1]),
                          X[[0, -1]] + 2.0 * s[[0, -1]] * d[[0, -1]]]))
    Wv, Wm, Wp, W2 = v[:n], v[n:2 * n], v[2 * n:3 * n], v[3 * n:]
    Ws = (Wp - Wm) / (2.0 * d)
    inward = np.array([Wp[0], Wm[-1]])
    Ws[[0, -1]] = s[[0, -1]] * (-3.0 * Wv[[0, -1]] + 4.0 * inward - W2) / (2.0 * d[[0, -1]])
    h00, h10 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t
    h01, h11 = -2 * t**3 + 3 * t**2, t**3 - t**2
    L = dx[:, None]
    Wi = (h00 * Wv[:-1, None] + h10 * L * Ws[:-1, None] + h01 * Wv[1:, None]
          + h11 * L * Ws[1:, None])
    pts = X[:-1, None] + L * t
    Wp = W(pts.ravel()).reshape(pts.shape)
    return np.abs(Wi - Wp), pts, Wp


def _lagrange_misfit(X, P, t, order: int):
    """|Lagrange interpolant of ``order`` (1 or 2: the ends and, for 2, the midpoint of
    each cell) - P| at the fractions ``t`` of each cell of ``X``."""
    pts = X[:-1, None] + np.diff(X)[:, None] * t
    a, b = P(X[:-1])[:, None], P(X[1:])[:, None]
    if order == 1:
        Pi = (1 - t) * a + t * b
    else:
        m = P(0.5 * (X[1:] + X[:-1]))[:, None]
        Pi = 2 * (t - 0.5) * (t - 1) * a - 4 * t * (t - 1) * m + 2 * t * (t - 0.5) * b
    return np.abs(Pi - P(pts.ravel()).reshape(pts.shape))


def interpolation_weights(X, gap, pressure, prm, order: int = 2, n: int = 4) -> np.ndarray:
    """Per cell of the nodes ``X``: its length times the largest misfit, at ``n`` points
    inside it, of the interpolants a mesh on ``X`` holds of a solved gap and film pressure
    (``gap(X)``, ``pressure(X)``: a solution on other nodes, the 1-D model's for the 2-D
    mesh): the web's cubic Hermite interpolant relative to the larger of the gap and the
    roughness S (:func:`~webfem.models.readout.error_scale`), plus the pressure's Lagrange
    interpolant of ``order`` (scaled: the wrap pressure is 1). The roller's departure
    outside the wrap is exact in every model and is left out of the web. The weighting is
    that of the error estimate's local rounds (:func:`webfem.models.mesh_error.
    _local_x_nodes`), with the solution's change between two meshes replaced by what one
    mesh misses of a solution in hand."""
    X = np.asarray(X, float)
    t = (np.arange(1, n + 1) / (n + 1))[None, :]
    web = lambda x: gap(x) - forms.departure(x, prm.beta)
    dW, pts, W = _hermite_misfit(X, web, t)
    H = W + forms.departure(pts, prm.beta)
    dH = dW / np.maximum(np.abs(H), prm.S)
    dP = _lagrange_misfit(X, pressure, t, order)
    return np.diff(X) * np.max(dH + dP, axis=1)


def interpolated_nodes(X, gap, pressure, prm, limit: float, min_cell: float,
                       order: int = 2, rounds: int = 2, max_cells: int = 4000) -> np.ndarray:
    """``X`` with the cells bisected, up to ``rounds`` times, whose
    :func:`interpolation_weights` exceed ``limit``, while their halves stay longer than
    ``min_cell``."""
    X = np.asarray(X, float)
    for _ in range(rounds):
        finer = _bisected(X, interpolation_weights(X, gap, pressure, prm, order) > limit,
                          min_cell, max_cells)
        if finer is None:
            break
        X = finer
    return X
