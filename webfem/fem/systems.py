"""The coupled film + web systems of one mesh, assembled from the declarations of
:mod:`webfem.fem.forms`: the 1-D system on a composite basis (:class:`LineSystem`) and the
2-D film on its tensor mesh with the 1-D web (:class:`FilmSystem`).

Each offers ``residual(u, prm)`` and ``jacobian(u, prm, newton)`` by the vectorised assembly
generated from the declarations (:class:`webfem.fem.weakform.FastForm`), and the same from
the scikit-fem forms generated from them (``reference_residual``, ``reference_jacobian``: the
readable reference, seconds on a 2-D mesh; tests/test_forms.py compares the two). The film's
blocks that reach the web on its own mesh (the 2-D film-web terms and the width average)
assemble through the transfer matrices there (:mod:`webfem.fem.transfer`). The state enters
both only through the coefficient functions of :mod:`webfem.fem.forms`.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from . import forms
from .fast import BasisData
from .transfer import basis_matrices
from .forms import (COUPLING, FILM, SINK, WEB, coupling_coefficients,
                    film_jacobian_coefficients, film_residual_coefficients, web_coefficients)
from .weakform import FastForm, Part, Space, coefficient, skfem_forms

__all__ = ["LineSystem", "FilmSystem", "width_load", "cell_lengths"]


def cell_lengths(basis) -> np.ndarray:
    """The length along X of the cell of each quadrature point of ``basis`` (element,
    point): the cell size in the film's streamline diffusion (:func:`webfem.fem.forms.
    film_coefficients`)."""
    mesh = basis.mesh
    x = mesh.p[0, mesh.t]                                       # (vertex, element)
    return np.broadcast_to((x.max(axis=0) - x.min(axis=0))[:, None],
                           np.shape(basis.dx)).copy()


def width_load(T: dict, Pq: np.ndarray, width: float) -> np.ndarray:
    """The web's load from the film: (1/width) int v(X) P(X, Z) dX dZ at the film's
    quadrature points (``Pq``, flattened), as web DOFs: ``M^T (dx P) / width``."""
    return T["M"].T @ (T["dx"] * Pq) / width


class _LastState:
    """The coefficients of the last state asked for: Newton asks for the Jacobian at the
    state whose residual its line search has just evaluated. The residual's coefficients
    are computed first, the Jacobian's (per ``newton``) from their parts only when a
    Jacobian is asked for: most residuals (line-search trials, chord steps) never get one."""

    def __init__(self):
        self._key = None
        self._value = None
        self._full: dict = {}

    def get(self, u, args, compute, newton=None, extend=None):
        """The residual's coefficients at ``u`` (``compute()``: ``(values, parts)``), or with
        ``newton`` (True/False) every coefficient: those merged with ``extend(parts,
        newton)``'s, one dict per part."""
        key = self._key
        if key is None or key[1] != args or not np.array_equal(key[0], u):
            self._value = compute()
            self._key = (np.array(u, float, copy=True), args)
            self._full = {}
        values, parts = self._value
        if newton is None:
            return values
        if newton not in self._full:
            self._full[newton] = [{**v, **j} for v, j in zip(values, extend(parts, newton))]
        return self._full[newton]

    def forget(self) -> None:
        """Let the kept coefficients go (computed again if asked for)."""
        self._key = self._value = None
        self._full = {}


class LineSystem:
    """The 1-D film + web system on ``basis`` (P1 or P2 pressure x Hermite web, one composite
    element). ``sink_basis``: the same element with nodal quadrature, on which the Darcy sink
    is lumped (P1); None: the sink is integrated with the rest (P2)."""

    def __init__(self, basis, sink_basis=None):
        self.basis, self.sink_basis = basis, sink_basis
        self.b = b = BasisData(basis, hess=(1,))
        spaces = {"p": Space.from_basis(b, 0), "w": Space.from_basis(b, 1)}
        main = (FILM, WEB, COUPLING) + (() if sink_basis is not None else (SINK,))
        parts = [Part(main, spaces, b.dx)]
        self.s = None
        if sink_basis is not None:
            self.s = s = BasisData(sink_basis)
            parts.append(Part((SINK,), {"p": Space.from_basis(s, 0)}, s.dx))
        self.fast = FastForm(parts, b.N)
        self.pattern = self.fast.pattern
        self.hx = cell_lengths(basis)
        self._last = _LastState()
        self._geometry = {}
        self._reference = None

    def _geometry_at(self, x, beta):
        if beta not in self._geometry:
            self._geometry = {beta: (forms.departure(x, beta), forms.in_wrap(x, beta))}
        return self._geometry[beta]

    def coefficients(self, x, P, dP, W, dW, ddW, prm, newton: bool = True,
                     geometry=None, hx=None) -> dict:
        """Every coefficient of the 1-D system at points x (in cells of lengths ``hx``) from
        the state there."""
        out, parts = self._residual_coefficients(x, P, dP, W, dW, ddW, prm, geometry, hx)
        return {**out, **film_jacobian_coefficients(parts, newton)}

    @staticmethod
    def _residual_coefficients(x, P, dP, W, dW, ddW, prm, geometry=None, hx=None):
        """:meth:`coefficients` without the film's Jacobian coefficients, and their parts
        (:func:`webfem.fem.forms.film_residual_coefficients`)."""
        args = prm.as_form_args()
        D, chi = geometry if geometry is not None else (forms.departure(x, prm.beta),
                                                        forms.in_wrap(x, prm.beta))
        film, parts = film_residual_coefficients(W + D, P, dP, 0.0, args, hx)
        return {**film, **web_coefficients(x, W, dW, ddW, args, (D, chi)),
                **coupling_coefficients(P, 1.0)}, parts

    def values(self, u, prm, newton: bool | None = True) -> list[dict]:
        """The coefficients of each part at the state ``u`` (``newton`` None: the
        residual's only)."""
        def compute():
            b = self.b
            P, dP = b.interpolate(u, 0)
            W, dW, ddW = b.interpolate(u, 1, hess=True)
            out, parts = self._residual_coefficients(b.x, P, dP[0], W, dW[0], ddW, prm,
                                                     self._geometry_at(b.x, prm.beta),
                                                     self.hx)
            values, kept = [out], [parts]
            if self.s is not None:
                Ps = self.s.interpolate(u, 0)[0]
                # the sink's coefficients need the pressure only (the gap is not read)
                sink, sink_parts = film_residual_coefficients(1.0, Ps, 0.0, 0.0,
                                                              prm.as_form_args())
                values.append(sink)
                kept.append(sink_parts)
            return values, kept

        def extend(kept, newton):
            return [film_jacobian_coefficients(parts, newton) for parts in kept]
        return self._last.get(u, prm.as_form_args(), compute,
                              None if newton is None else bool(newton), extend)

    def residual(self, u, prm) -> np.ndarray:
        return self.fast.residual(self.values(u, prm, None))

    def jacobian(self, u, prm, newton: bool = True) -> sp.csr_matrix:
        return self.fast.jacobian(self.values(u, prm, newton))

    # -- the scikit-fem reference ---------------------------------------------------------------
    def _reference_values(self, basis, u, prm, newton):
        (bp, bw) = basis.split_bases()
        x = np.asarray(basis.global_coordinates()[0])
        P = bp.interpolate(u[self.basis.split_indices()[0]])
        W = bw.interpolate(u[self.basis.split_indices()[1]])
        return self.coefficients(x, np.asarray(P), P.grad[0], np.asarray(W), W.grad[0],
                                 W.hess[0, 0], prm, newton, hx=cell_lengths(basis))

    def _reference_forms(self):
        if self._reference is None:
            main = (FILM, WEB, COUPLING) + (() if self.s is not None else (SINK,))
            self._reference = (skfem_forms(main, ("p", "w")),
                               skfem_forms((SINK,), ("p", "w")))
        return self._reference

    def reference_residual(self, u, prm) -> np.ndarray:
        (lin, _), (slin, _) = self._reference_forms()
        F = lin.assemble(self.basis, **self._reference_values(self.basis, u, prm, True))
        if self.s is not None:
            F = F + slin.assemble(self.sink_basis, **self._reference_values(
                self.sink_basis, u, prm, True))
        return F

    def reference_jacobian(self, u, prm, newton: bool = True) -> sp.csr_matrix:
        (_, bil), (_, sbil) = self._reference_forms()
        J = bil.assemble(self.basis, **self._reference_values(self.basis, u, prm, newton))
        if self.s is not None:
            J = J + sbil.assemble(self.sink_basis, **self._reference_values(
                self.sink_basis, u, prm, newton))
        return J.tocsr()


class FilmSystem:
    """The 2-D film (``fbasis``, Q1/Q2) coupled to the 1-D web (``wbasis``, Hermite) through
    the transfer matrices ``T`` (:func:`webfem.fem.transfer.quadrature_matrices`); the film
    averaged over ``width`` (a number, or one per quadrature point: a grooved web's edge
    strip weighs its innermost pitch); ``groove``: the groove depth at the film's quadrature
    points (None: smooth). Unknowns ``[p (film DOFs), w (web DOFs)]``."""

    def __init__(self, fbasis, wbasis, T, width, groove=None):
        self.fbasis, self.wbasis, self.T = fbasis, wbasis, T
        self.width = np.asarray(width, float) if np.ndim(width) else float(width)
        self.groove = 0.0 if groove is None else np.asarray(groove, float)
        self.f = f = BasisData(fbasis)
        f.share_gradients(fbasis)
        self.w = w = BasisData(wbasis, hess=(0,))
        self.nP = nP = f.N
        film = {"p": Space.from_basis(f), "w": Space.from_arrays(T["M_loc"], T["M_dofs"], nP)}
        web = {"w": Space.from_basis(w, 0, nP)}
        self.fast = FastForm([Part((FILM, SINK, COUPLING), film, f.dx),
                              Part((WEB,), web, w.dx)], nP + w.N)
        self.pattern = self.fast.pattern
        self.hx = cell_lengths(fbasis)
        self._last = _LastState()
        self._geometry = {}
        self._reference = None

    def _geometry_at(self, beta):
        """The roller's departure at the film's and the web's quadrature points and the
        wrap's indicator at the web's, for the wrap ``beta``: functions of the mesh and beta
        alone, computed once per beta (every state's coefficients read them)."""
        if beta not in self._geometry:
            x = self.w.x
            kept = (forms.departure(self.T["x"], beta), forms.departure(x, beta),
                    forms.in_wrap(x, beta))
            for a in kept:
                a.setflags(write=False)         # shared by every state's coefficients
            self._geometry = {beta: (kept[0], kept[1:])}
        return self._geometry[beta]

    def _film_values(self, P, PX, PZ, wv, prm, newton: bool | None = True):
        """The film part's coefficients (``newton`` None: the residual's, with the parts of
        the Jacobian's: ``(values, parts)``)."""
        T = self.T
        H = (T["M"] @ wv + self._geometry_at(prm.beta)[0]).reshape(np.shape(P)) \
            + self.groove
        film, parts = film_residual_coefficients(H, P, PX, PZ, prm.as_form_args(), self.hx)
        out = {**film, **coupling_coefficients(P, self.width)}
        if newton is None:
            return out, parts
        return {**out, **film_jacobian_coefficients(parts, newton)}

    def values(self, u, prm, newton: bool | None = True) -> list[dict]:
        """The coefficients of the film's and the web's parts at the state ``u``
        (``newton`` None: the residual's only)."""
        def compute():
            f, w, nP = self.f, self.w, self.nP
            P, gP = f.interpolate(u[:nP])
            W, dW, ddW = w.interpolate(u[nP:], 0, hess=True)
            film, parts = self._film_values(P, gP[0], gP[1], u[nP:], prm, None)
            return [film, web_coefficients(w.x, W, dW[0], ddW, prm.as_form_args(),
                                           self._geometry_at(prm.beta)[1])], parts

        def extend(parts, newton):
            return [film_jacobian_coefficients(parts, newton), {}]
        return self._last.get(u, prm.as_form_args(), compute,
                              None if newton is None else bool(newton), extend)

    def residual(self, u, prm) -> np.ndarray:
        return self.fast.residual(self.values(u, prm, None))

    def jacobian(self, u, prm, newton: bool = True) -> sp.csr_matrix:
        J = self.fast.jacobian(self.values(u, prm, newton))
        # the solvers ask for a residual at another state next (Newton's trial, Picard's
        # iterate): the coefficients (~100 MB at 3.9e5 unknowns) are not held through the
        # factorisation, when the process peaks
        self._last.forget()
        return J

    # -- the scikit-fem reference, the cross-mesh blocks through the transfer matrices -------
    def _reference_forms(self):
        if self._reference is None:
            self._reference = (skfem_forms((FILM, SINK), ("p",)),
                               skfem_forms((WEB,), ("w",)))
        return self._reference

    def _reference_values(self, u, prm, newton):
        nP = self.nP
        P = self.fbasis.interpolate(u[:nP])
        W = self.wbasis.interpolate(u[nP:])
        film = self._film_values(np.asarray(P), P.grad[0], P.grad[1], u[nP:], prm, newton)
        xw = np.asarray(self.wbasis.global_coordinates()[0])
        web = web_coefficients(xw, np.asarray(W), W.grad[0], W.hess[0, 0],
                               prm.as_form_args())
        return film, web

    def _cross(self, values: dict):
        """The film's blocks on the web and the width average, assembled through the
        transfer matrices: sum over blocks of A_op^T diag(c dx) B_op' (A, B: the film's
        basis or the web's functions at the film's points)."""
        T, B = self.T, basis_matrices(self.fbasis)      # built here: the reference only
        mats = {"p": {"val": B["B0"], "dx": B["BX"], "dz": B["BZ"]}, "w": {"val": T["M"]}}
        blocks = [b for form in (FILM, COUPLING) for b in form.blocks if "w" in (b.field,
                                                                               b.trial)]
        out = {}
        for b in blocks:
            c = np.broadcast_to(coefficient(values, b.coef), np.shape(values["jD"])).ravel()
            part = mats[b.field][b.op].T @ sp.diags(c * T["dx"]) @ mats[b.trial][b.trial_op]
            out[b.field, b.trial] = out.get((b.field, b.trial), 0) + part
        return out

    def reference_residual(self, u, prm) -> np.ndarray:
        (flin, _), (wlin, _) = self._reference_forms()
        film, web = self._reference_values(u, prm, True)
        Fp = flin.assemble(self.fbasis, **film)
        Fw = wlin.assemble(self.wbasis, **web)
        for t in COUPLING.terms:    # the width average, at the film's points
            Fw = Fw + self.T["M"].T @ (np.ravel(coefficient(film, t.coef)) * self.T["dx"])
        return np.concatenate([Fp, Fw])

    def reference_jacobian(self, u, prm, newton: bool = True) -> sp.csr_matrix:
        (_, fbil), (_, wbil) = self._reference_forms()
        film, web = self._reference_values(u, prm, newton)
        cross = self._cross(film)
        return sp.bmat([[fbil.assemble(self.fbasis, **film), cross["p", "w"]],
                        [cross["w", "p"], wbil.assemble(self.wbasis, **web)]], format="csr")
