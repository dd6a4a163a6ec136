"""2-D finite elements: Reynolds over the wrap domain with edge leakage, coupled to the 1-D web.

The discrete problem is :class:`webfem.fem.film_problem.FoilBearing2D` (the film on the
tensor product of the web's nodes in X and nodes across the width, Q2 or Q1, with the web's
Hermite beam/membrane; its Newton strategy and the width and depth continuations of
:mod:`webfem.fem.continuation`). This module is the model on the shared driver: the 1-D
(infinitely wide) solution gives the start and the X mesh (on a smooth roller the 2-D solve
on a coarse mesh first refines it where the 2-D film is thin and the mesh misses the 1-D
solution: :meth:`_Film._coarse_first`); :func:`problem_for` builds the problem from the case
and the options.

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
from ..fem.film_problem import DIRECT_STEPS, FoilBearing2D
from ..fem.mesh import graded_nodes
from ..fem.grooves import STRIP_PITCHES, STRIP_SCALED, STRIP_UNVENTED, GroovePattern, \
    choose_domain, edge_effect, graded_groove_nodes, groove_nodes, strip_start, strip_width
from ..fem.outcome import SolveInfo
from ..fem.transfer import width_nodes
from ..result import Rebuild, Result, State
from . import algebraic, continued, fe1d
from ..progress import stage
from .admissible import admissibility
from .driver import REST_CHECKED, Discretisation, Start, solve_fe
from .mesh_error import MAX_DOFS, bisected_nodes, coarser_nodes, kept_nodes
from .refine import FLAT_GAP, adapted_nodes, interpolated_nodes, interpolation_weights
from .fields import film_fields
from .options import FE1DOptions, FE2DOptions
from .outcome import Facts
from .groove_domain import cell_answers, domain_text, edge_error, sag_warning, solve_grooved

__all__ = ["FoilBearing2D", "FILM", "problem_for", "width_nodes_of", "groove_domain", "sag_warning", "solve",
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
    Z = width_nodes_of(case, options, pattern, domain)
    if domain == "strip":
        return FoilBearing2D(X, Z, order=options.order, grooves=pattern, strip=True,
                             ambient_grooves=options.groove_pressure == "ambient",
                             spans=fe1d.spans(case, X))
    return FoilBearing2D(X, Z, order=options.order, grooves=pattern,
                         web_edges=domain != "cell",
                         ambient_grooves=options.groove_pressure == "ambient",
                         spans=fe1d.spans(case, X))


def width_nodes_of(case: Case, options: FE2DOptions, pattern: GroovePattern | None,
                   domain: str) -> np.ndarray:
    """The nodes across the film (scaled) of the ``domain`` :func:`groove_domain` gives:
    the smooth width, the periodic cell (land centre to groove centre), the edge strip or
    the grooved half (or full) width with its edge lands."""
    if pattern is None:
        return problem_for_width(case, options)
    if domain == "cell":
        return groove_nodes(pattern, 0.0, 0.5 * pattern.pitch, options.width_fine,
                            options.level)
    if domain == "strip":
        width = options.strip_width or strip_width(pattern.pitch)
        z_c = strip_start(pattern, case.lam, max(width, STRIP_PITCHES * pattern.pitch))
        return graded_groove_nodes(pattern, z_c, case.lam, [case.lam], options.width_fine,
                                   options.level)
    Z = graded_groove_nodes(pattern, 0.0, case.lam, [case.lam], options.width_fine,
                            options.level)
    return Z if options.symmetry else np.concatenate([-Z[:0:-1], Z])


def problem_for_width(case: Case, options: FE2DOptions) -> np.ndarray:
    """The nodes across a smooth roller's film (scaled): graded towards the web's edge."""
    return width_nodes(case.lam, options.level, half=options.symmetry, fine=options.width_fine)


#: The most solves on the coarse mesh of a cold start (:meth:`_Film._coarse_first`): the
#: first, and the meshes its gap and the next one's ask for.
COARSE_ROUNDS = 3

#: A cold start's first coarse mesh (:func:`_coarse_rounds` with ``planning``) is solved to
#: this times its first residual (Newton's direct steps): enough to read where its gap asks
#: for finer cells; only where the rule keeps that mesh is it solved on to the tolerance.
#: Why: on the base case at 20 m/s it (2,199 unknowns) took 2.2e3 -> 5.1e-4 in three steps
#: and 2.4e-8 and 7.7e-12 in two more (a factorisation and a chord step, 5.5 ms), then was
#: refined, its state only the next mesh's start. Not on the later meshes, which the rule
#: mostly keeps: solved on from a looser state, Newton starts without the factorisation
#: its chord steps would reuse (the second mesh's 1.2e-7 took a factorisation to 4e-12).
PLANNING_RTOL = 1e-6

#: A cold start's coarse mesh (the 1-D start's nodes, every other one) has its cells bisected
#: where what it misses of the 1-D solution, the web's Hermite interpolant relative to the
#: gap plus the film pressure's interpolant, times the cell's length
#: (:func:`webfem.models.refine.interpolation_weights`), exceeds this times ``error_tol``
#: (:meth:`_Film._coarse_first`). Why: the base case at 20 m/s with the web held through
#: spans stated 1.3e-3 (h_min) on its 10,105 unknowns, and its estimate bisected every cell
#: along x (20,185). That change came from the cells 0.6-3 units past the outlet edge, where
#: the film pressure falls from its exit peak into a sub-ambient dip (-4 T/R) and recovers:
#: coarsening only the cells 1.6-3 units past the edge changed h_min by 1.1e-3 (only those
#: at 0.6-1 and 1-1.6 units: 2.5e-4 and 4.7e-4), only the 54 from the inlet edge to 3 units
#: before the outlet by 1e-6. The spans only moved the minimum 0.04 units downstream, off
#: a node of the coarser mesh, where those parts had cancelled (held at the zones' ends:
#: 6.8e-4). Those cells hold the five largest weights (0.65-2.5 units past the edge, 83 % of
#: their sum); bisected before the coarse solve, the estimate states 1.2e-4 on 10,777
#: unknowns, without a bisection round (its Richardson error: 1.2e-5). Q2 only: Q1's pressure
#: misfits are of lower order, and on the base case the rule added cells (105,327 unknowns
#: in the end against 79,759) without sparing any of the five bisection rounds Q1 takes.
LINE_MISFIT = 2.0

#: The thin-film rule's cells where the web lies flat on its asperities are this many times
#: longer (:func:`webfem.models.refine.adapted_nodes`' ``flat``; the driver's rounds, the
#: coarse mesh's planning, the fine start's check and a continued point's plan): the mesh
#: error estimate decides there. Why: below 5 m/s the base case's web rests over the whole
#: wrap on a uniform film (gap 1.09-1.25 sigma) and the film's reaction length bisected all
#: of it, 22,177 unknowns at 0.5 m/s where 13,089 state 1.1e-5 in h_min
#: (docs/performance_log.md, 'lowspeed10'). Only where it is flat: at 4 everywhere the 1 mm
#: board held at the zones' ends, pressed into its asperities over a short band, answered
#: 10 % away with a 0.55 % stated error its estimate could not confirm.
FLAT_RATIO = 4.0

#: A continued point judges a cell flat while its gap changes by less than this many times
#: :data:`webfem.models.refine.FLAT_GAP` (0.5 sigma; a cold solve: 0.01 sigma): a
#: hysteresis. A continued mesh's cells all met the rule at the previous point, so only
#: the cells left long there are concerned. Why: along a sweep the web lifts from the
#: entry on and the set of flat cells moves with the speed; with the cold bound the long
#: cells the lifting front had just reached asked the coarser mesh to be bisected at every
#: point from 1.9 to 10.5 m/s (9-10 Newton steps instead of 7; the 24-point sweep 193 ->
#: 209 iterations; with this factor at 4: 207, 10: 213, 16: 196, 25: 192, 50 and 100: 185,
#: the mesh then kept from 1.9 to 10.5 m/s). The mesh error estimate still decides: there
#: its stated errors are 3-15x Richardson's (``benchmarks/low_speed_meshes.py``'s).
FLAT_KEPT = 50.0

#: A continued point's coarser mesh is bisected where it misses the predicted state by
#: :data:`LINE_MISFIT` (as a cold start's, :func:`_misfit_kept`) only once some cell misses
#: it by this many times that: a hysteresis, as :data:`FLAT_KEPT`'s. Why: along the base
#: case's 24-point speed sweep the mesh planned at 12.8 m/s (9,001 unknowns) was kept to
#: 22.6 m/s, where the exit's sub-ambient pressure dip (1-1.5 units past the wrap edge) had
#: moved off its cells: the estimate refused it (h_min 1.02e-3 against 1e-3) and bisected
#: every cell along x (17,977 unknowns; 11 Newton steps, 7 factorisations, about 0.4 s of
#: the sweep's 3.4 s CPU). The largest cell weight there was 29 times the cold bound, at
#: the points before it at most 9.2 (18.7 m/s, stated 3.1e-4), on the meshes planned
#: afresh at 27.3 and 33.1 m/s 42 and 21 times. At 15 the cells at 22.6 m/s are bisected
#: before the solve (10,201 unknowns, stated at most 4.0e-4, 5 steps), and the planned meshes at
#: 27.3 and 33.1 m/s gain 8-9 cells along x (docs/performance_log.md, 'sweep38').
MISFIT_KEPT = 15.0

#: How many cold 1-D starts :class:`_Film` keeps (a case's direct start, on the 1-D starting
#: mesh where the mesh is decided up front, the refined one of its safe start, and its
#: finer-mesh remedy's).
LINES_KEPT = 3

#: The residual tolerance of the 1-D solve that starts a cold smooth-roller 2-D solve whose
#: mesh is decided up front (:meth:`_Film._coarse_first`): the 2-D solve's 1e-9. Looser
#: (1e-6) saved the last 1-D step on the base case (16 -> 15 iterations, the same mesh) but
#: made board idlers of the envelope benchmark 1.3-1.5x slower (#38: 3.7 -> 5.2 s CPU, the
#: same answer mesh). Why: their direct 1-D Newton fails, and the 1-D problem keeps one
#: Eshel-Elrod continuation path, keyed by its tolerance (:meth:`webfem.models.line.
#: FoilBearing1D.solve_continued`); at 1e-9 this start and the safe start that checks the
#: resting 2-D answer both reuse the path auto's fe1d solve ran, at 1e-6 this start runs
#: its own and evicts that one, so the check runs it again (#38 under auto: 563 -> 1,343
#: factorisations). At 1e-2 the misfit rule bisected other cells (10,777 -> 11,161
#: unknowns).
LINE_START_TOL = 1e-9


def _coarse_rounds(case: Case, prm, options: FE2DOptions, coarse: FoilBearing2D, u0, what,
                   planning: bool = False, flat_gap: float = FLAT_GAP,
                   balanced: bool = False):
    """The coarse mesh solved from ``u0`` and bisected where its own 2-D gap asks for cells
    half as fine as the thin-film rule's (:func:`continued.planned_nodes` with
    ``coarser=2``), then solved again, until the rule asks for nothing more
    (:data:`COARSE_ROUNDS` at most). ``what`` names the stage. ``planning``: the first
    mesh is likely to be refined (a cold start's, from the 1-D solution, whose gap is
    thicker than the 2-D film's): it is solved to :data:`PLANNING_RTOL` only, and on to the
    tolerance where the rule keeps it. ``flat_gap``: the rule's bound on a flat cell's gap
    change (a continued point's, :data:`FLAT_KEPT`). ``balanced``: each coarse mesh's
    Newton stops where its algebraic error is negligible (:mod:`webfem.models.algebraic`;
    the estimate's change from it then states that error too). Returns ``(coarse, state, info)``, or
    None where a solve fails or ends inadmissible, or the rounds run out."""
    info = None
    for rounds in range(COARSE_ROUNDS):
        if balanced:
            coarse.accept = algebraic.acceptor(case, prm, coarse, options)
        with stage(f"{NAME} newton on {what}, {coarse.n_dofs:,} unknowns"):
            uc, step = coarse.plain_newton(u0, prm, options.tol, options.max_iter,
                                           DIRECT_STEPS,
                                           rtol=PLANNING_RTOL if planning and rounds == 0
                                           else 0.0)
        info = step if info is None else step.after(info)
        if not info.converged or admissibility(case, coarse, uc, prm):
            return None
        X = continued.planned_nodes(coarse.X, prm, options,
                                    lambda x, p=coarse, v=uc: p.gap(v, prm, x), coarser=2,
                                    flat=FLAT_RATIO, flat_gap=flat_gap)
        if X.size == coarse.X.size:
            if step.residual > options.tol and step.algebraic is None:
                # the mesh stays: its state is the estimate's, solved to the tolerance
                with stage(f"{NAME} newton on {what}, {coarse.n_dofs:,} unknowns"):
                    uc, step = coarse.plain_newton(uc, prm, options.tol, options.max_iter,
                                                   DIRECT_STEPS)
                info = step.after(info)
                if not info.converged or admissibility(case, coarse, uc, prm):
                    return None
            return coarse, uc, info
        finer = coarse.variant(X=X)
        u0, coarse = coarse.transfer(uc, prm, finer), finer
    return None


def _fine_start(case: Case, prm, options: FE2DOptions, coarse, uc, info, fine, detail,
                flat_gap: float = FLAT_GAP, balanced: bool = False, minus=None):
    """The fine start of a two-grid start: the coarse state ``uc`` (solved on ``coarse``,
    the coarser mesh of ``fine``, or a refinement of it) carried to ``fine`` (that refinement
    bisected, where it is one) plus ``detail`` (what the coarse mesh does not carry, on
    ``fine``). Where the thin-film rule asks the fine start to bisect cells (the driver's
    refinement round, :func:`webfem.models.refine.adapted_nodes`, on the fine start's gap
    instead of the fine answer's), the coarse cells that hold them are bisected and the
    coarse mesh solved again from its state first (:func:`_coarse_rounds`), up to
    :data:`COARSE_ROUNDS` times: the mesh decided before the fine solve. Why: the coarse
    rule at cells twice as long reads the gap at the coarse nodes only; where the fine gap
    dips between them, the driver refined the fine answer (1-2 fine steps, a new fine
    factorisation) and the estimate solved its new coarser mesh again (4-5 steps): 13 of
    the 24-point sweep's 195 iterations at 8.7 m/s, 15 and 19 at 10 and 25 m/s of the
    traction-loss scan. ``flat_gap`` and ``balanced`` as :func:`_coarse_rounds`'.
    ``minus``: ``(problem, state)`` whose state carried to ``fine`` is part of ``detail``
    with a minus sign (the two-grid start's coarse start, :meth:`_Film._two_grid`): while
    ``coarse`` is that problem and ``fine`` unchanged, the two coarse states are carried
    over as their difference, one transfer instead of two (the transfers are linear: the
    same start to rounding; the base case's 24-point speed sweep 88 -> 66 transfers, the
    same meshes, iterations and factorisations). Returns ``(fine, state, info, (coarse, state))``, or None (a fine
    mesh that is not the coarse one bisected)."""
    e = 0.5 * prm.beta
    found = None
    for rounds in range(COARSE_ROUNDS + 1):
        if not np.array_equal(coarser_nodes(fine.X, (-e, e)), coarse.X):
            other = coarse.variant(X=bisected_nodes(coarse.X), Z=fine.Z)
            if not np.array_equal(coarser_nodes(other.X, (-e, e)), coarse.X):
                return found
            detail, minus = _less(detail, minus, prm, fine), None
            detail, fine = fine.transfer(detail, prm, other), other
        if minus is not None and coarse is minus[0]:
            u1 = coarse.transfer(uc - minus[1], prm, fine) + detail
        else:
            detail, minus = _less(detail, minus, prm, fine), None
            u1 = coarse.transfer(uc, prm, fine) + detail
        u1[fine.fixed] = 0.0
        if not np.all(np.isfinite(u1)):
            return found
        found = fine, u1, info, (coarse, uc)
        if rounds == COARSE_ROUNDS:
            return found
        X = adapted_nodes(fine, u1, prm, options.adapt_ratio, options.min_cell,
                          flat=FLAT_RATIO, flat_gap=flat_gap) \
            if options.adapt and options.mesh is None and options.nodes is None else None
        if X is None or fine.n_dofs * X.size / fine.X.size > MAX_DOFS:
            return found
        marked = np.setdiff1d(X, fine.X)
        cells = np.unique(np.clip(np.searchsorted(coarse.X, marked) - 1, 0, coarse.X.size - 2))
        finer = coarse.variant(X=np.sort(np.concatenate(
            [coarse.X, 0.5 * (coarse.X[cells] + coarse.X[cells + 1])])))
        settled = _coarse_rounds(case, prm, options, finer, coarse.transfer(uc, prm, finer),
                                 "the coarser mesh where the fine start's gap asks",
                                 flat_gap=flat_gap, balanced=balanced)
        if settled is None:
            return found
        coarse, uc, step = settled
        info = step.after(info)
    return found


def _misfit_kept(Xc, fine, u0, prm, options: FE2DOptions) -> np.ndarray:
    """A continued point's coarser mesh ``Xc`` (every other node of ``fine``), its cells
    bisected as a cold start's where the mesh misses the predicted state ``u0`` (on
    ``fine``) by the cold rule's :data:`LINE_MISFIT` (:func:`webfem.models.refine.
    interpolated_nodes`), but only once some cell misses it by :data:`MISFIT_KEPT` times
    that: a hysteresis, as :data:`FLAT_KEPT`'s, so that a mesh is kept along a sweep until
    it plainly misses the state. ``Xc`` itself otherwise."""
    gap = lambda x: fine.gap(u0, prm, x)
    pressure = lambda x: fine.pressure(u0, x)
    limit = LINE_MISFIT * options.error_tol
    with np.errstate(all="ignore"):
        w = interpolation_weights(Xc, gap, pressure, prm, options.order)
        if not np.max(w, initial=0.0) > MISFIT_KEPT * limit:
            return Xc
        return interpolated_nodes(Xc, gap, pressure, prm, limit, 2.0 * options.min_cell,
                                  options.order)


def _less(detail, minus, prm, fine):
    """``detail`` less ``minus``'s state carried to ``fine`` (:func:`_fine_start`); ``detail``
    itself where ``minus`` is None."""
    return detail if minus is None else detail - minus[0].transfer(minus[1], prm, fine)


#: The most unknowns of the edge strip's start on the periodic cell's own x mesh
#: (:func:`_cell_on_mesh`): half the estimate's cap, so that its first bisection along x
#: still fits.
CELL_MESH_DOFS = 0.5 * MAX_DOFS


def _cell_on_mesh(case: Case, prm, options: FE2DOptions, cell, u, problem):
    """The edge strip's start: the periodic cell solved on the strip's x nodes from its
    answer carried over (plain Newton: the same film on another mesh), so that the web the
    strip starts from is a discrete solution there. First on ``problem``'s x nodes (the 1-D
    start's) with the cell's refinement replayed on them (:func:`_replayed_nodes`: the
    strip's x mesh planned on the cell; ``problem`` moved to them), then on those nodes
    alone; where the cell does not converge there, on the cell answer's own x nodes
    coarsened (every other node, the wrap edges kept) until the strip has at most
    :data:`CELL_MESH_DOFS` unknowns, with ``problem`` moved to them. Returns ``(problem,
    cell problem, cell state, replayed)`` (``replayed``: on the replayed nodes, not a
    fallback), or None (neither converged or both are inadmissible: the
    cell's answer itself starts ``problem``).

    Why: a PET strip started on the 93 x cells of the 1-D start from the cell's answer on
    10,544 did not converge, and the depth continuation that followed took 200+ s on its
    81,455 unknowns; from the cell solved on its coarsened x mesh (3,351 unknowns) the
    strip's 93,131 converged directly. The 1-D start's x nodes come first: a foil strip on
    the cell's (coarsened) x nodes solved 150,841 unknowns where it had solved 95,161, for
    the same answer to 1e-11."""
    e = 0.5 * prm.beta
    per_node = problem.n_dofs / problem.X.size
    X = cell.X
    while X is not None and X.size * per_node > CELL_MESH_DOFS:
        X = coarser_nodes(X, (-e, e))
    planned = _replayed_nodes(problem.X, cell.X, per_node, options.adapt)
    tried = ([planned] if planned.size > problem.X.size else []) + [problem.X] + (
        [X] if X is not None and X.size > problem.X.size else [])
    for X in tried:
        on = cell if np.array_equal(X, cell.X) else cell.variant(X=X)
        uc = u
        if on is not cell:
            with stage(f"{NAME} the periodic cell on the strip's x mesh, {on.n_dofs:,} "
                       "unknowns"):
                uc, info = on.plain_newton(cell.transfer(u, prm, on), prm, options.tol,
                                           options.max_iter, DIRECT_STEPS)
            if not info.converged or admissibility(case, on, uc, prm):
                continue
        moved = problem if np.array_equal(X, problem.X) else problem.variant(X=X)
        return moved, on, uc, X is planned      # in ``tried`` only where it is finer
    return None


def _replayed_nodes(X0: np.ndarray, Xc: np.ndarray, per_node: float,
                    rounds: int) -> np.ndarray:
    """The strip's x nodes planned on the periodic cell's answer: ``X0`` (the 1-D start's,
    from which the cell's mesh ``Xc`` was refined) with its cells bisected where the cell's
    were, one bisection a round, up to ``rounds`` (``options.adapt``) and while the strip,
    ``per_node`` unknowns an x node, stays within :data:`MAX_DOFS` (the driver's cap on its
    rounds). ``Xc`` itself where it all fits.

    Why: the rule where the film is thin (:func:`webfem.models.refine.adapted_nodes`)
    reads the web's gap, and a strip's web (its width average dominated by the periodic
    interior) is the cell's: on envelope #115 (a 0.61 m PET strip) the strip's own rounds
    bisected its x cells 81,455 -> 105,919 -> 143,727 -> 195,435 unknowns, the ratios of
    the cell's rounds (1.30, 1.36, 1.36), and on #67 (a board strip) 139,987 -> 162,163 ->
    198,199 as the cell's 3,031 -> 3,511 -> 4,291: each round a Newton solve of the strip
    (10-17 s CPU). The strip's own rounds are then not made (its mesh error estimate checks
    the mesh): on #67 one would have added 8,316 unknowns for another 0.2 M-unknown solve.

    >>> _replayed_nodes(np.array([0.0, 1.0, 2.0]), np.array([0.0, 0.25, 0.5, 1.0, 2.0]),
    ...                 1.0, 6).tolist()
    [0.0, 0.25, 0.5, 1.0, 2.0]
    >>> _replayed_nodes(np.array([0.0, 1.0, 2.0]), np.array([0.0, 0.25, 0.5, 1.0, 2.0]),
    ...                 1.0, 1).tolist()
    [0.0, 0.5, 1.0, 2.0]
    """
    X = np.asarray(X0, float)
    Xc = np.asarray(Xc, float)
    for _ in range(rounds):
        mids = 0.5 * (X[1:] + X[:-1])
        at = np.clip(np.searchsorted(Xc, mids), 0, Xc.size - 1)
        near = np.minimum(np.abs(Xc[at] - mids), np.abs(Xc[np.maximum(at - 1, 0)] - mids))
        mark = near <= 1e-9 * np.diff(X)
        if not mark.any() or (X.size + mark.sum()) * per_node > MAX_DOFS:
            break
        X = np.sort(np.concatenate([X, mids[mark]]))
    return X


def _coarse_full_width(case: Case, prm, options: FE2DOptions, problem, u0):
    """The grooved full width's start ``u0`` (the periodic cell's web) solved first on
    ``problem``'s mesh coarsened along x and across the width (every other node, the wrap
    edges and the land/groove edges kept), and carried back. Returns ``(u0, info)`` or None
    (no coarser mesh, or its solve failed or ended inadmissible: ``u0`` itself starts).

    Why: the web's edges vent the film, so the full width's web sits below the cell's and
    Newton from the cell's web is damped all the way down; those steps cost a quarter as
    much on the coarser mesh. A 3.1 cm PET web (envelope #147): 33 damped steps on 27,247
    unknowns (3.4-3.7 s) became 33 on 7,251 and 7 on 27,247 (1.5 s), the same answer to
    1e-12; it did not help to solve the cell on the full width's x nodes first (as the strip
    does, :func:`_cell_on_mesh`): still 35 damped steps."""
    keep_x, keep_z = kept_nodes(problem, prm)
    Xc, Zc = coarser_nodes(problem.X, keep_x), coarser_nodes(problem.Z, keep_z)
    if Xc is None or Zc is None:
        return None
    coarse = problem.variant(X=Xc, Z=Zc)
    with stage(f"{NAME} newton on the full width coarsened first, {coarse.n_dofs:,} "
               "unknowns"):
        uc, info = coarse.plain_newton(problem.transfer(u0, prm, coarse), prm, options.tol,
                                       options.max_iter)
    if not info.converged or admissibility(case, coarse, uc, prm):
        return None
    return coarse.transfer(uc, prm, problem), info


def _decides_up_front(case: Case, options: FE2DOptions) -> bool:
    """Whether a cold start decides its mesh by a 2-D solve on a coarse mesh first
    (:meth:`_Film._coarse_first`): Newton with the mesh error estimate on, on a smooth
    roller and webfem's graded mesh."""
    return (options.method == "newton" and options.estimate and options.mesh is None
            and options.nodes is None and not case.grooved)


class _Film(Discretisation):
    """The 2-D model's part of the shared driver: the 1-D (infinitely wide) solution gives
    the start and the X mesh, already refined where the film is thin."""

    name = NAME
    flat_ratio = FLAT_RATIO

    def __init__(self):
        #: the cold 1-D starts of the solve under way, by case and 1-D options (bounded)
        self._lines: dict = {}
        #: the periodic cell's answer of the grooved solve under way (``grooves = "auto"``):
        #: its web starts the strip's or the full width's Newton (:meth:`start`)
        self.cell: Result | None = None

    def _line(self, smooth: Case, options: FE1DOptions, line: State | None) -> fe1d.LineStart:
        """The 1-D solution that starts the 2-D solve (:func:`webfem.models.fe1d.
        solve_start`: its state, without a result). A cold one is kept for the same case
        and options: the driver's safe start and its check of a resting answer start from
        the same 1-D solve as the direct start (a stiff board's took 5-10 s, each time), and
        it is deterministic, so the kept one is the one a new solve would give."""
        if line is not None:
            return fe1d.solve_start(smooth, options, initial=line)
        key = (smooth, options)
        one = self._lines.get(key)
        if one is None:
            one = fe1d.solve_start(smooth, options)
            if len(self._lines) >= LINES_KEPT:
                self._lines.clear()
            self._lines[key] = one
        return one

    def forget_lines(self) -> None:
        """Drop the kept 1-D starts (:meth:`_line`) and depth continuations
        (:func:`webfem.fem.continuation.groove_depth`): a solve starts and ends without them,
        so what one solve reports (its stages, the 1-D start's work) never depends on an
        earlier one."""
        self._lines.clear()
        self.cell = None
        continuation.forget_depth_paths()

    def start(self, case: Case, prm, options: FE2DOptions, restart: State | None,
              informed: bool = True) -> Start:
        """The start of a solve: continued from ``restart`` (:meth:`_continued`), else cold
        from the 1-D solution. With ``informed`` (not the safe start): on a smooth roller
        the mesh decided by a 2-D solve on the coarser mesh first (:meth:`_coarse_first`,
        from the 1-D solution on its starting mesh, not refined where the 1-D film is
        thin: the 2-D film is thinner, and the coarse solve's gap refines the mesh);
        on a grooved one's strip or full width, the web of the periodic cell's answer when
        the solve under way has one (:attr:`cell`: 10 -> 4 coupled Newton steps on a 1.27 mm
        pitch's full width, the same answer to Newton's tolerance)."""
        moved = continued.continued_state(case, options, restart)
        if moved is not None:
            start = self._continued(case, prm, options, moved, restart)
            if start is not None:
                return start
        smooth = case.updated({"roller.groove_width": 0.0}) if case.grooved else case
        line = restart.line if restart is not None and restart.model == NAME else None
        line_options = FE2DOptions.line_options(options)
        if informed and _decides_up_front(case, options):
            # the 1-D solution on its starting mesh: the 2-D coarse solve's gap decides where
            # the film is thin (:meth:`_coarse_first`), not the 1-D's, which is thicker
            one = self._line(smooth, line_options.replace(adapt=0, tol=LINE_START_TOL), line)
            spent = SolveInfo(converged=True, iterations=one.iterations)
            first = self._coarse_first(case, prm, options, one.problem, one.state)
            if first is not None:
                fine, u0, coarse_info, kept = first
                return Start(fine, u0, info=coarse_info.after(spent), line=one.restart,
                             kept={"line_start": one, **kept})
        one = self._line(smooth, line_options, line)
        p1, u1 = one.problem, one.state
        spent = SolveInfo(converged=True, iterations=one.iterations)
        problem = problem_for(case, options, p1.X)
        problem.line_start = (p1, u1)
        # on a smooth roller the 1-D solution is close enough for the coupled Newton; a
        # grooved film is not (the direct steps failed on the grooved cases: 0.27 -> 0.35 s)
        problem.direct = problem.grooves is None
        u0 = problem.start_from_line(p1, u1, prm)
        kept = {"line_start": one}
        if informed and self.cell is not None and problem.grooves is not None \
                and problem.web_edges and self.cell.case == case:
            # the cell's web (its film pressure is made consistent with it before the
            # coupled steps: ``direct`` stays False), solved on the x mesh of the start
            cell_p, cell_u = self.cell.state("problem"), self.cell.state("state")
            x_nodes = problem.X
            laid = _cell_on_mesh(case, prm, options, cell_p, cell_u, problem) \
                if problem.strip else None
            if laid is not None:
                problem, cell_p, cell_u, replayed = laid
                problem.line_start, problem.direct = (p1, u1), False
                u0 = problem.start_from_line(p1, u1, prm)
            web = problem.start_from_line(cell_p, cell_u, prm, pressure=False)
            u0[problem.nP:] = web[problem.nP:]
            kept["cell_web"] = "the web of the periodic cell's answer" + (
                ", solved on this x mesh" if laid is not None else "")
            # only the replayed mesh stands for the strip's rounds, not a fallback's
            planned = laid is not None and replayed and problem.X.size > x_nodes.size
            if planned and options.estimate:
                # the cell's refinement rounds stand for the strip's (:func:`_replayed_nodes`):
                # not made again on the strip, whose mesh error estimate checks the mesh
                problem.planned = True
                kept["cell_web"] += (", on the x mesh the cell's refinement rounds asked "
                                     "for")
            # the full width solved on its mesh coarsened first; not a strip: on its planned
            # mesh the fine Newton from the coarsened strip's answer took as many steps as
            # from the cell's web (envelope #67: 4; #115 more; 4-5 s CPU each at 0.2 M
            # unknowns; env38)
            first = None if problem.strip else _coarse_full_width(case, prm, options,
                                                                  problem, u0)
            if first is not None:
                # a solved state carried over: the coupled steps straight away
                u0, coarse_info = first
                problem.direct = True
                spent = coarse_info.after(spent)
                kept["cell_web"] += ", the full width solved from it on a coarser mesh first"
            # not checked against the safe start again: a strip from the cell's web (its
            # edges lower the gap: a board strip 3.8 nm deep where the cell flies at 0.11
            # um; the check re-solved its 0.14 M unknowns along the depth continuation for
            # 100-180 s and kept the direct answer), and a full width from a cell that
            # rests and whose own safe start rests as low or lower (the web's edges only
            # vent the film; #55, #143: the check took 11-33 s of 17-45 and kept the answer)
            checked = problem.strip
            if self.cell.state(REST_CHECKED) and self.cell["h_min"] < 0.0:
                kept[REST_CHECKED] = "the periodic cell's answer rests too, checked"
                checked = True
            return Start(problem, u0, info=spent, line=one.restart, kept=kept,
                         checked=checked)
        return Start(problem, u0, info=spent, line=one.restart, kept=kept)

    def _coarse_first(self, case: Case, prm, options: FE2DOptions, p1, u1):
        """The mesh decided before the 2-D solve on it (a cold start on a smooth roller with
        the mesh error estimate on). The 2-D problem is solved first on a coarse mesh,
        cheap at a quarter of the unknowns: every other node of the 1-D mesh and of the
        width's (:func:`webfem.models.mesh_error.coarser_nodes`), bisected where its 2-D
        gap asks for cells half as fine as the thin-film rule's (:func:`continued.
        planned_nodes` with ``coarser=2``) and solved again from its state, until the rule
        asks for nothing more (:data:`COARSE_ROUNDS` at most). The answer's mesh is that
        mesh with every cell bisected (it meets the rule for the coarse gap; the driver's
        rounds still check it against its own), started from the coarse state carried
        over; its coarser mesh is the coarse one, whose solved state the estimate reuses
        (``kept["coarse"]``). Before the coarse solve, the coarse cells where the mesh misses
        the 1-D solution (``p1``, ``u1``: on the 1-D starting mesh, not refined, the 2-D
        gap being thinner than the 1-D's decides that) are bisected (:data:`LINE_MISFIT`;
        Q2 elements): the mesh the estimate would otherwise have bisected after the fine
        solve, decided up front. Returns ``(problem, u0, info, kept)`` or None (the direct
        start on the 1-D mesh: a coarse solve failed or ended inadmissible)."""
        if not _decides_up_front(case, options):
            return None
        e = 0.5 * prm.beta
        Z = problem_for_width(case, options)
        Xc, Zc = coarser_nodes(p1.X, (-e, e)), coarser_nodes(Z)
        if Xc is None or Zc is None:
            return None
        if options.adapt and options.order == 2:
            # the mesh the 1-D solution asks for, decided before any 2-D solve
            Xc = interpolated_nodes(Xc, lambda x: p1.gap(u1, prm, x),
                                    lambda x: p1.pressure(u1, x), prm,
                                    LINE_MISFIT * options.error_tol, 2.0 * options.min_cell,
                                    options.order)
        coarse = FoilBearing2D(Xc, Zc, order=options.order, spans=fe1d.spans(case, Xc))
        coarse.line_start, coarse.direct = (p1, u1), True
        settled = _coarse_rounds(case, prm, options, coarse,
                                 coarse.start_from_line(p1, u1, prm), "a coarse mesh first",
                                 planning=True, balanced=True)
        if settled is None:
            return None
        coarse, uc, info = settled
        fine = coarse.variant(X=bisected_nodes(coarse.X), Z=Z)
        if not np.array_equal(coarser_nodes(fine.X, (-e, e)), coarse.X) or \
                not np.array_equal(coarser_nodes(fine.Z), coarse.Z):
            return None
        first = _fine_start(case, prm, options, coarse, uc, info, fine, np.zeros(fine.n_dofs),
                            balanced=True)
        if first is None:
            return None
        fine, u, info, solved = first
        # stopped where its algebraic error is negligible against the stated one, as a
        # continued point's (the cold base case: 20 -> 16 iterations)
        fine.accept = algebraic.acceptor(case, prm, fine, options)
        return fine, u, info, {"coarse": solved}

    def _continued(self, case: Case, prm, options: FE2DOptions, moved, restart: State):
        """The start from the previous point (:func:`continued.continued_state`), without a
        1-D solve: on the previous point's mesh moved to this case while it has about as
        many nodes as the mesh this case's predicted gap asks for (:func:`continued.
        planned_nodes`, within :data:`continued.MESH_SLACK`: along a sweep the meshes
        drift, and the previous point's may be twice as fine where its estimate bisected
        it) or, where the previous point's error estimate refined its mesh (``State.
        refined``, kept while the mesh is), while the step is short (:func:`continued.near`:
        the mesh this case's gap asks for is then likely to be refined again) or while the
        mesh this case's gap asks for is about the one that estimate refused
        (:func:`continued.refused_again`), else on that
        planned mesh with the moved state carried over. None (a cold
        start) when the moved state does not fit its mesh or is not finite."""
        X, Z = moved
        graded = graded_nodes(prm.beta, options.entry, level=options.level)
        # the moved ends are the graded mesh's to rounding: made equal, so that either
        # mesh's nodes lie inside the other's
        if not np.allclose(X[[0, -1]], graded[[0, -1]], rtol=1e-9, atol=1e-9):
            return None
        X[[0, -1]] = graded[[0, -1]]
        on_moved = FoilBearing2D(X, Z, order=options.order, spans=fe1d.spans(case, X))
        if on_moved.n_dofs != restart.u.size:
            return None
        u0, note = continued.predicted(on_moved, case, restart)
        if not np.all(np.isfinite(u0)):
            return None
        planned = continued.planned_nodes(graded, prm, options,
                                          lambda x: on_moved.gap(u0, prm, x), flat=FLAT_RATIO)
        Zc = problem_for_width(case, options)
        kept = {"continued": note}
        info = continued.start_info()
        if (continued.similar(X.size, planned.size) and continued.similar(Z.size, Zc.size)) \
                or (restart.refined and continued.near(restart.case, case)) \
                or continued.refused_again(restart, planned):
            problem = on_moved
            kept["kept_refined"] = restart.refined
            kept["continued_from"] = (restart.case, restart.u)
            if restart.prior is not None and restart.prior[1].shape == restart.u.shape:
                kept["continued_from2"] = restart.prior
        else:
            problem = FoilBearing2D(planned, Zc, order=options.order,
                                    spans=fe1d.spans(case, planned))
            u0 = on_moved.transfer(u0, prm, problem)
            kept["continued"] = note + ", carried over to the mesh its gap asks for"
            # the previous state carried over too: the next point's secant (from the
            # previous state alone, the points after a change of mesh took 9-10 steps)
            kept["continued_from"] = (restart.case, on_moved.transfer(restart.u, prm, problem))
        two = self._two_grid(case, prm, options, problem, u0, restart, on_moved)
        if two is not None:
            if two[0] is not problem:
                kept["continued"] += (", refined where its coarser mesh's gap or the "
                                      "predicted state asks")
                kept.pop("continued_from2", None)
                before = kept.pop("continued_from", None)
                if before is not None:
                    kept["continued_from"] = (before[0],
                                              problem.transfer(before[1], prm, two[0]))
            problem, u0, info, kept["coarse"] = two
            kept["continued"] += ", corrected by its coarser mesh solved first"
        # a solved state carried over: Newton's coupled steps straight away
        problem.direct = True
        # stopped where its algebraic error is negligible against the stated one
        problem.accept = algebraic.acceptor(case, prm, problem, options)
        # the driver's rounds judge flat cells as the start did (:data:`FLAT_KEPT`)
        problem.flat_gap = FLAT_KEPT * FLAT_GAP
        return Start(problem, u0, info=info, line=restart.line, kept=kept)

    def _two_grid(self, case: Case, prm, options: FE2DOptions, fine, u0, restart: State,
                  moved):
        """The two-grid start of a continued point on ``fine`` (the previous point's mesh
        ``moved``, or the mesh its predicted gap asks for), from the predicted state
        ``u0``: the coarser mesh (the error estimate's) solved first, from the prediction
        carried to it plus the previous point's coarse-minus-fine difference there; then the
        fine start is that solution carried back plus what the coarse mesh does not carry of
        the prediction (the previous point's fine-minus-coarse difference plus the predicted
        change's fine part: :func:`_fine_start`). Measured on the base case's 24-point speed
        sweep: the fine Newton from 4-5 steps (2-3 factorisations) to 3 (one factorisation
        and two chord steps) with the previous point's difference alone, 2-3 with the
        predicted change's fine part, and the estimate's coarse solve is the one made here
        (none left). Returns ``(u0, info,
        (coarse, state))`` or None (no coarse state kept, a coarse solve that fails or ends
        inadmissible: the fine start alone). Where the coarse solution's gap asks for a finer
        mesh (the thin-film rule at cells twice as long, :func:`continued.planned_nodes`),
        the coarse mesh is refined and solved again and the fine mesh is that one bisected
        (the mesh decided before the fine solve, as a cold start's: on the sweep, two points
        whose fine solve had the driver refine and solve again). Before the coarse solve,
        the coarser mesh's cells that miss the predicted state are bisected once some cell
        misses it plainly (:func:`_misfit_kept`, :data:`MISFIT_KEPT`). Returns ``(fine, u0,
        info, (coarse, state))``."""
        kept = restart.coarse
        if kept is None or options.method != "newton" or not options.estimate:
            return None
        Xp, Zp, up = kept
        e0, e = 0.5 * restart.case.beta, 0.5 * prm.beta
        Xc, Zc = coarser_nodes(fine.X, (-e, e)), coarser_nodes(fine.Z)
        if Xc is None or Zc is None:
            return None
        if options.adapt and options.order == 2:
            Xc = _misfit_kept(Xc, fine, u0, prm, options)
        coarse = fine.variant(X=Xc, Z=Zc)
        # the previous point's two states on the moved meshes (the DOFs keep their meaning:
        # values and slopes at the same nodes), carried to this point's meshes if others
        before = restart.u.copy()
        before[moved.fixed] = 0.0
        Xo = continued.moved_nodes(Xp, 2.0 * e0, 2.0 * e)
        Zo = Zp * (case.lam / restart.case.lam)
        if not np.allclose(Xo[[0, -1]], moved.X[[0, -1]], rtol=1e-9, atol=1e-9):
            return None
        Xo[[0, -1]] = moved.X[[0, -1]]          # the ends to rounding, as :meth:`_continued`
        if Xo.size == Xc.size and Zo.size == Zc.size and np.allclose(Xo, Xc, rtol=1e-12, atol=1e-12) \
                and np.allclose(Zo, Zc, rtol=1e-12, atol=1e-12):
            if coarse.n_dofs != up.size:        # the previous coarse mesh, moved
                return None
        else:
            old = moved.variant(X=Xo, Z=Zo)
            if old.n_dofs != up.size:
                return None
            up = old.transfer(up, prm, coarse)
        if fine is not moved:
            before = moved.transfer(before, prm, fine)
        # the transfers are linear: the difference carried once
        uc0 = up + fine.transfer(u0 - before, prm, coarse)
        coarse_first = coarse
        uc0[coarse.fixed] = 0.0
        if not np.all(np.isfinite(uc0)):
            return None
        # the mesh decided before the fine solve, as a cold start's (:meth:`_coarse_first`)
        settled = _coarse_rounds(case, prm, options, coarse, uc0, "the coarser mesh first",
                                 flat_gap=FLAT_KEPT * FLAT_GAP, balanced=True)
        if settled is None:
            return None
        coarse, uc, info = settled
        # what the coarse mesh does not carry of the prediction, added to the coarse
        # solution carried back (a full-approximation two-grid start): on the sweep the
        # fine start's error 8e-3 -> 2.5e-4 where the predictor is good (the fine Newton 3
        # -> 2 steps there); the previous point's fine-minus-coarse difference alone (the
        # prediction's change carried only through the coarse mesh) is its special case
        # without the predicted change's fine part
        return _fine_start(case, prm, options, coarse, uc, info, fine, u0,
                           flat_gap=FLAT_KEPT * FLAT_GAP, balanced=True,
                           minus=(coarse_first, uc0))

    def safe_start(self, case: Case, prm, options: FE2DOptions) -> Start | None:
        """The starting mesh solved along the continuation that follows the flying film's
        branch (Newton only): from shallow grooves on a grooved roller, from a wide web on a
        smooth one (:mod:`webfem.fem.continuation`); None when it does not converge. The
        driver's check of an answer that rests where it need not (on an 8 mm web on the base
        grooved roller, one level finer, the direct Newton rested the web 2.8 um deep where
        the depth continuation finds it flying at 2.4 um)."""
        if options.method != "newton":
            return None
        start = self.start(case, prm, options, None, informed=False)
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
                     "exit zones; no uniform central gap exists",) if case.beta < 6.0 else ()) \
            + fe1d.ends_warnings(case, prm, problem.X)
        common = dict(n_cells=int(problem.mesh.nelements), width_cells=len(problem.Z) - 1,
                      land_fraction=case.land_fraction, warnings=warnings)
        if problem.grooves is None:
            return Facts(**common)
        kind = "strip" if problem.strip else "full" if problem.web_edges else "cell"
        why, edges = {}, {}
        if kind == "cell":
            # a cell asked for by name states the edges' estimated effect too
            X = np.linspace(-0.5 * case.beta, 0.5 * case.beta, 201)
            vent = min(max(1.0 - problem.groove_pressure_ratio(u, X), 0.0), 1.0)
            film = 1.0 - readout.contact_share
            why = {"vent": vent, "film": film, "tol": options.edge_tol,
                   "estimate": edge_effect(case.lam, problem.grooves.pitch, vent, film)}
            edges = {"error_edges": edge_error(why["estimate"]),
                     "edges_basis": f"the web's edges the periodic cell leaves out, twice "
                                    f"their estimated effect {why['estimate']:.3g}"}
            if not cell_answers(why["estimate"], options):      # auto's own rule
                # a cell asked for by name where auto would not answer with it: said
                # beside the numbers, not only in the stated errors (a 1 um groove's cell
                # was 37 % off its full width's mu without a word)
                common["warnings"] = warnings + (
                    f"periodic cell: the web's edges it leaves out are estimated to change "
                    f"its answer by {why['estimate']:.3g} (its stated errors include "
                    f"{edges['error_edges']:.3g}, which with a mesh error up to error_tol = "
                    f"{options.error_tol:g} is above edge_tol = {options.edge_tol:g}): "
                    "grooves = \"strip\" or \"full\" (or auto) solves them",)
        domain = domain_text(case, kind, problem.grooves, **why,
                             width=(case.lam - problem.Z[0]) if problem.strip else None)
        # the share of the lands' load carried by asperity contact, over the wrap
        pts, wts = readout.pts, readout.wts
        Pl = problem.at(pts, problem.land_average(u))
        Pc = forms.contact_law(problem.gap(u, prm, pts), prm.as_form_args())[0]
        share = float(np.sum(Pc * wts) / max(np.sum((Pl + Pc) * wts), 1e-300))
        sag = sag_warning(case, readout.h_min)
        if sag:
            common["warnings"] = common["warnings"] + (sag,)
        return Facts(**common, groove_domain=domain, contact_share_lands=share, **edges)

    def film(self, case, problem, u, prm):
        return film_fields(case, problem, u, prm)

    def kept(self, problem):
        build, args, kwargs = problem.recipe()
        return Rebuild(build, *args, **kwargs)

    def state(self, case: Case, problem, u, start: Start, options=None,
              coarse=None, refined: bool = False) -> State:
        # the secant's second point: the state this one continued from, while this answer
        # stayed on the same mesh (refinement changes the DOFs' meaning)
        before = start.kept.get("continued_from")
        same = (before is not None and problem.X.size == start.problem.X.size
                and problem.Z.size == start.problem.Z.size)
        return State(case, NAME, problem.X.copy(), np.asarray(u).copy(), problem.Z.copy(),
                     line=start.line,
                     key=continued.mesh_key(options) if options is not None else None,
                     prior=before if same else None,
                     prior2=start.kept.get("continued_from2") if same else None,
                     # a mesh the estimate refined stays marked while it is kept
                     refined=refined or (same and start.kept.get("kept_refined", False)),
                     coarse=None if coarse is None or coarse[0].grooves is not None else
                     (coarse[0].X.copy(), coarse[0].Z.copy(), np.asarray(coarse[1]).copy()))


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
        return solve_grooved(case, pattern, options,
                             lambda o, raising, cell=None, estimate_if=None: _with_cell(
                                 cell, lambda: solve_fe(FILM, case, o, initial,
                                                        raising and raise_on_failure,
                                                        estimate_if)))
    finally:
        FILM.forget_lines()


def _with_cell(cell: Result | None, solve):
    """``solve()`` with :attr:`_Film.cell` set to ``cell`` (a converged periodic cell's
    answer of this solve) while it runs."""
    FILM.cell = cell if cell is not None and cell.summary.converged else None
    try:
        return solve()
    finally:
        FILM.cell = None


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
