"""The 1-D <-> 2-D transfer of webfem.fem.transfer against scikit-fem's general evaluation.

``web_values`` evaluates the web's Hermite basis at the film's quadrature points cell by cell
(instead of scikit-fem's ``probes``, which locates every point); ``tensor_interpolation``
carries a film field to a finer tensor mesh (instead of ``probes`` on the quadrilaterals,
seconds at 1e4 points). Both must agree with scikit-fem's own evaluation.
"""

import numpy as np
import pytest
import scipy.sparse as sp
from skfem import (Basis, ElementLineHermite, ElementLineP1, ElementLineP2, ElementQuad1,
                   ElementQuad2)

from webfem.fem.hermite import HermiteLine, LineProbes
from webfem.fem.mesh import graded_nodes, line_mesh
from webfem.fem import transfer
from webfem.fem.transfer import (basis_matrices, cellwise_matrices, film_basis, film_mesh,
                                 interpolate_values, point_lines, quadrature_matrices,
                                 tensor_grid, tensor_interpolation, web_values, width_nodes)


def _hermite(X, x):
    """The exact cubic Hermite functions (value, slope at each node) of the cells of X at x,
    as a dense (points, 2 len(X)) matrix in the DOF order value, slope per node."""
    k = np.clip(np.searchsorted(X, x) - 1, 0, X.size - 2)
    L = X[k + 1] - X[k]
    s = (x - X[k]) / L
    out = np.zeros((x.size, 2 * X.size))
    rows = np.arange(x.size)
    out[rows, 2 * k] = 2 * s**3 - 3 * s**2 + 1
    out[rows, 2 * k + 1] = (s**3 - 2 * s**2 + s) * L
    out[rows, 2 * k + 2] = -2 * s**3 + 3 * s**2
    out[rows, 2 * k + 3] = (s**3 - s**2) * L
    return out


@pytest.mark.parametrize("order", [1, 2])
@pytest.mark.parametrize("web_edges, strip", [(True, False), (False, False), (True, True)])
def test_film_basis_on_a_moved_mesh_is_scikit_fems(order, web_edges, strip):
    """A film mesh and basis on nodes moved from a mesh of the same size built before (what
    :data:`transfer.TOPOLOGIES` shares with it) equal scikit-fem's built from scratch on the
    moved nodes with the cells' affine map (:func:`transfer.parallelogram_mapping`) to the
    last bit: boundaries, DOFs, values, gradients and weights; and scikit-fem's default
    (isoparametric) basis to rounding (1e-13 relative; the DOF locations to 1e-15)."""
    from types import SimpleNamespace

    from skfem import MeshQuad
    from skfem.mapping import MappingAffine

    X = graded_nodes(3.0, 2.0, level=0)
    Z = width_nodes(5.0, half=True) + (2.0 if strip else 0.0)
    elem, intorder = (ElementQuad2(), 4) if order == 2 else (ElementQuad1(), 3)
    transfer.TOPOLOGIES.clear()
    film_basis(film_mesh(X, Z, web_edges, strip), elem, intorder)
    # moved: stretched unevenly in X (the cells' shapes change), scaled in Z
    Xm, Zm = X * 1.3 + 0.01 * X**2, Z * 0.7
    mesh = film_mesh(Xm, Zm, web_edges, strip)
    assert mesh.t is transfer.TOPOLOGIES[(X.size, Z.size)]["t"]    # the shared topology
    ours = film_basis(mesh, elem, intorder)
    ref_mesh = MeshQuad.init_tensor(Xm, Zm)
    x0, x1, z0, z1 = Xm[0], Xm[-1], Zm[0], Zm[-1]
    bnd = {"ends": lambda p: np.isclose(p[0], x0) | np.isclose(p[0], x1)}
    if web_edges:
        bnd["edges"] = lambda p: np.isclose(p[1], z1)
    bnd["symmetry"] = (lambda p: np.isclose(p[1], z0)) if web_edges else \
        (lambda p: np.isclose(p[1], z0) | np.isclose(p[1], z1))
    ref_mesh = ref_mesh.with_boundaries(bnd)
    affine = MappingAffine(SimpleNamespace(p=ref_mesh.p, t=ref_mesh.t[[0, 1, 3]]))
    ref = Basis(ref_mesh, elem, intorder=intorder, mapping=affine)
    iso = Basis(ref_mesh, elem, intorder=intorder)
    assert set(mesh.boundaries) == set(ref.mesh.boundaries)
    for name in ref.mesh.boundaries:
        assert np.array_equal(mesh.boundaries[name], ref.mesh.boundaries[name])
        assert np.array_equal(ours.get_dofs(name).all(), ref.get_dofs(name).all())
    assert np.array_equal(ours.element_dofs, ref.element_dofs)
    assert np.array_equal(ours.doflocs, ref.doflocs)
    assert np.array_equal(ours.dx, ref.dx)
    # the quadrature kept once per rule (transfer.quadrature) is scikit-fem's
    assert np.array_equal(ours.X, ref.X) and np.array_equal(ours.W, ref.W)
    for a, b in zip(ours.basis, ref.basis):
        assert np.array_equal(np.asarray(a[0]), np.asarray(b[0]))
        assert np.array_equal(a[0].grad, b[0].grad)
    # scikit-fem's isoparametric map gives the same basis to rounding
    np.testing.assert_allclose(ours.doflocs, iso.doflocs, rtol=0.0,
                               atol=1e-15 * np.max(np.abs(iso.doflocs)))
    np.testing.assert_allclose(ours.dx, iso.dx, rtol=1e-13)
    for a, b in zip(ours.basis, iso.basis):
        np.testing.assert_allclose(np.asarray(a[0]), np.asarray(b[0]), rtol=0.0, atol=1e-13)
        np.testing.assert_allclose(a[0].grad, b[0].grad, rtol=0.0,
                                   atol=1e-13 * np.max(np.abs(b[0].grad)))
    # the mapping answers as scikit-fem's again once the basis is built
    assert "invDF" not in vars(ours.mapping)


