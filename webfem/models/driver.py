"""The one FE driver shared by the 1-D and 2-D models.

:func:`solve_fe` takes a case, an options object and a :class:`Discretisation` (what differs
between the models: how the discrete problem is built and started, how a state moves to
another mesh, what the mesh is called, what the summary adds) and does everything else once:
the method dispatch (Newton, Picard, staggered Picard), the adaptive refinement where the film
is thin, the admissibility check of the answer and what a careful analyst tries when there is
none, the error estimate and the refinement it asks for, and the failure handling. The typed
result is built by :mod:`webfem.models.outcome`.

A discrete problem (:class:`FEProblem`) offers ``X`` (its scaled x nodes), ``n_dofs``,
``gap(u, prm, X)``, ``pressure(u, X)`` and ``solve_newton/solve_picard(u0, prm, options)``
returning ``(u, SolveInfo)``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from ..case import Case
from ..errors import ConvergenceError, InputError, NoAdmissibleSolution
from ..fem.outcome import SolveInfo
from ..fem.scaling import FoilParameters
from ..physics.contact import contact_pressure
from ..physics.validity import thin_film_check, wrap_length_check
from ..progress import stage
from ..result import Result, State
from .admissible import admissibility, no_admissible_solution, through_thickness
from .mesh_error import MAX_DOFS, MeshError, estimate_mesh_error, release
from .outcome import Facts, build_result
from .readout import errors_between, read_out
from .refine import FLAT_GAP, adapted_nodes, minimum

__all__ = ["FEProblem", "Discretisation", "Start", "solve_fe", "solve_state", "adapted_nodes",
           "admissibility", "REMEDY_MAX_DOFS", "REST_CHECKED"]

#: The methods of a problem that each ``method`` option calls.
METHODS = {"newton": "solve_newton", "picard": "solve_picard",
           "picard-staggered": "solve_picard_staggered"}


class FEProblem(Protocol):
    """What the driver needs of a discrete problem on one mesh."""

    X: np.ndarray
    n_dofs: int

    def gap(self, u, prm, X) -> np.ndarray: ...
    def pressure(self, u, X) -> np.ndarray: ...
    def solve_newton(self, u0, prm, options) -> tuple[np.ndarray, SolveInfo]: ...
    def solve_picard(self, u0, prm, options) -> tuple[np.ndarray, SolveInfo]: ...


@dataclass
class Start:
    """A discrete problem and its start vector; ``info`` of the work already spent getting
    there (the 2-D model's 1-D solve) and ``line``: the 1-D state a 2-D start came from,
    which its result keeps to restart from."""

    problem: Any
    u0: np.ndarray
    info: SolveInfo | None = None
    line: State | None = None
    #: objects of the solving process the result keeps for inspection (dropped on pickling)
    kept: dict = field(default_factory=dict)
    #: the start is the web of an answer already on the branch the safe start follows (the
    #: periodic groove cell's of the same case, reached by the depth continuation or checked
    #: itself): an answer from it that rests is the web's edges' doing, not a spurious
    #: branch, and is not checked against the safe start again (:func:`_higher_branch`)
    checked: bool = False


class Discretisation:
    """What differs between the 1-D and 2-D models: every method the driver calls. The
    defaults are those of a model without them (no safe start, nothing to add)."""

    name = ""
    #: the thin-film rule's factor where the web lies flat (:func:`webfem.models.refine.
    #: adapted_nodes`' ``flat``)
    flat_ratio = 1.0

    def start(self, case: Case, prm: FoilParameters, options,
              restart: State | None) -> Start:
        raise NotImplementedError

    def safe_start(self, case: Case, prm: FoilParameters, options) -> Start | None:
        """A start on the starting mesh that reaches the physical branch when a direct one
        does not (None: the model has none)."""
        return None

    def remeshed(self, problem, u, prm, X, Z, options) -> tuple[Any, np.ndarray]:
        """The problem on other nodes (X, and Z for the 2-D film) and ``u`` carried over."""
        raise NotImplementedError

    def mesh_text(self, problem, options) -> str:
        raise NotImplementedError

    def facts(self, case: Case, problem, u, prm, options, readout) -> Facts:
        """What the model adds to the summary (cells, grooves, warnings)."""
        return Facts(n_cells=len(problem.X) - 1)

    def film(self, case: Case, problem, u, prm):
        """The 2-D film's fields (None for a 1-D model)."""
        return None

    def kept(self, problem):
        """What a result keeps of the discrete problem (:meth:`webfem.result.Result.state`):
        the problem itself by default (a 1-D problem is small and the model's cache holds
        it anyway)."""
        return problem

    def state(self, case: Case, problem, u, start: Start, options=None,
              coarse=None, refined: bool = False) -> State:
        """What a later solve restarts from (``options``: those it was solved with;
        ``coarse``: ``(problem, state)`` solved on the answer's coarser mesh, or None;
        ``refined``: whether the error estimate refined the answer's mesh)."""
        return State(case, self.name, np.asarray(problem.X).copy(), np.asarray(u).copy())


def _iterate(problem, u0, prm, options) -> tuple[np.ndarray, SolveInfo]:
    method = METHODS[options.method]
    if not hasattr(problem, method):
        raise InputError(f"method = {options.method!r} is not available for this model")
    return getattr(problem, method)(u0, prm, options)


def _solve_and_refine(disc: Discretisation, start: Start, prm, options, case: Case,
                      cold: bool = False):
    """Solve on the starting mesh, then refine where the film is thin and solve again, up to
    ``options.adapt`` rounds. With ``cold`` (a cold start of a model with a safe start), a
    state inadmissible on the starting mesh is returned unrefined (the fourth value True):
    the driver tries the safe start next, and refines this state only if that fails
    (refining a spurious branch costs rounds for nothing)."""
    problem = start.problem
    with stage(f"{disc.name} {options.method}, {problem.n_dofs:,} unknowns"):
        u, info = _iterate(problem, start.u0, prm, options)
    if start.info is not None:
        info = info.after(start.info)
    if cold and info.converged and admissibility(case, problem, u, prm):
        return problem, u, info, True
    return (*_refine(disc, case, problem, u, info, prm, options), False)


def _rests(case, problem, u, prm) -> bool:
    """Whether the state has the web resting with its surface compressed (a gap < 0): an
    answer when the case calls for it, but also what a spurious branch of the discrete
    problem looks like (the paper's case at 10 m/s continued from 2 m/s: -11.8 um where the
    web flies at 4.5 um; an 8 mm web on the base grooved roller, one level finer: -2.8 um
    where it flies at 2.4 um). Such a state is checked against the model's safe start."""
    return minimum(problem, u, prm)[0] < 0.0


def _must_rest(case) -> bool:
    """Whether the wrap pressure T_eff/R exceeds what the asperities (on the lands of a
    grooved roller) carry uncompressed, at h = 0: the web must rest compressed somewhere."""
    w = case.web
    carried = case.land_fraction * float(contact_pressure(
        0.0, w.modulus_thickness, case.sigma, w.thickness, case.friction.distribution))
    return case.p_bar > carried


#: The refinement where the film is thin stops once a round changes no quantity a user
#: reads by more than this fraction of ``error_tol`` (option ``adapt_settle``; the mesh
#: error estimate then checks the mesh the rounds ended on). The length rule bisects wherever a
#: cell is longer than the contact length, also where the web lies flat on its asperities
#: and nothing varies: a landed foil web on a 114-unit wrap went from 396 to 1,574 cells
#: (4x the unknowns and the time) while mu moved by 1e-8.
ADAPT_SETTLED = 0.1


def _refine(disc: Discretisation, case: Case, problem, u, info: SolveInfo, prm, options):
    """The refinement rounds of :func:`_solve_and_refine` from a solved state: up to
    ``options.adapt``, fewer once a round has settled (:data:`ADAPT_SETTLED`)."""
    rounds = 0
    if getattr(problem, "planned", False) and options.estimate and info.converged \
            and not admissibility(case, problem, u, prm):
        # a mesh decided before the solve from the rounds made on the same film (fe2d's
        # edge strip on the periodic cell's, :func:`webfem.models.fe2d._replayed_nodes`):
        # not refined again (a round that adds a few nodes costs a solve of 0.2 M
        # unknowns; the mesh error estimate that follows checks the mesh). An answer
        # that is not admissible is refined as any other (the driver's remedy)
        info.adapt_rounds = 0
        return problem, u, info
    settle = options.adapt_settle and options.mesh is None and options.nodes is None
    before = None
    while info.converged and rounds < options.adapt:
        # a continued start's problem judges flat cells with its own (wider) bound
        X = adapted_nodes(problem, u, prm, options.adapt_ratio, options.min_cell,
                          flat=disc.flat_ratio,
                          flat_gap=getattr(problem, "flat_gap", FLAT_GAP))
        if X is None:
            break
        if settle and rounds == 0:
            # read only when a round follows (most continued points refine nothing); quietly:
            # the starting mesh's fields can swing between its nodes (a newsprint line at
            # 31.6 m/s: -154 kPa absolute between nodes of 89-155 kPa) where the friction
            # has no value, and the comparison below then refines on
            with np.errstate(invalid="ignore", divide="ignore"):
                before = read_out(case, problem, u, prm)
        if problem.n_dofs * X.size / problem.X.size > MAX_DOFS:
            # beyond the mesh error estimate's cap (the unknowns grow with the x nodes): a
            # round it could not check (an edge strip of PET went 93,131 -> 172,083 ->
            # 327,207 unknowns, 5+ GB)
            break
        finer, u_fine = disc.remeshed(problem, u, prm, X, getattr(problem, "Z", None),
                                      options)
        release(problem)         # only its nodes and state are read again
        rounds += 1
        with stage(f"{disc.name} refinement round {rounds}, {finer.n_dofs:,} unknowns"):
            u, info_fine = _iterate(finer, u_fine, prm, options)
        problem, info = finer, info_fine.after(info)
        if before is None or not info.converged or admissibility(case, problem, u, prm):
            continue
        after = read_out(case, problem, u, prm)
        change = errors_between(case, after, before)
        before = after
        if all(c <= ADAPT_SETTLED * options.error_tol for c in change.values()):
            break       # (a change not defined, NaN, is not settled)
    info.adapt_rounds = rounds
    return problem, u, info


def solve_fe(disc: Discretisation, case: Case, options, initial=None,
             raise_on_failure: bool = True, estimate_if=None) -> Result:
    """Solve ``case`` with the model ``disc`` and its ``options``; see the module text.

    ``estimate_if(problem, u, prm) -> bool``: whether the answer's mesh error is estimated
    (with ``options.estimate``; None: always). A caller that solves a problem only to decide
    what to solve next (the periodic groove cell before an edge strip) skips the estimate
    and the refinement it asks for where the answer will not be returned, and stops that
    refinement once a refined answer no longer would be.

    ``initial``: a result (or its :class:`~webfem.result.State`) to start from; a start
    from it that fails or ends inadmissible is retried from a cold start, so the answer never
    depends on the path. A cold start that fails or ends inadmissible is retried from the
    model's safe start on the same mesh, then on finer meshes. Raises
    :class:`~webfem.errors.ConvergenceError` (carrying the last iterate) when no converged,
    admissible solution is found, unless ``raise_on_failure`` is False.
    """
    t0 = time.perf_counter()
    start, problem, u, info, options, prm = _solved(disc, case, options, initial)
    mesh_error = MeshError()
    # a coarse solve the start made (fe2d's cold start): the estimate's, not the result's
    solved = start.kept.pop("coarse", None)
    if info.converged and options.estimate and (estimate_if is None
                                                 or estimate_if(problem, u, prm)):
        problem, u, finer, mesh_error = estimate_mesh_error(disc, case, problem, u, prm,
                                                            options, _iterate, solved,
                                                            estimate_if, info.algebraic)
        info.iterations += mesh_error.iterations
        if finer is not None:
            rounds = mesh_error.rounds
            # the start's notes (a cold start after a failed continued one) stay said
            noted = ") (".join(info.notes)
            # the answer is the finer mesh's, solved to the tolerance (the earlier one's
            # bounds, if any, stay added to the stated errors: mesh_error.algebraic)
            info = SolveInfo(**{**info.__dict__, "residual": finer.residual,
                                "algebraic": finer.algebraic,
                                "history": list(info.history) + list(finer.history),
                                "reason": f"{finer.reason} (on the mesh the error estimate "
                                          f"asked for, " + (mesh_error.refined or
                                          f"{rounds} bisection{'s' if rounds > 1 else ''} "
                                          "of the cells along x, across the width or both")
                                          + ")" + (f" ({noted})" if noted else "")})
    result = build_result(disc, case, problem, u, prm, info, time.perf_counter() - t0,
                          options, start, mesh_error)
    crushed = None if result.summary.converged else through_thickness(case, prm)
    if crushed and raise_on_failure:
        # the failure has a physical reason: a web that must rest cannot, the contact law
        # ends at the web's thickness
        raise NoAdmissibleSolution(f"no admissible solution: {crushed} ({disc.name} found "
                                   f"no equilibrium: {info.reason})")
    if not result.summary.converged and raise_on_failure:
        raise ConvergenceError(f"{disc.name} ({options.method}) did not converge: "
                               f"{info.reason} after {info.iterations} iterations, "
                               f"residual {info.residual:.3e}", result, info.history)
    return result


def solve_state(disc: Discretisation, case: Case, options, initial=None):
    """:func:`solve_fe`'s solve without its result: ``(start, problem, u, info)`` of the
    answer, or of the last attempt with ``info.converged`` False (the same remedies, the
    same checks and errors). No mesh error estimate is made. Why: fe2d's 1-D start reads
    only the state, its problem and its iterations, and the 1-D result (its read-out,
    friction and fields) was 3 ms of a cold fe2d base solve's 135."""
    start, problem, u, info, _, _ = _solved(disc, case, options, initial)
    return start, problem, u, info


def _solved(disc: Discretisation, case: Case, options, initial):
    """The checks of ``case`` up front, then :func:`_answer` from ``initial`` (a result or
    its state): ``(start, problem, u, info, options, prm)``."""
    thin_film_check(case)
    wrap_length_check(case)
    _resting_through(case, options)
    restart = initial.restart if isinstance(initial, Result) else initial
    prm = FoilParameters.from_case(case, options.compressible, options.contact, options.floor)
    try:
        return (*_answer(disc, case, prm, options, restart), prm)
    except (np.linalg.LinAlgError, ArithmeticError) as err:
        raise ConvergenceError(
            f"{disc.name}: the discrete problem could not be built or solved "
            f"({type(err).__name__}: {err}); cells this short or this many lose the "
            "precision the solver needs: a lower level or webfem's default mesh may help",
            None) from None


def _resting_through(case: Case, options) -> None:
    """Refuse up front a web that must rest (the closed form lands it) and that contact
    alone would compress through its thickness: no equilibrium is admissible, and the
    solvers would only find that out in minutes."""
    prm = FoilParameters.from_case(case, options.compressible, options.contact, options.floor)
    crushed = through_thickness(case, prm)
    if crushed is None:
        return
    from .closed import NO_ANSWER, evaluate_case
    if NO_ANSWER[evaluate_case(case)] in ("compressed", "landed"):
        raise NoAdmissibleSolution(f"no admissible solution: {crushed}")


def _ok(info: SolveInfo, why) -> bool:
    return info.converged and not why


def _hopeless(info: SolveInfo) -> bool:
    """A failure no other start or finer mesh mends: the Newton correction vanishes while
    the residual stays above the tolerance and its rounding floor (a finer mesh only raises
    the floor)."""
    return "the residual stalls" in info.reason


def _answer(disc, case, prm, options, restart):
    """The remedies a careful analyst tries, in order: the continued start (``restart``),
    the cold start, the model's safe start on the same mesh, the direct state refined, finer
    meshes. Returns ``(start, problem, u, info, options)`` of the answer, or of the last
    attempt with ``info.converged`` False and the reason."""
    with stage(f"{disc.name} start"):
        start = disc.start(case, prm, options, restart)
    problem, u, info, unrefined = _solve_and_refine(disc, start, prm, options, case,
                                                    cold=restart is None)
    why = admissibility(case, problem, u, prm) if info.converged else None
    if restart is not None and (not _ok(info, why) or _rests(case, problem, u, prm)):
        cold = disc.start(case, prm, options, None)
        problem, u, info2, unrefined = _solve_and_refine(disc, cold, prm, options, case,
                                                         cold=True)
        info = info2.after(info, "cold start after the continued start " + (
            f"ended inadmissible: {why}" if why else "failed" if not info.converged
            else "ended resting, to be checked"))
        start = cold
        why = admissibility(case, problem, u, prm) if info.converged else None
    if not _ok(info, why) and not _hopeless(info):
        start, problem, u, info, why, used = _from_safe_start(disc, case, prm, options, start,
                                                              problem, u, info, why)
        unrefined = unrefined and not used
    if unrefined and why:
        # no safe answer: the direct state is refined as any other (a coarse mesh may be
        # what let the web through its asperities)
        problem, u, info = _refine(disc, case, problem, u, info, prm, options)
        why = admissibility(case, problem, u, prm) if info.converged else None
    if why:
        no_admissible_solution(case, prm, why)
    if not _ok(info, why) and not _hopeless(info):
        start, problem, u, info, options, why = _on_finer_meshes(disc, case, prm, options,
                                                                 start, problem, u, info, why)
    if why and info.converged:
        no_admissible_solution(case, prm, why, problem, u)
    if why:
        info.converged = False
        info.reason = f"converged to an inadmissible field: {why}"
    elif info.converged and _rests(case, problem, u, prm) and not _must_rest(case) \
            and not start.checked:
        start, problem, u, info = _higher_branch(disc, case, prm, options, start, problem, u,
                                                 info)
    return start, problem, u, info, options


#: The key of :attr:`Start.kept` (and so of a result's solver objects) saying that a resting
#: answer was checked and stands: the model's safe start, solved, rests as low or lower
#: (:func:`_higher_branch`). A start that carries it is not checked again: fe2d's strip or
#: full width started from a periodic cell's resting answer so checked.
REST_CHECKED = "rest_checked"


def _higher_branch(disc, case, prm, options, start, problem, u, info):
    """An answer that rests compressed where the wrap pressure does not require it: the
    model's safe start (which follows the flying film's branch) is solved too, and its
    answer taken when admissible with the web higher (the web rests only where it must);
    otherwise the resting answer stands (the film's suction may pull a web into its
    asperities)."""
    with stage(f"{disc.name} safe start (checks a resting answer)"):
        safe = disc.safe_start(case, prm, options)
    if safe is None:
        return start, problem, u, info
    problem2, u2, info2, _ = _solve_and_refine(disc, safe, prm, options, case)
    if not _ok(info2, admissibility(case, problem2, u2, prm) if info2.converged else "failed"):
        return start, problem, u, info
    if minimum(problem2, u2, prm)[0] <= minimum(problem, u, prm)[0] + 1e-9:
        start.kept[REST_CHECKED] = "its safe start rests as low or lower"
        return start, problem, u, info
    note = "from the safe start: the direct start ended on a branch with the web resting lower"
    return safe, problem2, u2, info2.after(info, note)


def _from_safe_start(disc, case, prm, options, start, problem, u, info, why):
    """A state on the starting mesh that failed, or converged but is inadmissible, may be a
    spurious branch of the nonlinear problem or a poor start, not a mesh too coarse: the
    model's safe start on the same mesh (e.g. the 1-D model's continuation from the
    Eshel-Elrod problem) is tried first. Its answer is taken only when it is converged and
    admissible (the last value says whether it was)."""
    with stage(f"{disc.name} safe start"):
        safe = disc.safe_start(case, prm, options)
    if safe is None:
        return start, problem, u, info, why, False
    problem2, u2, info2, _ = _solve_and_refine(disc, safe, prm, options, case)
    why2 = admissibility(case, problem2, u2, prm) if info2.converged else why
    if not _ok(info2, why2):
        return start, problem, u, info, why, False
    note = "from the safe start on the same mesh: the direct start " + (
        f"ended on an inadmissible branch: {why}" if why else f"failed: {info.reason}")
    return safe, problem2, u2, info2.after(info, note), None, True


#: The second finer mesh of :func:`_on_finer_meshes` is tried only while the first finer one
#: times 4 (a 2-D level) stays below this many unknowns (the base case's fe2d level 2 has
#: 1.0e5; a grooved cell two levels up took 8 minutes and 7 GB to confirm a negative gap).
REMEDY_MAX_DOFS = 1.2e5


def _on_finer_meshes(disc, case, prm, options, start, problem, u, info, why):
    """A state that failed, or converged but is inadmissible (a coarse mesh that lets the
    web through its asperities): solve again from cold on meshes one and two levels finer,
    as an analyst would (the second only while it stays below :data:`REMEDY_MAX_DOFS`).
    Returns the first admissible solution, else the last one tried."""
    limit = type(options).__dataclass_fields__["level"].metadata["hi"]
    first = options.level + 1
    for level in range(first, min(first + 1, limit) + 1):
        if level > first and problem.n_dofs * 4 > REMEDY_MAX_DOFS:
            break     # a 2-D mesh two levels finer: minutes and gigabytes for a likely no
        finer_options = options.replace(level=level)
        with stage(f"{disc.name} on mesh level {level}"):
            cold = disc.start(case, prm, finer_options, None)
            problem2, u2, info2, _ = _solve_and_refine(disc, cold, prm, finer_options, case)
        why2 = admissibility(case, problem2, u2, prm) if info2.converged else why
        note = f"on mesh level {level}: level {options.level} " + (
            f"gave an inadmissible field: {why}" if why else f"did not converge: {info.reason}")
        start, problem, u, info, why = cold, problem2, u2, info2.after(info, note), why2
        options = finer_options
        if _ok(info, why) or _hopeless(info):
            break
    return start, problem, u, info, options, why
