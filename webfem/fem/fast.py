"""The machinery of the vectorised assembly, in scikit-fem's terms.

scikit-fem assembles a bilinear form by calling its kernel once per pair of local basis
functions, which made the Jacobian assembly most of the cost of a solve. The assembly that
:mod:`webfem.fem.weakform` generates from the declared forms computes the same integrals from
the same scikit-fem objects (a basis's values ``basis.basis``, quadrature weights ``basis.dx``
and DOF map ``basis.element_dofs``), read once per mesh by :class:`BasisData`, with each
element contribution contracted over all elements at once:

    F_i = sum_e sum_q dx[e, q] f[e, q] phi_i[e, q],
    A_ij = sum_e sum_q dx[e, q] a[e, q] phi_i[e, q] psi_j[e, q]

(:func:`contract_layout`; ``f``, ``a``: the coefficient arrays of the forms' coefficient
functions, so the physics lives in one place). The sparsity pattern of a Jacobian is built
once per mesh (:class:`Pattern`); each call only refills the data array of a CSR matrix
whose index arrays stay the same objects, which lets :class:`webfem.fem.newton.PatternSolver`
reuse its reduction to the free unknowns and its fill-reducing ordering.

Examples
--------
>>> import numpy as np
>>> from skfem import Basis, ElementLineP1, MeshLine
>>> b = BasisData(Basis(MeshLine(np.linspace(0.0, 1.0, 5)), ElementLineP1()))
>>> pat = Pattern([b.pairs(b.all, b.all)], (b.N, b.N))
>>> A = pat.matrix([b.bilinear(b.phi, b.phi, b.dx)])     # the mass matrix
>>> round(float(A.sum()), 12)
1.0
"""

from __future__ import annotations

import hashlib

import numpy as np
import scipy.sparse as sp

__all__ = ["BasisData", "Pattern", "pattern_of", "test_layout", "contract_layout",
           "contract_laid", "PATTERNS_KEPT"]