@pytest.mark.parametrize("order", [1, 2])
def test_web_values_are_the_hermite_basis_at_the_film_points(order):
    """M from web_values equals scikit-fem's probes, and both the exact Hermite functions.

    The tolerance is 1e-6, not 1e-12: scikit-fem 12 builds the Hermite element as a global
    element (monomials in the global x inverted per cell), whose values at |x| ~ 20 carry
    rounding errors of ~1e-7 (measured: probes 5e-8, the cell-wise evaluation 7e-8 from
    the exact 0.9647580015 on the base case mesh). An error in the cell or reference
    coordinate is O(1) and fails it."""
    X = graded_nodes(20.0, 30.0, level=0)
    Z = width_nodes(4.0)
    line = line_mesh(X)
    wbasis = Basis(line, ElementLineHermite(), intorder=6)
    fbasis = Basis(film_mesh(X, Z), ElementQuad2() if order == 2 else ElementQuad1(),
                   intorder=4 if order == 2 else 3)
    T = quadrature_matrices(fbasis, wbasis)
    xq = T["x"]
    probes = wbasis.probes(xq[None, :]).toarray()
    exact = _hermite(X, xq)[:, _dof_order(wbasis, X)]
    assert np.max(np.abs(T["M"].toarray() - probes)) < 1e-6
    assert np.max(np.abs(T["M"].toarray() - exact)) < 1e-6
    cell, dofs, values = web_values(fbasis, wbasis)
    assert values.shape == (4,) + fbasis.dx.shape
    assert np.all(line.p[0, line.t[0, cell]] <= np.asarray(fbasis.global_coordinates()[0])
                  .min(axis=1) + 1e-12)
    # webfem's Hermite element (values read without a basis on the reference points): the
    # same bits as scikit-fem's element through a basis
    ours = web_values(fbasis, Basis(line, HermiteLine(), intorder=6))
    for a, b in zip(ours, (cell, dofs, values)):
        assert np.array_equal(a, b)


