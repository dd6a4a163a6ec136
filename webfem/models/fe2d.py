"""2-D finite elements: Reynolds over the wrap domain with edge leakage, coupled to the 1-D web.

The film is solved on [X_s, X_e] x [0, lambda] (half width, symmetry at the centreline; the
default) or [-lambda, lambda] (full width) in scaled coordinates (:mod:`webfem.fem.film2d`),
with P2 quadrilaterals (Q1 on request) on a tensor-product mesh: the web's graded nodes in X
times nodes graded towards the web edges in Z. The web is the 1-D Hermite beam/membrane of the
1-D model (:mod:`webfem.fem.web`), loaded by the width-averaged film pressure plus the asperity
contact (paper's Eq. 16). The two meshes share their X nodes and the web's basis is evaluated
exactly at the film's quadrature points (:mod:`webfem.fem.transfer`), so the gap on the film and
the width average on the web are consistent discretisations, not nearest-node lookups.

Coupling: Newton on the whole film + web system with the exact Jacobian (default), started
from the 1-D solution (the lambda -> infinity limit); or Picard with the film's coefficients
frozen (relaxed, Aitken). The X mesh is refined where the film is thin, as in 1-D.

Examples
--------
>>> from webfem import Case
>>> r = solve(Case().updated({"roller.speed": 40.0}))
>>> r["model"], r["converged"]
('fe2d', True)
"""

from __future__ import annotations

import numpy as np
import scipy.sparse.linalg as spla
from skfem import Basis, ElementLineHermite, ElementQuad1, ElementQuad2

from ..case import Case
from ..errors import InputError
from ..fem import forms
from ..fem.mesh import line_mesh
from ..fem.newton import newton
from ..fem.picard import frozen_coefficient_picard
from ..fem.scaling import FoilParameters
from ..fem.grooves import GroovePattern, groove_nodes
from ..fem.hermite import LineProbes
from ..fem.transfer import (film_mesh, interpolate_values, quadrature_matrices,
                             tensor_interpolation, width_nodes)
from ..fem.systems import FilmSystem, width_load
from ..physics.friction import friction_for
from ..progress import stage
from ..result import Film, Result
from . import fe1d
from .driver import Start, solve_fe
from .options import FE2DOptions

__all__ = ["FoilBearing2D", "FILM", "solve", "solve_case", "NAME"]

NAME = "fe2d"
#: The defaults of :class:`~webfem.models.options.FE2DOptions`, by name (read-only view).
DEFAULTS = FE2DOptions().to_dict()


