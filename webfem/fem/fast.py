"""Vectorised assembly of the weak forms, in scikit-fem's terms.

The decorated forms of :mod:`webfem.fem.forms`, :mod:`webfem.fem.film2d` and
:mod:`webfem.fem.web` are the definition of the discrete problem; scikit-fem assembles a
bilinear form by calling its kernel once per pair of local basis functions, which made the
Jacobian assembly most of the cost of a solve. This module assembles the same integrals from
the same scikit-fem objects (a basis's values ``basis.basis``, quadrature weights ``basis.dx``
and DOF map ``basis.element_dofs``), read once per mesh, with each element contribution
contracted by ``numpy.einsum`` over all elements at once:

    F_i = sum_e sum_q dx[e, q] f[e, q] phi_i[e, q],
    A_ij = sum_e sum_q dx[e, q] a[e, q] phi_i[e, q] psi_j[e, q]

(``f``, ``a``: the coefficient arrays of the forms' own coefficient functions, so the physics
lives in one place). The sparsity pattern of a Jacobian is built once per mesh
(:class:`Pattern`); each call only refills the data array of a CSR matrix whose index arrays
stay the same objects, which lets :func:`webfem.fem.newton.solve_linear` reuse its
reduction to the free unknowns and its fill-reducing ordering.

``USE_FORMS = True`` (or the models' ``reference=True``) assembles with the decorated forms
instead: tests/test_fast.py checks the two against each other to 1e-12.

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

import numpy as np
import scipy.sparse as sp

__all__ = ["USE_FORMS", "BasisData", "Pattern"]

#: True: the models assemble with the decorated forms (the reference), not this module.
USE_FORMS = False


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
            self.phi_c.append(np.array([np.asarray(fields[i]) for i in idx]))
            self.grad_c.append(np.array([np.asarray(fields[i].grad) for i in idx]))
            self.hess_c.append(np.array([np.asarray(fields[i].hess)[0, 0] for i in idx])
                               if c in hess else None)
        self.all = self.index[0]

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
        keys, self.slot = _unique_inverse(rows * self.shape[1] + cols)
        r = keys // self.shape[1]
        self.indices = (keys - r * self.shape[1]).astype(np.int32)     # cheaper than %
        self.indptr = np.searchsorted(r, np.arange(self.shape[0] + 1)).astype(np.int32)
        self.nnz = keys.size

    def matrix(self, values) -> sp.csr_matrix:
        """The CSR matrix with the blocks' values (same order and shapes as the blocks)."""
        data = np.bincount(self.slot, weights=np.concatenate([np.ravel(v) for v in values]),
                           minlength=self.nnz)
        A = sp.csr_matrix(self.shape)
        A.data, A.indices, A.indptr = data, self.indices, self.indptr
        return A


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


def _test_layout(test) -> np.ndarray:
    """A test-function array, (function, element, point) or stacked (term, function, element,
    point), as the right operand of :func:`_contract`: (element, [term x] point, function)."""
    if np.ndim(test) == 4:
        ns, ni, ne, nq = test.shape
        return np.einsum("sieq->esqi", test).reshape(ne, ns * nq, ni)
    return np.einsum("ieq->eqi", test)


