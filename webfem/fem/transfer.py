"""1-D <-> 2-D transfer: the web's gap on the film, the film's width-averaged pressure on the web.

The film mesh is the tensor product of the web's nodes in X with nodes across the width, so
each film cell lies inside one web cell. The web's Hermite basis is evaluated exactly at the
film's quadrature points (``M``: quadrature point x web DOF), so

* the gap on the film is ``H_q = M @ w + D(X_q)`` (no interpolation between meshes), and
* the web's load from the film is ``(1 / width) * M.T @ (dx * P_q)``, the consistent
  discretisation of (1/width) int v(X) P(X, Z) dX dZ, i.e. of the paper's width average.

``B0``, ``BX``, ``BZ`` (:func:`basis_matrices`) are the film basis values and derivatives at
the same points (quadrature point x film DOF): the off-diagonal blocks of the scikit-fem
reference Jacobian, built only there (the fast assembly takes the film's functions cell by
cell; the three matrices held ~300 MB at 3.9e5 unknowns).

Examples
--------
>>> Z = width_nodes(5.0, half=True)
>>> float(Z[0]), float(Z[-1]), bool(np.all(np.diff(Z) > 0))
(0.0, 5.0, True)
"""

from __future__ import annotations

import dataclasses

import numpy as np
import scipy.sparse as sp
from .hermite import HermiteLine

__all__ = ["width_nodes", "film_mesh", "film_basis", "parallelogram_mapping", "quadrature_matrices",
           "basis_matrices",
           "web_values", "cellwise_matrices", "interpolate_values", "tensor_interpolation",
           "tensor_grid", "point_lines", "quadrature",
           "TOPOLOGIES_KEPT"]

#: Film mesh topologies kept (:func:`film_mesh`): a continued sweep point builds its
#: problems on the previous point's meshes moved (46 of the 67 problems of the base case's
#: 24-point speed sweep have a topology built before, among at most 4 recent ones).
TOPOLOGIES_KEPT = 4
#: (nodes in X, nodes in Z) -> what a tensor film mesh of that size has that does not depend
#: on where its nodes are: its cells ``t``, facets, their maps (``t2f``, ``f2t``) and, per
#: element, scikit-fem's DOF numbering (:func:`film_basis`)
TOPOLOGIES: dict = {}


def width_nodes(lam: float, level: int = 0, half: bool = True, fine: float = 0.25,
                growth: float = 0.25, cells: int = 6) -> np.ndarray:
    """Nodes across the width, graded towards the web edge(s) where P falls to ambient.

    ``half``: Z in [0, lam] (symmetry at 0); else Z in [-lam, lam]. Cells are ``fine`` at the
    edge and grow by ``growth`` per unit distance, capped so that the half width has at least
    ``cells`` cells (the pressure is close to a parabola across the width, which quadratic
    elements carry exactly). ``level`` bisects every cell.
    """
    from .mesh import segment, refine_nodes

    if not (lam > 0):
        raise ValueError(f"lam = {lam} must be > 0")
    Z = segment(0.0, lam, [lam], min(fine, lam / cells), growth, lam / cells)
    Z[0], Z[-1] = 0.0, lam
    Z = refine_nodes(Z, level)
    return Z if half else np.concatenate([-Z[:0:-1], Z])


def film_mesh(X: np.ndarray, Z: np.ndarray, web_edges: bool = True, strip: bool = False):
    """Tensor-product quadrilateral mesh with boundaries ``ends`` (X = X_s, X_e), ``edges``
    (the web edges, Z = +-lam) and, for the half width, ``symmetry`` (Z = 0).
    ``web_edges=False`` (the periodic cell of a grooved roller): no ``edges``, both sides
    are ``symmetry``; ``strip`` (a wide web's edge strip): Z[0] is ``symmetry``, Z[-1] the
    web's edge."""
    x0, x1, z0, z1 = X[0], X[-1], Z[0], Z[-1]
    bnd = {"ends": lambda p: np.isclose(p[0], x0) | np.isclose(p[0], x1)}
    if not web_edges:
        bnd["symmetry"] = lambda p: np.isclose(p[1], z0) | np.isclose(p[1], z1)
        return _tensor_mesh(X, Z, bnd)
    inner = z0 == 0.0 or strip
    bnd["edges"] = ((lambda p: np.isclose(p[1], z1)) if inner else
                    (lambda p: np.isclose(p[1], z0) | np.isclose(p[1], z1)))
    if inner:
        bnd["symmetry"] = lambda p: np.isclose(p[1], z0)
    return _tensor_mesh(X, Z, bnd)