class FoilBearing2D:
    """The discrete coupled problem: film basis on the 2-D mesh, web basis on the line.

    Unknowns ``u = [p (film DOFs), w (web DOFs)]``. Built once per mesh.
    """

    def __init__(self, X: np.ndarray, Z: np.ndarray, order: int = 2,
                 grooves: GroovePattern | None = None, web_edges: bool = True,
                 ambient_grooves: bool = False):
        if order not in (1, 2):
            raise InputError(f"order = {order!r} is not valid: must be 1 or 2")
        self.X, self.Z = np.asarray(X, float), np.asarray(Z, float)
        #: the roller's grooves (None: smooth) and whether Z ends at web edges (False: the
        #: periodic cell of a grooved roller, symmetric on both sides)
        self.grooves, self.web_edges = grooves, bool(web_edges)
        #: True: P = 0 in the grooves and on their edges (the deep-groove limit)
        self.ambient_grooves = bool(ambient_grooves) and grooves is not None
        self.width = float(self.Z[-1] - self.Z[0])
        self.order = order
        self.line = line_mesh(self.X)
        # a new Hermite element per mesh: it caches mesh data (scikit-fem 12)
        self.wbasis = Basis(self.line, ElementLineHermite(), intorder=6)
        self.mesh = film_mesh(self.X, self.Z, web_edges=self.web_edges)
        self.fbasis = Basis(self.mesh, ElementQuad2() if order == 2 else ElementQuad1(),
                            intorder=4 if order == 2 else 3)
        self.T = quadrature_matrices(self.fbasis, self.wbasis)
        self.nP, self.nW = self.fbasis.N, self.wbasis.N
        self.qshape = self.fbasis.X.shape[-1]
        fixed_p = self.fbasis.get_dofs({"ends", "edges"} if self.web_edges
                                       else {"ends"}).all()
        zq = np.asarray(self.fbasis.global_coordinates()[1])
        #: groove depth Delta(Z) at the film's quadrature points (0: land or smooth)
        self.groove_q = (grooves.depth_at(zq) if grooves is not None else np.zeros_like(zq))
        fixed_w = self.wbasis.get_dofs({"left", "right"}).all("u") + self.nP
        if self.ambient_grooves:
            zd = self.fbasis.doflocs[1]
            off = np.abs(zd - grooves.pitch * np.round(zd / grooves.pitch))
            fixed_p = np.concatenate([fixed_p, np.flatnonzero(
                off >= 0.5 * grooves.land * (1.0 - 1e-9))])
        self.fixed = np.unique(np.concatenate([fixed_p, fixed_w]))
        is_free = np.ones(self.n_dofs, dtype=bool)
        is_free[self.fixed] = False
        self.free = np.flatnonzero(is_free)          # np.setdiff1d's answer, without a sort
        self._xw = np.asarray(self.wbasis.global_coordinates()[0])
        self.iWv = self.wbasis.nodal_dofs[0] + self.nP      # web values at the nodes
        self.iWx = self.wbasis.nodal_dofs[1] + self.nP      # web slopes
        self._mass = None
        self._system = None
        #: the web basis at point sets asked for again (the nodes: refinement, admissibility
        #: and results), by the points' bytes; the last width average (film DOFs, result)
        self._web_probes, self._average = LineProbes(self.wbasis), None
        #: the 1-D problem and state this problem started from (width continuation)
        self.line_start = None
        #: True: Newton tries the coupled system straight from its start (a solved state
        #: carried over from another mesh, or the 1-D solution) before a film-only pre-solve
        self.direct = False

    @property
    def n_dofs(self) -> int:
        return self.nP + self.nW

    def _split(self, u):
        return u[:self.nP], u[self.nP:]

    @property
    def system(self) -> FilmSystem:
        """The assembly of this mesh's film + web system (:class:`webfem.fem.systems.
        FilmSystem`), built on first use."""
        if self._system is None:
            self._system = FilmSystem(self.fbasis, self.wbasis, self.T, self.width,
                                      self.groove_q)
        return self._system

    def residual(self, u, prm: FoilParameters) -> np.ndarray:
        """The coupled residual."""
        return self.system.residual(u, prm)

    def jacobian(self, u, prm: FoilParameters, newton: bool = True):
        """Exact Jacobian, or (``newton=False``) Picard's."""
        return self.system.jacobian(u, prm, bool(newton))

    # -- fields ---------------------------------------------------------------------------
    def at(self, X, dofs) -> np.ndarray:
        """The web-space function with Hermite ``dofs`` at scaled points X: scikit-fem's
        ``probes(X) @ dofs`` to the last bit (:class:`~webfem.fem.hermite.LineProbes`, the
        values at the last point sets kept)."""
        return self._web_probes(np.asarray(X, float), dofs)

    def gap(self, u, prm, X) -> np.ndarray:
        X = np.asarray(X, float)
        return self.at(X, self._split(u)[1]) + forms.departure(X, prm.beta)

    def width_average(self, u) -> np.ndarray:
        """Hermite DOFs of the width-averaged film pressure: the L2 projection of
        (1/width) int P dZ onto the web's space (the same load vector the web sees)."""
        if self._mass is None:
            from skfem import BilinearForm

            @BilinearForm
            def mass(a, b, w):
                return a * b

            self._mass = spla.splu(mass.assemble(self.wbasis).tocsc())
        p = self._split(u)[0]
        # the results ask for the pressure of one state several times (fields, summary,
        # admissibility): the projection is kept for the last film DOFs
        if self._average is None or not np.array_equal(self._average[0], p):
            Pq = interpolate_values(self.fbasis, p).ravel()
            self._average = (p.copy(), self._mass.solve(width_load(self.T, Pq, self.width)))
        return self._average[1].copy()

    def land_average(self, u) -> np.ndarray:
        """Hermite DOFs of the film pressure averaged over the lands only (as
        :meth:`width_average`; the whole width on a smooth roller)."""
        land = (self.groove_q.ravel() == 0.0).astype(float)
        Pq = interpolate_values(self.fbasis, self._split(u)[0]).ravel()
        width = float(np.sum(self.T["dx"] * land)) / float(np.sum(self.T["dx"])) * self.width
        self.width_average(u)          # builds the mass matrix
        return self._mass.solve(width_load(self.T, land * Pq, width))

    def pressure(self, u, X) -> np.ndarray:
        """Width-averaged film pressure at X (through :meth:`width_average`)."""
        return self.at(X, self.width_average(u))

    def film_pressure_at_vertices(self, u) -> np.ndarray:
        """Film pressure at the mesh vertices (for VTU)."""
        return self._split(u)[0][self.fbasis.nodal_dofs[0]]

    # -- starts and solvers ---------------------------------------------------------------
    def start_from_line(self, problem1d, u1d, prm, pressure: bool = True) -> np.ndarray:
        """The 1-D (infinitely wide) solution as a start: its web, and (``pressure``) its
        pressure shaped across the width like 1 - (Z/lambda)^2 scaled to the same width
        average."""
        u = np.zeros(self.n_dofs)
        xn = self.X
        d = 1e-6
        xa, xb = np.clip(xn - d, xn[0], xn[-1]), np.clip(xn + d, xn[0], xn[-1])
        # one evaluation at the nodes and both sides (each point's value is its own)
        Hn, Hb, Ha = problem1d.gap(u1d, prm, np.concatenate([xn, xb, xa])).reshape(3, -1)
        u[self.iWv] = Hn - forms.departure(xn, prm.beta)
        u[self.iWx] = ((Hb - forms.departure(xb, prm.beta))
                       - (Ha - forms.departure(xa, prm.beta))) / (xb - xa)
        if not pressure:
            return u
        loc = self.fbasis.doflocs
        lam = max(abs(self.Z[0]), abs(self.Z[-1]))
        shape = 1.5 * (1.0 - (loc[1] / lam) ** 2) if self.web_edges else 1.0
        # the film's DOFs lie on a few lines X = const: the 1-D pressure once per line
        x, line = np.unique(loc[0], return_inverse=True)
        u[:self.nP] = problem1d.pressure(u1d, x)[line] * shape
        u[self.fixed] = 0.0
        return u

    def _newton(self, u0, prm, tol, max_iter, rows=None, rtol=0.0, chord=True):
        return newton(lambda v: self.residual(v, prm), lambda v: self.jacobian(v, prm), u0,
                      self.free if rows is None else rows, tol=tol, max_iter=max_iter,
                      rtol=rtol, chord=chord)

    def consistent_pressure(self, u, prm, tol=1e-8, rtol=0.0):
        """Film pressure for the web as it is (a film-only Newton solve, to ``tol`` or
        ``rtol`` times its first residual)."""
        rows = self.free[self.free < self.nP]
        # no chord steps: a looser start pressure sends the coupled solve on another path
        # (on the grooved cases, more iterations before its continuation)
        out = self._newton(u, prm, tol, 10, rows=rows, rtol=rtol, chord=False)
        return out.u if out.converged else u

    def solve_newton(self, u0, prm, options: FE2DOptions | None = None):
        """Newton on film + web; on failure, when the problem knows the 1-D state it started
        from (``line_start``), continuation in the web width (:func:`_width_continuation`)."""
        options = options or FE2DOptions()
        u, info = self._plain_newton(u0, prm, options.tol, options.max_iter,
                                     DIRECT_STEPS if self.direct else 0)
        if not info["converged"] and self.ambient_grooves:
            # the solved groove pressure is close to ambient in deep grooves: start there
            solved = FoilBearing2D(self.X, self.Z, self.order, self.grooves, self.web_edges)
            v, first = solved.solve_newton(u0, prm, options)
            if first["converged"]:
                v[self.fixed] = 0.0
                u, info = self._plain_newton(v, prm, options.tol, options.max_iter)
                info["iterations"] += first["iterations"]
                info["reason"] += " (from the solved groove pressure)"
        elif not info["converged"] and self.grooves is not None:
            u, info = _depth_continuation(self, u0, prm, options, info)
        elif not info["converged"] and self.line_start is not None:
            p1, u1 = self.line_start
            u, info = _width_continuation(self, p1, u1, prm, options, info)
        return u, info

    def _plain_newton(self, u0, prm, tol, max_iter, direct_budget: int = 0):
        """Newton on film + web from ``u0`` with the film pressure made consistent with its
        web first (a film-only solve: it rescues starts whose pressure is far from the
        web's). ``direct_budget > 0``: first try that many coupled steps straight from
        ``u0`` (a state carried over from a solved mesh, or the 1-D solution, needs no
        film-only solve)."""
        first = self._newton(u0, prm, tol, direct_budget) if direct_budget else None
        out = first
        if first is None or not first.converged:
            out = self._newton(self.consistent_pressure(u0, prm, rtol=START_RTOL), prm, tol,
                               max_iter)
        if first is not None and out is not first:
            out.iterations += first.iterations
            out.history = list(first.history) + list(out.history)
        return out.u, dict(converged=out.converged, iterations=out.iterations,
                           residual=out.residual, history=list(out.history), reason=out.reason,
                           steps=[1.0])

    def solve_picard(self, u0, prm, options: FE2DOptions | None = None):
        """Picard with the film's coefficients frozen (see :meth:`fe1d.FoilBearing1D.
        solve_picard`); stops on the coupled residual norm, like Newton."""
        options = options or FE2DOptions()
        o = options
        return frozen_coefficient_picard(self, u0, prm, o.tol, o.omega, o.aitken,
                                         o.picard_max_iter, o.backtrack or None, o.anderson)