def _contract(test_layout, trial) -> np.ndarray:
    """:meth:`BasisData.bilinear` (``a=None``) with the test side from :func:`_test_layout`.

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
    return np.matmul(a, test_layout).transpose(2, 1, 0)


class LineAssembler:
    """The 1-D film + web system (:func:`webfem.fem.forms.residual`, ``jacobian`` and, for P1
    pressure, the lumped ``sink_residual`` / ``sink_jacobian`` on ``sink_basis``).

    ``basis``: the composite (pressure x Hermite web) basis; ``sink``: True when the Darcy
    sink is in :func:`~webfem.fem.forms.coefficients` (P2), False when it is lumped apart.
    """

    def __init__(self, basis, sink_basis=None):
        from . import forms

        self.forms = forms
        self.b = b = BasisData(basis, hess=(1,))
        self.s = BasisData(sink_basis) if sink_basis is not None else None
        ip, iw = b.index
        q, gq = b.phi_c[0], b.grad_c[0][:, 0]
        v, gv, hv = b.phi_c[1], b.grad_c[1][:, 0], b.hess_c[1]
        self.q, self.gq, self.v, self.gv, self.hv = q, gq, v, gv, hv
        blocks = [b.pairs(ip, ip), b.pairs(ip, iw), b.pairs(iw, ip), b.pairs(iw, iw)]
        if self.s is not None:
            blocks.append(self.s.pairs(self.s.index[0], self.s.index[0]))
        self.pattern = Pattern(blocks, (b.N, b.N))
        # the test functions of the Jacobian's blocks, laid out once for _contract (its
        # operand as numpy's einsum optimiser prepares it on every call)
        self._t_pp = _test_layout(np.stack([gq, q]))
        self._t_gq = _test_layout(gq)
        self._t_v = _test_layout(v)
        # the state-independent blocks: -dp v, dw' v' and dw'' v'' (times Dn)
        self.wp = -_contract(self._t_v, q * b.dx)
        self.ww_membrane = _contract(_test_layout(gv), gv * b.dx)
        self.ww_bending = _contract(_test_layout(hv), hv * b.dx)
        self._t_sink = _test_layout(self.s.phi) if self.s is not None else None
        self._last = None       # (u, args, sink, coefficients) of the last state
        self._geometry = {}     # beta: the roller's departure and the wrap at the points

    def _coefficients(self, u, args, sink):
        """The forms' coefficients at the quadrature points for the state u, kept for the
        last (u, args, sink): Newton asks for the Jacobian at the state whose residual its
        line search has just evaluated."""
        last = self._last
        if last is not None and last[2] == sink and last[1] == args \
                and np.array_equal(last[0], u):
            return last[3]
        b = self.b
        P, dP = b.interpolate(u, 0)
        W, dW, ddW = b.interpolate(u, 1, hess=True)
        beta = args["beta"]
        if beta not in self._geometry:
            self._geometry = {beta: (self.forms.departure(b.x, beta),
                                     self.forms.in_wrap(b.x, beta))}
        out = (self.forms.coefficients(b.x, P, dP[0], W, args, sink=sink,
                                       geometry=self._geometry[beta]), dW[0], ddW)
        self._last = (np.array(u, float, copy=True), args, sink, out)
        return out

    def residual(self, u, prm, sink: bool) -> np.ndarray:
        b, dx = self.b, self.b.dx
        args = prm.as_form_args()
        c, dW, ddW = self._coefficients(u, args, sink)
        fp = b.linear(self.gq, c["flux"] * dx)
        if sink:
            fp = fp + b.linear(self.q, c["sink"] * dx)
        fw = (b.linear(self.gv, dW * dx) + b.linear(self.hv, prm.Dn * (ddW - c["chi"]) * dx)
              - b.linear(self.v, c["load"] * dx))
        F = b.scatter(fp, b.index[0]) + b.scatter(fw, b.index[1])
        if self.s is not None and prm.K:
            s = self.s
            P = s.interpolate(u, 0)[0]
            F += s.scatter(s.linear(s.phi, prm.K * (1.0 + prm.ds * P) * P * s.dx), s.index[0])
        return F

    def jacobian(self, u, prm, newton: bool, sink: bool) -> sp.csr_matrix:
        b, dx = self.b, self.b.dx
        c, _, _ = self._coefficients(u, prm.as_form_args(), sink)
        j = self.forms.jacobian_coefficients(c, newton)
        q, gq = self.q, self.gq
        # BasisData.bilinear's products, with the test side prepared once per mesh
        if sink:
            pp = _contract(self._t_pp, np.stack([gq * (j["j_dp"] * dx) + q * (j["j_p"] * dx),
                                                 q * (j["j_sink"] * dx)]))
        else:
            pp = _contract(self._t_gq, gq * (j["j_dp"] * dx) + q * (j["j_p"] * dx))
        pw = _contract(self._t_gq, self.v * (j["j_w"] * dx))
        ww = (self.ww_membrane + prm.Dn * self.ww_bending
              + _contract(self._t_v, self.v * (j["k_c"] * dx)))
        values = [pp, pw, self.wp, ww]
        if self.s is not None:
            s = self.s
            if prm.K:
                P = s.interpolate(u, 0)[0]
                a = prm.K * (1.0 + (2.0 if newton else 1.0) * prm.ds * P) * s.dx
                values.append(_contract(self._t_sink, s.phi * a))
            else:
                values.append(np.zeros(self.pattern.sizes[-1]))
        return self.pattern.matrix(values)


class FilmAssembler:
    """The 2-D film + 1-D web system (:mod:`webfem.fem.film2d`, :mod:`webfem.fem.web` and
    the transfer matrices ``T`` of :func:`webfem.fem.transfer.quadrature_matrices`).

    Unknowns ``[p (film DOFs), w (web DOFs)]``. Each film cell lies in one web cell, so the
    web's Hermite functions at a film cell's quadrature points are a dense (4, points) block:
    the film-web Jacobian block is assembled element by element like the others.
    """

    def __init__(self, fbasis, wbasis, T, width: float, groove=None):
        self.f = f = BasisData(fbasis)
        #: groove depth at the quadrature points (grooved roller), added to the web's gap
        self.groove = 0.0 if groove is None else np.asarray(groove, float)
        self.w = w = BasisData(wbasis, hess=(0,))
        self.T, self.width = T, width
        self.nP = nP = f.N
        nel, nq = f.dx.shape
        # the web cell holding each film cell and the web functions there
        wd, self.M_loc = T["M_dofs"], T["M_loc"]                    # (4, nel), (4, nel, nq)
        M = T["M"].tocsr()
        self.gx, self.gz = f.grad_c[0][:, 0], f.grad_c[0][:, 1]
        self.gw, self.hw = w.grad_c[0][:, 0], w.hess_c[0]
        # the width average's load on the web: -(1/width) M^T dx B0, constant (the product
        # is CSC: to CSR directly, canonical, not through COO)
        self.Jwp = (-(M.T @ sp.diags(T["dx"]) @ T["B0"]) / width).tocsr()
        Jwp = self.Jwp.tocoo()
        blocks = [f.pairs(f.all, f.all),
                  (np.broadcast_to(f.dofs[:, None, :], (f.dofs.shape[0],) + wd.shape),
                   np.broadcast_to(wd[None, :, :] + nP, (f.dofs.shape[0],) + wd.shape)),
                  (Jwp.row + nP, Jwp.col),
                  w.pairs(w.all, w.all, nP, nP)]
        self.pattern = Pattern(blocks, (nP + w.N, nP + w.N))
        self.Jwp_data = Jwp.data
        self.ww_membrane = w.bilinear(self.gw, self.gw, w.dx)
        self.ww_bending = w.bilinear(self.hw, self.hw, w.dx)
        self.tests_pp = f.tests([self.gx, self.gz, f.phi])
        self.tests_pw = f.tests([self.gx, self.gz])

    def _film(self, u, prm, newton=True):
        from .film2d import film_coefficients
        from .forms import departure

        f, T = self.f, self.T
        p, wv = u[:self.nP], u[self.nP:]
        P, gP = f.interpolate(p)
        H = (T["M"] @ wv + departure(T["x"], prm.beta)).reshape(P.shape) + self.groove
        return P, gP, film_coefficients(H, P, gP[0], gP[1], prm.as_form_args(), newton)

    def _web(self, u, prm):
        from .web import web_coefficients

        W, dW, ddW = self.w.interpolate(u[self.nP:], 0, hess=True)
        return dW[0], ddW, web_coefficients(self.w.x, W, prm.as_form_args())

    def residual(self, u, prm) -> np.ndarray:
        f, w = self.f, self.w
        P, gP, c = self._film(u, prm)
        dx = f.dx
        Fp = f.scatter(f.linear(self.gx, (c["D"] * gP[0] - c["C"]) * dx)
                       + f.linear(self.gz, c["D"] * gP[1] * dx) + f.linear(f.phi, c["S"] * dx),
                       f.all)
        dW, ddW, wc = self._web(u, prm)
        dx = w.dx
        Fw = w.scatter(w.linear(self.gw, dW * dx)
                       + w.linear(self.hw, prm.Dn * (ddW - wc["chi"]) * dx)
                       - w.linear(w.phi, wc["load"] * dx), w.all)
        return np.concatenate([Fp, Fw + self.Jwp @ u[:self.nP]])

    def jacobian(self, u, prm, newton: bool = True) -> sp.csr_matrix:
        f, w = self.f, self.w
        _, _, c = self._film(u, prm, newton)
        dx, q, gx, gz = f.dx, f.phi, self.gx, self.gz
        jD, jS = c["jD"] * dx, c["jS"] * dx
        jX, jZ = c["jX"] * dx, c["jZ"] * dx
        pp = f.contract(self.tests_pp, [gx * jD + q * jX, gz * jD + q * jZ, q * jS])
        pw = f.contract(self.tests_pw, [self.M_loc * (c["hX"] * dx),
                                        self.M_loc * (c["hZ"] * dx)])
        _, _, wc = self._web(u, prm)
        ww = (self.ww_membrane + prm.Dn * self.ww_bending
              + w.bilinear(w.phi, w.phi, wc["k_c"] * w.dx))
        return self.pattern.matrix([pp, pw, self.Jwp_data, ww])
