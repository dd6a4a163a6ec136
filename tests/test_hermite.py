"""webfem.fem.hermite against scikit-fem's own: the same numbers, bit for bit, in the bases.

The Hermite element's global monomial basis carries relative errors of about 1e-8 on the
graded meshes (short cells far from X = 0); the bases' fast evaluation reproduces them
exactly (the assembled systems are scikit-fem's). The probes (the web's values at points:
gaps, read-outs, transfers) evaluate the cubic Hermite interpolant in each cell's own
coordinate instead, exact to rounding: they are checked against an independent
construction of that interpolant, and against scikit-fem's probes within its error.
"""

import numpy as np
import pytest
from skfem import Basis, ElementLineHermite, ElementLineP1, ElementLineP2

from webfem.fem.hermite import HermiteLine, LineProbes
from webfem.fem.mesh import graded_nodes, line_mesh
from webfem.models.line import FoilBearing1D

X = graded_nodes(beta=30.0, entry=20.0)


def _fields(basis):
    """Every value, gradient and Hessian array of a basis, component by component."""
    out = []
    for fun in basis.basis:
        for f in fun:
            out += [np.asarray(f), np.asarray(f.grad)]
            if f.hess is not None:
                out.append(np.asarray(f.hess))
    return out


@pytest.mark.parametrize("pressure", [None, ElementLineP1, ElementLineP2])
@pytest.mark.parametrize("quadrature", ["gauss", "lobatto"])
def test_basis_bitwise(pressure, quadrature):
    """A basis (plain, or composite with a pressure element, as the 1-D model builds it)
    and its split bases: the same arrays as with scikit-fem's ElementLineHermite."""
    mesh = line_mesh(X)
    kw = (dict(intorder=6) if quadrature == "gauss"
          else dict(quadrature=(np.array([[0.0, 1.0]]), np.array([0.5, 0.5]))))
    ours, theirs = HermiteLine(), ElementLineHermite()
    if pressure is not None:
        ours, theirs = pressure() * ours, pressure() * theirs
    a, b = Basis(mesh, ours, **kw), Basis(mesh, theirs, **kw)
    for fa, fb in zip(_fields(a), _fields(b)):
        np.testing.assert_array_equal(fa, fb)
    for sa, sb in zip(a.split_bases(), b.split_bases()):
        for fa, fb in zip(_fields(sa), _fields(sb)):
            np.testing.assert_array_equal(fa, fb)


def test_gbasis_repeated_and_new_points():
    """The kept result is reused only for the same points and elements, and what it returns
    is a copy (a caller changing it does not change the next answer)."""
    mesh = line_mesh(X)
    basis = Basis(mesh, ElementLineHermite(), intorder=4)
    ours = HermiteLine()
    for pts, tind in [(basis.X, None), (basis.X, np.arange(3)), (basis.X * 0.5, None),
                      (basis.X, None)]:
        for i in range(4):
            got = ours.gbasis(basis.mapping, pts, i, tind)[0]
            want = basis.elem.gbasis(basis.mapping, pts, i, tind)[0]
            np.testing.assert_array_equal(got, want)
            np.testing.assert_array_equal(got.grad, want.grad)
            np.testing.assert_array_equal(got.hess, want.hess)
            got.grad[...] = np.nan
    with pytest.raises(ValueError):
        ours.gbasis(basis.mapping, basis.X, 4)


def test_values_alone_bitwise():
    """HermiteLine.values (the probes' path) is gbasis's values, bit for bit, at the
    quadrature points and at one point per listed cell (as a probe asks)."""
    mesh = line_mesh(X)
    basis = Basis(mesh, ElementLineHermite(), intorder=4)
    rng = np.random.default_rng(11)
    cells = rng.integers(0, mesh.t.shape[1], 300)
    pts = rng.uniform(0.0, 1.0, (1, cells.size, 1))
    for where, tind in [(basis.X, np.arange(mesh.t.shape[1])), (pts, cells)]:
        got = HermiteLine().values(basis.mapping, where, tind)
        for i in range(4):
            want = basis.elem.gbasis(basis.mapping, where, i, tind)[0]
            np.testing.assert_array_equal(got[i], np.asarray(want))


def _hermite_interpolant(nodes, values, slopes, x):
    """The cubic Hermite interpolant of node ``values`` and ``slopes`` on the sorted
    ``nodes`` at ``x``, built independently of webfem: per cell, the cubic's coefficients in
    the cell's coordinate t = (x - a) / h solved from its four conditions (a point on a
    node in the cell on its right, the last node in the last cell, as scikit-fem)."""
    k = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, nodes.size - 2)
    a, h = nodes[k], nodes[k + 1] - nodes[k]
    conditions = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [1.0, 1.0, 1.0, 1.0],
                           [0.0, 1.0, 2.0, 3.0]])
    rhs = np.stack([values[k], h * slopes[k], values[k + 1], h * slopes[k + 1]])
    c = np.linalg.solve(conditions, rhs)
    t = (x - a) / h
    return c[0] + t * (c[1] + t * (c[2] + t * c[3]))


def _nodal(basis, y):
    """The node values and slopes of the Hermite DOF vector ``y``, in the order of the
    sorted nodes."""
    order = np.argsort(basis.mesh.p[0])
    return y[basis.nodal_dofs[0][order]], y[basis.nodal_dofs[1][order]]


