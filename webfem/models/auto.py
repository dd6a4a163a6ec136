"""Automatic model choice: the cheapest model whose stated errors meet the tolerance.

Every model states its error per quantity a user reads (the summary keys ``error_h_center``,
``error_h_min``, ``error_mu``, ``error_contact_share``): the closed form and fe1d their model
error against the 2-D film (:mod:`webfem.models.model_error`) plus, for fe1d, its mesh error;
fe2d, the reference, its mesh error (:mod:`webfem.models.mesh_error`). Candidates, cheapest
first:

1. **closed form** (microseconds), unless outside Eq. 21's range (beta > 6, lambda > 7) or
   where its gap falls below h_c in the wrap (with the friction from the loads it rests the
   web at h_c, the asperities carrying all of T/R; with the paper's physics Eq. 21 lands it
   at h = 0; the FE models share the load with the film and dip below h_c at the exit). Eq. 21 has no exit constriction, so its h_min is never
   within a tolerance below about 0.5: it answers only where mu (``quantity = "mu"``) or the
   central gap is the question.
2. **fitted** (about 0.1 ms): a fit of fe2d solutions in the dimensionless groups
   (:mod:`webfem.models.fitted`), inside its domain (smooth rollers, the default full physics,
   the groups' box), judged on the errors its hold-out set states for the point's region.
3. **fe1d** (tens of milliseconds): infinitely wide, so its gaps are off by the edge leakage
   (about 1.5/lambda).
4. **fe2d** (about 0.3 s), the reference.

With ``quantity = "all"`` (the default) each of the four errors must be within ``tol``;
otherwise only the named one. The FE models refine their meshes until their mesh error
estimates meet :data:`~webfem.models.options.MESH_SHARE` (a quarter) of ``tol``, unless
``error_tol`` is given. The result is the chosen model's, with ``model = "auto"``,
``model_used``, ``estimated_error`` (the largest judged error), ``why`` and the chosen
model's ``error_*`` keys.
"""

from __future__ import annotations

import dataclasses

from ..case import Case
from ..errors import ConvergenceError, NoAdmissibleSolution
from ..fem.scaling import FoilParameters
from ..physics.validity import BETA_MAX
from ..result import Result
from . import closed, fe1d, fe2d, fitted
from .options import (AutoOptions, ClosedFormOptions, FE1DOptions, FE2DOptions, FittedOptions,
                      fe_options)
from .readout import READ_QUANTITIES

__all__ = ["solve", "solve_case", "NAME", "judged", "stated_errors"]

NAME = "auto"
_LABEL = {"h_center": "h_center", "h_min": "h_min", "mu": "mu",
          "contact_share": "contact share"}


def judged(quantity: str) -> tuple[str, ...]:
    """The quantities whose errors the choice bounds."""
    return READ_QUANTITIES if quantity == "all" else (quantity,)


def stated_errors(r: Result) -> dict[str, float | None]:
    """A result's stated error per quantity (None where it states none)."""
    return {q: r.summary.get(f"error_{q}") for q in READ_QUANTITIES}


def _verdict(name: str, errors: dict, quantities, tol: float) -> tuple[bool, str]:
    """Whether the errors meet ``tol`` in every judged quantity, and the text saying so."""
    missing = [q for q in quantities if errors.get(q) is None]
    if missing:
        return False, f"{name}: no error estimate of {', '.join(_LABEL[q] for q in missing)}"
    worst = max(quantities, key=lambda q: errors[q])
    ok = errors[worst] <= tol
    return ok, (f"{name}: estimated {_LABEL[worst]} error {errors[worst]:.2g} "
                f"{'<=' if ok else '>'} {tol:g}")


def solve_case(case: Case, options: AutoOptions, *, initial: Result | None = None,
               raise_on_failure: bool = True) -> Result:
    """Solve with the cheapest model whose stated errors meet ``options.tol`` in the
    judged quantities. The FE options go to the FE model that is used; ``initial`` is
    accepted for sweeps and not used (each point picks its model afresh)."""
    quantities, tol = judged(options.quantity), options.tol
    fe2d_options = fe_options(options, FE2DOptions)
    if case.grooved:   # only the 2-D film carries the grooves across the width
        if options.edge_tol is None:
            # the periodic cell answers where the web's edges change it by at most tol
            fe2d_options = fe2d_options.replace(edge_tol=tol)
        why = ["grooved roller: only fe2d solves the land and groove film"]
        return _answer(_fe2d(case, fe2d_options, raise_on_failure, quantities, tol, why),
                       quantities, tol, why)
    why = []
    if case.beta > BETA_MAX:   # beyond the FE meshes: the web rests on its asperities
        r = _closed(case)
        if closed.no_answer(r):
            raise NoAdmissibleSolution(
                f"the wrap is {case.beta:.4g} entry lengths long (> {BETA_MAX:g}), beyond "
                f"the FE models, and no admissible closed-form answer: {closed.no_answer(r)}")
        return _answer(r, quantities, tol,
                       [f"the wrap is {case.beta:.4g} entry lengths long (> {BETA_MAX:g}), "
                        "beyond the FE models; the air film is negligible: closed form"])
    r = _closed(case)
    ok, text = _closed_verdict(r, quantities, tol)
    why.append(text)
    if ok:
        return _answer(r, quantities, tol, why)
    ok, text, r = _fitted(case, quantities, tol)
    why.append(text)
    if ok:
        return _answer(r, quantities, tol, why)
    # an fe1d that does not converge is not the end: fe2d has its own remedies (the 2-D
    # film's start and continuation), and its failure is the one reported
    r = fe1d.solve_case(case, fe_options(options, FE1DOptions), raise_on_failure=False)
    if r.summary.converged:
        ok, text = _verdict("fe1d", stated_errors(r), quantities, tol)
        why.append(text + (" (edge leakage left out: ~1.5/lambda, more where permeation "
                           "drains the film down the wrap)"
                           if FoilParameters.from_case(case).K > 0.0
                           else " (edge leakage ~1.5/lambda left out)"))
        if ok:
            return _answer(r, quantities, tol, why)
    else:
        why.append(f"fe1d: did not converge ({r.summary.solver_message})")
    r = _fe2d(case, fe2d_options, raise_on_failure, quantities, tol, why)
    _, text = _verdict("fe2d", stated_errors(r), quantities, tol)
    return _answer(r, quantities, tol, why + [text + " (the reference: its mesh error)"])