#: The film-only solve before a coupled Newton stops at this fraction of its first residual:
#: it only gives Newton a pressure consistent with the web (one or two steps; solving it to
#: 1e-8 cost two more factorisations without saving a coupled step, measured on the cases).
START_RTOL = 1e-4

#: Coupled Newton steps tried straight from the start before the film-only solve (from the
#: 1-D solution the coupled Newton converged in 4-6 steps on the base case from 1 to 60 m/s,
#: the same answers and 13 % less time than with the film-only solve first).
DIRECT_STEPS = 6


def _continuation(problem_at, u, prm, opts, failed: dict, f: float, what: str):
    """Newton along a factor f stepped geometrically (by 4) to 1 from ``f``: each step starts
    from the last converged state on ``problem_at(f)``; a failed step is halved (in log f)."""
    its, hist = failed["iterations"], list(failed["history"])
    f_prev = None
    while True:
        with stage(f"{what} continuation, {f:.3g} x"):
            v, info = problem_at(f)._plain_newton(u, prm, opts.tol, opts.max_iter)
        its += info["iterations"]
        hist += info["history"]
        if info["converged"]:
            u, f_prev = v, f
            if f == 1.0:
                info.update(iterations=its, history=hist,
                            reason=info["reason"] + f" (after continuation in {what})")
                return u, info
            f = max(1.0, f / 4.0) if f > 1.0 else min(1.0, 4.0 * f)
        else:
            if f_prev is None or abs(np.log(f / f_prev)) < np.log(1.01):
                info.update(iterations=its, history=hist,
                            reason=f"{what} continuation failed at {f:.3g} x the {what}: "
                                   + info["reason"])
                return v, info
            f = float(np.sqrt(f * f_prev))