@pytest.mark.parametrize("order", [1, 2])
def test_probes(order):
    """Pressure values at points (inside cells, on nodes, on the mesh's ends) as
    ``basis.probes(x) @ y`` gives them, bit for bit; the web's the cubic Hermite interpolant
    of its node values and slopes to rounding (1e-13 of its largest value), within
    scikit-fem's own error of its probes (its global monomial basis: 1e-8 relative here);
    from the split bases or read from the composite basis; points outside the mesh are
    refused."""
    p = FoilBearing1D(X, order=order)
    rng = np.random.default_rng(3)
    u = rng.standard_normal(p.n_dofs)
    x = np.concatenate([X, 0.5 * (X[1:] + X[:-1]), rng.uniform(X[0], X[-1], 500),
                        [X[0], X[-1], X[-1], X[0] + 1e-12]])
    want = p.pbasis.probes(x[None, :]) @ u[p.iP]
    np.testing.assert_array_equal(LineProbes(p.pbasis)(x, u[p.iP]), want)
    np.testing.assert_array_equal(LineProbes(p.basis, component=0)(x, u), want)
    exact = _hermite_interpolant(np.sort(X), *_nodal(p.wbasis, u[p.iW_all]), x)
    scale = np.max(np.abs(exact))
    for got in (LineProbes(p.wbasis)(x, u[p.iW_all]), LineProbes(p.basis, component=1)(x, u)):
        np.testing.assert_allclose(got, exact, rtol=0.0, atol=1e-13 * scale)
        np.testing.assert_allclose(got, p.wbasis.probes(x[None, :]) @ u[p.iW_all], rtol=0.0,
                                   atol=1e-7 * scale)
    for c, (basis, dofs) in enumerate([(p.pbasis, p.iP), (p.wbasis, p.iW_all)]):
        split, composite = LineProbes(basis), LineProbes(p.basis, component=c)
        np.testing.assert_array_equal(split.cells(x),
                                      basis.mesh.element_finder(mapping=basis.mapping)(x))
        for outside in ([X[0] - 1.0], [X[-1] + 1.0]):
            with pytest.raises(ValueError):
                composite(np.array(outside), u)
    np.testing.assert_array_equal(p.pressure(u, x), p.pbasis.probes(x[None, :]) @ u[p.iP])


@pytest.mark.parametrize("reverse", [False, True])
def test_hermite_interpolates_cubics(reverse):
    """The nodal DOFs are values and slopes: the probes reproduce a cubic to rounding (1e-14
    of its largest value; scikit-fem's global monomial basis misses by about 1e-8 relative
    far from X = 0), also on a mesh whose nodes and cells run from right to left."""
    mesh = line_mesh(X)
    if reverse:
        mesh = type(mesh)(mesh.p[:, ::-1].copy(), (mesh.p.shape[1] - 1 - mesh.t)[::-1].copy())
    b = Basis(mesh, HermiteLine(), intorder=4)
    xn = b.doflocs[0]
    y = np.zeros(b.N)
    y[b.nodal_dofs[0]] = xn[b.nodal_dofs[0]] ** 3 - xn[b.nodal_dofs[0]]
    y[b.nodal_dofs[1]] = 3 * xn[b.nodal_dofs[1]] ** 2 - 1
    x = np.concatenate([np.linspace(X[0], X[-1], 301), X])
    want = x**3 - x
    np.testing.assert_allclose(LineProbes(b)(x, y), want, rtol=0.0,
                               atol=1e-14 * np.max(np.abs(want)))


@pytest.mark.parametrize("pressure", [ElementLineP1, ElementLineP2])
def test_composite_function_map(pressure):
    """Composite's memoised map of local functions is scikit-fem's ElementComposite's."""
    from skfem import ElementComposite

    from webfem.fem.hermite import Composite

    ours, theirs = Composite(pressure(), HermiteLine()), pressure() * ElementLineHermite()
    for i in range(len(theirs.doflocs)):
        assert tuple(map(int, ours._deduce_bfun(i))) == tuple(map(int, theirs._deduce_bfun(i)))
    np.testing.assert_array_equal(ours.doflocs, theirs.doflocs)
    assert isinstance(ours, ElementComposite)


@pytest.mark.parametrize("nodes", [X, np.array([0.0, 1.0]), np.array([0.0, 1e-9, 1.0]),
                                   np.array([-1.0, 1.0 - 1e-12, 1.0])])
def test_line_mesh_boundaries(nodes):
    """line_mesh's end sets are what scikit-fem's midpoint test gives."""
    from skfem import MeshLine

    lo, hi = nodes[0], nodes[-1]
    want = MeshLine(nodes).with_boundaries({"left": lambda x: np.isclose(x[0], lo),
                                            "right": lambda x: np.isclose(x[0], hi)})
    got = line_mesh(nodes)
    for name in ("left", "right"):
        np.testing.assert_array_equal(got.boundaries[name], want.boundaries[name])
        assert got.boundaries[name].dtype == want.boundaries[name].dtype


def test_probes_keep_recent_point_sets():
    """A point set asked for again is evaluated from its kept values: the same numbers for
    any DOF vector as a probe that never saw it; only the last few point sets are kept."""
    p = FoilBearing1D(X)
    rng = np.random.default_rng(7)
    probes = LineProbes(p.basis, component=1)
    sets = [rng.uniform(X[0], X[-1], 50) for _ in range(probes.keep + 2)]
    for x in sets + sets[::-1]:
        u = rng.standard_normal(p.n_dofs)
        np.testing.assert_array_equal(probes(x, u), LineProbes(p.basis, component=1)(x, u))
    assert len(probes._tables) == probes.keep