def _fe2d(case: Case, options: FE2DOptions, raise_on_failure: bool, quantities, tol,
          why) -> Result:
    """fe2d's result; where it does not converge, the error's last iterate says, as an
    answer would, that auto used fe2d and why (``model_used``, ``why``), and that it failed."""
    try:
        return fe2d.solve_case(case, options, raise_on_failure=raise_on_failure)
    except ConvergenceError as err:
        if err.result is not None:
            err.result = _answer(err.result, quantities, tol,
                                 [*why, f"fe2d: did not converge "
                                        f"({err.result.summary.solver_message})"])
        raise


def _closed(case: Case) -> Result:
    """The closed form's result with its stated errors; a point where it has no answer as
    a result with ``converged = False`` and the reason (:func:`closed.no_answer`), never
    returned as an answer."""
    return closed.solve_case(case, ClosedFormOptions(), raise_on_failure=False)


def _fitted(case: Case, quantities, tol) -> tuple[bool, str, Result | None]:
    """Whether the fitted model answers within ``tol``, the text saying so, its result.
    Outside its domain (or without its coefficients) it is passed over."""
    try:
        r = fitted.solve_case(case, FittedOptions())
    except fitted.OutsideDomain as err:
        return False, f"fitted: {str(err).removeprefix('no fitted answer: ')}", None
    except NoAdmissibleSolution as err:
        return False, f"fitted: {err}", None
    ok, text = _verdict("fitted", stated_errors(r), quantities, tol)
    return ok, text + " (hold-out)", r


def _closed_verdict(r: Result, quantities, tol) -> tuple[bool, str]:
    s = r.summary
    if closed.no_answer(r):
        return False, f"closed form: no answer ({closed.no_answer(r)})"
    if not s.eq21_valid:
        return False, (f"closed form rejected: outside Eq. 21's range (beta = {s.beta:.3g}, "
                       f"lambda = {s.lambda_:.3g})")
    if s.h_outlet <= s.h_c:
        return False, "closed form rejected: " + _landed_text(r.case, s)
    return _verdict("closed form", stated_errors(r), quantities, tol)


def _landed_text(case: Case, s) -> str:
    """Why a closed form whose gap falls below h_c is not trusted, true for its physics: with
    the friction from the loads it rests the web at h_c, with the paper's it keeps Eq. 21's
    gap, clamped at 0 where it lands the web."""
    if case.friction_variant == "loads":
        return ("its gap falls below h_c in the wrap, where it rests the web at h_c on "
                "asperities carrying all of T/R; the FE models share the load with the film "
                "and dip below h_c at the exit")
    if s.h_outlet <= 0.0:
        return ("its gap falls below h_c in the wrap, where Eq. 21 lands the web (h -> 0, "
                "clamped as the paper prints it) and the FE models rest it on the asperities "
                "at h_c")
    return ("its gap falls below h_c in the wrap, where it keeps Eq. 21's gap as the paper "
            "prints it and the FE models rest the web on the asperities at h_c")


def _answer(r: Result, quantities, tol, why) -> Result:
    """The chosen model's result, saying which model answered and why."""
    used = r["model"]
    errors = stated_errors(r)
    known = [errors[q] for q in quantities if errors[q] is not None]
    summary = r.summary.replace(model=NAME, model_used=used,
                                estimated_error=max(known) if known else None,
                                quantity="all" if len(quantities) > 1 else quantities[0],
                                tolerance=tol, why="; ".join(why) + f" -> {used}")
    return dataclasses.replace(r, summary=summary)


def solve(case: Case, options: AutoOptions | None = None, *, initial=None,
          raise_on_failure: bool = True, **values) -> Result:
    """:func:`solve_case` with the options as keywords (``quantity``, ``tol``, and any FE
    option for the model used)."""
    options = options.replace(**values) if options is not None else \
        AutoOptions.from_mapping(values)
    return solve_case(case, options, initial=initial, raise_on_failure=raise_on_failure)