class BasisData:
    """A scikit-fem basis read once: per local basis function, its values, gradients and
    (when asked) second X-derivatives at the quadrature points, split by component.

    For a composite element (1-D: pressure x Hermite web) ``component`` picks which part;
    ``index[c]`` lists the local functions that are non-zero in component c (the others are
    identically zero there and skipped). Arrays are shaped (local function, element,
    quadrature point); gradients (local function, direction, element, quadrature point).
    """

    def __init__(self, basis, hess: tuple[int, ...] = ()):
        self.N = basis.N
        self.dofs = np.asarray(basis.element_dofs)                  # (Nbfun, nel)
        self.dx = np.asarray(basis.dx)                              # (nel, nq)
        self.x = np.asarray(basis.global_coordinates()[0])          # (nel, nq) X
        ncomp = len(basis.basis[0])
        self.index, self.phi_c, self.grad_c, self.hess_c = [], [], [], []
        for c in range(ncomp):
            fields = [basis.basis[i][c] for i in range(basis.Nbfun)]
            idx = [i for i, f in enumerate(fields)
                   if np.any(np.asarray(f)) or np.any(np.asarray(f.grad))]
            self.index.append(np.array(idx, dtype=int))
            self.phi_c.append(_values(fields[i] for i in idx))
            self.grad_c.append(np.array([np.asarray(fields[i].grad) for i in idx]))
            self.hess_c.append(np.array([np.asarray(fields[i].hess)[0, 0] for i in idx])
                               if c in hess else None)
        self.all = self.index[0]

    def share_gradients(self, basis) -> None:
        """Make the gradients ``basis`` (the one read, a scalar element) holds views of this
        object's copies: the same numbers, each a C-contiguous array shaped as before, held
        once instead of twice (120 MB at 3.9e5 film unknowns). scikit-fem's values are a
        broadcast of the reference element's and cost nothing; its gradients are per element."""
        if len(self.grad_c) != 1 or len(self.index[0]) != basis.Nbfun:
            raise ValueError("share_gradients: a scalar element with every function present")
        for i in range(basis.Nbfun):
            field = basis.basis[i][0]
            if field.grad.shape != self.grad_c[0][i].shape:
                raise ValueError("share_gradients: not the basis this object read")
            field.grad = self.grad_c[0][i]

    @property
    def phi(self):
        return self.phi_c[0]

    def dofs_of(self, c: int = 0) -> np.ndarray:
        """Global DOFs (local function, element) of component c's local functions."""
        return self.dofs[self.index[c]]

    def interpolate(self, u, c: int = 0, hess: bool = False):
        """Value, gradient (direction, element, point) and, with ``hess``, second X-derivative
        of the finite element function with global DOFs ``u`` (component c)."""
        coef = u[self.dofs_of(c)]                                   # (n, nel)
        val = np.einsum("ie,ieq->eq", coef, self.phi_c[c])
        grad = np.einsum("ie,ideq->deq", coef, self.grad_c[c])
        if hess:
            return val, grad, np.einsum("ie,ieq->eq", coef, self.hess_c[c])
        return val, grad

    @staticmethod
    def linear(test, f) -> np.ndarray:
        """sum_q f[e, q] test[i, e, q] per (local function, element); ``f`` includes dx."""
        return np.einsum("ieq,eq->ie", test, f)

    @staticmethod
    def bilinear(test, trial, a=None) -> np.ndarray:
        """sum_q a[e, q] test[i, e, q] trial[j, e, q] per (i, j, element); ``a`` includes dx.

        ``test`` and ``trial`` may be stacked (term, function, element, point), ``trial``
        already weighted (``a=None``): the terms are summed in one contraction.
        """
        if a is not None:
            trial = trial * a
        if np.ndim(test) == 4:
            return np.einsum("sieq,sjeq->ije", test, trial, optimize=True)
        return np.einsum("ieq,jeq->ije", test, trial, optimize=True)

    @staticmethod
    def tests(arrays) -> np.ndarray:
        """Test-function arrays (each (function, element, point)) stacked for
        :meth:`contract`: (element, function, term x point), built once per mesh."""
        st = np.stack(arrays)                                       # (s, i, e, q)
        return np.ascontiguousarray(st.transpose(2, 1, 0, 3)).reshape(
            st.shape[2], st.shape[1], -1)

    @staticmethod
    def contract(tests, trials) -> np.ndarray:
        """sum_s sum_q tests_s[i, e, q] trials_s[j, e, q] per (i, j, element), with ``tests``
        from :meth:`tests` and ``trials`` weighted (coefficient times dx): one batched
        matrix product over the elements."""
        nj, nel, nq = trials[0].shape
        tr = np.empty((nel, len(trials), nq, nj))
        for k, a in enumerate(trials):
            tr[:, k] = a.transpose(1, 2, 0)
        return np.matmul(tests, tr.reshape(nel, -1, nj)).transpose(1, 2, 0)

    def pairs(self, rows, cols, row_offset: int = 0, col_offset: int = 0):
        """Global (row, column) arrays of the local block (local rows, local cols), shaped
        like :meth:`bilinear`'s output."""
        r = self.dofs[rows][:, None, :] + row_offset
        c = self.dofs[cols][None, :, :] + col_offset
        return np.broadcast_to(r, (len(rows), len(cols), r.shape[-1])), \
            np.broadcast_to(c, (len(rows), len(cols), c.shape[-1]))

    def scatter(self, local, rows, n: int | None = None) -> np.ndarray:
        """Sum a (local function, element) array into a global vector of length n."""
        return np.bincount(self.dofs[rows].ravel(), weights=local.ravel(),
                           minlength=self.N if n is None else n)


def _values(fields) -> np.ndarray:
    """The functions' values stacked (function, element, point). Where scikit-fem's are a
    broadcast of the reference element's along the elements (an H1 element: the values do
    not depend on the cell's map), so is the stack: read-only, the same numbers (60 MB
    fewer at 3.9e5 film unknowns; numpy's contractions over it give the same bits,
    tests/test_fast.py)."""
    vals = [np.asarray(f) for f in fields]
    if vals and all(v.ndim == 2 and v.strides[0] == 0 for v in vals):
        return np.broadcast_to(np.array([v[:1] for v in vals]), (len(vals),) + vals[0].shape)
    return np.array(vals)


