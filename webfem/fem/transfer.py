"""1-D <-> 2-D transfer: the web's gap on the film, the film's width-averaged pressure on the web.

The film mesh is the tensor product of the web's nodes in X with nodes across the width, so
each film cell lies inside one web cell. The web's Hermite basis is evaluated exactly at the
film's quadrature points (``M``: quadrature point x web DOF), so

* the gap on the film is ``H_q = M @ w + D(X_q)`` (no interpolation between meshes), and
* the web's load from the film is ``(1 / width) * M.T @ (dx * P_q)``, the consistent
  discretisation of (1/width) int v(X) P(X, Z) dX dZ, i.e. of the paper's width average.

``B0``, ``BX``, ``BZ`` are the film basis values and derivatives at the same points
(quadrature point x film DOF), used for the off-diagonal blocks of the Jacobian.

Examples
--------
>>> Z = width_nodes(5.0, half=True)
>>> float(Z[0]), float(Z[-1]), bool(np.all(np.diff(Z) > 0))
(0.0, 5.0, True)
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["width_nodes", "film_mesh", "quadrature_matrices"]


def width_nodes(lam: float, level: int = 0, half: bool = True, fine: float = 0.25,
                growth: float = 0.25, cells: int = 6) -> np.ndarray:
    """Nodes across the width, graded towards the web edge(s) where P falls to ambient.

    ``half``: Z in [0, lam] (symmetry at 0); else Z in [-lam, lam]. Cells are ``fine`` at the
    edge and grow by ``growth`` per unit distance, capped so that the half width has at least
    ``cells`` cells (the pressure is close to a parabola across the width, which quadratic
    elements carry exactly). ``level`` bisects every cell.
    """
    from .mesh import _segment, refine_nodes

    if not (lam > 0):
        raise ValueError(f"lam = {lam} must be > 0")
    Z = _segment(0.0, lam, [lam], min(fine, lam / cells), growth, lam / cells)
    Z[0], Z[-1] = 0.0, lam
    Z = refine_nodes(Z, level)
    return Z if half else np.concatenate([-Z[:0:-1], Z])


def film_mesh(X: np.ndarray, Z: np.ndarray, web_edges: bool = True):
    """Tensor-product quadrilateral mesh with boundaries ``ends`` (X = X_s, X_e), ``edges``
    (the web edges, Z = +-lam) and, for the half width, ``symmetry`` (Z = 0).
    ``web_edges=False`` (the periodic cell of a grooved roller): no ``edges``, both sides
    are ``symmetry``."""
    from skfem import MeshQuad

    x0, x1, z0, z1 = X[0], X[-1], Z[0], Z[-1]
    bnd = {"ends": lambda p: np.isclose(p[0], x0) | np.isclose(p[0], x1)}
    if not web_edges:
        bnd["symmetry"] = lambda p: np.isclose(p[1], z0) | np.isclose(p[1], z1)
        return MeshQuad.init_tensor(np.asarray(X, float),
                                    np.asarray(Z, float)).with_boundaries(bnd)
    bnd["edges"] = ((lambda p: np.isclose(p[1], z1)) if z0 == 0.0 else
                    (lambda p: np.isclose(p[1], z0) | np.isclose(p[1], z1)))
    if z0 == 0.0:
        bnd["symmetry"] = lambda p: np.isclose(p[1], 0.0)
    return MeshQuad.init_tensor(np.asarray(X, float), np.asarray(Z, float)).with_boundaries(bnd)


def _basis_matrix(basis, what: str) -> sp.csr_matrix:
    """(n_points x N) matrix of basis values (``what='value'``) or X/Z derivatives."""
    nel = basis.nelems
    nqp = basis.X.shape[-1]
    rows, cols, vals = [], [], []
    pts = np.arange(nel * nqp).reshape(nel, nqp)
    for i in range(basis.Nbfun):
        phi = basis.basis[i][0]
        v = np.asarray(phi) if what == "value" else phi.grad[0 if what == "x" else 1]
        rows.append(pts)
        cols.append(np.broadcast_to(basis.element_dofs[i][:, None], (nel, nqp)))
        vals.append(v)
    return sp.csr_matrix((np.concatenate([a.ravel() for a in vals]),
                          (np.concatenate([a.ravel() for a in rows]),
                           np.concatenate([a.ravel() for a in cols]))),
                         shape=(nel * nqp, basis.N))


def quadrature_matrices(film_basis, web_basis) -> dict:
    """Transfer and basis matrices at the film's quadrature points.

    Returns ``M`` (web Hermite basis at the points' X), ``B0``, ``BX``, ``BZ`` (film basis),
    ``dx`` (quadrature weights times Jacobians, flattened) and ``x`` (the points' X).
    """
    xq = np.asarray(film_basis.global_coordinates()[0]).ravel()
    M = web_basis.probes(xq[None, :])
    return {"M": sp.csr_matrix(M), "B0": _basis_matrix(film_basis, "value"),
            "BX": _basis_matrix(film_basis, "x"), "BZ": _basis_matrix(film_basis, "z"),
            "dx": np.asarray(film_basis.dx).ravel(), "x": xq}