def _width_continuation(problem: FoilBearing2D, p1, u1, prm, opts, failed: dict):
    """Newton from a web 16 times wider (close to the 1-D solution it starts from) down to
    the true width. The meshes differ only by the scaling of Z, so a state carries over as it
    is (the pressure as a function of Z / lambda)."""
    scaled = {}

    def at(f):
        if f not in scaled:
            scaled[f] = FoilBearing2D(problem.X, problem.Z * f, order=problem.order)
        return scaled[f]

    return _continuation(at, at(16.0).start_from_line(p1, u1, prm), prm, opts, failed, 16.0,
                         "width")


def _depth_continuation(problem: FoilBearing2D, u0, prm, opts, failed: dict):
    """Newton from shallow grooves (close to the smooth roller the start comes from) to the
    true depth, from 1/64 of it."""
    g = problem.grooves

    def at(f):
        return FoilBearing2D(problem.X, problem.Z, problem.order,
                             GroovePattern(g.pitch, g.width, g.depth * f), problem.web_edges,
                             problem.ambient_grooves)

    return _continuation(at, u0, prm, opts, failed, 1.0 / 64.0, "groove depth")


def _transfer2d(coarse: FoilBearing2D, u, prm, fine: FoilBearing2D) -> np.ndarray:
    """A state on a finer mesh: the web through its values and slopes, the film pressure
    through its own Q1/Q2 interpolant (exact on a nested mesh, as the refinement's), so a
    solved state arrives solved up to what the finer mesh adds."""
    v = fine.start_from_line(coarse, u, prm, pressure=False)
    v[:fine.nP] = tensor_interpolation(coarse.X, coarse.Z, coarse.order,
                                       coarse.fbasis.doflocs, u[:coarse.nP],
                                       fine.fbasis.doflocs)
    v[fine.fixed] = 0.0
    return v