@pytest.mark.parametrize("order", [1, 2])
def test_cellwise_matrices_are_scipys(order):
    """The quadrature-point matrices built in canonical CSR form directly equal scipy's
    construction from (point, DOF) pairs, array for array: values, indices, indptr."""
    X = graded_nodes(12.0, 6.0, level=0)
    wbasis = Basis(line_mesh(X), ElementLineHermite(), intorder=6)
    fbasis = Basis(film_mesh(X, width_nodes(3.0)), ElementQuad2() if order == 2
                   else ElementQuad1(), intorder=4 if order == 2 else 3)
    T = quadrature_matrices(fbasis, wbasis) | basis_matrices(fbasis)
    nel, nq = fbasis.dx.shape

    def scipys(values, dofs, n):
        pts = np.broadcast_to(np.arange(nel * nq).reshape(1, nel, nq), values.shape)
        cols = np.broadcast_to(np.asarray(dofs)[:, :, None], values.shape)
        return sp.csr_matrix((values.ravel(), (pts.ravel(), cols.ravel())),
                             shape=(nel * nq, n))

    fields = [fbasis.basis[i][0] for i in range(fbasis.Nbfun)]
    want = {"M": scipys(T["M_loc"], T["M_dofs"], wbasis.N),
            "B0": scipys(np.array([np.asarray(f) for f in fields]), fbasis.element_dofs,
                         fbasis.N),
            "BX": scipys(np.array([f.grad[0] for f in fields]), fbasis.element_dofs, fbasis.N),
            "BZ": scipys(np.array([f.grad[1] for f in fields]), fbasis.element_dofs, fbasis.N)}
    for key, B in want.items():
        A = T[key]
        assert A.shape == B.shape and A.has_canonical_format, key
        for a, b in [(A.data, B.data), (A.indices, B.indices), (A.indptr, B.indptr)]:
            assert np.array_equal(a, b), key
    # unsorted DOFs within a cell are sorted per row
    dofs = np.array([[3, 0], [1, 2]])
    vals = np.arange(8.0).reshape(2, 2, 2)
    A, = cellwise_matrices([vals], dofs, 4)
    assert A.has_canonical_format
    assert np.array_equal(A.toarray(), [[0, 4, 0, 0], [0, 5, 0, 1], [2, 0, 6, 0], [3, 0, 7, 0]])


@pytest.mark.parametrize("nb", [3, 6, 13])
def test_cellwise_matrices_of_cells_numbered_unlike(nb):
    """Cells whose DOFs come in many different orders (a few, more than 32, and too many
    functions to code an order) give scipy's matrix all the same."""
    rng = np.random.default_rng(nb)
    nel, nq, n = 200, 3, 40
    dofs = np.array([rng.choice(n, nb, replace=False) for _ in range(nel)]).T
    vals = rng.normal(size=(nb, nel, nq))
    A, = cellwise_matrices([vals], dofs, n)
    pts = np.broadcast_to(np.arange(nel * nq).reshape(1, nel, nq), vals.shape)
    B = sp.csr_matrix((vals.ravel(), (pts.ravel(), np.broadcast_to(dofs[:, :, None],
                                                                   vals.shape).ravel())),
                      shape=(nel * nq, n))
    for a, b in [(A.data, B.data), (A.indices, B.indices), (A.indptr, B.indptr)]:
        assert np.array_equal(a, b)


def test_parallelogram_mapping_only_for_parallelograms():
    """The affine map is taken only where every cell is a parallelogram: a tensor mesh's
    rectangles yes, a mesh with one corner moved no (scikit-fem's isoparametric map then)."""
    from skfem import MeshQuad

    mesh = film_mesh(graded_nodes(3.0, 2.0, level=0), width_nodes(5.0, half=True))
    assert transfer.parallelogram_mapping(mesh) is not None
    p = mesh.p.copy()
    p[:, mesh.t[2, 0]] += 0.1
    assert transfer.parallelogram_mapping(MeshQuad(p, mesh.t)) is None