class Pattern:
    """A fixed CSR sparsity pattern: the union of element blocks' (row, column) pairs.

    Built once per mesh; :meth:`matrix` sums the blocks' values into it. Each returned matrix
    shares the same ``indices`` and ``indptr`` arrays (a consumer may cache what it derives
    from the pattern, keyed on them).
    """

    def __init__(self, blocks, shape):
        self.shape = tuple(int(s) for s in shape)
        rows = np.concatenate([np.ravel(r) for r, _ in blocks]).astype(np.int64)
        cols = np.concatenate([np.ravel(c) for _, c in blocks]).astype(np.int64)
        self.sizes = [np.size(r) for r, _ in blocks]
        keys, slot = _unique_inverse(rows * self.shape[1] + cols)
        # int32: half the memory of a kept pattern, the same bincount time
        self.slot = slot.astype(np.int32) if keys.size < 2**31 else slot
        r = keys // self.shape[1]
        self.indices = (keys - r * self.shape[1]).astype(np.int32)     # cheaper than %
        self.indptr = np.searchsorted(r, np.arange(self.shape[0] + 1)).astype(np.int32)
        self.nnz = keys.size
        #: what a consumer derives from the pattern, kept with it (the factorisation plans
        #: of :class:`webfem.fem.newton.PatternSolver`)
        self.plans: dict = {}

    def matrix(self, values) -> sp.csr_matrix:
        """The CSR matrix with the blocks' values (same order and shapes as the blocks)."""
        # the blocks in one array, in their order, copied once (a block from
        # :func:`contract_laid` is a transposed view: ravel and concatenate copied it twice)
        weights = np.empty(sum(np.size(v) for v in values))
        at = 0
        for v in values:
            weights[at:at + np.size(v)].reshape(np.shape(v))[...] = v
            at += np.size(v)
        data = np.bincount(self.slot, weights=weights, minlength=self.nnz)
        A = sp.csr_matrix(self.shape)
        A.data, A.indices, A.indptr = data, self.indices, self.indptr
        return A


#: The patterns used last, by the bytes of the blocks' DOF maps, the least recently used
#: dropped first (:func:`pattern_of`): a continued sweep point's mesh is the previous point's
#: moved (the same cells and DOFs at other coordinates), so the same pattern. A pattern is a
#: function of the DOF maps alone: one kept is the one built again, and sharing its index
#: arrays lets :class:`webfem.fem.newton.PatternSolver` reuse its ordering plan too (a pure
#: cache: no answer depends on what was built before). A kept pattern's plans go with it
#: (:attr:`Pattern.plans`).
PATTERNS: dict = {}
#: At most this many patterns are kept ...
PATTERNS_KEPT = 8
#: ... and beyond the :data:`PATTERNS_ALWAYS` used last, only while all kept hold at most
#: :data:`PATTERNS_BYTES` (their arrays and plans). Why: a cold fe2d solve of the base case
#: uses five patterns (the 1-D start's two meshes, the coarse mesh, the one its gap asks for,
#: the answer's), and four kept first in first out dropped each before it was asked for
#: again: every repeated cold solve built all five and their seven plans again (the bytes
#: bound keeps the memory of large meshes' patterns where four of them put it).
PATTERNS_ALWAYS = 4
PATTERNS_BYTES = 64 * 2**20


def pattern_of(dof_pairs, shape) -> Pattern:
    """The :class:`Pattern` of the blocks whose (row, column) DOFs are the outer products of
    ``dof_pairs`` ((row DOFs (function, element), column DOFs (function, element)) per
    block), kept in :data:`PATTERNS`."""
    h = hashlib.blake2b(repr(tuple(int(s) for s in shape)).encode(), digest_size=32)
    # each array hashed once, then named by its place among the distinct ones: a system's
    # blocks share their fields' DOF maps (the film's appeared in three of its four
    # blocks), and hashing them was a sixth of building a 2-D system on a kept pattern
    seen: dict = {}
    for r, c in dof_pairs:
        for a in (r, c):
            if id(a) not in seen:
                seen[id(a)] = (len(seen), a)     # ``a`` held: its id stays its own
                b = np.ascontiguousarray(a, dtype=np.int64)
                h.update(b"new" + repr(b.shape).encode())
                h.update(b.tobytes())
            else:
                h.update(b"seen" + repr(seen[id(a)][0]).encode())
    key = h.digest()
    pattern = PATTERNS.pop(key, None)
    if pattern is None:
        blocks = [(np.broadcast_to(r[:, None, :], (r.shape[0],) + c.shape),
                   np.broadcast_to(c[None, :, :], (r.shape[0],) + c.shape))
                  for r, c in dof_pairs]
        pattern = Pattern(blocks, shape)
        while len(PATTERNS) >= PATTERNS_KEPT or (
                len(PATTERNS) >= PATTERNS_ALWAYS
                and sum(_nbytes(p) for p in PATTERNS.values()) + _nbytes(pattern)
                > PATTERNS_BYTES):
            PATTERNS.pop(next(iter(PATTERNS)))
    PATTERNS[key] = pattern                 # the most recently used last
    return pattern


