"""The 1-D web's cubic Hermite element, evaluated as scikit-fem does but once per point set.

scikit-fem 12's :class:`~skfem.element.ElementLineHermite` is an ``ElementGlobal``: each call
of ``gbasis(mapping, X, i, tind)`` maps the points to global coordinates, evaluates the
monomials 1, x, x^2, x^3 and their derivatives there (Python lambdas) and combines them with
column i of the cached inverse Vandermonde matrices. A basis, its ``split_bases`` and every
``probes`` call ask for the four functions one at a time at the same points (and the
composite pressure x Hermite element asks for function 0 once more per pressure function), so
the same work is done up to eight times; it was the largest cost of building a 1-D problem
and of evaluating the gap at points.

The classes below override scikit-fem internals (``gbasis``, ``_pbasis_init``,
``_deduce_bfun``), so pyproject.toml pins scikit-fem to 12.x, the versions the bitwise checks
pass on.

:class:`HermiteLine` computes all four functions in one pass and keeps the last point set's
result. The arithmetic is scikit-fem's own, operation by operation and in the same order, so
the values are bitwise the same (tests/test_hermite.py). That matters: the global monomial
basis is ill-conditioned on short cells far from X = 0 (the values carry relative errors of
about 1e-8), and a more accurate formula would move every answer by that much.

:class:`LineProbes` is ``basis.probes(x) @ y`` of a scalar 1-D basis without the probe matrix:
scikit-fem's line element finder compares every point with every cell (quadratic in the
mesh size); here a ``searchsorted`` on the sorted nodes picks the same cells, and the sum over
the local functions runs in the order of the sparse product, so for a Lagrange element the
values are bitwise the same. The local functions' values at the last few point sets are kept
(the driver asks for the nodes several times a solve). On :class:`HermiteLine` (the web's
values at points: gaps, read-outs, the slopes a transfer between meshes differences) they
are the cubic Hermite functions in each cell's own coordinate (:func:`cubic_hermite`), exact
to rounding where the global monomials miss by up to 1e-8 relative: the answers move by
that much (at most 2.5e-4 of their stated errors on the base, grooved and board cases and a
speed sweep), a cold fe2d base solve spends about 4 % less CPU time, and a state carried to
a finer mesh arrives with its slopes right (the cold base case's second coarse mesh started
at a residual of 1.9e-2 instead of 0.31). :class:`Composite` is scikit-fem's composite
element with its map of local functions computed once.

Examples
--------
>>> import numpy as np
>>> from skfem import Basis, MeshLine
>>> b = Basis(MeshLine(np.linspace(0.0, 2.0, 5)), HermiteLine(), intorder=4)
>>> y = np.zeros(b.N); y[b.nodal_dofs[0]] = b.doflocs[0, b.nodal_dofs[0]] ** 2
>>> y[b.nodal_dofs[1]] = 2 * b.doflocs[0, b.nodal_dofs[1]]          # x^2 and its slope
>>> x = np.array([0.3, 1.25, 2.0])
>>> bool(np.allclose(LineProbes(b)(x, y), b.probes(x[None, :]) @ y, rtol=0.0, atol=1e-12))
True
>>> bool(np.allclose(LineProbes(b)(x, y), x ** 2))
True
"""

from __future__ import annotations

import numpy as np
from skfem import ElementComposite, ElementLineHermite
from skfem.element.discrete_field import DiscreteField

__all__ = ["Composite", "HermiteLine", "LineProbes", "cubic_hermite"]


def _same(a, b) -> bool:
    """The same point set or element list (None for all elements)."""
    if a is None or b is None:
        return a is None and b is None
    return a.shape == b.shape and bool(np.array_equal(a, b))


#: (component, its function) of each local function of a composite element, by the
#: sub-elements' types (scikit-fem's ``_deduce_bfun`` depends on their DOF counts only)
_COMPOSITE: dict = {}


def _composite_functions(elem) -> list:
    """``[elem._deduce_bfun(i) for i in range(n)]`` of an ``ElementComposite``, computed
    once per combination of element types (it costs 30 us a call)."""
    key = tuple(type(e) for e in elem.elems)
    if key not in _COMPOSITE:
        n = sum(len(e.doflocs) for e in elem.elems)
        _COMPOSITE[key] = [tuple(int(v) for v in ElementComposite._deduce_bfun(elem, i))
                           for i in range(n)]
    return _COMPOSITE[key]


class Composite(ElementComposite):
    """``ElementComposite`` (what ``P2() * HermiteLine()`` makes) with its map from a local
    function to (component, function) computed once per element types: scikit-fem derives it
    anew on each of the 14 calls a basis makes."""

    def _deduce_bfun(self, i: int):
        return _composite_functions(self)[i]