def _tensor_mesh(X, Z, boundaries):
    """``MeshQuad.init_tensor(X, Z).with_boundaries(boundaries)`` with the facets and their
    maps of a mesh of the same size built before (:data:`TOPOLOGIES`): they depend only on
    the cells, and computing them (a sort of all the cells' facets, twice: scikit-fem's
    ``with_boundaries`` returns a copy without them) was most of the cost of a mesh. The
    boundaries are still found from this mesh's nodes."""
    from skfem import MeshQuad

    mesh = MeshQuad.init_tensor(np.asarray(X, float), np.asarray(Z, float))
    key = (np.size(X), np.size(Z))
    topo = TOPOLOGIES.get(key)
    if topo is None or not np.array_equal(topo["t"], mesh.t):
        topo = {"t": mesh.t, "facets": mesh.facets, "t2f": mesh.t2f, "f2t": mesh.f2t,
                "boundary": mesh.boundary_facets()}
        if len(TOPOLOGIES) >= TOPOLOGIES_KEPT:
            TOPOLOGIES.pop(next(iter(TOPOLOGIES)))
        TOPOLOGIES[key] = topo
    _attach(mesh, topo)
    # scikit-fem's facets_satisfying(test, boundaries_only=True), the boundary facets kept
    midp = mesh.p[:, topo["facets"]].mean(axis=1)
    found = {name: np.intersect1d(np.nonzero(test(midp))[0].astype(np.int32),
                                  topo["boundary"])
             for name, test in boundaries.items()}
    out = dataclasses.replace(mesh, _boundaries=found)
    _attach(out, topo)
    return out


def _attach(mesh, topo) -> None:
    # scikit-fem computes these on first use into the same attributes (skfem.Mesh.facets)
    mesh.t = topo["t"]
    mesh._facets, mesh._t2f, mesh._f2t = topo["facets"], topo["t2f"], topo["f2t"]


#: scikit-fem's quadrature rules by (reference domain, order), read-only (:func:`quadrature`)
_QUADRATURES: dict = {}


def quadrature(refdom, intorder: int) -> tuple[np.ndarray, np.ndarray]:
    """``skfem.quadrature.get_quadrature(refdom, intorder)``, computed once per rule (a
    basis asks for it on every mesh: Gauss-Legendre nodes from an eigenvalue problem); the
    arrays are read-only, being shared by every basis built with them."""
    key = (refdom, int(intorder))
    if key not in _QUADRATURES:
        from skfem.quadrature import get_quadrature

        X, W = get_quadrature(refdom, int(intorder))
        X, W = np.array(X), np.array(W)
        X.setflags(write=False)
        W.setflags(write=False)
        _QUADRATURES[key] = (X, W)
    return _QUADRATURES[key]


def parallelogram_mapping(mesh):
    """scikit-fem's affine mapping (``skfem.mapping.MappingAffine``) of a quadrilateral mesh
    whose cells are all parallelograms: x = p0 + (p1 - p0) X + (p3 - p0) Y on the reference
    square, exact there (the isoparametric map's bilinear term vanishes); None where a cell
    is not one (to 1e-12 of the mesh's extent). The tensor film meshes' cells are rectangles.
    Why: scikit-fem maps a quadrilateral isoparametrically, summing the four corners'
    bilinear functions for the Jacobian at every quadrature point of every cell; that was
    most of a film basis's cost (the cold base case's 10,777-unknown mesh: 8.3 -> 2.5 ms
    for the mesh and basis, load 9). The basis then differs from scikit-fem's default by
    rounding (gradients 4e-14, weights 2e-15 relative)."""
    from types import SimpleNamespace

    from skfem.mapping import MappingAffine

    p, t = mesh.p, mesh.t
    if t.shape[0] != 4:
        return None
    extent = float(np.max(np.ptp(p, axis=1))) if p.size else 0.0
    far = p[:, t[1]] + p[:, t[3]] - p[:, t[0]]
    if not np.all(np.abs(far - p[:, t[2]]) <= 1e-12 * extent):
        return None
    # the affine map of the corners 0, 1, 3 (the reference square's (0, 0), (1, 0), (0, 1))
    return MappingAffine(SimpleNamespace(p=p, t=t[[0, 1, 3]]))


