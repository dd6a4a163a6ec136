"""1-D finite elements: the infinitely wide foil bearing with permeation and asperity contact.

Solves the compressible Reynolds equation with the Darcy sink coupled to the web (membrane, or
beam when ``web.bending_stiffness`` > 0) on a graded line over the wrap plus entry and exit
zones (:mod:`webfem.fem.forms` states the equations). Elements: P2 Lagrange for the film
pressure (P1 on request) and cubic Hermite for the web deflection, so the beam's second
derivatives are conforming; one composite scikit-fem basis holds both and is built once per
mesh. Coupling: Newton on the whole system with the exact Jacobian (default), with
continuation in the permeability when a cold start fails; or Picard (film, then web, with
fixed or Aitken under-relaxation) as asked by the user.

The web lands on the roller at low speed or with a permeable web (Eq. 21 clamps h <= 0 to 0).
Here the asperity contact pressure of Eq. 10 joins the web equilibrium (``contact=True``, the
default; the paper does not do this), so the gap stays positive; the summary reports the share
of the wrap load carried by contact (``contact_share``). Friction is the paper's Eqs. 10-13,
28-31 on the solved gap, averaged over the wrap.

Examples
--------
>>> from webfem import Case
>>> r = solve(Case().updated({"roller.speed": 40.0}))
>>> r["converged"], r["model"]
(True, 'fe1d')
>>> bool(15e-6 < r["h_min"] < r["h_center"] < 50e-6)
True
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np
from numpy.polynomial.legendre import leggauss
from skfem import Basis, ElementLineHermite, ElementLineP1, ElementLineP2

from ..case import Case, CaseError
from ..errors import ConvergenceError
from ..fem import forms
from ..fem.mesh import graded_nodes, line_mesh, refine_nodes
from ..fem.newton import newton
from ..fem.picard import frozen_coefficient_picard, picard
from ..physics.closed_form import eq21_valid
from ..physics.contact import REGIMES, contact_gap
from ..physics.friction import delta_T_from_mu, local_friction
from ..result import Result

__all__ = ["FoilParameters", "FoilBearing1D", "solve", "NAME", "DEFAULTS"]

NAME = "fe1d"
#: Coupling schemes: Newton (exact Jacobian, line search, continuation), Picard (coupled,
#: frozen film coefficients, relaxed), staggered Picard (film then web; fails on long wraps).
METHODS = ("newton", "picard", "picard-staggered")

#: Default discretisation and solver settings (see :func:`solve`).
DEFAULTS = dict(entry=40.0, level=0, order=2, compressible=True, contact=True,
                method="newton", tol=1e-9, max_iter=60, omega=1.0, aitken=True, anderson=10,
                picard_max_iter=500, floor=0.1, adapt=6, adapt_ratio=1.0,
                min_cell=2e-3, nodes=None, continuation=True, backtrack=1.5)


@dataclass(frozen=True)
class FoilParameters:
    """Dimensionless parameters of the scaled problem (see :mod:`webfem.fem.forms`).

    beta wrap length B/eps^(1/3); K = 12 k/(R t eps^(4/3)) permeation; d = T/(R p_a)
    compressibility (0: incompressible); Dn = D/(T (R eps^(1/3))^2) bending; c, S contact
    pressure Pc = c exp(-H/S) (exponential heights, ``law`` 0; Gaussian, ``law`` 1, see
    :func:`webfem.fem.forms.contact_law`); contact 1/0; floor: the scaled film thickness
    below which Reynolds sees a smooth floor (from_case takes it as a fraction of sigma);
    H_c: the scaled gap at which contact alone carries T/R.
    """

    beta: float
    K: float
    d: float
    Dn: float
    c: float
    S: float
    contact: float
    floor: float
    law: int = 0
    H_c: float = 0.0

    @classmethod
    def from_case(cls, case: Case, compressible=True, contact=True, floor=0.1):
        R, T, eps = case.roller.radius, case.web.tension, case.eps
        w = case.web
        gaussian = case.friction.distribution == "gaussian"
        # exponential: Pc = c exp(-H/S); Gaussian: Pc = c (S/sqrt(2 pi) e^(-H^2/2S^2) - ...)
        c = (w.modulus_thickness * R * case.h_scale / (w.thickness * T) if gaussian else
             w.modulus_thickness * case.sigma * R / (2.0 * w.thickness * T))
        h_c = contact_gap(case.p_bar, w.modulus_thickness, case.sigma, w.thickness,
                          case.friction.distribution)
        return cls(
            beta=case.beta,
            K=12.0 * w.permeability / (R * w.thickness * eps ** (4 / 3)),
            d=case.p_bar / case.air.ambient_pressure if compressible else 0.0,
            Dn=w.bending_stiffness / (T * case.x_scale**2),
            c=c, S=case.sigma / case.h_scale, contact=1.0 if contact else 0.0,
            floor=floor * case.sigma / case.h_scale,
            law=1 if gaussian else 0, H_c=float(h_c / case.h_scale),
        )

    def as_form_args(self) -> dict:
        return dict(beta=self.beta, K=self.K, d=self.d, Dn=self.Dn, c=self.c, S=self.S,
                    contact=self.contact, floor=self.floor, law=self.law)


class FoilBearing1D:
    """The discrete coupled problem on one mesh: basis, DOF sets, residual and Jacobian.

    Built once per mesh; parameters may change between calls (continuation).

    Parameters
    ----------
    X : node positions (scaled), from :func:`webfem.fem.mesh.graded_nodes`.
    order : 1 or 2, the Lagrange order of the film pressure.
    """

    def __init__(self, X: np.ndarray, order: int = 2):
        if order not in (1, 2):
            raise CaseError(f"order = {order!r} is not valid: must be 1 or 2")
        self.X = np.asarray(X, float)
        self.mesh = line_mesh(self.X)
        pressure = ElementLineP2() if order == 2 else ElementLineP1()
        # a new Hermite element per mesh: it caches mesh data (scikit-fem 12)
        element = pressure * ElementLineHermite()
        self.basis = Basis(self.mesh, element, intorder=6)
        # nodal (Gauss-Lobatto) quadrature lumps the sink for P1 (no pressure wiggles where
        # the film is thin); P2 keeps Gauss and relies on the adaptive refinement instead
        self.sink_basis = (Basis(self.mesh, element,
                                 quadrature=(np.array([[0.0, 1.0]]), np.array([0.5, 0.5])))
                           if order == 1 else self.basis)
        self.order = order
        # split bases once: building them is most of the cost of interpolating a state
        self._split = {id(b): b.split_bases() for b in (self.basis, self.sink_basis)}
        self._x = {id(b): np.asarray(b.global_coordinates()[0])
                   for b in (self.basis, self.sink_basis)}
        self.iP, self.iW_all = self.basis.split_indices()
        self.iW = self.basis.nodal_dofs[1]        # web deflection at the nodes
        self.iWx = self.basis.nodal_dofs[2]       # its slope
        fixed = np.concatenate([self.basis.get_dofs({"left", "right"}).all("u^1"),
                                self.basis.get_dofs({"left", "right"}).all("u^2")])
        self.fixed = np.unique(fixed)
        self.free = np.setdiff1d(np.arange(self.basis.N), self.fixed)
        self.free_P = np.intersect1d(self.iP, self.free)
        self.free_W = np.intersect1d(self.iW_all, self.free)
        self.pbasis, self.wbasis = self.basis.split_bases()

    @property
    def n_dofs(self) -> int:
        return self.basis.N

    def _state(self, basis, u, prm: FoilParameters, sink: bool = False,
               newton: bool | None = None) -> dict:
        """Form arguments at ``basis``'s quadrature points for the state ``u``: for the
        residual (``newton=None``), or for the Jacobian (exact if ``newton`` else Picard's)."""
        bp, bw = self._split[id(basis)]
        P = bp.interpolate(u[self.iP])
        if sink:
            return {"P": np.asarray(P), "K": prm.K, "d": prm.d,
                    "newton": 1.0 if newton or newton is None else 0.0}
        W = bw.interpolate(u[self.iW_all])
        coef = forms.coefficients(self._x[id(basis)], np.asarray(P), P.grad[0], np.asarray(W),
                                  prm.as_form_args(), sink=self.order == 2)
        if newton is None:
            return {"W": W, "Dn": prm.Dn, **coef}
        return {"Dn": prm.Dn, **forms.jacobian_coefficients(coef, newton)}

    def residual(self, u, prm: FoilParameters) -> np.ndarray:
        F = forms.residual.assemble(self.basis, **self._state(self.basis, u, prm))
        if prm.K and self.order == 1:
            sb = self.sink_basis
            F += forms.sink_residual.assemble(sb, **self._state(sb, u, prm, sink=True))
        return F

    def jacobian(self, u, prm: FoilParameters, newton: bool = True):
        """Exact Jacobian, or (``newton=False``) the Picard operator with frozen film
        coefficients."""
        J = forms.jacobian.assemble(self.basis, **self._state(self.basis, u, prm, False,
                                                              bool(newton)))
        if prm.K and self.order == 1:
            sb = self.sink_basis
            J += forms.sink_jacobian.assemble(sb, **self._state(sb, u, prm, True, bool(newton)))
        return J

    def initial_guess(self, prm: FoilParameters, H0: float = 0.643) -> np.ndarray:
        """A large-gap start: the Eshel-Elrod film H0 at the inlet edge, falling along the wrap
        with the permeation slope -K (where P = 1) down to the contact gap, and P = 1 in the
        wrap; W tapers linearly to 0 at the ends. Without the slope, a permeable web's
        consistent film pressure is about 0 and the first Newton step collapses the web."""
        u = np.zeros(self.basis.N)
        x = self.basis.doflocs[0]
        e = 0.5 * prm.beta
        u[self.iP] = forms.in_wrap(x[self.iP], prm.beta)
        H_land = max(prm.H_c, 0.1) if prm.contact else 0.1
        xn = x[self.iW]
        X0, X1 = self.X[0], self.X[-1]

        def wrap_gap(X):
            return np.maximum(H0 - prm.K * (np.clip(X, -e, e) + e), min(H_land, H0))

        edge_in, edge_out = wrap_gap(-e), wrap_gap(e)
        W = np.where(xn < -e, edge_in * (xn - X0) / (-e - X0),
                     np.where(xn > e, edge_out * (X1 - xn) / (X1 - e), wrap_gap(xn)))
        dW = np.where(xn < -e, edge_in / (-e - X0), np.where(xn > e, -edge_out / (X1 - e),
                      np.where(wrap_gap(xn) > H_land, -prm.K, 0.0)))
        u[self.iW] = W
        u[self.iWx] = dW
        u[self.fixed] = 0.0
        return u

    def gap(self, u, prm: FoilParameters, X: np.ndarray) -> np.ndarray:
        """Scaled gap H at points X (exact Hermite evaluation)."""
        X = np.asarray(X, float)
        Wv = self.wbasis.probes(X[None, :]) @ u[self.iW_all]
        return Wv + forms.departure(X, prm.beta)

    def pressure(self, u, X: np.ndarray) -> np.ndarray:
        """Scaled film pressure P at points X."""
        return self.pbasis.probes(np.asarray(X, float)[None, :]) @ u[self.iP]

    # -- solvers ------------------------------------------------------------------------
    def _newton(self, u0, prm, tol, max_iter, rows=None):
        return newton(lambda v: self.residual(v, prm), lambda v: self.jacobian(v, prm), u0,
                      self.free if rows is None else rows, tol=tol, max_iter=max_iter)

    def consistent_pressure(self, u, prm, tol=1e-8):
        """Film pressure for the web as it is (a film-only solve): without it a cold
        start's first coupled Newton step is wild and the line search fails."""
        out = self._newton(u, prm, tol, 10, rows=self.free_P)
        return out.u if out.converged else u

    @staticmethod
    def _homotopy(prm, s):
        return replace(prm, K=s * prm.K, d=s * prm.d, Dn=s * prm.Dn)

    def solve_newton(self, u0, prm, tol=1e-9, max_iter=60, continuation=True):
        """Newton on the coupled system; on failure, continuation from the Eshel-Elrod
        problem (K, d and Dn scaled by s from 0 to 1, adaptive steps).

        Returns ``(u, info)``; ``info`` has converged, iterations (all Newton steps, including
        the continuation's), residual, history, reason and continuation steps.
        """
        # a direct attempt; a start that needs more than ~25 damped steps is better served by
        # the continuation below
        first_try = min(max_iter, 25) if continuation else max_iter
        out = self._newton(self.consistent_pressure(u0, prm), prm, tol, first_try)
        info = dict(iterations=out.iterations, history=list(out.history), steps=[1.0])
        if out.converged or not continuation:
            info.update(converged=out.converged, residual=out.residual, reason=out.reason)
            return out.u, info
        # continuation from the Eshel-Elrod problem: permeation K, compressibility d and
        # bending Dn scaled by s from 0 to 1 (the impermeable membrane converges from cold)
        target = prm
        u = self.initial_guess(self._homotopy(target, 0.0))
        s, ds, steps = 0.0, 0.25, []
        first = True
        while True:
            p = self._homotopy(target, s)
            out = self._newton(self.consistent_pressure(u, p), p, tol, max_iter)
            info["iterations"] += out.iterations
            info["history"] += list(out.history)
            if out.converged:
                u = out.u
                steps.append(s)
                if s >= 1.0:
                    info.update(converged=True, residual=out.residual, reason=out.reason,
                                steps=steps)
                    return u, info
                ds = min(2.0 * ds, 1.0) if not first else ds
                first = False
                s_prev = s
                s = min(1.0, s + ds)
            else:
                if first:
                    info.update(converged=False, residual=out.residual,
                                reason="continuation: Eshel-Elrod start failed: " + out.reason,
                                steps=steps)
                    return out.u, info
                ds *= 0.25
                if ds < 1e-4:
                    info.update(converged=False, residual=out.residual,
                                reason=f"continuation stalled at s = {s_prev:.4g}",
                                steps=steps)
                    return u, info
                s = min(1.0, s_prev + ds)

    def solve_picard(self, u0, prm, tol=1e-9, omega=1.0, aitken=True, max_iter=3000,
                     backtrack=1.5, anderson=10):
        """Picard iteration on the coupled system: film and web solved together each sweep
        with the film's nonlinear coefficients H^3 and 1 + d P frozen at the last iterate,
        under-relaxed: Anderson acceleration of depth ``anderson`` (default 10) and, if that
        fails, Aitken's dynamic factor (``aitken``) or the fixed ``omega``. With ``backtrack``
        (default 1.5) a step that raises the residual more than that factor is undone and
        omega halved; ``anderson=0, aitken=False, backtrack=None`` is the plain fixed-factor
        iteration.

        Stops when the coupled residual ||F||_2 <= ``tol``, the same test as Newton, so the
        two compare at equal tolerance.
        """
        return frozen_coefficient_picard(self, u0, prm, tol, omega, aitken, max_iter,
                                         backtrack, anderson)

    def solve_picard_staggered(self, u0, prm, tol=1e-9, omega=0.5, aitken=True,
                               max_iter=3000):
        """Staggered Picard: film pressure from the gap, web from the pressure, relaxed on the
        web. Kept to show where it fails: for a long wrap the web's response to a pressure
        error grows like the cube of the wavelength, so the scalar-relaxed iteration
        diverges or stalls on the paper's cases (see the tests and the issue notes).

        The fixed-point residual is the change of the web DOFs, ``||G(W) - W||_inf`` in scaled
        units; ``info['residual']`` is the coupled residual norm at the end (as in Newton).
        """
        iP, iW = self.free_P, self.free_W
        u = np.array(u0, float, copy=True)
        counts = {"film": 0, "web": 0}

        def sub_newton(v, rows):
            """Newton on one block (rows) with the other block frozen."""
            return self._newton(v, prm, tol * 1e-2, 30, rows=rows)

        def G(w_dofs):
            v = u.copy()
            v[iW] = w_dofs
            film = sub_newton(v, iP)
            counts["film"] += film.iterations
            web = sub_newton(film.u, iW)
            counts["web"] += web.iterations
            if not (film.converged and web.converged):
                raise RuntimeError("a block solve failed: " + (film.reason if not film.converged
                                                                else web.reason))
            u[iP] = web.u[iP]   # keep the latest pressure for the next sweep
            return web.u[iW]

        out = picard(G, u[iW], omega=omega, aitken=aitken, tol=tol, max_iter=max_iter)
        u[iW] = out.x
        # pressure consistent with the final web
        film = sub_newton(u, iP)
        u = film.u
        res = float(np.linalg.norm(self.residual(u, prm)[self.free]))
        return u, dict(converged=out.converged, iterations=out.iterations, residual=res,
                       history=out.history, reason=out.reason, omegas=out.omegas,
                       block_iterations=counts)


def _wrap_samples(X: np.ndarray, beta: float, n: int = 8):
    """Gauss points and weights over the wrap cells (nodes sit on the wrap edges)."""
    e = 0.5 * beta
    inner = X[(X >= -e - 1e-12) & (X <= e + 1e-12)]
    g, gw = leggauss(n)
    a, b = inner[:-1, None], inner[1:, None]
    pts = 0.5 * (a + b) + 0.5 * (b - a) * g[None, :]
    wts = 0.5 * (b - a) * gw[None, :]
    return pts.ravel(), wts.ravel()


def _minimum(problem: FoilBearing1D, u, prm):
    """Smallest gap in the domain and where: nodal search refined inside the adjacent cells."""
    Hn = problem.gap(u, prm, problem.X)
    i = int(np.argmin(Hn))
    lo, hi = problem.X[max(i - 1, 0)], problem.X[min(i + 1, len(problem.X) - 1)]
    Xs = np.linspace(lo, hi, 81)
    Hs = problem.gap(u, prm, Xs)
    j = int(np.argmin(Hs))
    return float(Hs[j]), float(Xs[j])


def _local(case: Case, h):
    """The paper's local contact and friction (Eqs. 10-13, 28-30) at gaps h [m]."""
    return local_friction(h, R=case.roller.radius, T=case.web.tension, U_s=case.U_slide,
                          eta=case.air.viscosity, E_b=case.web.modulus_thickness,
                          sigma=case.sigma, t=case.web.thickness, mu_cc=case.friction.mu_cc,
                          C=case.friction.speed_constant, variant=case.friction.variant,
                          distribution=case.friction.distribution)


def _summary(case: Case, problem, u, prm: FoilParameters, info: dict, elapsed: float,
             opts: dict, model: str = NAME, mesh: str | None = None) -> tuple[dict, dict]:
    """Summary keys and diagnostics from a solved state. ``problem`` needs ``X``, ``n_dofs``,
    ``gap(u, prm, X)`` and ``pressure(u, X)`` (the width-averaged film pressure in 2-D)."""
    Hs, Xs = case.h_scale, case.x_scale
    T = case.web.tension
    e = 0.5 * prm.beta
    pts, wts = _wrap_samples(problem.X, prm.beta)
    h = problem.gap(u, prm, pts) * Hs
    loc = _local(case, h)
    mu = float(np.sum(loc["mu"] * wts) / prm.beta)
    shares = [float(np.sum(wts * (loc["regime"] == k)) / prm.beta) for k in range(3)]
    Pf = problem.pressure(u, pts)
    Pc = forms.contact_law(h / Hs, prm.as_form_args())[0]
    contact_share = float(np.sum(Pc * wts) / max(np.sum((Pf + Pc) * wts), 1e-300))
    Hmin, Xmin = _minimum(problem, u, prm)
    H3 = problem.gap(u, prm, np.array([0.0, -e, e]))
    summary = {
        "model": model,
        "h_center": H3[0] * Hs, "h_inlet": H3[1] * Hs, "h_outlet": H3[2] * Hs,
        "h_min": Hmin * Hs, "x_min": Xmin * Xs,
        "mu": mu, "delta_T": float(delta_T_from_mu(mu, T, case.B)),
        "regime": REGIMES[int(np.argmax(shares))],
        "lambda": case.lam, "beta": case.beta,
        "eq21_valid": bool(eq21_valid(case.beta, case.lam)),
        "converged": bool(info["converged"]), "iterations": int(info["iterations"]),
        "n_dofs": int(problem.n_dofs), "solve_time_s": elapsed,
        "residual": float(info["residual"]),
        "h_c": float(prm.H_c * Hs), "sigma": case.sigma,
        "share_boundary": shares[0], "share_mixed": shares[1], "share_fluid": shares[2],
        "contact_share": contact_share,
        "eps": case.eps, "kappa": case.kappa, "U": case.U, "U_slide": case.U_slide,
        "method": opts["method"], "n_cells": len(problem.X) - 1,
        "mesh": mesh or f"{'user' if opts.get('nodes') is not None else 'graded'} line, "
                        f"{len(problem.X) - 1} cells, entry/exit "
                        f"{opts['entry']:g} R eps^(1/3), level {opts['level']}, "
                        f"P{opts['order']}/Hermite",
        "warnings": [],
    }
    if not opts["compressible"] and case.p_bar > 0.02 * case.air.ambient_pressure:
        ratio = case.p_bar / case.air.ambient_pressure
        summary["warnings"].append(
            f"incompressible film with T/R = {ratio:.3g} p_a > 0.02 p_a: compressibility "
            f"shifts the central gap by about {-45 * ratio:.2g} % (use compressible=True)")
    if case.lam < 7.0 and model == NAME:
        summary["warnings"].append(
            f"lambda = {case.lam:.3g}: a narrow web leaks air at its edges, which the 1-D "
            "(infinitely wide) model ignores; its gap is too large")
    summary["adapt_rounds"] = info.get("adapt_rounds", 0)
    summary["solver_message"] = info.get("reason", "")
    diagnostics = {"wrap_h": h, "wrap_w": wts / prm.beta,   # for re-evaluating friction
                   "history": info.get("history", []), "reason": info.get("reason", ""),
                   "continuation": info.get("steps", []), "options": dict(opts)}
    if "omegas" in info:
        diagnostics["omegas"] = info["omegas"]
        diagnostics["block_iterations"] = info.get("block_iterations")
    return summary, diagnostics


def _node_fields(case: Case, problem: FoilBearing1D, u, prm: FoilParameters) -> dict:
    X = problem.X
    Hs = case.h_scale
    H = problem.gap(u, prm, X)
    P = problem.pressure(u, X)
    h = H * Hs
    loc = _local(case, h)
    p_rel = P * case.p_bar
    return {"x": X * case.x_scale, "h": h, "w": h - forms.departure(X, prm.beta) * Hs,
            "p_rel": p_rel, "p": p_rel + case.air.ambient_pressure,
            "p_contact": forms.contact_law(H, prm.as_form_args())[0] * case.p_bar,
            "in_wrap": forms.in_wrap(X, prm.beta), **loc}


_CACHE: dict = {}


def _nodes(beta, entry, level, nodes=None) -> np.ndarray:
    """The starting X nodes: webfem's graded mesh, or the user's (``nodes``, scaled), with the
    wrap edges added as nodes (the wrap pressure T/R starts and stops there)."""
    if nodes is None:
        return graded_nodes(beta, entry, level=level)
    X = np.unique(np.asarray(nodes, float))
    e = 0.5 * beta
    if X.size < 3 or not (X[0] < -e and X[-1] > e):
        raise CaseError(f"mesh spans X = {X[0]:.4g} .. {X[-1]:.4g} (scaled), which does not "
                        f"cover the wrap |X| <= {e:.4g} with entry and exit zones; valid: a "
                        "line mesh over the wrap plus both zones")
    tol = 1e-9 * (X[-1] - X[0])
    X = X[(np.abs(X + e) > tol) & (np.abs(X - e) > tol)]       # snap onto the exact edges
    X = np.unique(np.concatenate([X, [-e, e]]))
    X = X[np.concatenate([[True], np.diff(X) > tol])]          # drop near-duplicates
    return refine_nodes(X, level)


def _problem(beta, entry, level, order, nodes=None) -> FoilBearing1D:
    """One discrete problem per mesh, reused across solves of a sweep."""
    X = _nodes(beta, entry, level, nodes)
    key = (X.size, float(X[0]), float(X[-1]), order, X.tobytes())
    if key not in _CACHE:
        if len(_CACHE) > 8:
            _CACHE.clear()
        _CACHE[key] = FoilBearing1D(X, order=order)
    return _CACHE[key]


def checked_options(model: str, options: dict, defaults: dict, methods) -> dict:
    """The model's defaults updated by ``options``, rejecting unknown names and methods."""
    unknown = set(options) - set(defaults)
    if unknown:
        raise CaseError(f"unknown {model} option(s) {sorted(unknown)}; valid: "
                        f"{sorted(defaults)}")
    opts = {**defaults, **options}
    if opts["method"] not in methods:
        raise CaseError(f"method = {opts['method']!r} is not valid: must be one of "
                        + ", ".join(repr(m) for m in methods))
    return opts


def solve(case: Case, *, initial: Result | None = None, raise_on_failure: bool = True,
          **options) -> Result:
    """Solve one case with the 1-D FE model.

    Options (defaults in :data:`DEFAULTS`): ``entry`` length of the entry and exit zones in
    units of R eps^(1/3); ``level`` mesh refinement level (each bisects all cells);
    ``order`` 1 or 2 (pressure element); ``compressible``; ``contact`` (asperity contact in
    the web equilibrium); ``method`` "newton" or "picard"; ``tol`` (Newton: residual 2-norm;
    Picard: web update max-norm, scaled units); ``max_iter``; ``omega`` and ``aitken``
    (Picard relaxation), ``anderson`` (Picard acceleration depth, 0 off), ``backtrack``
    (Picard's step-undo factor, 0 off); ``continuation`` (Newton's fallback, on by default);
    ``floor``: the film thickness floor in Reynolds, as a fraction of the roughness sigma
    (default 0.1: air still seeps through the roughness where the web rests on it).
    ``nodes``: starting mesh nodes in scaled X (instead of webfem's graded mesh; the API's
    ``mesh=PATH`` option reads them from a mesh file).
    ``initial``: a previous fe1d result to start from (continuation in a sweep).

    Raises :class:`webfem.errors.ConvergenceError` (carrying the unconverged result and the
    residual history) when the solve fails, unless ``raise_on_failure=False``.
    """
    opts = checked_options(NAME, options, DEFAULTS, METHODS)
    if not opts["entry"] > 0:
        raise CaseError(f"entry = {opts['entry']!r} is out of range: must be > 0")
    if int(opts["level"]) != opts["level"] or not 0 <= opts["level"] <= 8:
        raise CaseError(f"level = {opts['level']!r} is out of range: integer 0..8")
    t0 = time.perf_counter()
    prm = FoilParameters.from_case(case, opts["compressible"], opts["contact"], opts["floor"])
    problem = _problem(prm.beta, opts["entry"], int(opts["level"]), opts["order"],
                       opts["nodes"])
    u0 = _start(problem, prm, case, initial)
    u, info = _run(problem, u0, prm, opts)
    rounds = 0
    while info["converged"] and rounds < opts["adapt"]:
        X = _adapted_nodes(problem, u, prm, opts["adapt_ratio"], opts["min_cell"])
        if X is None:
            break
        rounds += 1
        finer = FoilBearing1D(X, order=opts["order"])
        u_fine = _transfer(problem, u, prm, finer)
        u, info_fine = _run(finer, u_fine, prm, opts)
        info_fine["iterations"] += info["iterations"]
        info_fine["history"] = info["history"] + info_fine["history"]
        problem, info = finer, info_fine
    info["adapt_rounds"] = rounds
    elapsed = time.perf_counter() - t0
    summary, diagnostics = _summary(case, problem, u, prm, info, elapsed, opts)
    fields = _node_fields(case, problem, u, prm)
    diagnostics["state"] = u
    diagnostics["problem"] = problem
    result = Result(case, summary, fields, diagnostics)
    if not info["converged"] and raise_on_failure:
        raise ConvergenceError(f"fe1d ({opts['method']}) did not converge: {info['reason']} "
                               f"after {info['iterations']} iterations, residual "
                               f"{info['residual']:.3e}", result, info.get("history"))
    return result


def _run(problem, u0, prm, opts):
    if opts["method"] == "newton":
        return problem.solve_newton(u0, prm, tol=opts["tol"], max_iter=opts["max_iter"],
                                    continuation=bool(opts["continuation"]))
    if opts["method"] == "picard":
        return problem.solve_picard(u0, prm, tol=opts["tol"], omega=opts["omega"],
                                    aitken=opts["aitken"], max_iter=opts["picard_max_iter"],
                                    anderson=int(opts["anderson"]),
                                    backtrack=opts["backtrack"] or None)
    return problem.solve_picard_staggered(u0, prm, tol=opts["tol"], omega=opts["omega"],
                                          aitken=opts["aitken"],
                                          max_iter=opts["picard_max_iter"])


def _adapted_nodes(problem, u, prm, ratio, min_cell, max_cells=4000):
    """Bisect cells longer than ``ratio`` times the local film or contact length, or None.

    Where the film is thin the sink and the contact springs make boundary layers far
    shorter than the entry-zone scale: the film's reaction length sqrt(H^3 / K) and the
    contact length sqrt(S / (c exp(-H/S))) of the web on its asperities. No refinement past
    ``max_cells`` cells.
    """
    X = problem.X
    # films thinner than the roughness carry nothing the asperities do not: resolve to S
    H = np.maximum(problem.gap(u, prm, X), max(prm.floor, prm.S if prm.contact else 0.0))
    Hc = np.minimum(H[1:], H[:-1])
    scale = np.full(Hc.shape, np.inf)
    if prm.K > 0:
        scale = np.minimum(scale, np.sqrt(Hc**3 / prm.K))
    if prm.contact:
        with np.errstate(all="ignore"):
            scale = np.minimum(scale, 1.0 / np.sqrt(forms.contact_law(Hc, prm.as_form_args())[1]))
    dx = np.diff(X)
    mark = (dx > ratio * scale) & (dx > 2.0 * min_cell)
    if not mark.any() or X.size + mark.sum() > max_cells:
        return None
    return np.sort(np.concatenate([X, 0.5 * (X[1:] + X[:-1])[mark]]))


def _transfer(coarse: FoilBearing1D, u, prm, fine: FoilBearing1D) -> np.ndarray:
    """A coarse state on a finer nested mesh (exact for the nested P1/P2 and Hermite spaces
    up to the interpolation of P2 midpoints)."""
    v = np.zeros(fine.n_dofs)
    xn = fine.X
    v[fine.iW] = coarse.gap(u, prm, xn) - forms.departure(xn, prm.beta)
    # slope of W: derivative of the Hermite interpolant through probes at +- a small offset
    d = 1e-7 * max(1.0, float(np.ptp(xn)))
    xa, xb = np.clip(xn - d, xn[0], xn[-1]), np.clip(xn + d, xn[0], xn[-1])
    v[fine.iWx] = ((coarse.gap(u, prm, xb) - forms.departure(xb, prm.beta))
                   - (coarse.gap(u, prm, xa) - forms.departure(xa, prm.beta))) / (xb - xa)
    xP = fine.basis.doflocs[0][fine.iP]
    v[fine.iP] = coarse.pressure(u, xP)
    v[fine.fixed] = 0.0
    return v


def _start(problem: FoilBearing1D, prm: FoilParameters, case: Case, initial) -> np.ndarray:
    """Start vector: the previous sweep point mapped through the scaled gap, else cold."""
    if initial is None or initial["model"] != NAME or "x" not in initial.fields:
        return problem.initial_guess(prm)
    prev = initial.fields
    # carry the gap shape over in scaled units: H(X) of the previous point, re-centred
    X = problem.X
    Hs_prev = initial.case.h_scale
    Xprev = prev["x"] / initial.case.x_scale
    e_prev = 0.5 * initial.case.beta
    e = 0.5 * prm.beta
    # map positions relative to the nearer wrap edge so the entry and exit zones line up
    Xmap = np.where(X < 0, X + e - e_prev, X - e + e_prev)
    H = np.interp(Xmap, Xprev, prev["h"] / Hs_prev)
    P = np.interp(Xmap, Xprev, prev["p_rel"] / initial.case.p_bar)
    u = problem.initial_guess(prm)
    W = H - forms.departure(X, prm.beta)
    W[0] = W[-1] = 0.0
    u[problem.iW] = W
    u[problem.iWx] = np.gradient(W, X)
    xP = problem.basis.doflocs[0][problem.iP]
    u[problem.iP] = np.interp(xP, X, P)
    u[problem.fixed] = 0.0
    return u
