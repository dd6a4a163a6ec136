"""The one FE driver shared by the 1-D and 2-D models.

:func:`solve_fe` takes a case, an options object and a :class:`Discretisation` (what differs
between the models: how the discrete problem is built and started, how a state moves to a
finer mesh, what the mesh is called) and does everything else once: the method dispatch
(Newton, Picard, staggered Picard), the adaptive refinement where the film is thin, the
admissibility check of the answer (and what a careful analyst tries when it fails), the
summary, the fields and the failure handling.

A discrete problem (:class:`FEProblem`) offers ``X`` (its scaled x nodes), ``n_dofs``,
``gap(u, prm, X)``, ``pressure(u, X)`` and ``solve_newton/solve_picard(u0, prm, options)``
returning ``(u, info)``; ``info`` has converged, iterations, residual, history, reason.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from ..case import Case
from ..errors import ConvergenceError, InputError
from ..fem import forms
from ..fem.scaling import FoilParameters
from ..physics.closed_form import eq21_valid
from ..physics.contact import REGIMES
from ..physics.effects import included
from ..physics.friction import friction_for
from ..physics.validity import slip_warning, thin_film_check, wrap_length_check
from ..progress import stage
from ..result import Diagnostics, Fields, Result, Summary
from .admissible import no_admissible_solution, admissibility
from .mesh_error import MeshError, estimate_mesh_error, summary_keys
from .readout import pressure_and_gradient, read_out
from .refine import adapted_nodes

__all__ = ["FEProblem", "Discretisation", "Start", "solve_fe", "adapted_nodes",
           "admissibility"]

#: The methods of a problem that each ``method`` option calls.
METHODS = {"newton": "solve_newton", "picard": "solve_picard",
           "picard-staggered": "solve_picard_staggered"}


class FEProblem(Protocol):
    """What the driver needs of a discrete problem on one mesh."""

    X: np.ndarray
    n_dofs: int

    def gap(self, u, prm, X) -> np.ndarray: ...
    def pressure(self, u, X) -> np.ndarray: ...
    def solve_newton(self, u0, prm, options) -> tuple[np.ndarray, dict]: ...
    def solve_picard(self, u0, prm, options) -> tuple[np.ndarray, dict]: ...


@dataclass
class Start:
    """A discrete problem and its start vector; ``iterations`` already spent getting there
    (the 2-D model's 1-D solve) and ``solver`` objects to keep in the result."""

    problem: Any
    u0: np.ndarray
    iterations: int = 0
    solver: dict = field(default_factory=dict)


class Discretisation(Protocol):
    """What differs between the 1-D and 2-D models."""

    name: str

    def start(self, case: Case, prm: FoilParameters, options, initial) -> Start: ...
    def refined(self, problem, u, prm, X: np.ndarray, options) -> tuple[Any, np.ndarray]: ...
    def mesh_text(self, problem, options) -> str: ...
    def summary_extra(self, case: Case, problem, options) -> dict: ...
    def film(self, case: Case, problem, u, prm): ...


def _iterate(problem, u0, prm, options) -> tuple[np.ndarray, dict]:
    method = METHODS[options.method]
    if not hasattr(problem, method):
        raise InputError(f"method = {options.method!r} is not available for this model")
    return getattr(problem, method)(u0, prm, options)


def _solve_and_refine(disc: Discretisation, start: Start, prm, options, case=None):
    """Solve on the starting mesh, then refine where the film is thin and solve again, up to
    ``options.adapt`` rounds. With ``case`` (a cold start of a model with a safe start), a
    state inadmissible on the starting mesh is returned unrefined (``info["unrefined"]``):
    the driver tries the safe start next, and refines this state only if that fails
    (refining a spurious branch costs rounds for nothing)."""
    problem = start.problem
    with stage(f"{disc.name} {options.method}, {problem.n_dofs:,} unknowns"):
        u, info = _iterate(problem, start.u0, prm, options)
    info["iterations"] += start.iterations
    if case is not None and info["converged"] and admissibility(case, problem, u, prm):
        info.update(adapt_rounds=0, unrefined=True)
        return problem, u, info
    return _refine(disc, problem, u, info, prm, options)


def _refine(disc: Discretisation, problem, u, info, prm, options):
    """The refinement rounds of :func:`_solve_and_refine` from a solved state."""
    rounds = 0
    while info["converged"] and rounds < options.adapt:
        X = adapted_nodes(problem, u, prm, options.adapt_ratio, options.min_cell)
        if X is None:
            break
        rounds += 1
        finer, u_fine = disc.refined(problem, u, prm, X, options)
        with stage(f"{disc.name} refinement round {rounds}, {finer.n_dofs:,} unknowns"):
            u, info_fine = _iterate(finer, u_fine, prm, options)
        info_fine["iterations"] += info["iterations"]
        info_fine["history"] = list(info["history"]) + list(info_fine["history"])
        problem, info = finer, info_fine
    info["adapt_rounds"] = rounds
    return problem, u, info


def solve_fe(disc: Discretisation, case: Case, options, initial: Result | None = None,
             raise_on_failure: bool = True) -> Result:
    """Solve ``case`` with the model ``disc`` and its ``options``; see the module text.

    A start from ``initial`` (continuation) that fails or ends inadmissible is retried from
    a cold start, so the answer never depends on the path. A cold start that fails or ends
    inadmissible is retried from the model's safe start on the same mesh, then on finer
    meshes. Raises :class:`~webfem.errors.ConvergenceError` (carrying the last iterate) when
    no converged, admissible solution is found, unless ``raise_on_failure`` is False.
    """
    thin_film_check(case)
    wrap_length_check(case)
    t0 = time.perf_counter()
    prm = FoilParameters.from_case(case, options.compressible, options.contact, options.floor)
    try:
        start, problem, u, info, options = _answer(disc, case, prm, options, initial)
    except (np.linalg.LinAlgError, ArithmeticError) as err:
        raise ConvergenceError(
            f"{disc.name}: the discrete problem could not be built or solved "
            f"({type(err).__name__}: {err}); cells this short or this many lose the "
            "precision the solver needs: a lower level or webfem's default mesh may help",
            None) from None
    mesh_error = MeshError()
    if info["converged"] and options.estimate:
        problem, u, finer, mesh_error = estimate_mesh_error(disc, case, problem, u, prm,
                                                            options, _iterate)
        info["iterations"] += mesh_error.iterations
        if finer is not None:
            info["history"] = list(info["history"]) + list(finer["history"])
            info.update(residual=finer["residual"], reason=finer.get("reason", "") + (
                f" (on the mesh the error estimate asked for, {mesh_error.rounds} "
                f"bisection{'s' if mesh_error.rounds > 1 else ''} of every cell)"))
    elapsed = time.perf_counter() - t0
    result = _result(disc, case, problem, u, prm, info, elapsed, options, start.solver,
                     mesh_error)
    if not result.summary.converged and raise_on_failure:
        raise ConvergenceError(f"{disc.name} ({options.method}) did not converge: "
                               f"{info['reason']} after {info['iterations']} iterations, "
                               f"residual {info['residual']:.3e}", result, info.get("history"))
    return result


def _ok(info, why) -> bool:
    return bool(info["converged"]) and not why


def _hopeless(info) -> bool:
    """A failure no other start or finer mesh mends: the residual stalls at its rounding
    floor above the tolerance (a finer mesh only raises the floor)."""
    return "rounding floor" in info.get("reason", "")


def _answer(disc, case, prm, options, initial):
    """The remedies a careful analyst tries, in order: the continued start (``initial``),
    the cold start, the model's safe start on the same mesh, the direct state refined, finer
    meshes. Returns ``(start, problem, u, info, options)`` of the answer, or of the last
    attempt with ``info["converged"]`` False and the reason."""
    with stage(f"{disc.name} start"):
        start = disc.start(case, prm, options, initial)
    safe = case if hasattr(disc, "safe_start") else None
    problem, u, info = _solve_and_refine(disc, start, prm, options,
                                         safe if initial is None else None)
    why = admissibility(case, problem, u, prm) if info["converged"] else None
    if initial is not None and not _ok(info, why):
        cold = disc.start(case, prm, options, None)
        problem2, u2, info2 = _solve_and_refine(disc, cold, prm, options, safe)
        _merge(info2, info, f"cold start after the continued start "
                            f"{'ended inadmissible: ' + why if why else 'failed'}")
        start, problem, u, info = cold, problem2, u2, info2
        why = admissibility(case, problem, u, prm) if info["converged"] else None
    if not _ok(info, why) and not _hopeless(info):
        start, problem, u, info, why = _from_safe_start(disc, case, prm, options, start,
                                                        problem, u, info, why)
    if info.pop("unrefined", False) and why:
        # no safe answer: the direct state is refined as any other (a coarse mesh may be
        # what let the web through its asperities)
        problem, u, info = _refine(disc, problem, u, info, prm, options)
        why = admissibility(case, problem, u, prm) if info["converged"] else None
    if why:
        no_admissible_solution(case, prm, why)
    if not _ok(info, why) and not _hopeless(info):
        start, problem, u, info, options, why = _on_finer_meshes(disc, case, prm, options,
                                                                 start, problem, u, info, why)
    if why and info["converged"]:
        no_admissible_solution(case, prm, why, problem, u)
    if why:
        info["converged"] = False
        info["reason"] = f"converged to an inadmissible field: {why}"
    return start, problem, u, info, options


def _merge(info: dict, before: dict, note: str = "") -> None:
    """``info`` of a solve that followed the solve of ``before``: iterations and residual
    history added, ``note`` appended to the reason."""
    info["iterations"] += before["iterations"]
    info["history"] = list(before["history"]) + list(info["history"])
    if note:
        info["reason"] = f"{info.get('reason', '')} ({note})"


def _from_safe_start(disc, case, prm, options, start, problem, u, info, why):
    """A state on the starting mesh that failed, or converged but is inadmissible, may be a
    spurious branch of the nonlinear problem or a poor start, not a mesh too coarse: the
    model's safe start on the same mesh (``disc.safe_start``, e.g. the 1-D model's
    continuation from the Eshel-Elrod problem) is tried first. Its answer is taken only when
    it is converged and admissible."""
    if not hasattr(disc, "safe_start"):
        return start, problem, u, info, why
    with stage(f"{disc.name} safe start"):
        safe = disc.safe_start(case, prm, options)
    if safe is None:
        return start, problem, u, info, why
    problem2, u2, info2 = _solve_and_refine(disc, safe, prm, options)
    why2 = admissibility(case, problem2, u2, prm) if info2["converged"] else why
    if not _ok(info2, why2):
        return start, problem, u, info, why
    _merge(info2, info, "from the safe start on the same mesh: the direct start "
                        + (f"ended on an inadmissible branch: {why}" if why
                           else f"failed: {info.get('reason', '')}"))
    return safe, problem2, u2, info2, None


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
            problem2, u2, info2 = _solve_and_refine(disc, cold, prm, finer_options)
        why2 = admissibility(case, problem2, u2, prm) if info2["converged"] else why
        _merge(info2, info, f"on mesh level {level}: level {options.level} "
                            + (f"gave an inadmissible field: {why}" if why
                               else f"did not converge: {info.get('reason', '')}"))
        start, problem, u, info, why = cold, problem2, u2, info2, why2
        options = finer_options
        if _ok(info, why) or _hopeless(info):
            break
    return start, problem, u, info, options, why


def _result(disc, case, problem, u, prm, info, elapsed, options, solver,
            mesh_error: MeshError) -> Result:
    Hs = case.h_scale
    ro = read_out(case, problem, u, prm)
    extra = dict(disc.summary_extra(case, problem, options))
    if hasattr(disc, "summary_state"):
        extra.update(disc.summary_state(case, problem, u, prm, ro.pts, ro.wts))
    warnings = (list(_warnings(case, options)) + list(extra.pop("warnings", []))
                + list(mesh_error.notes))
    slip = slip_warning(case, ro.h_min)
    if slip:
        warnings.append(slip)
    shares = ro.shares
    summary = Summary(
        model=disc.name, h_center=ro.h_center, h_inlet=ro.h_inlet, h_outlet=ro.h_outlet,
        h_min=ro.h_min, x_min=ro.x_min,
        regime=REGIMES[int(np.argmax(shares))], lambda_=case.lam, beta=case.beta,
        eq21_valid=bool(eq21_valid(case.beta, case.lam)),
        converged=bool(info["converged"]), iterations=int(info["iterations"]),
        n_dofs=int(problem.n_dofs), solve_time_s=elapsed, residual=float(info["residual"]),
        h_c=float(prm.H_c * Hs), sigma=case.sigma, share_boundary=shares[0],
        share_mixed=shares[1], share_fluid=shares[2], contact_share=ro.contact_share,
        eps=case.eps, kappa=case.kappa, U=case.U, U_slide=case.U_slide,
        method=options.method, mesh=disc.mesh_text(problem, options),
        warnings=tuple(warnings), adapt_rounds=info.get("adapt_rounds", 0),
        solver_message=info.get("reason", ""), T_eff=case.tension_eff,
        bending_stiffness_used=case.bending_used, effects=included(case), **ro.traction,
        **summary_keys(mesh_error), **{"n_cells": len(problem.X) - 1, **extra})
    diagnostics = Diagnostics(
        method=options.method, history=tuple(info.get("history", [])),
        reason=info.get("reason", ""), continuation=tuple(info.get("steps", [])),
        options=options, wrap_h=ro.h, wrap_w=ro.wts / prm.beta, wrap_p=ro.p,
        wrap_dpdx=ro.dpdx,
        omegas=info.get("omegas"),
        block_iterations=info.get("block_iterations"),
        solver={**solver, "problem": problem, "state": u})
    return Result(case, summary, _node_fields(case, problem, u, prm), diagnostics,
                  disc.film(case, problem, u, prm))


def _warnings(case: Case, options):
    if not options.compressible and case.p_bar > 0.02 * case.air.ambient_pressure:
        ratio = case.p_bar / case.air.ambient_pressure
        yield (f"incompressible film with T/R = {ratio:.3g} p_a > 0.02 p_a: compressibility "
               f"shifts the central gap by about {-45 * ratio:.2g} % (use compressible=True)")


def _node_fields(case: Case, problem, u, prm: FoilParameters) -> Fields:
    X = problem.X
    Hs = case.h_scale
    H = problem.gap(u, prm, X)
    h = H * Hs
    # one-sided differences at the ends (the pressure is only defined inside the domain)
    inner = np.clip(X, X[0] + 1e-6, X[-1] - 1e-6)
    p, dpdx = pressure_and_gradient(case, problem, u, inner)
    p_rel = p - case.air.ambient_pressure
    return Fields(x=X * case.x_scale, h=h, w=h - forms.departure(X, prm.beta) * Hs,
                  p_rel=p_rel, p=p, p_contact=forms.contact_law(H, prm.as_form_args())[0]
                  * case.p_bar, in_wrap=forms.in_wrap(X, prm.beta),
                  **friction_for(case, h, resting=True, p=p, dpdx=dpdx))