def film_basis(mesh, elem, intorder: int):
    """``skfem.Basis(mesh, elem, intorder=intorder)`` on a mesh from :func:`film_mesh`, built
    with less work: the cells' affine map (:func:`parallelogram_mapping`; the same to
    rounding) for scikit-fem's isoparametric one, scikit-fem's DOF numbering (``skfem.Dofs``)
    shared by the meshes of one topology (it depends only on the cells and facets), and the
    inverse of the mapping's Jacobian at the quadrature points computed once instead of
    once per local function (scikit-fem's ``ElementH1.gbasis`` asks the mapping for it each
    time; the nine of Q2 were a third of a basis's cost)."""
    from skfem import Basis
    from skfem.assembly import Dofs

    topo = next((t for t in TOPOLOGIES.values() if t["t"] is mesh.t), None)
    name = type(elem).__name__
    if topo is None:
        dofs = Dofs(mesh, elem)
    else:
        dofs = topo.get(name)
        if dofs is None:
            # numbered on a copy of the mesh without its caches: a Dofs keeps its mesh, and
            # this one's mapping will hold the Jacobians at the quadrature points
            bare = dataclasses.replace(mesh)
            _attach(bare, topo)
            dofs = topo[name] = Dofs(bare, elem)
    mapping = parallelogram_mapping(mesh) or mesh._mapping()
    invDF, last = mapping.invDF, []

    def once(X, tind=None):
        # the same points (the basis's quadrature) every call: the first answer, read only
        if tind is not None or not last or last[0] is not X:
            last[:] = [X, invDF(X, tind)]
        return last[1]
    mapping.invDF = once
    try:
        return Basis(mesh, elem, mapping=mapping, quadrature=quadrature(elem.refdom, intorder),
                     dofs=dofs)
    finally:
        del mapping.invDF


def cellwise_matrices(values: list[np.ndarray], dofs: np.ndarray,
                      n: int) -> list[sp.csr_matrix]:
    """(points x n) CSR matrices, one per array of ``values``: the row for quadrature point
    q of cell e holds ``values[k][:, e, q]`` in the columns ``dofs[:, e]`` (distinct within
    a cell).

    Built in canonical form directly: each row's columns are its cell's DOFs, so sorting the
    DOFs once per cell gives the index arrays, and the values are gathered in that order.
    Each equals ``csr_matrix((values[k], (point, dof)))`` array for array
    (tests/test_transfer.py), at a fraction of the cost (scipy sorts and sums ~5e5 entries
    there).
    """
    nb, nel, nq = values[0].shape
    dofs = np.asarray(dofs)
    order = np.argsort(dofs, axis=0)                                # (nb, nel)
    # the cells of a tensor mesh number their DOFs alike: a few distinct orders, each
    # applied to its cells by whole rows (several times cheaper than entry by entry)
    kinds = (np.unique(np.ravel_multi_index(tuple(order), (nb,) * nb), return_index=True,
                       return_inverse=True) if nb <= 12 else None)

    def gather(v):
        if kinds is None or kinds[0].size > 32:
            return np.take_along_axis(v, order[:, :, None], axis=0).transpose(1, 2, 0).ravel()
        if kinds[0].size == 1:
            return np.moveaxis(v[order[:, 0]], 0, -1).ravel()
        out = np.empty((nel, nq, nb), dtype=v.dtype)
        for k, first in enumerate(kinds[1]):
            cells = np.flatnonzero(kinds[2] == k)
            out[cells] = np.moveaxis(v[order[:, first]][:, cells], 0, -1)
        return out.ravel()

    idx_dtype = np.int32 if max(n, nb * nel * nq) < 2**31 else np.int64
    cols = np.take_along_axis(dofs, order, axis=0).T.astype(idx_dtype)     # (nel, nb)
    indices = np.broadcast_to(cols[:, None, :], (nel, nq, nb)).ravel()
    indptr = np.arange(0, nb * nel * nq + 1, nb, dtype=idx_dtype)
    return [sp.csr_matrix((gather(v), indices.copy(), indptr.copy()), shape=(nel * nq, n))
            for v in values]


def basis_matrices(basis) -> dict:
    """``B0``, ``BX``, ``BZ``: (n_points x N) matrices of the basis's values and X and Z
    derivatives at its quadrature points."""
    fields = [basis.basis[i][0] for i in range(basis.Nbfun)]
    return dict(zip(("B0", "BX", "BZ"), cellwise_matrices(
        [np.array([np.asarray(phi) for phi in fields]), np.array([phi.grad[0] for phi in fields]),
         np.array([phi.grad[1] for phi in fields])], basis.element_dofs, basis.N)))