def _nbytes(value) -> int:
    """The bytes of the arrays in ``value`` (a :class:`Pattern` with its plans, or the
    tuples, dicts and arrays they hold)."""
    if isinstance(value, np.ndarray):
        return value.nbytes
    if isinstance(value, Pattern):
        return _nbytes((value.slot, value.indices, value.indptr, value.plans))
    if isinstance(value, dict):
        return sum(_nbytes(v) for v in value.values())
    if isinstance(value, (tuple, list)):
        return sum(_nbytes(v) for v in value)
    return 0


def _unique_inverse(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``np.unique(keys, return_inverse=True)``, element for element (tests/test_fast.py).

    np.unique argsorts with quicksort: most of the cost of a 2-D :class:`Pattern` (~5e5
    keys). The keys of element blocks come in long sorted runs (each element's DOFs, element
    after element), which numpy's stable sort merges about twice as fast.
    """
    order = np.argsort(keys, kind="stable")
    ordered = keys[order]
    new = np.empty(keys.size, dtype=bool)
    new[:1] = True
    np.not_equal(ordered[1:], ordered[:-1], out=new[1:])
    inverse = np.empty(keys.size, dtype=np.intp)
    inverse[order] = np.cumsum(new, dtype=np.intp) - 1
    return ordered[new], inverse


def test_layout(test) -> np.ndarray:
    """A test-function array, (function, element, point) or stacked (term, function, element,
    point), as the right operand of :func:`contract_layout`: (element, [term x] point,
    function). A list of (function, element, point) arrays is taken as their stack, laid
    out without it (the same array: each term copied once into place, where the stack and
    the layout of it copied the film's operators twice per mesh)."""
    if isinstance(test, (list, tuple)):
        ni, ne, nq = np.shape(test[0])
        out = np.empty((ne, len(test), nq, ni))
        for s, op in enumerate(test):
            out[:, s] = np.transpose(op, (1, 2, 0))
        return out.reshape(ne, len(test) * nq, ni)
    if np.ndim(test) == 4:
        ns, ni, ne, nq = test.shape
        return np.einsum("sieq->esqi", test).reshape(ne, ns * nq, ni)
    return np.einsum("ieq->eqi", test)


def contract_layout(layout, trial) -> np.ndarray:
    """:meth:`BasisData.bilinear` (``a=None``) with the test side from :func:`test_layout`.

    ``np.einsum(..., optimize=True)`` searches a contraction path on every call, which cost
    as much as the contraction for these small arrays; its path for both equations is one
    batched matrix product over the elements, (e, j, [s] q) @ (e, [s] q, i), done here
    directly with the operands laid out as numpy's ``bmm_einsum`` lays them out, so the
    values are the same bit for bit (tests/test_fast.py).
    """
    if np.ndim(trial) == 4:
        ns, nj, ne, nq = trial.shape
        a = np.einsum("sjeq->ejsq", trial).reshape(ne, nj, ns * nq)
    else:
        a = np.einsum("jeq->ejq", trial)
    return contract_laid(layout, a)


def contract_laid(layout, a) -> np.ndarray:
    """:func:`contract_layout` with the trial side already laid out, ``a`` of shape
    (element, trial function, [term x] point): (test function, trial function, element)."""
    return np.matmul(a, layout).transpose(2, 1, 0)
