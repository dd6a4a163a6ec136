"""The typed result of an FE solve: the summary from the quantities read off the solved
state, what the model adds (:class:`Facts`), the stated errors, the fields, the diagnostics
and the state to restart from."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..case import Case
from ..fem.outcome import SolveInfo
from ..physics.closed_form import eq21_valid
from ..physics.contact import REGIMES, tail_warning
from ..physics.effects import included
from ..physics.validity import answer_warnings
from ..result import Diagnostics, Result, Summary
from .fields import node_fields
from .mesh_error import MeshError
from .readout import read_out

__all__ = ["Facts", "build_result"]


@dataclass(frozen=True)
class Facts:
    """What a model adds to the summary: the cells of its mesh (``n_cells``; the 2-D film's
    ``width_cells`` across), a grooved roller's ``land_fraction``, ``groove_domain`` and
    ``contact_share_lands``, its ``warnings``, and a periodic groove cell's ``error_edges``
    (:func:`webfem.models.groove_domain.edge_error`, added to each stated error) with the
    text saying so for ``error_basis``."""

    n_cells: int
    width_cells: int | None = None
    land_fraction: float | None = None
    groove_domain: str | None = None
    contact_share_lands: float | None = None
    warnings: tuple[str, ...] = ()
    error_edges: float | None = None
    edges_basis: str | None = None


def _warnings(case: Case, options):
    if not options.compressible and case.p_bar > 0.02 * case.air.ambient_pressure:
        ratio = case.p_bar / case.air.ambient_pressure
        yield (f"incompressible film with T/R = {ratio:.3g} p_a > 0.02 p_a: compressibility "
               f"shifts the central gap by about {-45 * ratio:.2g} % (use compressible=True)")


def build_result(disc, case: Case, problem, u, prm, info: SolveInfo, elapsed: float,
                 options, start, mesh_error: MeshError) -> Result:
    """The :class:`~webfem.result.Result` of the state ``u`` of ``problem``."""
    ro = read_out(case, problem, u, prm)
    facts = disc.facts(case, problem, u, prm, options, ro)
    warnings = list(_warnings(case, options)) + list(facts.warnings) + list(mesh_error.notes)
    tail = tail_warning(case, float(prm.H_c * case.h_scale), ro.contact_share)
    warnings.extend(answer_warnings(case, ro.h_min, tail))
    if not info.converged:
        # the last iterate is kept for inspection; its numbers must not pass for an answer
        # wherever the result is read (JSON, a sweep's row, a report)
        warnings.insert(0, f"NOT converged ({info.reason}): the numbers are the last "
                           "iterate's, not an answer")
    shares, t, e = ro.shares, ro.traction, mesh_error.errors
    basis = mesh_error.basis
    if facts.error_edges is not None and e["h_center"] is not None:
        # the cell leaves the web's edges out: a model error, added as fe1d adds its edge
        # leakage (never without a mesh error estimate: no stated error then at all)
        e = {q: v + facts.error_edges for q, v in e.items()}
        basis = f"mesh: {basis}; model: {facts.edges_basis}"
    summary = Summary(
        model=disc.name, h_center=ro.h_center, h_inlet=ro.h_inlet, h_outlet=ro.h_outlet,
        h_min=ro.h_min, x_min=ro.x_min,
        regime=REGIMES[int(np.argmax(shares))], lambda_=case.lam, beta=case.beta,
        eq21_valid=bool(eq21_valid(case.beta, case.lam)),
        converged=bool(info.converged), iterations=int(info.iterations),
        n_dofs=int(problem.n_dofs), solve_time_s=elapsed, residual=float(info.residual),
        h_c=float(prm.H_c * case.h_scale), sigma=case.sigma, share_boundary=shares[0],
        share_mixed=shares[1], share_fluid=shares[2], contact_share=ro.contact_share,
        eps=case.eps, kappa=case.kappa, U=case.U, U_slide=case.U_slide,
        method=options.method, mesh=disc.mesh_text(problem, options),
        warnings=tuple(warnings), adapt_rounds=info.adapt_rounds,
        solver_message=info.reason, T_eff=case.tension_eff,
        bending_stiffness_used=case.bending_used, effects=included(case),
        mu=t["mu"], delta_T=t["delta_T"], mu_film=t["mu_film"], delta_T_film=t["delta_T_film"],
        delta_T_required=t["delta_T_required"], delta_T_available=t["delta_T_available"],
        slip_margin=t["slip_margin"], mu_onset=t["mu_onset"],
        error_h_center=e["h_center"], error_h_min=e["h_min"], error_mu=e["mu"],
        error_contact_share=e["contact_share"], error_basis=basis,
        # no stated errors (estimate = False): no part of them either
        error_edges=facts.error_edges if mesh_error.errors["h_center"] is not None else None,
        resting=ro.compression > 0.0, compression=ro.compression,
        n_cells=facts.n_cells, width_cells=facts.width_cells,
        land_fraction=facts.land_fraction, groove_domain=facts.groove_domain,
        contact_share_lands=facts.contact_share_lands)
    diagnostics = Diagnostics(
        method=options.method, history=tuple(info.history), reason=info.reason,
        continuation=tuple(info.steps), options=options, wrap_h=ro.h,
        wrap_w=ro.wts / prm.beta, wrap_p=ro.p, wrap_dpdx=ro.dpdx, omegas=info.omegas,
        block_iterations=info.block_iterations,
        solver={**start.kept, "problem": disc.kept(problem), "state": u,
                # the answer's own algebraic error bounds where Newton stopped on them
                # (:mod:`webfem.models.algebraic`; None: solved to the tolerance), and
                # those added to the stated errors
                "algebraic": info.algebraic, "algebraic_stated": mesh_error.algebraic})
    return Result(case, summary, node_fields(case, problem, u, prm), diagnostics,
                  disc.film(case, problem, u, prm),
                  restart=disc.state(case, problem, u, start, options, mesh_error.coarse,
                                     refined=mesh_error.rounds > 0))
