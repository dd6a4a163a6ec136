"""2-D finite elements: Reynolds over the wrap domain with edge leakage, coupled to the 1-D web.

The discrete problem is :class:`webfem.fem.film_problem.FoilBearing2D` (the film on the
tensor product of the web's nodes in X and nodes across the width, Q2 or Q1, with the web's
Hermite beam/membrane; its Newton strategy and the width and depth continuations of
:mod:`webfem.fem.continuation`). This module is the model on the shared driver: the 1-D
(infinitely wide) solution gives the start and the X mesh, already refined where the film is
thin; :func:`problem_for` builds the problem from the case and the options.

Examples
--------
>>> from webfem import Case
>>> r = solve(Case().updated({"roller.speed": 40.0}))
>>> r["model"], r["converged"]
('fe2d', True)
"""

from __future__ import annotations

import numpy as np

from ..case import Case
from ..fem import continuation, forms
from ..fem.film_problem import FoilBearing2D
from ..fem.mesh import graded_nodes
from ..fem.grooves import STRIP_PITCHES, STRIP_SCALED, STRIP_UNVENTED, GroovePattern, \
    choose_domain, edge_effect, graded_groove_nodes, groove_nodes, strip_start, strip_width
from ..fem.outcome import SolveInfo
from ..fem.transfer import width_nodes
from ..result import Rebuild, Result, State
from . import continued, fe1d
from .driver import Discretisation, Start, solve_fe
from .fields import film_fields
from .options import FE1DOptions, FE2DOptions
from .outcome import Facts
from .groove_domain import domain_text, sag_warning, solve_grooved

__all__ = ["FoilBearing2D", "FILM", "problem_for", "groove_domain", "sag_warning", "solve",
           "solve_case", "NAME"]

NAME = "fe2d"
#: The defaults of :class:`~webfem.models.options.FE2DOptions`, by name (read-only view).
DEFAULTS = FE2DOptions().to_dict()


def groove_domain(case: Case, options: FE2DOptions):
    """The scaled groove pattern of ``case`` (None: smooth roller) and the domain across the
    width the options ask for: "cell", "full", "strip" (:func:`webfem.fem.grooves.
    choose_domain`; "auto" without the periodic cell's estimate of the edges: the strip,
    or the full width of a web too narrow for one) or "smooth"."""
    if not case.grooved:
        return None, "smooth"
    r = case.roller
    pattern = GroovePattern(r.groove_pitch / case.x_scale, r.groove_width / case.x_scale,
                            r.groove_depth / case.h_scale)
    return pattern, choose_domain(options.grooves, pattern, case.lam,
                                  vent=_vent_of(pattern, options))


def _vent_of(pattern: GroovePattern, options: FE2DOptions) -> float:
    """The venting a strip's width stands for: none unless ``strip_width`` says otherwise."""
    if options.strip_width is None:
        return 0.0
    return 1.0 - (options.strip_width - STRIP_SCALED) / STRIP_UNVENTED


def problem_for(case: Case, options: FE2DOptions, X: np.ndarray) -> FoilBearing2D:
    """The 2-D problem of ``case`` on the X nodes ``X`` (scaled): the width's nodes, the
    grooves and the domain from the case and the options."""
    pattern, domain = groove_domain(case, options)
    if pattern is None:
        Z = problem_for_width(case, options)
    elif domain == "cell":
        Z = groove_nodes(pattern, 0.0, 0.5 * pattern.pitch, options.width_fine, options.level)
    elif domain == "strip":
        width = options.strip_width or strip_width(pattern.pitch)
        z_c = strip_start(pattern, case.lam, max(width, STRIP_PITCHES * pattern.pitch))
        Z = graded_groove_nodes(pattern, z_c, case.lam, [case.lam], options.width_fine,
                                options.level)
        return FoilBearing2D(X, Z, order=options.order, grooves=pattern, strip=True,
                             ambient_grooves=options.groove_pressure == "ambient")
    else:
        Z = graded_groove_nodes(pattern, 0.0, case.lam, [case.lam], options.width_fine,
                                options.level)
        if not options.symmetry:
            Z = np.concatenate([-Z[:0:-1], Z])
    return FoilBearing2D(X, Z, order=options.order, grooves=pattern,
                         web_edges=domain != "cell",
                         ambient_grooves=options.groove_pressure == "ambient")