@pytest.mark.parametrize("elem", [ElementLineHermite, ElementLineP1, ElementLineP2])
def test_line_probes_are_scikit_fems(elem):
    """LineProbes (the web at points in the 2-D model) is scikit-fem's probes @ dofs to the
    last bit (the same cells, also for points on nodes and at both ends), on a mesh whose
    nodes are not in order; a point outside the mesh is refused like probes does."""
    X = graded_nodes(12.0, 6.0, level=0)
    rng = np.random.default_rng(3)
    line = line_mesh(X)
    line = type(line)(line.p[:, ::-1].copy(), (line.p.shape[1] - 1 - line.t)[::-1].copy())
    basis = Basis(line, elem())
    x = np.concatenate([X, rng.uniform(X[0], X[-1], 500), [X[0], X[-1], 0.0]])
    probe = LineProbes(basis)
    for _ in range(2):                  # the second time from the kept values
        w = rng.normal(size=basis.N)
        assert np.array_equal(probe(x, w), basis.probes(x[None, :]) @ w)
    for outside in (X[0] - 1e-9, X[-1] + 1e-9):
        with pytest.raises(ValueError):
            probe(np.array([outside]), w)


@pytest.mark.parametrize("order", [1, 2])
def test_interpolate_values_are_scikit_fems(order):
    """The film's values at its quadrature points equal scikit-fem's interpolate's bit for
    bit (the width average of the results is computed from them)."""
    X = graded_nodes(12.0, 6.0, level=0)
    fbasis = Basis(film_mesh(X, width_nodes(3.0)), ElementQuad2() if order == 2
                   else ElementQuad1(), intorder=4 if order == 2 else 3)
    p = np.random.default_rng(4).normal(size=fbasis.N)
    assert np.array_equal(interpolate_values(fbasis, p), np.asarray(fbasis.interpolate(p)))


def _dof_order(wbasis, X):
    """Columns of :func:`_hermite` in the order of the basis's global DOFs."""
    cols = np.empty(wbasis.N, dtype=int)
    node = np.argsort(np.argsort(wbasis.mesh.p[0]))      # node index -> position in X
    cols[wbasis.nodal_dofs[0]] = 2 * node
    cols[wbasis.nodal_dofs[1]] = 2 * node + 1
    return np.argsort(cols)


@pytest.mark.parametrize("order", [1, 2])
def test_tensor_interpolation_is_exact_on_a_nested_mesh(order):
    """A random Q1/Q2 field carried to a mesh with cells bisected in X and Z equals
    scikit-fem's probes of it to rounding; on a mesh moved in X it interpolates."""
    X = np.array([-3.0, -1.0, 0.0, 0.5, 2.0])
    Z = np.array([0.0, 0.7, 1.5])
    elem = ElementQuad2 if order == 2 else ElementQuad1
    coarse = Basis(film_mesh(X, Z), elem())
    u = np.random.default_rng(3).normal(size=coarse.N)
    Xf = np.sort(np.concatenate([X, 0.5 * (X[1:] + X[:-1])]))
    Zf = np.sort(np.concatenate([Z, [0.3]]))
    fine = Basis(film_mesh(Xf, Zf), elem())
    pts = fine.doflocs
    want = coarse.probes(pts) @ u
    got = tensor_interpolation(X, Z, order, coarse.doflocs, u, pts)
    assert np.max(np.abs(got - want)) < 1e-12 * (1 + np.max(np.abs(want)))
    # a field that is not in the space: not reproduced (the test can fail)
    bent = u + 1e-3 * np.sin(7 * coarse.doflocs[0])
    assert np.max(np.abs(tensor_interpolation(X, Z, order, coarse.doflocs, bent, pts)
                         - want)) > 1e-5
    # the mesh-only parts given (as FoilBearing2D.transfer keeps them): the same bits
    kept = tensor_interpolation(X, Z, order, coarse.doflocs, u, pts,
                                grid=tensor_grid(coarse.doflocs), lines=point_lines(pts))
    assert np.array_equal(kept, got)
