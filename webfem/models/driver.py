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
from ..physics.effects import included, traction_summary
from ..physics.friction import friction_for
from ..physics.validity import slip_warning, thin_film_check, wrap_length_check
from ..progress import stage
from ..result import Diagnostics, Fields, Result, Summary
from .admissible import _no_admissible_solution, admissibility
from .refine import adapted_nodes, minimum, wrap_samples

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
    a cold start, so the answer never depends on the path. Raises
    :class:`~webfem.errors.ConvergenceError` (carrying the last iterate) when no converged,
    admissible solution is found, unless ``raise_on_failure`` is False.
    """
    thin_film_check(case)
    wrap_length_check(case)
    t0 = time.perf_counter()
    prm = FoilParameters.from_case(case, options.compressible, options.contact, options.floor)
    with stage(f"{disc.name} start"):
        start = disc.start(case, prm, options, initial)
    safe = case if hasattr(disc, "safe_start") else None
    problem, u, info = _solve_and_refine(disc, start, prm, options,
                                         safe if initial is None else None)
    why = admissibility(case, problem, u, prm) if info["converged"] else None
    if initial is not None and (not info["converged"] or why):
        cold = disc.start(case, prm, options, None)
        problem2, u2, info2 = _solve_and_refine(disc, cold, prm, options, safe)
        info2["iterations"] += info["iterations"]
        info2["history"] = list(info["history"]) + list(info2["history"])
        info2["reason"] = (f"{info2.get('reason', '')} (cold start after the continued "
                           f"start {'ended inadmissible: ' + why if why else 'failed'})")
        start, problem, u, info = cold, problem2, u2, info2
        why = admissibility(case, problem, u, prm) if info["converged"] else None
    if why and info["converged"]:
        start, problem, u, info, why = _from_safe_start(disc, case, prm, options, start,
                                                        problem, u, info, why)
    if info.pop("unrefined", False) and why:
        # no safe answer: the direct state is refined as any other (a coarse mesh may be
        # what let the web through its asperities)
        problem, u, info = _refine(disc, problem, u, info, prm, options)
        why = admissibility(case, problem, u, prm) if info["converged"] else None
    if why:
        _no_admissible_solution(case, prm, why)
        start, problem, u, info, options, why = _on_finer_meshes(disc, case, prm, options,
                                                                 start, problem, u, info, why)
    if why and info["converged"]:
        _no_admissible_solution(case, prm, why, problem, u)
    if why:
        info["converged"] = False
        info["reason"] = f"converged to an inadmissible field: {why}"
    notes = _user_mesh_check(disc, case, problem, u, prm, options) if info["converged"] else []
    elapsed = time.perf_counter() - t0
    result = _result(disc, case, problem, u, prm, info, elapsed, options, start.solver, notes)
    if not result.summary.converged and raise_on_failure:
        raise ConvergenceError(f"{disc.name} ({options.method}) did not converge: "
                               f"{info['reason']} after {info['iterations']} iterations, "
                               f"residual {info['residual']:.3e}", result, info.get("history"))
    return result


def _from_safe_start(disc, case, prm, options, start, problem, u, info, why):
    """A converged but inadmissible state on the starting mesh may be a spurious branch of
    the nonlinear problem, not a mesh too coarse: the model's safe start on the same mesh
    (``disc.safe_start``, e.g. the 1-D model's continuation from the Eshel-Elrod problem)
    is tried first. Its answer is taken only when it is converged and admissible."""
    if not hasattr(disc, "safe_start"):
        return start, problem, u, info, why
    with stage(f"{disc.name} safe start"):
        safe = disc.safe_start(case, prm, options)
    if safe is None:
        return start, problem, u, info, why
    problem2, u2, info2 = _solve_and_refine(disc, safe, prm, options)
    why2 = admissibility(case, problem2, u2, prm) if info2["converged"] else why
    if not info2["converged"] or why2:
        return start, problem, u, info, why
    info2["iterations"] += info["iterations"]
    info2["history"] = list(info["history"]) + list(info2["history"])
    info2["reason"] = (f"{info2.get('reason', '')} (from the safe start on the same mesh: "
                       f"the direct start ended on an inadmissible branch: {why})")
    return safe, problem2, u2, info2, None


#: The second finer mesh of :func:`_on_finer_meshes` is tried only while the first finer one
#: times 4 (a 2-D level) stays below this many unknowns (the base case's fe2d level 2 has
#: 1.0e5; a grooved cell two levels up took 8 minutes and 7 GB to confirm a negative gap).
REMEDY_MAX_DOFS = 1.2e5


def _on_finer_meshes(disc, case, prm, options, start, problem, u, info, why):
    """A converged but inadmissible state (a coarse mesh that lets the web through its
    asperities): solve again from cold on meshes one and two levels finer, as an analyst
    would (the second only while it stays below :data:`REMEDY_MAX_DOFS`). Returns the
    first admissible solution, else the last one tried."""
    limit = type(options).__dataclass_fields__["level"].metadata["hi"]
    first = options.level + 1
    for level in range(first, min(first + 1, limit) + 1):
        if level > first and problem.n_dofs * 4 > REMEDY_MAX_DOFS:
            break     # a 2-D mesh two levels finer: minutes and gigabytes for a likely no
        finer_options = options.replace(level=level)
        cold = disc.start(case, prm, finer_options, None)
        problem2, u2, info2 = _solve_and_refine(disc, cold, prm, finer_options)
        info2["iterations"] += info["iterations"]
        info2["history"] = list(info["history"]) + list(info2["history"])
        why2 = admissibility(case, problem2, u2, prm) if info2["converged"] else why
        info2["reason"] = (f"{info2.get('reason', '')} (on mesh level {level}: level "
                           f"{options.level} gave an inadmissible field: {why})")
        start, problem, u, info, why = cold, problem2, u2, info2, why2
        options = finer_options
        if info["converged"] and not why:
            break
    return start, problem, u, info, options, why


#: A user mesh is checked when its cells near the wrap edges are longer than this, in units
#: of R eps^(1/3) (the film's entry length; webfem's graded mesh puts 0.08 there).
USER_CELL_LIMIT = 0.5


def _user_mesh_check(disc, case: Case, problem, u, prm, options) -> list[str]:
    """For a user mesh coarser than the film's length scale near the wrap edges: a warning
    with an a-posteriori error estimate (the change of the gaps when every cell is halved)."""
    if options.mesh is None and options.nodes is None:
        return []
    X = problem.X
    mid = 0.5 * (X[1:] + X[:-1])
    near = np.abs(np.abs(mid) - 0.5 * prm.beta) < 5.0
    longest = float(np.diff(X)[near].max()) if near.any() else float(np.ptp(X))
    if longest <= USER_CELL_LIMIT:
        return []
    finer, u_fine = disc.refined(problem, u, prm, np.sort(np.concatenate([X, mid])), options)
    u_fine, info = _iterate(finer, u_fine, prm, options)
    text = (f"user mesh: cells up to {longest:.3g} R eps^(1/3) long near the wrap edges, "
            f"where the film changes over about one R eps^(1/3) (webfem's graded mesh: 0.08)")
    if not info["converged"]:
        return [text + "; on the mesh with every cell halved the solve does not converge: "
                "its error is unknown and likely large"]
    a = problem.gap(u, prm, np.array([0.0])), finer.gap(u_fine, prm, np.array([0.0]))
    b = minimum(problem, u, prm)[0], minimum(finer, u_fine, prm)[0]
    dc, dm = abs(a[1][0] / a[0][0] - 1.0), abs(b[1] / b[0] - 1.0)
    return [text + f"; halving every cell changes h_center by {100 * dc:.2g} % and h_min by "
            f"{100 * dm:.2g} % (an estimate of this mesh's error): refine the mesh or use "
            "webfem's graded one"]


def _result(disc, case, problem, u, prm, info, elapsed, options, solver, notes) -> Result:
    Hs, Xs = case.h_scale, case.x_scale
    pts, wts = wrap_samples(problem.X, prm.beta)
    h = problem.gap(u, prm, pts) * Hs
    p, dpdx = _pressure_and_gradient(case, problem, u, pts)
    loc = friction_for(case, h, resting=True, p=p, dpdx=dpdx)
    mu = float(np.sum(loc["mu"] * wts) / prm.beta)
    shares = [float(np.sum(wts * (loc["regime"] == k)) / prm.beta) for k in range(3)]
    Pf = (p - case.air.ambient_pressure) / case.p_bar
    Pc = prm.land * forms.contact_law(h / Hs, prm.as_form_args())[0]  # lands only
    contact_share = float(np.sum(Pc * wts) / max(np.sum((Pf + Pc) * wts), 1e-300))
    # mu, delta_T and the idler keys; where nothing slides, the traction at the onset of
    # slip (the film's own drag goes to mu_film)
    traction = traction_summary(case, mu, contact_share)
    Hmin, Xmin = minimum(problem, u, prm)
    e = 0.5 * prm.beta
    H3 = problem.gap(u, prm, np.array([0.0, -e, e]))
    extra = dict(disc.summary_extra(case, problem, options))
    if hasattr(disc, "summary_state"):
        extra.update(disc.summary_state(case, problem, u, prm, pts, wts))
    warnings = list(_warnings(case, options)) + list(extra.pop("warnings", [])) + notes
    slip = slip_warning(case, Hmin * Hs)
    if slip:
        warnings.append(slip)
    summary = Summary(
        model=disc.name, h_center=H3[0] * Hs, h_inlet=H3[1] * Hs, h_outlet=H3[2] * Hs,
        h_min=Hmin * Hs, x_min=Xmin * Xs,
        regime=REGIMES[int(np.argmax(shares))], lambda_=case.lam, beta=case.beta,
        eq21_valid=bool(eq21_valid(case.beta, case.lam)),
        converged=bool(info["converged"]), iterations=int(info["iterations"]),
        n_dofs=int(problem.n_dofs), solve_time_s=elapsed, residual=float(info["residual"]),
        h_c=float(prm.H_c * Hs), sigma=case.sigma, share_boundary=shares[0],
        share_mixed=shares[1], share_fluid=shares[2], contact_share=contact_share,
        eps=case.eps, kappa=case.kappa, U=case.U, U_slide=case.U_slide,
        method=options.method, mesh=disc.mesh_text(problem, options),
        warnings=tuple(warnings), adapt_rounds=info.get("adapt_rounds", 0),
        solver_message=info.get("reason", ""), T_eff=case.tension_eff,
        bending_stiffness_used=case.bending_used, effects=included(case), **traction,
        **{"n_cells": len(problem.X) - 1, **extra})
    diagnostics = Diagnostics(
        method=options.method, history=tuple(info.get("history", [])),
        reason=info.get("reason", ""), continuation=tuple(info.get("steps", [])),
        options=options, wrap_h=h, wrap_w=wts / prm.beta, wrap_p=p, wrap_dpdx=dpdx,
        omegas=info.get("omegas"),
        block_iterations=info.get("block_iterations"),
        solver={**solver, "problem": problem, "state": u})
    return Result(case, summary, _node_fields(case, problem, u, prm), diagnostics,
                  disc.film(case, problem, u, prm))


def _pressure_and_gradient(case: Case, problem, u, X) -> tuple[np.ndarray, np.ndarray]:
    """Absolute (width-averaged) film pressure [Pa] and its x-derivative [Pa/m] at scaled
    points X inside cells (a central difference well inside the cell: the pressure is a
    polynomial there)."""
    delta = 1e-7
    P = problem.pressure(u, np.concatenate([X, X - delta, X + delta]))
    n = len(X)
    dPdX = (P[2 * n:] - P[n:2 * n]) / (2.0 * delta)
    return (case.air.ambient_pressure + P[:n] * case.p_bar,
            dPdX * case.p_bar / case.x_scale)


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
    p, dpdx = _pressure_and_gradient(case, problem, u, inner)
    p_rel = p - case.air.ambient_pressure
    return Fields(x=X * case.x_scale, h=h, w=h - forms.departure(X, prm.beta) * Hs,
                  p_rel=p_rel, p=p, p_contact=forms.contact_law(H, prm.as_form_args())[0]
                  * case.p_bar, in_wrap=forms.in_wrap(X, prm.beta),
                  **friction_for(case, h, resting=True, p=p, dpdx=dpdx))
