"""Graded 1-D meshes over the wrap plus entry and exit zones, in scaled coordinates.

Coordinates are X = x / (R eps^(1/3)) from the wrap centre; the wrap is |X| <= beta/2. The
entry zone at the inlet edge and the exit constriction just past the outlet edge both have
width of order 1 in X, so cells are fine there (``fine``) and grow linearly with the distance
from them (rate ``growth``) up to ``coarse``; nodes sit exactly on the wrap edges, where the
roller's curvature starts and stops. Refinement levels bisect every cell, so a refinement
sequence keeps the grading (what a convergence study needs).

Examples
--------
>>> X = graded_nodes(beta=30.0, entry=20.0)
>>> float(X[0]), float(X[-1]), bool(np.any(X == -15.0) and np.any(X == 15.0))
(-35.0, 35.0, True)
"""

from __future__ import annotations

import numpy as np

__all__ = ["graded_nodes", "refine_nodes", "line_mesh", "segment"]

#: Points the mesh resolves, relative to the wrap edges: inlet edge, outlet edge, exit
#: constriction (about 0.5 past the outlet edge, physics.md).
_EXIT_OFFSET = 0.5


def _size(X, features, fine, growth, coarse):
    dist = np.min(np.abs(X[:, None] - np.asarray(features)[None, :]), axis=1)
    return np.minimum(fine + growth * dist, coarse)


def segment(a, b, features, fine, growth, coarse):
    """Nodes on [a, b] equidistributing 1/size (a, b both kept)."""
    s = np.linspace(a, b, 4001)
    density = 1.0 / _size(s, features, fine, growth, coarse)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(s))])
    n = max(int(np.ceil(cum[-1])), 1)
    return np.interp(np.linspace(0.0, cum[-1], n + 1), cum, s)


def graded_nodes(beta: float, entry: float, fine: float = 0.08, growth: float = 0.12,
                 coarse: float = 2.0, level: int = 0) -> np.ndarray:
    """Node positions in X over [-beta/2 - entry, beta/2 + entry].

    Parameters
    ----------
    beta : wrap length in X (= B / eps^(1/3)).
    entry : length of the entry and of the exit zone beyond each wrap edge, in X.
    fine, growth, coarse : cell size at the features, growth per unit distance, largest size.
    level : number of uniform bisections of the graded base mesh.
    """
    if not (beta > 0 and entry > 0):
        raise ValueError(f"beta = {beta} and entry = {entry} must be > 0")
    e = beta / 2.0
    features = [-e, e, e + _EXIT_OFFSET]
    parts = [segment(-e - entry, -e, features, fine, growth, coarse),
             segment(-e, e, features, fine, growth, coarse),
             segment(e, e + entry, features, fine, growth, coarse)]
    X = np.unique(np.concatenate(parts))
    return refine_nodes(X, level)


def refine_nodes(X: np.ndarray, level: int) -> np.ndarray:
    """Bisect every cell ``level`` times."""
    for _ in range(level):
        mid = 0.5 * (X[1:] + X[:-1])
        X = np.sort(np.concatenate([X, mid]))
    return X


def line_mesh(X: np.ndarray):
    """A scikit-fem ``MeshLine`` with boundaries ``left`` and ``right``: the boundary facets
    (end nodes) at X[0] and X[-1], to ``np.isclose``."""
    from skfem import MeshLine

    X = np.asarray(X, float)
    lo, hi = X[0], X[-1]
    mesh = MeshLine(X)
    if X.size < 2 or not np.all(np.diff(X) > 0):
        return mesh.with_boundaries({"left": lambda x: np.isclose(x[0], lo),
                                     "right": lambda x: np.isclose(x[0], hi)})
    # nodes in order: facet k is node k and the boundary facets are the two end nodes, so
    # the sets are what scikit-fem's test of the facet midpoints gives, without building
    # the facets of a mesh that with_boundaries then copies (the copy builds them again)
    ends = np.array([0, X.size - 1], dtype=np.int32)
    return mesh.with_boundaries({"left": ends[np.isclose(X[ends], lo)],
                                 "right": ends[np.isclose(X[ends], hi)]})