def _film_fields(case: Case, problem: FoilBearing2D, u, prm) -> Film:
    """Film fields at the 2-D mesh vertices, physical units (for VTU and pictures)."""
    pts = problem.mesh.p
    Hs = case.h_scale
    x, line = np.unique(pts[0], return_inverse=True)     # the vertices lie on the X nodes
    H = problem.gap(u, prm, x)[line]
    groove = (problem.grooves.depth_at(pts[1]) if problem.grooves is not None
              else np.zeros_like(H))
    on_land = groove == 0.0
    h = (H + groove) * Hs          # the film gap: web gap plus groove depth
    p_rel = problem.film_pressure_at_vertices(u) * case.p_bar
    loc = friction_for(case, H * Hs, resting=True)
    return Film(
        points=np.vstack([pts * case.x_scale, np.zeros(pts.shape[1])]).T,
        quads=problem.mesh.t.T.copy(),
        p=p_rel + case.air.ambient_pressure, p_rel=p_rel, h=h,
        p_contact=forms.contact_law(H, prm.as_form_args())[0] * case.p_bar * on_land,
        chi_c=loc["chi_c"], mu=loc["mu"], regime=loc["regime"].astype(float))


def self_probe(problem: FoilBearing2D, dofs, X) -> np.ndarray:
    """The web-space function with Hermite ``dofs`` at scaled points X."""
    return problem.at(X, dofs)


#: A wide web is solved on the periodic groove cell from this many groove pitches across it
#: (``grooves = "auto"``).
CELL_PITCHES = 10.0


def groove_domain(case: Case, options: FE2DOptions):
    """The scaled groove pattern of ``case`` (None: smooth roller) and the domain across the
    width: "cell" (the periodic cell land centre to groove centre), "full" (the web's width
    with its edge lands) or "smooth"."""
    if not case.grooved:
        return None, "smooth"
    r = case.roller
    pattern = GroovePattern(r.groove_pitch / case.x_scale, r.groove_width / case.x_scale,
                            r.groove_depth / case.h_scale)
    domain = options.grooves
    if domain == "auto":
        domain = "cell" if case.web.width >= CELL_PITCHES * r.groove_pitch else "full"
    return pattern, domain