class HermiteLine(ElementLineHermite):
    """:class:`~skfem.element.ElementLineHermite` with all four functions evaluated at once.

    ``gbasis(mapping, X, i, tind)`` returns what scikit-fem's does, bitwise; the four
    functions at the last (mapping, X, tind) are kept, so the calls for i = 1, 2, 3 (and
    repeated calls for the same points) cost a copy. Like scikit-fem's element it caches mesh
    data (the inverse Vandermonde matrices): use a new instance per mesh.
    """

    #: the power basis (monomials and their derivatives as functions), the same for every
    #: instance: built once, not per mesh
    _shared_pbasis: dict = {}

    def __init__(self):
        super().__init__()
        self._last = None          # (mapping, X, tind, [(value, grad, hess) per function])

    def _pbasis_init(self, maxdeg, dim, Ndiff, is_tensorial=False):
        key = (maxdeg, dim, Ndiff, is_tensorial)
        if key not in HermiteLine._shared_pbasis:
            super()._pbasis_init(maxdeg, dim, Ndiff, is_tensorial)
            HermiteLine._shared_pbasis[key] = self._pbasis
        self._pbasis = HermiteLine._shared_pbasis[key]

    def _all(self, mapping, X, tind):
        """The four functions at X: scikit-fem's ``ElementGlobal.gbasis`` loop, with the
        monomials evaluated once and the sum over them for all four functions at a time."""
        if tind is None:
            tind = np.arange(mapping.mesh.t.shape[1])
        if self.V is None:
            # as ElementGlobal.gbasis: the power basis and the inverted Vandermonde matrices
            self._pbasis_init(self.maxdeg, self.dim, self.derivatives, self.tensorial_basis)
            self.V = np.linalg.inv(self._eval_dofs(mapping.mesh))
        V = self.V[tind]
        x = mapping.F(X, tind=tind)
        n_fun = V.shape[2]
        U = [np.zeros((n_fun,) + (self.dim,) * k + x[0].shape)
             for k in range(self.derivatives + 1)]
        # V[:, itr, :] as (function, element, 1): each product is scikit-fem's
        # V[:, itr, i][:, None] * monomial, and the terms are added in the same order
        Vt = [np.ascontiguousarray(V[:, itr, :].T)[:, :, None] for itr in range(V.shape[1])]
        for k in range(self.derivatives + 1):
            diffs = [()] if k == 0 else [(0,) * k]          # dim = 1: one derivative per order
            for itr in range(len(self._pbasis[()])):
                for diff in diffs:
                    U[k][(slice(None),) + diff] += Vt[itr] * self._pbasis[diff][itr](*x)
        return [(U[0][i], U[1][i], U[2][i]) for i in range(n_fun)]

    def values(self, mapping, X, tind) -> np.ndarray:
        """The four functions' values at X, shape (function, element, point): :meth:`_all`'s
        values alone, by the same operations in the same order (so bitwise the same),
        without the derivatives :meth:`_all` computes too and nothing kept. Why: a probe
        (:class:`LineProbes`) reads values only, at a new point set nearly every call (the
        read-out's root brackets, the minimum's search), and the first and second
        derivatives were two thirds of the work."""
        if self.V is None:
            self._pbasis_init(self.maxdeg, self.dim, self.derivatives, self.tensorial_basis)
            self.V = np.linalg.inv(self._eval_dofs(mapping.mesh))
        V = self.V[tind]
        x = mapping.F(X, tind=tind)
        out = np.zeros((V.shape[2],) + x[0].shape)
        for itr, monomial in enumerate(self._pbasis[()]):
            out += np.ascontiguousarray(V[:, itr, :].T)[:, :, None] * monomial(*x)
        return out

    def gbasis(self, mapping, X, i, tind=None):
        last = self._last
        if last is None or last[0] is not mapping or not _same(last[1], X) \
                or not _same(last[2], tind):
            last = self._last = (mapping, np.array(X), None if tind is None else
                                 np.array(tind), self._all(mapping, X, tind))
        if not 0 <= i < 4:
            self._index_error()
        value, grad, hess = last[3][i]
        # copies: a caller may keep or change what it is given
        return (DiscreteField(value=value.copy(), grad=grad.copy(), hess=hess.copy()),)