def problem_for_width(case: Case, options: FE2DOptions) -> np.ndarray:
    """The nodes across a smooth roller's film (scaled): graded towards the web's edge."""
    return width_nodes(case.lam, options.level, half=options.symmetry, fine=options.width_fine)


#: How many cold 1-D starts :class:`_Film` keeps (a case's direct start and its finer-mesh
#: remedy's).
LINES_KEPT = 2


class _Film(Discretisation):
    """The 2-D model's part of the shared driver: the 1-D (infinitely wide) solution gives
    the start and the X mesh, already refined where the film is thin."""

    name = NAME

    def __init__(self):
        #: the cold 1-D starts of the solve under way, by case and 1-D options (bounded)
        self._lines: dict = {}
        #: the solved periodic cell (problem, state) of the grooved solve under way, which
        #: starts its edge strip or full width (:meth:`FoilBearing2D.start_from_cell`)
        self._cell = None

    def _line(self, smooth: Case, options: FE1DOptions, line: State | None) -> Result:
        """The 1-D solution that starts the 2-D solve. A cold one is kept for the same case
        and options: the driver's safe start and its check of a resting answer start from
        the same 1-D solve as the direct start (a stiff board's took 5-10 s, each time), and
        it is deterministic, so the kept one is the one a new solve would give."""
        if line is not None:
            return fe1d.solve_case(smooth, options, initial=line, raise_on_failure=False)
        key = (smooth, options)
        one = self._lines.get(key)
        if one is None:
            one = fe1d.solve_case(smooth, options, raise_on_failure=False)
            if len(self._lines) >= LINES_KEPT:
                self._lines.clear()
            self._lines[key] = one
        return one

    def forget_lines(self) -> None:
        """Drop the kept 1-D starts (:meth:`_line`): a solve starts and ends without them,
        so what one solve reports (its stages, the 1-D start's work) never depends on an
        earlier one. The periodic cell's start goes with them."""
        self._lines.clear()
        self._cell = None

    def start(self, case: Case, prm, options: FE2DOptions, restart: State | None) -> Start:
        moved = continued.continued_state(case, options, restart)
        if moved is not None:
            start = self._continued(case, prm, options, moved, restart)
            if start is not None:
                return start
        smooth = case.updated({"roller.groove_width": 0.0}) if case.grooved else case
        line = restart.line if restart is not None and restart.model == NAME else None
        one = self._line(smooth, FE2DOptions.line_options(options), line)
        p1, u1 = one.state("problem"), one.state("state")
        problem = problem_for(case, options, p1.X)
        problem.line_start = (p1, u1)
        # on a smooth roller the 1-D solution is close enough for the coupled Newton; a
        # grooved film is not (the direct steps failed on the grooved cases: 0.27 -> 0.35 s)
        problem.direct = problem.grooves is None
        spent = SolveInfo(converged=True, iterations=one["iterations"])
        kept = {"line_result": one}
        cell = self._cell if restart is None and problem.web_edges else None
        if cell is not None and cell[0].grooves == problem.grooves:
            # the grooves' own periodic cell, solved: a solved state, so coupled steps first
            problem.direct = True
            kept["started_from"] = "the periodic cell's solution repeated across the width"
            return Start(problem, problem.start_from_cell(*cell, prm), info=spent,
                         line=one.restart, kept=kept)
        return Start(problem, problem.start_from_line(p1, u1, prm), info=spent,
                     line=one.restart, kept=kept)

    def _continued(self, case: Case, prm, options: FE2DOptions, moved, restart: State):
        """The start from the previous point (:func:`continued.continued_state`), without a
        1-D solve: on the previous point's mesh moved to this case while it has about as
        many nodes as the mesh this case's predicted gap asks for (:func:`continued.
        planned_nodes`, within :data:`continued.MESH_SLACK`: along a sweep the meshes
        drift, and the previous point's may be twice as fine where its estimate bisected
        it), else on that planned mesh with the moved state carried over. None (a cold
        start) when the moved state does not fit its mesh or is not finite."""
        X, Z = moved
        graded = graded_nodes(prm.beta, options.entry, level=options.level)
        # the moved ends are the graded mesh's to rounding: made equal, so that either
        # mesh's nodes lie inside the other's
        if not np.allclose(X[[0, -1]], graded[[0, -1]], rtol=1e-9, atol=1e-9):
            return None
        X[[0, -1]] = graded[[0, -1]]
        on_moved = FoilBearing2D(X, Z, order=options.order)
        if on_moved.n_dofs != restart.u.size:
            return None
        u0, note = continued.predicted(on_moved, case, restart)
        if not np.all(np.isfinite(u0)):
            return None
        planned = continued.planned_nodes(graded, prm, options,
                                          lambda x: on_moved.gap(u0, prm, x))
        Zc = problem_for_width(case, options)
        kept = {"continued": note}
        if continued.similar(X.size, planned.size) and continued.similar(Z.size, Zc.size):
            problem = on_moved
            kept["continued_from"] = (restart.case, restart.u)
        else:
            problem = FoilBearing2D(planned, Zc, order=options.order)
            u0 = on_moved.transfer(u0, prm, problem)
            kept["continued"] = note + ", carried over to the mesh its gap asks for"
        # a solved state carried over: Newton's coupled steps straight away
        problem.direct = True
        return Start(problem, u0, info=continued.start_info(), line=restart.line, kept=kept)

    def safe_start(self, case: Case, prm, options: FE2DOptions) -> Start | None:
        """The starting mesh solved along the continuation that follows the flying film's
        branch (Newton only): from shallow grooves on a grooved roller, from a wide web on a
        smooth one (:mod:`webfem.fem.continuation`); None when it does not converge. The
        driver's check of an answer that rests where it need not (on an 8 mm web on the base
        grooved roller, one level finer, the direct Newton rested the web 2.8 um deep where
        the depth continuation finds it flying at 2.4 um)."""
        if options.method != "newton":
            return None
        # from the smooth 1-D solution, not the periodic cell: a path of its own
        cell, self._cell = self._cell, None
        try:
            start = self.start(case, prm, options, None)
        finally:
            self._cell = cell
        p = start.problem
        if p.grooves is not None:
            u, info = continuation.groove_depth(p, start.u0, prm, options.tol,
                                                options.max_iter, SolveInfo())
        else:
            u, info = continuation.web_width(p, *p.line_start, prm, options.tol,
                                             options.max_iter, SolveInfo())
        if not info.converged:
            return None
        return Start(p, u, info=info.after(start.info), line=start.line, kept=start.kept)

    def remeshed(self, problem, u, prm, X, Z, options):
        """The problem on the nodes X x Z (coarser or finer; the same grooves and domain)
        and ``u`` carried over to it."""
        other = problem.variant(X=X, Z=Z)
        return other, problem.transfer(u, prm, other)

    def mesh_text(self, problem, options) -> str:
        if not problem.web_edges:
            where = "periodic groove cell (land centre to groove centre)"
        elif problem.strip:
            where = (f"edge strip Z = {problem.Z[0]:.4g}-{problem.Z[-1]:.4g} (a land centre "
                     "to the web's edge; scaled), its innermost land and groove weighted")
        else:
            where = f"{'half' if options.symmetry else 'full'} width" + (
                " with its edge lands (a land centred on the web's centreline)"
                if problem.grooves is not None else "")
        return (f"{where}, {len(problem.X) - 1} x {len(problem.Z) - 1} Q{options.order} "
                f"cells; x: {fe1d.line_mesh_text(problem.X, options)}; web: Hermite line")

    def facts(self, case: Case, problem, u, prm, options, readout) -> Facts:
        warnings = ((f"beta = {case.beta:.3g} < 6: the wrap is shorter than the entry and "
                     "exit zones; no uniform central gap exists",) if case.beta < 6.0 else ())
        common = dict(n_cells=int(problem.mesh.nelements), width_cells=len(problem.Z) - 1,
                      land_fraction=case.land_fraction, warnings=warnings)
        if problem.grooves is None:
            return Facts(**common)
        kind = "strip" if problem.strip else "full" if problem.web_edges else "cell"
        why = {}
        if kind == "cell":
            # a cell asked for by name states the edges' estimated effect too
            X = np.linspace(-0.5 * case.beta, 0.5 * case.beta, 201)
            vent = min(max(1.0 - problem.groove_pressure_ratio(u, X), 0.0), 1.0)
            film = 1.0 - readout.contact_share
            why = {"vent": vent, "film": film, "tol": options.edge_tol,
                   "estimate": edge_effect(case.lam, problem.grooves.pitch, vent, film)}
        domain = domain_text(case, kind, problem.grooves, **why,
                             width=(case.lam - problem.Z[0]) if problem.strip else None)
        # the share of the lands' load carried by asperity contact, over the wrap
        pts, wts = readout.pts, readout.wts
        Pl = problem.at(pts, problem.land_average(u))
        Pc = forms.contact_law(problem.gap(u, prm, pts), prm.as_form_args())[0]
        share = float(np.sum(Pc * wts) / max(np.sum((Pl + Pc) * wts), 1e-300))
        sag = sag_warning(case, readout.h_min)
        if sag:
            common["warnings"] = warnings + (sag,)
        return Facts(**common, groove_domain=domain, contact_share_lands=share)

    def film(self, case, problem, u, prm):
        return film_fields(case, problem, u, prm)

    def kept(self, problem):
        build, args, kwargs = problem.recipe()
        return Rebuild(build, *args, **kwargs)

    def state(self, case: Case, problem, u, start: Start, options=None) -> State:
        # the secant's second point: the state this one continued from, while this answer
        # stayed on the same mesh (refinement changes the DOFs' meaning)
        before = start.kept.get("continued_from")
        same = (before is not None and problem.X.size == start.problem.X.size
                and problem.Z.size == start.problem.Z.size)
        return State(case, NAME, problem.X.copy(), np.asarray(u).copy(), problem.Z.copy(),
                     line=start.line,
                     key=continued.mesh_key(options) if options is not None else None,
                     prior=before if same else None)