def web_values(film_basis, web_basis) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The web's Hermite functions at the film's quadrature points, cell by cell.

    Each film cell lies inside one web cell (the meshes share their X nodes), so the points'
    reference coordinates in their web cells take a few distinct values; the web basis is
    evaluated there once, by scikit-fem on a quadrature made of those values, instead of
    locating every point on the line mesh (``probes``: most of the cost of building a 2-D
    problem). Returns ``cell`` (the web cell of each film cell), ``dofs`` (its 4 global web
    DOFs, shape (4, film cells)) and ``values`` (shape (4, film cells, points)).
    """
    from skfem import Basis

    line = web_basis.mesh
    x0, x1 = line.p[0, line.t[0]], line.p[0, line.t[1]]
    lo = np.minimum(x0, x1)
    order = np.argsort(lo)
    xq = np.asarray(film_basis.global_coordinates()[0])             # (film cells, points)
    centre = xq.mean(axis=1)
    cell = order[np.clip(np.searchsorted(lo[order], centre) - 1, 0, lo.size - 1)]
    s = (xq - x0[cell][:, None]) / (x1 - x0)[cell][:, None]          # reference coordinate
    s = np.round(s, 12)
    ref, where = np.unique(s, return_inverse=True)
    # the web basis's own element: scikit-fem 12's Hermite element caches data of its mesh
    # (the inverse Vandermonde matrices), which is this mesh
    elem = web_basis.elem
    if isinstance(elem, HermiteLine):
        # the values alone, as a basis on that quadrature holds them (bitwise: the same
        # element's sums on the same mapping), without building the basis
        vals = elem.values(web_basis.mapping, ref[None, :], np.arange(line.t.shape[1]))
    else:
        at = Basis(line, elem, quadrature=(ref[None, :], np.ones(ref.size)))
        vals = np.array([np.asarray(at.basis[i][0]) for i in range(at.Nbfun)])
    # vals: (4, cells, ref)
    where = where.reshape(s.shape)
    values = vals[:, cell[:, None], where]
    return cell, np.asarray(web_basis.element_dofs)[:, cell], values


def interpolate_values(basis, w: np.ndarray) -> np.ndarray:
    """``np.asarray(basis.interpolate(w))`` for a scalar element: the values at the
    quadrature points, summed in scikit-fem's order (so equal to the last bit), without the
    gradients and the DOF split scikit-fem computes too (a third of the cost each)."""
    dofs = basis.element_dofs
    out = 0.0 * (w[dofs[0]][:, None] * np.asarray(basis.basis[0][0]))
    for i in range(basis.Nbfun):
        out += w[dofs[i]][:, None] * np.asarray(basis.basis[i][0])
    return out


def quadrature_matrices(film_basis, web_basis) -> dict:
    """Transfer matrices at the film's quadrature points.

    Returns ``M`` (web Hermite basis at the points' X), ``dx`` (quadrature weights times
    Jacobians, flattened), ``x`` (the points' X) and ``M_loc``, ``M_dofs`` (``M`` cell by
    cell, from :func:`web_values`). The film basis's own matrices: :func:`basis_matrices`.
    """
    xq = np.asarray(film_basis.global_coordinates()[0]).ravel()
    _, dofs, values = web_values(film_basis, web_basis)
    return {"M": cellwise_matrices([values], dofs, web_basis.N)[0],
            "dx": np.asarray(film_basis.dx).ravel(), "x": xq, "M_loc": values,
            "M_dofs": dofs}


def tensor_grid(doflocs: np.ndarray) -> tuple:
    """The DOF lines of a tensor film field (:func:`tensor_interpolation`'s ``grid``): the
    distinct x and z values of ``doflocs`` and the line of each DOF."""
    return _levels(doflocs[0]) + _levels(doflocs[1])


def point_lines(points: np.ndarray) -> tuple:
    """The distinct x and z values of ``points`` (shape (2, n)) and the index of each point's
    (:func:`tensor_interpolation`'s ``lines``)."""
    return (np.unique(points[0], return_inverse=True),
            np.unique(points[1], return_inverse=True))


def tensor_interpolation(X: np.ndarray, Z: np.ndarray, order: int, doflocs: np.ndarray,
                         values: np.ndarray, points: np.ndarray, grid: tuple | None = None,
                         lines: tuple | None = None) -> np.ndarray:
    """A Q1/Q2 film field on the tensor mesh ``X`` x ``Z`` evaluated at ``points`` (shape
    (2, n); points outside are moved onto the nearest edge).

    The Lagrange field is, in each cell, the product of 1-D Lagrange polynomials through the
    cell's DOF lines in x and in z: evaluated so here, cell by cell, exact on a mesh nested
    in the field's (the adaptive refinement's bisection in X), an interpolation otherwise.
    scikit-fem's ``probes`` does the same for any mesh but locates every point among all
    cells (seconds at 1e4 points).

    Examples
    --------
    >>> X, Z = np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0])
    >>> locs = np.array([[0.0, 0.5, 1.0, 1.5, 2.0] * 3, [0.0] * 5 + [0.5] * 5 + [1.0] * 5])
    >>> f = locs[0] ** 2 + locs[1] ** 2                # biquadratic: exact in Q2
    >>> pts = np.array([[0.25, 1.75], [1.0, 0.3]])
    >>> tensor_interpolation(X, Z, 2, locs, f, pts).round(12).tolist()
    [1.0625, 3.1525]

    ``grid`` (:func:`tensor_grid` of ``doflocs``) and ``lines`` (:func:`point_lines` of
    ``points``): what depends on the meshes alone, computed once by a caller that carries
    several states between the same meshes (:meth:`webfem.fem.film_problem.FoilBearing2D.
    transfer`: the sorts in them were a third of a transfer); the same numbers to the bit.
    """
    xs, ix, zs, iz = tensor_grid(doflocs) if grid is None else grid
    (xu, xw), (zu, zw) = point_lines(points) if lines is None else lines
    field = np.full((xs.size, zs.size), np.nan)
    field[ix, iz] = values
    wx, jx = _lagrange_at(np.asarray(X, float), order, xs, xu, xw)
    wz, jz = _lagrange_at(np.asarray(Z, float), order, zs, zu, zw)
    out = np.zeros(points.shape[1])
    for a in range(wx.shape[0]):
        for b in range(wz.shape[0]):
            out += wx[a] * wz[b] * field[jx[a], jz[b]]
    if np.isnan(out).any():
        raise ValueError("tensor_interpolation: the field's DOFs do not form a tensor grid")
    return out


def _lagrange_at(nodes: np.ndarray, order: int, levels: np.ndarray, values, where):
    """:func:`_lagrange_1d` at ``values[where]``, computed once per distinct value
    (``values``, ``where``: ``np.unique(x, return_inverse=True)`` of the points x):
    another mesh's DOFs lie on a few lines in x and in z (the 2-D film's 22,049 on 691 x
    and 33 z values), and each weight is a function of its value alone, so the same numbers
    to the bit. Carrying a state between the meshes of a continued sweep point (the
    two-grid start: 4-5 transfers a point) spent 5 % of the base case's 24-point speed
    sweep here."""
    weights, index = _lagrange_1d(nodes, order, levels, values)
    return weights[:, where], index[:, where]


def _lagrange_1d(nodes: np.ndarray, order: int, levels: np.ndarray, x):
    """Weights (order + 1, n) and level indices of the 1-D Lagrange interpolant of degree
    ``order`` through the DOF lines of the cell of ``nodes`` holding each x."""
    x = np.clip(x, nodes[0], nodes[-1])
    k = np.clip(np.searchsorted(nodes, x) - 1, 0, nodes.size - 2)
    a, b = nodes[k], nodes[k + 1]
    at = [a, b] if order == 1 else [a, 0.5 * (a + b), b]
    weights = np.ones((len(at), x.size))
    for i, xi in enumerate(at):
        for j, xj in enumerate(at):
            if j != i:
                weights[i] *= (x - xj) / (xi - xj)
    return weights, np.array([_nearest(levels, xi) for xi in at])


def _levels(values, rel: float = 1e-10) -> tuple[np.ndarray, np.ndarray]:
    """The distinct values of ``values`` (equal within ``rel`` of their range: coordinates
    computed in different orders differ in the last digits) and the index of each value."""
    v = np.asarray(values, float)
    order = np.argsort(v)
    sv = v[order]
    tol = rel * (1.0 + np.ptp(sv))
    new = np.concatenate([[True], np.diff(sv) > tol])
    group = np.cumsum(new) - 1
    index = np.empty(v.size, dtype=int)
    index[order] = group
    return sv[new], index


def _nearest(levels: np.ndarray, values) -> np.ndarray:
    """Index of the nearest of the sorted ``levels`` to each value."""
    i = np.clip(np.searchsorted(levels, values), 1, levels.size - 1)
    return np.where(np.abs(values - levels[i - 1]) <= np.abs(levels[i] - values), i - 1, i)