def cubic_hermite(x: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The four cubic Hermite functions of the cells [a, b] (node values, in
    :class:`HermiteLine`'s local order: the value and the slope at ``a``, then at ``b``; the
    slopes in global x) at the points ``x``, one cell per point: shape (4, points).

    In the cell's own coordinate s = (x - a) / (b - a), where they are exact to rounding:
    scikit-fem's global monomial basis (:meth:`HermiteLine.values`) is ill-conditioned on
    short cells far from X = 0 and misses even the node values by up to 2.5e-9 (scaled
    gap; 3e-8 of sigma) on the base case's fine mesh. Why here: a probe reads values only,
    at a new point set nearly every call (45 new sets in a cold fe2d base solve), and this
    is a few array operations against the monomials' per-cell Vandermonde products: the
    probes' values 4.1 -> 0.35 ms CPU of that solve's 140 ms (load 4)."""
    h = b - a
    s = (x - a) / h
    s2 = s * s
    s3 = s2 * s
    return np.array([1.0 - 3.0 * s2 + 2.0 * s3, h * (s - 2.0 * s2 + s3), 3.0 * s2 - 2.0 * s3,
                     h * (s3 - s2)])


class LineProbes:
    """Values at points of a finite element function on a line mesh:
    ``LineProbes(basis)(x, y)`` equals ``basis.probes(x[None, :]) @ y`` bitwise, but on
    :class:`HermiteLine`, whose values are the cubic Hermite interpolant's to rounding
    (:func:`cubic_hermite`; scikit-fem's within its own error, 1e-8 relative).

    Parameters
    ----------
    basis : a scikit-fem cell basis on a ``MeshLine`` with one scalar component, or a
        composite basis (``ElementComposite``) and ``component``.
    component : for a composite basis, the part to evaluate: ``LineProbes(basis, c)(x, u)``
        with the composite DOF vector ``u`` equals ``split_bases()[c].probes(x[None, :])
        @ u[split_indices()[c]]`` (as above), without building the split basis.
    """

    #: point sets whose values are kept
    keep = 4

    def __init__(self, basis, component: int | None = None):
        self.basis = basis
        self._tables: dict = {}
        mesh = basis.mesh
        p = mesh.p[0]
        # scikit-fem's finder: the cell whose right node is the first node right of x
        self._ix = np.argsort(p)
        self._sorted = p[self._ix]
        right = mesh.t[np.argmax(p[mesh.t], 0), np.arange(mesh.t.shape[1])]
        self._cell_of_right = np.full(p.size, -1, dtype=np.int64)
        self._cell_of_right[right] = np.arange(mesh.t.shape[1])
        dofs = np.asarray(basis.element_dofs)
        if component is None:
            self._elem, self._dofs = basis.elem, dofs
        else:
            # the composite's local functions of this component, in the sub-element's order
            # (the split basis's): (sub-element function, composite function)
            elem = basis.elem
            local = sorted((k, i) for i, (c, k) in enumerate(_composite_functions(elem))
                           if c == component)
            self._elem = elem.elems[component]
            self._dofs = dofs[[i for _, i in local]]

    def cells(self, x: np.ndarray) -> np.ndarray:
        """The cell holding each point, as scikit-fem's ``MeshLine1.element_finder`` picks it
        (a point on a node belongs to the cell on its right, the last node to the last cell).

        Raises
        ------
        ValueError
            For a point outside the mesh (as scikit-fem).
        """
        xin = x.copy()
        xin[x == self._sorted[-1]] = self._sorted[-2:].mean()
        j = np.digitize(xin, self._sorted)
        if np.any(j >= self._sorted.size):
            raise ValueError("Point is outside of the mesh.")
        cells = self._cell_of_right[self._ix[j]]
        if np.any(cells < 0):
            raise ValueError("Point is outside of the mesh.")
        return cells.astype(np.int32)

    def _table(self, x: np.ndarray):
        """Per local function, its values at the points x and the DOFs it multiplies; the
        last few point sets are kept (the driver asks for the nodes several times)."""
        key = x.tobytes()
        table = self._tables.pop(key, None)
        if table is None:
            b = self.basis
            cells = self.cells(x)
            if isinstance(self._elem, HermiteLine):
                t, p = b.mesh.t, b.mesh.p[0]
                phi = cubic_hermite(x, p[t[0, cells]], p[t[1, cells]])
                table = [(phi[k], self._dofs[k, cells]) for k in range(self._dofs.shape[0])]
            else:
                pts = b.mapping.invF(x[None, :, None], tind=cells)
                table = [(np.asarray(self._elem.gbasis(b.mapping, pts, k, tind=cells)[0])
                          .ravel(), self._dofs[k, cells]) for k in range(self._dofs.shape[0])]
            while len(self._tables) >= self.keep:
                self._tables.pop(next(iter(self._tables)))
        self._tables[key] = table              # the most recently used last
        return table

    def __call__(self, x, y) -> np.ndarray:
        """The function with global DOFs ``y`` (of ``basis``) at the points ``x`` (1-D
        array)."""
        x = np.asarray(x, float).ravel()
        out = np.zeros(x.size)
        # the sparse product adds the local functions' terms in this order
        for phi, dofs in self._table(x):
            out += phi * y[dofs]
        return out