class _Film:
    """The 2-D model's part of the shared driver: the 1-D (infinitely wide) solution gives
    the start and the X mesh, already refined where the film is thin."""

    name = NAME

    def start(self, case: Case, prm: FoilParameters, options: FE2DOptions, initial) -> Start:
        line_start = initial.state("line_result") if initial is not None else None
        smooth = case.updated({"roller.groove_width": 0.0}) if case.grooved else case
        one = fe1d.solve_case(smooth, FE2DOptions.line_options(options), initial=line_start,
                              raise_on_failure=False)
        p1, u1 = one.state("problem"), one.state("state")
        pattern, domain = groove_domain(case, options)
        if pattern is None:
            Z = width_nodes(case.lam, options.level, half=options.symmetry,
                            fine=options.width_fine)
        elif domain == "cell":
            Z = groove_nodes(pattern, 0.0, 0.5 * pattern.pitch, options.width_fine,
                             options.level)
        else:
            Z = groove_nodes(pattern, 0.0, case.lam, options.width_fine, options.level)
            if not options.symmetry:
                Z = np.concatenate([-Z[:0:-1], Z])
        problem = FoilBearing2D(p1.X, Z, order=options.order, grooves=pattern,
                                web_edges=domain != "cell",
                                ambient_grooves=options.groove_pressure == "ambient")
        problem.line_start = (p1, u1)
        # on a smooth roller the 1-D solution is close enough for the coupled Newton; a
        # grooved film is not (the direct steps failed on the grooved cases: 0.27 -> 0.35 s)
        problem.direct = pattern is None
        return Start(problem, problem.start_from_line(p1, u1, prm),
                     iterations=one["iterations"], solver={"line_result": one})

    def refined(self, problem, u, prm, X, options):
        finer = FoilBearing2D(X, problem.Z, order=options.order, grooves=problem.grooves,
                              web_edges=problem.web_edges,
                              ambient_grooves=problem.ambient_grooves)
        finer.direct = True
        return finer, _transfer2d(problem, u, prm, finer)

    def remeshed(self, problem, u, prm, X, Z, options):
        """The problem on the nodes X x Z (coarser or finer; the same grooves and domain)
        and ``u`` carried over to it."""
        other = FoilBearing2D(X, Z, order=options.order, grooves=problem.grooves,
                              web_edges=problem.web_edges,
                              ambient_grooves=problem.ambient_grooves)
        other.direct = True
        other.line_start = problem.line_start
        return other, _transfer2d(problem, u, prm, other)

    def mesh_text(self, problem, options) -> str:
        if not problem.web_edges:
            where = "periodic groove cell (land centre to groove centre)"
        else:
            where = f"{'half' if options.symmetry else 'full'} width" + (
                " with its edge lands (a land centred on the web's centreline)"
                if problem.grooves is not None else "")
        return (f"{where}, {len(problem.X) - 1} x "
                f"{len(problem.Z) - 1} Q{options.order} cells; x: "
                f"{fe1d.line_mesh_text(problem.X, options)}; web: Hermite line")

    def summary_extra(self, case: Case, problem, options) -> dict:
        extra = {"n_cells": int(problem.mesh.nelements), "width_cells": len(problem.Z) - 1,
                 "land_fraction": case.land_fraction}
        warnings = []
        if problem.grooves is not None:
            spans = case.web.width / case.roller.groove_pitch
            if problem.web_edges:
                extra["groove_domain"] = (f"full width: the web spans {spans:.3g} groove "
                                          "pitches, edge lands included")
            else:
                extra["groove_domain"] = (
                    f"periodic cell: the web spans {spans:.3g} groove pitches; the web's "
                    f"edges are left out (the edge pitches are "
                    f"{100 * 2 * case.roller.groove_pitch / case.web.width:.2g} % of the "
                    f"width, a bound on the error they leave; grooves = \"full\" solves "
                    f"them)")
        if case.beta < 6.0:
            warnings += [f"beta = {case.beta:.3g} < 6: the wrap is shorter than the "
                                 "entry and exit zones; no uniform central gap exists"]
        if warnings:
            extra["warnings"] = warnings
        return extra

    def summary_state(self, case: Case, problem, u, prm, pts, wts) -> dict:
        """The contact share of the load on the lands: asperity contact over (film pressure
        averaged over the lands + contact), integrated over the wrap."""
        if problem.grooves is None:
            return {}
        Pl = self_probe(problem, problem.land_average(u), pts)
        Pc = forms.contact_law(problem.gap(u, prm, pts), prm.as_form_args())[0]
        share = float(np.sum(Pc * wts) / max(np.sum((Pl + Pc) * wts), 1e-300))
        return {"contact_share_lands": share}

    def film(self, case, problem, u, prm) -> Film:
        return _film_fields(case, problem, u, prm)


#: The 2-D model as the driver sees it.
FILM = _Film()


def solve_case(case: Case, options: FE2DOptions, *, initial: Result | None = None,
               raise_on_failure: bool = True) -> Result:
    """The registry's entry: :func:`solve` with a ready options object."""
    return solve_fe(FILM, case, options, initial, raise_on_failure)


def solve(case: Case, options: FE2DOptions | None = None, *, initial: Result | None = None,
          raise_on_failure: bool = True, **values) -> Result:
    """Solve one case with the 2-D film and the 1-D web.

    ``options`` (or keywords, see :class:`~webfem.models.options.FE2DOptions`): those of
    the 1-D model plus ``width_fine`` (cell size at the web edges, scaled units; ``level``
    bisects) and ``symmetry`` (True: half width with dP/dZ = 0 at the centreline; False:
    full width). ``initial``: a previous fe2d result; its 1-D part starts this point's 1-D
    solve (continuation in a sweep). The 2-D solve always starts from the 1-D solution.
    """
    options = options.replace(**values) if options is not None else \
        FE2DOptions.from_mapping(values)
    return solve_case(case, options, initial=initial, raise_on_failure=raise_on_failure)