#: The 2-D model as the driver sees it.
FILM = _Film()


def solve_case(case: Case, options: FE2DOptions, *, initial: Result | None = None,
               raise_on_failure: bool = True) -> Result:
    """The registry's entry: :func:`solve` with a ready options object. On a grooved roller
    with ``grooves = "auto"`` the domain across the width is chosen by what the web's edges
    do (:func:`webfem.models.groove_domain.solve_grooved`)."""
    pattern, _ = groove_domain(case, options)
    FILM.forget_lines()      # the 1-D starts are kept within one solve only
    try:
        if pattern is None or options.grooves != "auto":
            return solve_fe(FILM, case, options, initial, raise_on_failure)
        def solve_domain(o, raising, cell=None):
            FILM._cell = cell
            try:
                return solve_fe(FILM, case, o, initial, raising and raise_on_failure)
            finally:
                FILM._cell = None

        return solve_grooved(case, pattern, options, solve_domain)
    finally:
        FILM.forget_lines()


def solve(case: Case, options: FE2DOptions | None = None, *, initial: Result | None = None,
          raise_on_failure: bool = True, **values) -> Result:
    """Solve one case with the 2-D film and the 1-D web.

    ``options`` (or keywords, see :class:`~webfem.models.options.FE2DOptions`): those of
    the 1-D model plus ``width_fine`` (cell size at the web edges, scaled units; ``level``
    bisects) and ``symmetry`` (True: half width with dP/dZ = 0 at the centreline; False:
    full width). ``initial``: a previous fe2d result at a nearby point (continuation in a
    sweep): on a smooth roller with the same options this point starts from its solved
    state on its mesh, moved to this case, with a secant predictor along the path
    (:mod:`webfem.models.continued`; no 1-D solve), and falls back to the cold start when
    that fails; otherwise its 1-D state starts this point's 1-D solve.
    """
    options = options.replace(**values) if options is not None else \
        FE2DOptions.from_mapping(values)
    return solve_case(case, options, initial=initial, raise_on_failure=raise_on_failure)
