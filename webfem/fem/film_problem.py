"""The 2-D discrete problem: the film over the wrap domain coupled to the 1-D web, on one mesh.

The film is solved on [X_s, X_e] x [0, lambda] (half width, symmetry at the centreline) or
[-lambda, lambda] (full width) in scaled coordinates, with Q2 (or Q1) quadrilaterals on the
tensor product of the web's nodes in X and nodes across the width; a grooved roller's periodic
cell is [0, pitch/2] with symmetry on both sides, and a wide web's edge strip [z_c, lambda]
(z_c a land centre, a symmetry line) stands for the half width: its innermost half land and
groove, weighted, for the periodic interior [0, z_c] (:attr:`FilmConfig.strip`). The web is the Hermite beam/membrane of the
1-D model, loaded by the width-averaged film pressure plus the asperity contact; the two
meshes share their X nodes and the web's basis is evaluated exactly at the film's quadrature
points (:mod:`webfem.fem.transfer`). The weak forms are :mod:`webfem.fem.forms`', assembled by
:class:`webfem.fem.systems.FilmSystem`.

Every problem of a solve (the finer mesh, the coarser one of the error estimate, the wider
web or shallower grooves of a continuation) is built from another by :meth:`FoilBearing2D.
variant`, so what it is made of (element order, grooves, domain) is stated once.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spla
from skfem import Basis, BilinearForm, ElementQuad1, ElementQuad2

from . import continuation, ends, forms
from .grooves import GroovePattern
from .hermite import HermiteLine, LineProbes
from .mesh import line_mesh
from .newton import PatternSolver, newton
from .outcome import SolveInfo
from .picard import frozen_coefficient_picard
from .systems import FilmSystem, width_load
from .transfer import (film_basis, film_mesh, interpolate_values, point_lines, quadrature,
                       quadrature_matrices, tensor_grid, tensor_interpolation)

__all__ = ["FilmConfig", "FoilBearing2D", "START_RTOL", "DIRECT_STEPS", "strip_weights"]

#: The film-only solve before a coupled Newton stops at this fraction of its first residual:
#: it only gives Newton a pressure consistent with the web (one or two steps; solving it to
#: 1e-8 cost two more factorisations without saving a coupled step, measured on the cases).
START_RTOL = 1e-4

#: Coupled Newton steps tried straight from the start before the film-only solve (from the
#: 1-D solution the coupled Newton converged in 4-6 steps on the base case from 1 to 60 m/s,
#: the same answers and 13 % less time than with the film-only solve first).
DIRECT_STEPS = 6


@dataclass(frozen=True)
class FilmConfig:
    """What a 2-D problem is made of besides its nodes: the pressure element ``order`` (1 or
    2), the roller's ``grooves`` (None: smooth), whether Z ends at the ``web_edges`` (False:
    the periodic cell of a grooved roller), ``ambient_grooves`` (P = 0 in the grooves: the
    deep-groove limit, for checks), ``strip`` and ``spans`` (the web held through the spans
    beyond the domain, ``wrap.span``: :mod:`webfem.fem.ends`).

    ``strip``: Z[0] > 0 is a land centre inside the web (a symmetry line) and Z[-1] the web's
    edge; the film on [Z[0], Z[-1]] stands for the half width [0, Z[-1]]: the interior
    [0, Z[0]] is periodic, made of Z[0]/pitch lands and grooves like the innermost ones, so
    the innermost half land counts 1 + 2 Z[0]/pitch times and the innermost groove
    1 + Z[0]/pitch times in the width average the web carries. Valid where the web's edges
    no longer reach the innermost pitch (the strip is wide enough), which the model chooses
    (:mod:`webfem.models.fe2d`)."""

    order: int = 2
    grooves: GroovePattern | None = None
    web_edges: bool = True
    ambient_grooves: bool = False
    strip: bool = False
    spans: bool = False

    def __post_init__(self):
        if self.order not in (1, 2):
            raise ValueError(f"order = {self.order!r} is not valid: must be 1 or 2")
        if self.strip and (self.grooves is None or not self.web_edges):
            raise ValueError("an edge strip needs grooves and a web edge")
        object.__setattr__(self, "ambient_grooves",
                           bool(self.ambient_grooves) and self.grooves is not None)


def strip_weights(grooves: GroovePattern, Z: np.ndarray, zq: np.ndarray) -> np.ndarray:
    """The weights of an edge strip's quadrature points at ``zq`` (:attr:`FilmConfig.
    strip`): 1 + 2 Z[0]/pitch on the innermost half land [Z[0], Z[0] + land/2], 1 + Z[0]/pitch
    on the innermost groove after it, 1 elsewhere; they add up to the half width Z[-1].

    >>> g = GroovePattern(pitch=1.0, width=0.25, depth=1.0)
    >>> strip_weights(g, np.array([3.0, 8.0]), np.array([3.1, 3.5, 3.9, 5.0])).tolist()
    [7.0, 4.0, 1.0, 1.0]
    """
    z0, p = float(Z[0]), grooves.pitch
    half_land = z0 + 0.5 * grooves.land
    tol = 1e-9 * p
    return np.where(zq < half_land + tol, 1.0 + 2.0 * z0 / p,
                    np.where(zq < half_land + grooves.width + tol, 1.0 + z0 / p, 1.0))


class FoilBearing2D:
    """The discrete coupled problem on the nodes ``X`` x ``Z``: film basis on the 2-D mesh,
    web basis on the line. Unknowns ``u = [p (film DOFs), w (web DOFs)]``. Built once per
    mesh; the parameters may change between calls (continuation)."""

    def __init__(self, X: np.ndarray, Z: np.ndarray, order: int = 2,
                 grooves: GroovePattern | None = None, web_edges: bool = True,
                 ambient_grooves: bool = False, strip: bool = False, spans: bool = False):
        self.config = FilmConfig(order, grooves, bool(web_edges), ambient_grooves,
                                 bool(strip), bool(spans))
        self.X, self.Z = np.asarray(X, float), np.asarray(Z, float)
        self.order, self.grooves = order, grooves
        self.web_edges, self.ambient_grooves = self.config.web_edges, \
            self.config.ambient_grooves
        self.strip = self.config.strip
        #: the width the film stands for: the domain's, or for a strip the half web's
        self.width = float(self.Z[-1] - (0.0 if self.strip else self.Z[0]))
        self.line = line_mesh(self.X)
        # a new Hermite element per mesh: it caches mesh data (scikit-fem 12); HermiteLine
        # evaluates its four functions at once, bitwise as scikit-fem's (the web's values at
        # each new point set: 9 % of a 24-point speed sweep's time with scikit-fem's)
        web = HermiteLine()
        self.wbasis = Basis(self.line, web, quadrature=quadrature(web.refdom, 6))
        self.mesh = film_mesh(self.X, self.Z, web_edges=self.web_edges, strip=self.strip)
        # scikit-fem's basis on the rectangles' affine map (its isoparametric one to
        # rounding), with the DOF numbering of a mesh of the same topology (a moved mesh: a
        # continued point's) shared
        self.fbasis = film_basis(self.mesh, ElementQuad2() if order == 2 else ElementQuad1(),
                                 intorder=4 if order == 2 else 3)
        self._T = None
        self.nP, self.nW = self.fbasis.N, self.wbasis.N
        fixed_p = self.fbasis.get_dofs({"ends", "edges"} if self.web_edges
                                       else {"ends"}).all()
        zq = np.asarray(self.fbasis.global_coordinates()[1])
        #: groove depth Delta(Z) at the film's quadrature points (0: land or smooth)
        self.groove_q = grooves.depth_at(zq) if grooves is not None else np.zeros_like(zq)
        #: how many times each quadrature point counts in the width average (1 but in a
        #: strip's innermost half land and groove)
        self.weight_q = strip_weights(grooves, self.Z, zq) if self.strip \
            else np.ones_like(zq)
        # held at the domain's ends (Eq. 20), or through the spans beyond them (wrap.span:
        # the end deflections are unknowns on springs, :mod:`webfem.fem.ends`)
        fixed_w = (np.array([], dtype=np.int64) if self.spans
                   else self.wbasis.get_dofs({"left", "right"}).all("u") + self.nP)
        if self.ambient_grooves:
            zd = self.fbasis.doflocs[1]
            off = np.abs(zd - grooves.pitch * np.round(zd / grooves.pitch))
            fixed_p = np.concatenate([fixed_p, np.flatnonzero(
                off >= 0.5 * grooves.land * (1.0 - 1e-9))])
        self.fixed = np.unique(np.concatenate([fixed_p, fixed_w]))
        is_free = np.ones(self.n_dofs, dtype=bool)
        is_free[self.fixed] = False
        self.free = np.flatnonzero(is_free)          # np.setdiff1d's answer, without a sort
        self.iWv = self.wbasis.nodal_dofs[0] + self.nP      # web values at the nodes
        self.iWx = self.wbasis.nodal_dofs[1] + self.nP      # web slopes
        px = self.line.p[0]
        #: the web's deflection at the domain's entry and exit ends
        self.iW_ends = self.iWv[[int(np.argmin(px)), int(np.argmax(px))]]
        #: the web's uniform lift, where its ends are unknowns (Picard corrects along it)
        self.lift = ends.uniform_lift(self.n_dofs, self.iWv) if self.spans else None
        self._mass, self._system, self._solver, self._lines = None, None, None, None
        #: the web basis at point sets asked for again (the nodes: refinement, admissibility
        #: and results), by the points' bytes; the last width average (film DOFs, result)
        self._web_probes, self._average = LineProbes(self.wbasis), []
        #: the 1-D problem and state this problem started from (width continuation)
        self.line_start = None
        #: True: Newton tries the coupled system straight from its start (a solved state
        #: carried over from another mesh, or the 1-D solution) before a film-only pre-solve
        self.direct = False
        #: :func:`webfem.fem.newton.newton`'s ``accept`` for the coupled solves of this
        #: problem (balanced stopping, :mod:`webfem.models.algebraic`; None: to ``tol``)
        self.accept = None
        #: what ``accept`` returned for the state the last coupled solve ended on (its
        #: algebraic error bounds), None where that solve met ``tol`` or found nothing
        self.bounds = None

    def variant(self, X=None, Z=None, **config) -> "FoilBearing2D":
        """A problem like this one on other nodes and/or with ``config`` changed (the
        fields of :class:`FilmConfig`); it starts directly and knows the same 1-D start."""
        cfg = dataclasses.replace(self.config, **config)
        other = FoilBearing2D(self.X if X is None else X, self.Z if Z is None else Z,
                              **dataclasses.asdict(cfg) | {"grooves": cfg.grooves})
        other.direct, other.line_start = True, self.line_start
        return other

    @property
    def T(self) -> dict:
        """The web's basis at the film's quadrature points (:func:`webfem.fem.transfer.
        quadrature_matrices`), built on first use: a problem made only to carry a state to
        another mesh or to read its gap (a continued point's previous mesh moved, where this
        point's mesh is another: 2 of the 4 problems of such a point) never needs it."""
        if self._T is None:
            self._T = quadrature_matrices(self.fbasis, self.wbasis)
        return self._T

    @property
    def n_dofs(self) -> int:
        return self.nP + self.nW

    def release(self) -> None:
        """Drop what this problem builds on first use for its solves (its assembly, the
        factorisation plans it holds): built again if it is solved again. Why: a problem is
        kept for its nodes and state while the finer mesh carried over from it is solved,
        and its assembly held ~0.5 GB at 1.2e5 unknowns beside the finer one's. The web's
        mass factorisation and the last two width averages (of the web's size and of the film's
        DOFs) are kept: the result reads the film pressure of the released answer again,
        and building them again was 1 of the 3 mass factorisations of a continued sweep
        point (23 of 76 on the 24-point speed sweep)."""
        self._system, self._solver = None, None

    def recipe(self) -> tuple:
        """``(FoilBearing2D, args, kwargs)`` that build this problem again: what a result
        keeps instead of the problem (its bases, assembly maps and factorisation plans held
        about 600 MB per result at 1.4e5 unknowns in a process that keeps results, a
        traction-loss search or a sweep)."""
        c = self.config
        # every field of the configuration (a strip's or the spans' rebuilt as they were)
        return (FoilBearing2D, (self.X.copy(), self.Z.copy()),
                dataclasses.asdict(c) | {"grooves": c.grooves})

    def _split(self, u):
        return u[:self.nP], u[self.nP:]

    @property
    def system(self) -> FilmSystem:
        """The assembly of this mesh's film + web system, built on first use."""
        if self._system is None:
            # the strip's weights enter as a width per quadrature point: the web's load
            # (1/width) int P dZ counts a weighted point's pressure that many times
            width = self.width / self.weight_q if self.strip else self.width
            self._system = FilmSystem(self.fbasis, self.wbasis, self.T, width, self.groove_q)
        return self._system

    @property
    def solver(self) -> PatternSolver:
        """The factorisations of this mesh's Jacobians, each with a unit diagonal (a landing
        web's contact stiffness otherwise forces row exchanges that undo the ordering:
        :class:`~webfem.fem.newton.PatternSolver`); their plans (fill-reducing ordering)
        kept with the pattern, which a moved mesh shares (:func:`webfem.fem.fast.
        pattern_of`)."""
        if self._solver is None:
            self._solver = PatternSolver(scaled=True, plans=self.system.pattern.plans)
        return self._solver

    def residual(self, u, prm) -> np.ndarray:
        """The coupled residual."""
        return ends.with_springs(self.system.residual(u, prm), u, self.iW_ends,
                                 ends.springs(self, prm))

    def jacobian(self, u, prm, newton: bool = True):
        """Exact Jacobian, or (``newton=False``) Picard's."""
        return ends.jacobian_with_springs(self.system.jacobian(u, prm, bool(newton)),
                                          self.iW_ends, ends.springs(self, prm))

    @property
    def spans(self) -> bool:
        """The web held through spans beyond the domain (``wrap.span``), not at its ends."""
        return self.config.spans

    # -- fields -------------------------------------------------------------------------------
    def at(self, X, dofs) -> np.ndarray:
        """The web-space function with Hermite ``dofs`` at scaled points X: scikit-fem's
        ``probes(X) @ dofs`` to the last bit (the values at the last point sets kept)."""
        return self._web_probes(np.asarray(X, float), dofs)

    def gap(self, u, prm, X) -> np.ndarray:
        X = np.asarray(X, float)
        return self.at(X, self._split(u)[1]) + forms.departure(X, prm.beta)

    def _mass_solve(self, load) -> np.ndarray:
        if self._mass is None:
            mass = BilinearForm(lambda a, b, w: a * b)
            self._mass = spla.splu(mass.assemble(self.wbasis).tocsc())
        return self._mass.solve(load)

    def width_average(self, u) -> np.ndarray:
        """Hermite DOFs of the width-averaged film pressure: the L2 projection of
        (1/width) int P dZ onto the web's space (the same load vector the web sees)."""
        p = self._split(u)[0]
        # the results ask for the pressure of one state several times (fields, summary,
        # admissibility): the projections of the last two film DOFs are kept (balanced
        # stopping reads an iterate and its corrected state in turn, then the iterate again)
        for i, (kept, average) in enumerate(self._average):
            if np.array_equal(kept, p):
                self._average.append(self._average.pop(i))
                return average.copy()
        Pq = interpolate_values(self.fbasis, p).ravel() * self.weight_q.ravel()
        average = self._mass_solve(width_load(self.T, Pq, self.width))
        self._average = self._average[-1:] + [(p.copy(), average)]
        return average.copy()

    def land_average(self, u) -> np.ndarray:
        """Hermite DOFs of the film pressure averaged over the lands only (as
        :meth:`width_average`; the whole width on a smooth roller)."""
        land = (self.groove_q.ravel() == 0.0) * self.weight_q.ravel()
        Pq = interpolate_values(self.fbasis, self._split(u)[0]).ravel()
        width = float(np.sum(self.T["dx"] * land)) / float(
            np.sum(self.T["dx"] * self.weight_q.ravel())) * self.width
        return self._mass_solve(width_load(self.T, land * Pq, width))

    def groove_pressure_ratio(self, u, X) -> float:
        """The film pressure over the grooves relative to that over the lands, summed over
        the points X (the wrap): 0 where the grooves vent to ambient, 1 where they hold the
        lands' pressure (as a smooth roller)."""
        weights = self.weight_q.ravel() * self.T["dx"]
        land = float(np.sum(weights * (self.groove_q.ravel() == 0.0)) / np.sum(weights))
        if land >= 1.0:
            return 1.0
        Pw, Pl = self.at(X, self.width_average(u)), self.at(X, self.land_average(u))
        Pg = (Pw - land * Pl) / (1.0 - land)
        return float(np.sum(Pg) / np.sum(Pl)) if np.sum(Pl) > 0.0 else 1.0

    def pressure(self, u, X) -> np.ndarray:
        """Width-averaged film pressure at X (through :meth:`width_average`)."""
        return self.at(X, self.width_average(u))

    def film_pressure_at_vertices(self, u) -> np.ndarray:
        """Film pressure at the mesh vertices (for VTU)."""
        return self._split(u)[0][self.fbasis.nodal_dofs[0]]

    # -- states --------------------------------------------------------------------------------
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

    def transfer(self, u, prm, other: "FoilBearing2D") -> np.ndarray:
        """The state ``u`` on ``other``'s mesh: the web through its values and slopes, the
        film pressure through its own Q1/Q2 interpolant (exact on a nested finer mesh, as the
        refinement's), so a solved state arrives solved up to what the other mesh adds."""
        v = other.start_from_line(self, u, prm, pressure=False)
        v[:other.nP] = tensor_interpolation(self.X, self.Z, self.order,
                                            self.fbasis.doflocs, u[:self.nP],
                                            other.fbasis.doflocs, grid=self._dof_lines()[0],
                                            lines=other._dof_lines()[1])
        v[other.fixed] = 0.0
        return v

    def _dof_lines(self) -> tuple:
        """The film DOFs' lines, as a field's source (:func:`webfem.fem.transfer.
        tensor_grid`) and as target points (:func:`~webfem.fem.transfer.point_lines`):
        functions of the mesh alone, found on first use (a continued point carries 4-5
        states between its meshes)."""
        if self._lines is None:
            loc = self.fbasis.doflocs
            self._lines = (tensor_grid(loc), point_lines(loc))
        return self._lines

    # -- solvers -------------------------------------------------------------------------------
    def newton(self, u0, prm, tol, max_iter, rows=None, rtol=0.0, chord=True):
        """Damped Newton on the ``rows`` (default: every free unknown). With spans an
        iterate whose correction is the rounding floor's noise is accepted
        (:func:`webfem.fem.newton.newton`'s ``noise``), as on the 1-D line
        (:meth:`webfem.models.line.FoilBearing1D.newton`): a stiff web held through spans
        has nearly singular Jacobians. Envelope #171 (a 3.1 cm board strip, Dn 1800):
        on the estimate's 156,871 unknowns the direct steps reached 1.06e-6 against a floor
        of 8.9e-6, where no step lowered it and the correction, 1.3e-6 of the state, was as
        large as random residuals' of that size; rejected, the same mesh was solved twice
        more (6 s of 25) to an answer 8e-7 from it (mu; stated errors 1e-2 to 2e-2). The
        held ends keep the strict test."""
        out = newton(lambda v: self.residual(v, prm), lambda v: self.jacobian(v, prm), u0,
                     self.free if rows is None else rows, tol=tol, max_iter=max_iter,
                     rtol=rtol, chord=chord, solver=self.solver, noise=self.spans,
                     accept=self.accept if rows is None else None)
        if rows is None:
            self.bounds = out.algebraic
        return out

    def consistent_pressure(self, u, prm, tol=1e-8, rtol=0.0):
        """Film pressure for the web as it is (a film-only Newton solve, to ``tol`` or
        ``rtol`` times its first residual)."""
        rows = self.free[self.free < self.nP]
        # no chord steps: a looser start pressure sends the coupled solve on another path
        # (on the grooved cases, more iterations before its continuation)
        out = self.newton(u, prm, tol, 10, rows=rows, rtol=rtol, chord=False)
        return out.u if out.converged else u

    def plain_newton(self, u0, prm, tol, max_iter, direct_budget: int = 0,
                     rtol: float = 0.0):
        """Newton on film + web from ``u0`` with the film pressure made consistent with its
        web first (a film-only solve: it rescues starts whose pressure is far from the
        web's). ``direct_budget > 0``: first try that many coupled steps straight from
        ``u0`` (a state carried over from a solved mesh, or the 1-D solution, needs no
        film-only solve), converged at ``rtol`` times their first residual already (where
        above ``tol``; the film-only path always solves to ``tol``). Returns ``(u,
        SolveInfo)``."""
        first = self.newton(u0, prm, tol, direct_budget, rtol=rtol) if direct_budget \
            else None
        if first is not None and first.converged:
            return first.u, SolveInfo.of(first)
        out = self.newton(self.consistent_pressure(u0, prm, rtol=START_RTOL), prm, tol,
                          max_iter)
        info = SolveInfo.of(out)
        return out.u, info.after(SolveInfo.of(first)) if first is not None else info

    def solve_newton(self, u0, prm, options, continued: bool = True):
        """Newton on film + web (``options.tol``, ``options.max_iter``); on failure: with
        ambient grooves from the solved groove pressure, then (``continued``) on a grooved
        roller continuation in the groove depth, on a smooth one (when the problem knows the
        1-D state it started from, ``line_start``) continuation in the web width
        (:mod:`webfem.fem.continuation`). Returns ``(u, SolveInfo)``."""
        tol, max_iter = options.tol, options.max_iter
        u, info = self.plain_newton(u0, prm, tol, max_iter,
                                    DIRECT_STEPS if self.direct else 0)
        if info.converged:
            return u, info
        if self.ambient_grooves:
            # the solved groove pressure is close to ambient in deep grooves: start there
            v, first = self.variant(ambient_grooves=False).solve_newton(u0, prm, options,
                                                                        continued)
            if first.converged:
                v[self.fixed] = 0.0
                u, second = self.plain_newton(v, prm, tol, max_iter)
                return u, second.after(first, "from the solved groove pressure")
            return u, info
        if not continued:
            return u, info
        if self.grooves is not None:
            return continuation.groove_depth(self, u0, prm, tol, max_iter, info)
        if self.line_start is not None:
            return continuation.web_width(self, *self.line_start, prm, tol, max_iter, info)
        return u, info

    def solve_near(self, u0, prm, options):
        """Newton from ``u0``, a solved state carried over from another mesh of the same
        problem: :meth:`solve_newton` without its continuation fallback (the ambient grooves'
        restart, cheap, is kept). Why: the mesh error estimate's finer mesh is a check of
        the answer it is carried from; where Newton does not reach the discrete solution
        near it, a continuation from the smooth roller on that finer mesh answers another
        question at the cost of several solves on it (a resting board's 94,489-unknown
        groove cell: 86 s of depth continuation that ended without an answer, where the
        estimate's next remedy, its cells along x quartered, converged in 15 s).
        Returns ``(u, SolveInfo)``."""
        return self.solve_newton(u0, prm, options, continued=False)

    def solve_picard(self, u0, prm, options):
        """Picard with the film's coefficients frozen (:func:`webfem.fem.picard.
        frozen_coefficient_picard`); stops on the coupled residual norm, like Newton."""
        o = options
        return frozen_coefficient_picard(self, u0, prm, o.tol, o.omega, o.aitken,
                                         o.picard_max_iter, o.backtrack or None, o.anderson)
