"""The 1-D discrete problem: the infinitely wide foil bearing on one mesh.

Film pressure (P2 or P1 Lagrange) and web deflection (cubic Hermite) in one composite
scikit-fem basis, built once per mesh; the residual and exact Jacobian of the declared weak
forms (:mod:`webfem.fem.forms`, assembled by :class:`webfem.fem.systems.LineSystem`);
Newton with continuation from the Eshel-Elrod problem, and the two Picard schemes. The model
around it (start, refinement, summary) is :mod:`webfem.models.fe1d` on the shared driver.
"""

from __future__ import annotations

import copy
import dataclasses

import numpy as np
from skfem import Basis, ElementLineP1, ElementLineP2

from ..errors import InputError
from ..fem import ends, forms
from ..fem.hermite import Composite, HermiteLine, LineProbes
from ..fem.mesh import line_mesh
from ..fem.continuation import FIRST_TRY, eshel_elrod, film_strength
from ..fem.newton import PatternSolver, newton, norm2
from ..fem.outcome import SolveInfo
from ..fem.picard import frozen_coefficient_picard, picard
from ..fem.scaling import FoilParameters
from ..fem.systems import LineSystem
from .options import FE1DOptions

__all__ = ["FoilBearing1D"]


class FoilBearing1D:
    """The discrete coupled problem on one mesh: basis, DOF sets, residual and Jacobian.

    Built once per mesh; parameters may change between calls (continuation).

    Parameters
    ----------
    X : node positions (scaled), from :func:`webfem.fem.mesh.graded_nodes`.
    order : 1 or 2, the Lagrange order of the film pressure.
    spans : the web's end deflections are unknowns, held through the spans beyond the
        domain (``wrap.span``, :mod:`webfem.fem.ends`); False: held at the ends (Eq. 20).
    """

    def __init__(self, X: np.ndarray, order: int = 2, spans: bool = False):
        if order not in (1, 2):
            raise InputError(f"order = {order!r} is not valid: must be 1 or 2")
        self.X = np.asarray(X, float)
        self.mesh = line_mesh(self.X)
        pressure = ElementLineP2() if order == 2 else ElementLineP1()
        # a new Hermite element per mesh: it caches mesh data (scikit-fem 12); HermiteLine
        # is scikit-fem's, bitwise, with its four functions evaluated in one pass
        element = Composite(pressure, HermiteLine())      # pressure * HermiteLine()
        self.basis = Basis(self.mesh, element, intorder=6)
        # nodal (Gauss-Lobatto) quadrature lumps the sink for P1 (no pressure wiggles where
        # the film is thin); P2 keeps Gauss and relies on the adaptive refinement instead
        self.sink_basis = (Basis(self.mesh, element,
                                 quadrature=(np.array([[0.0, 1.0]]), np.array([0.5, 0.5])))
                           if order == 1 else self.basis)
        self.order = order
        self.iP, self.iW_all = self.basis.split_indices()
        self.iW = self.basis.nodal_dofs[1]        # web deflection at the nodes
        self.iWx = self.basis.nodal_dofs[2]       # its slope
        end_dofs = self.basis.get_dofs({"left", "right"})
        self.spans = bool(spans)
        #: the web's deflection at the domain's entry and exit ends
        px = self.mesh.p[0]
        self.iW_ends = self.iW[[int(np.argmin(px)), int(np.argmax(px))]]
        #: the web's uniform lift, where its ends are unknowns (Picard corrects along it)
        self.lift = ends.uniform_lift(self.basis.N, self.iW) if self.spans else None
        fixed = np.concatenate([end_dofs.all("u^1")]
                               + ([] if self.spans else [end_dofs.all("u^2")]))
        self.fixed = np.unique(fixed)
        self.free = np.setdiff1d(np.arange(self.basis.N), self.fixed)
        self.free_P = np.intersect1d(self.iP, self.free)
        self.free_W = np.intersect1d(self.iW_all, self.free)
        # point values as pbasis/wbasis.probes(x) @ u[iP]/u[iW_all] (bitwise), read from
        # the composite basis: no probe matrix, no split basis
        self._probe_p = LineProbes(self.basis, component=0)
        self._probe_w = LineProbes(self.basis, component=1)
        self.system = LineSystem(self.basis, self.sink_basis if order == 1 else None)
        #: the factorisation plans of this mesh's Jacobians (fill-reducing ordering)
        self.solver = PatternSolver()

    @property
    def n_dofs(self) -> int:
        return self.basis.N

    @property
    def pbasis(self):
        """The pressure part of :attr:`basis` (scikit-fem's split basis, built on first use)."""
        return self._split_bases()[0]

    @property
    def wbasis(self):
        """The web part of :attr:`basis` (scikit-fem's split basis)."""
        return self._split_bases()[1]

    def _split_bases(self):
        if getattr(self, "_split", None) is None:
            self._split = self.basis.split_bases()
        return self._split

    def residual(self, u, prm: FoilParameters) -> np.ndarray:
        """The coupled residual (:class:`webfem.fem.systems.LineSystem`)."""
        return ends.with_springs(self.system.residual(u, prm), u, self.iW_ends,
                                 ends.springs(self, prm))

    def jacobian(self, u, prm: FoilParameters, newton: bool = True):
        """Exact Jacobian, or (``newton=False``) the Picard operator with frozen film
        coefficients."""
        return ends.jacobian_with_springs(self.system.jacobian(u, prm, bool(newton)),
                                          self.iW_ends, ends.springs(self, prm))

    def initial_guess(self, prm: FoilParameters, H0: float = 0.643) -> np.ndarray:
        """A large-gap start: the Eshel-Elrod film H0 at the inlet edge, falling along the wrap
        with the permeation slope -K (where P = 1) down to the contact gap, and P = 1 in the
        wrap; W tapers linearly from the wrap edges to 0 at the ends, or, held through spans
        (:mod:`webfem.fem.ends`), to 0 at the neighbouring rollers: the straight spans the
        springs hold. Without the slope, a permeable web's consistent film pressure is
        about 0 and the first Newton step collapses the web."""
        u = np.zeros(self.basis.N)
        x = self.basis.doflocs[0]
        e = 0.5 * prm.beta
        u[self.iP] = forms.in_wrap(x[self.iP], prm.beta)
        H_land = max(prm.H_c, 0.1) if prm.contact else 0.1
        xn = x[self.iW]
        X0, X1 = self.X[0], self.X[-1]
        if self.spans and prm.span > 0.0:
            X0, X1 = -e - prm.span, e + prm.span

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
        Wv = self._probe_w(X, u)
        return Wv + forms.departure(X, prm.beta)

    def pressure(self, u, X: np.ndarray) -> np.ndarray:
        """Scaled film pressure P at points X."""
        return self._probe_p(np.asarray(X, float), u)

    # -- solvers ------------------------------------------------------------------------
    def newton(self, u0, prm, tol, max_iter, rows=None):
        """Damped Newton on the ``rows`` (default: every free unknown). With spans an
        iterate whose correction is the rounding floor's noise is accepted
        (:func:`webfem.fem.newton.newton`'s ``noise``): a stiff web held through spans has
        nearly singular Jacobians (the spans' tilt, stiffness T/(span - zone), and the
        film pressure at the edge of a resting board's contact patch), and its
        corrections at the floor are large (1 mm board on the base roller, span 1 m: 2.1
        scaled units of pressure at the patch's edge where random residuals of the same
        size moved it by 0.6-1.7; no step lowered the residual). The held ends keep the
        strict test."""
        return newton(lambda v: self.residual(v, prm), lambda v: self.jacobian(v, prm), u0,
                      self.free if rows is None else rows, tol=tol, max_iter=max_iter,
                      solver=self.solver, noise=self.spans)

    def consistent_pressure(self, u, prm, tol=1e-8):
        """Film pressure for the web as it is (a film-only solve): without it a cold
        start's first coupled Newton step is wild and the line search fails."""
        out = self.newton(u, prm, tol, 10, rows=self.free_P)
        return out.u if out.converged else u

    def solve_newton(self, u0, prm, options: FE1DOptions | None = None):
        """Newton on the coupled system; on failure (``options.continuation``), the
        continuation from the Eshel-Elrod problem (:func:`webfem.fem.continuation.
        eshel_elrod`). Returns ``(u, SolveInfo)``; its iterations count every Newton step,
        the continuation's included."""
        options = options or FE1DOptions()
        tol, max_iter = options.tol, options.max_iter
        # a direct attempt; a start that needs more than ~25 damped steps is better served by
        # the continuation
        first_try = min(max_iter, FIRST_TRY) if options.continuation else max_iter
        out = self.newton(self.consistent_pressure(u0, prm), prm, tol, first_try)
        info = SolveInfo.of(out)
        if out.converged or not options.continuation:
            return out.u, info
        return self.solve_continued(prm, options, info)

    def solve_continued(self, prm, options: FE1DOptions | None = None,
                        before: SolveInfo | None = None):
        """The Eshel-Elrod continuation from its cold start (the safe start: the driver also
        uses it when a direct start converged to an inadmissible branch) and, where that
        fails or ends with the absolute film pressure <= 0 (:meth:`vacuum`), the
        continuation in the film's strength from the web resting on its asperities
        (:func:`webfem.fem.continuation.film_strength`: the resting branch of stiff webs,
        past the flying branch's fold). The Eshel-Elrod answer stands where the other
        fails too. ``before``: the iterations already spent. Returns ``(u, SolveInfo)``.

        The film strength's path is the second choice, not the first: where both converge
        they may end on different branches (the base case at 20 m/s, mesh level 0: H_min
        0.020 with a suction of -3.0 T/R against 0.112 and -0.20 by the Eshel-Elrod path;
        at T = 300 N/m, -3.77 and -43 against -0.054 and -0.011), and the Eshel-Elrod path
        is the validated one."""
        options = options or FE1DOptions()
        key = (prm, options.tol, options.max_iter)
        kept = getattr(self, "_continued", None)
        if kept is not None and kept[0] == key:
            # the same path from the same cold start: a board's took 600 Newton steps, run
            # by the direct start's fallback and again by the driver's safe start
            u, info = kept[1].copy(), copy.deepcopy(kept[2])
        else:
            u, info = self._continued_path(prm, options)
            # copies: callers mark an info failed or refine the state in place
            self._continued = (key, u.copy(), copy.deepcopy(info))
        return u, (info.after(before) if before is not None else info)

    def _continued_path(self, prm, options: FE1DOptions):
        """:meth:`solve_continued`'s work: a pure function of this mesh, ``prm`` and the
        Newton tolerance and limit (it starts from its own cold state)."""
        u, info = eshel_elrod(self, prm, options.tol, options.max_iter)
        if prm.contact and (not info.converged or self.vacuum(u, prm)):
            v, rest = film_strength(self, prm, options.tol, options.max_iter, info)
            why = (info.reason if not info.converged else
                   "it ended with the absolute film pressure <= 0")
            if rest.converged and not self.vacuum(v, prm):
                u, info = v, rest.noted(f"the Eshel-Elrod continuation failed: {why}")
            else:
                # the existing answer (or failure) stands, with the work spent on the other
                other = rest.reason if not rest.converged else \
                    "the film strength continuation ended with the absolute film pressure <= 0"
                info = dataclasses.replace(info, iterations=rest.iterations,
                                           history=list(rest.history),
                                           reason=f"{info.reason}; then {other}")
        return u, info

    def vacuum(self, u, prm) -> bool:
        """Whether the absolute film pressure reaches 0 or below at the mesh's pressure
        nodes: 1 + d P <= 0 (d = T/(R p_a); never for the incompressible film, d = 0)."""
        return bool(prm.d > 0.0 and np.min(1.0 + prm.d * u[self.iP]) <= 0.0)

    def solve_picard(self, u0, prm, options: FE1DOptions | None = None):
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
        options = options or FE1DOptions()
        o = options
        return frozen_coefficient_picard(self, u0, prm, o.tol, o.omega, o.aitken,
                                         o.picard_max_iter, o.backtrack or None, o.anderson)

    def solve_picard_staggered(self, u0, prm, options: FE1DOptions | None = None):
        """Staggered Picard: film pressure from the gap, web from the pressure, relaxed on the
        web. Kept to show where it fails: for a long wrap the web's response to a pressure
        error grows like the cube of the wavelength, so the scalar-relaxed iteration
        diverges or stalls on the paper's cases (see the tests and the issue notes).

        The fixed-point residual is the change of the web DOFs, ``||G(W) - W||_inf`` in scaled
        units; the info's ``residual`` is the coupled residual norm at the end (as in Newton).
        """
        options = options or FE1DOptions()
        tol, omega, aitken = options.tol, options.omega, options.aitken
        max_iter = options.picard_max_iter
        iP, iW = self.free_P, self.free_W
        u = np.array(u0, float, copy=True)
        counts = {"film": 0, "web": 0}

        def sub_newton(v, rows):
            """Newton on one block (rows) with the other block frozen."""
            return self.newton(v, prm, tol * 1e-2, 30, rows=rows)

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
        res = norm2(self.residual(u, prm)[self.free])
        return u, SolveInfo(converged=out.converged, iterations=out.iterations, residual=res,
                            history=list(out.history), reason=out.reason, omegas=out.omegas,
                            block_iterations=counts)
