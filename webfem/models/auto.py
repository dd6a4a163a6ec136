"""Automatic model choice: the cheapest model whose estimated error meets the tolerance.

Candidates, cheapest first, each with an error estimate against the converged 2-D solution
(the reference of the studies):

1. **closed form** (microseconds). Rejected outside Eq. 21's range (beta > 6, lambda > 7) and
   where the web lands on the roller (the closed form clamps h to 0, the FE models carry the
   load on the asperities at h ~ h_c, and their mu differ by up to the boundary/mixed jump).
   All estimates are doubled (:data:`SAFETY`).
   Otherwise its error is estimated by re-evaluating the closed form with its fitted gap
   R eps^(2/3) (0.589 - 1.614/lambda + 1.764/lambda^2) replaced by the wide-web limit
   0.643 R eps^(2/3) (1 - 1.48/lambda) that the 2-D studies measured (Eshel-Elrod's 0.643 and
   edge leakage of 1.48/lambda in the central gap), keeping its permeation term.
2. **fe1d** (about 0.1 s). Its error is the edge leakage it leaves out: the gap scaled by
   (1 - 1.48/lambda) (1.87/lambda for the minimum gap), mu re-evaluated on the scaled gap.
3. **fe2d** (about 1-2 s), the reference: its estimated error is the mesh error measured in the
   convergence study (below 1e-4 on the default mesh).

The estimate is for ``quantity`` ("mu", "h_center" or "h_min"), relative, and must be within
``tol`` (default: mu within 1 %). The result is the chosen model's, with ``model = "auto"``,
``model_used``, ``estimated_error`` and ``why`` added.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..case import Case
from ..errors import NoAdmissibleSolution
from ..physics import closed_form as cf
from ..physics.contact import contact_pressure
from ..physics.friction import friction_for
from ..physics.validity import BETA_MAX
from ..result import Result
from . import closed, fe1d, fe2d
from .options import AutoOptions, ClosedFormOptions, FE1DOptions, FE2DOptions, fe_options

__all__ = ["solve", "solve_case", "NAME"]

NAME = "auto"
#: Relative edge-leakage loss of the central and minimum gaps, times lambda (tests/test_fe2d.py).
LEAK_CENTER, LEAK_MIN = 1.48, 1.87
#: Eshel-Elrod's central gap of the infinitely wide foil bearing.
H0_WIDE = 0.643
#: Mesh error of fe2d's default mesh (convergence study: about 2e-5 in the central gap).
FE2D_ERROR = 1e-4
#: The estimates above come from flying-film studies; doubled, they bound the errors measured
#: against the finest 2-D solutions (tests/test_auto.py), where unscaled they fell up to 2x
#: short in mixed lubrication.
SAFETY = 2.0
QUANTITIES = ("mu", "h_center", "h_min")


def _relative(estimate: float, value: float) -> float:
    """|estimate/value - 1|; where nothing slides mu is about 0 and the difference is
    measured against mu_cc instead (a relative error of 0 would be meaningless)."""
    scale = abs(value) if abs(value) > 1e-3 else 1e-3
    return abs(estimate - value) / scale


def _friction(case: Case, h, w, resting=False, p=None, dpdx=None):
    return float(np.sum(friction_for(case, h, resting, p, dpdx)["mu"] * w))


def _onset(case: Case, h, w) -> float:
    """mu_cc times the share of T/R asperity contact carries on gaps ``h`` (weights ``w``
    summing to 1): where nothing slides the headline mu is this onset traction
    (:func:`webfem.physics.effects.traction_summary`), so its estimates compare it, not the
    film's drag."""
    web = case.web
    pc = contact_pressure(h, web.modulus_thickness, case.sigma, web.thickness,
                          case.friction.distribution)
    return case.friction.mu_cc * float(np.sum(np.minimum(pc / case.p_bar, 1.0) * w))


def _closed_estimate(case: Case, r: Result, quantity: str):
    if not r["eq21_valid"]:
        return None, (f"closed form rejected: outside Eq. 21's range (beta = {r['beta']:.3g}, "
                      f"lambda = {r['lambda']:.3g})")
    if r["h_outlet"] <= r["h_c"]:
        return None, ("closed form rejected: its gap falls below h_c in the wrap, where it "
                      "lands the web (h -> 0) and the FE models rest it on the asperities")
    lam = case.lam
    fit = cf.width_factor(lam)
    wide = H0_WIDE * (1.0 - LEAK_CENTER / lam)
    shift = case.h_scale * (wide - fit)              # corrected minus fitted gap [m]
    if quantity == "mu":
        x, h = r.fields["x"], r.fields["h"]
        g, gw = np.polynomial.legendre.leggauss(200)
        s = 0.5 * (g + 1.0) * (x[-1] - x[0]) + x[0]
        hq = np.interp(s, x, h)
        traction = _friction if r["mu_film"] is None else _onset
        est = _relative(traction(case, np.maximum(hq + shift, 0.0), 0.5 * gw), r["mu"])
    elif quantity == "h_min":   # Eq. 21 has no exit constriction: compare with its 0.716
        est = abs((r["h_min"] + shift) * 0.716 / r["h_min"] - 1.0)
    else:
        est = abs(shift / r["h_center"])
    est *= SAFETY
    return est, f"closed form: estimated {quantity} error {est:.2g} (fit against the wide-web " \
                f"gap with 1.48/lambda edge leakage)"


def _fe1d_estimate(case: Case, r: Result, quantity: str):
    lam = case.lam
    if quantity == "mu":
        d = r.diagnostics
        h = d.wrap_h
        # edge leakage lowers a flying film; a web resting on its asperities (h ~ h_c) stays
        lowered = np.maximum(h * (1.0 - LEAK_CENTER / lam), np.minimum(h, r["h_c"]))
        if r["mu_film"] is None:
            est = _relative(_friction(case, lowered, d.wrap_w, True, d.wrap_p, d.wrap_dpdx),
                            r["mu"])
        else:   # nothing slides: the onset traction moves with the contact the gap leaves
            est = _relative(r["mu"] + _onset(case, lowered, d.wrap_w)
                            - _onset(case, h, d.wrap_w), r["mu"])
    else:
        est = (LEAK_CENTER if quantity == "h_center" else LEAK_MIN) / lam
    est *= SAFETY
    return est, f"fe1d: estimated {quantity} error {est:.2g} (edge leakage ~1.5/lambda left out)"


def solve_case(case: Case, options: AutoOptions, *, initial: Result | None = None,
               raise_on_failure: bool = True) -> Result:
    """Solve with the cheapest model whose estimated relative error in ``options.quantity``
    is within ``options.tol``. The FE options go to the FE model that is used; ``initial``
    is accepted for sweeps and not used (each point picks its model afresh)."""
    quantity, tol = options.quantity, options.tol
    why = []
    if case.grooved:   # only the 2-D film carries the grooves across the width
        r = fe2d.solve_case(case, fe_options(options, FE2DOptions),
                            raise_on_failure=raise_on_failure)
        return _answer(r, FE2D_ERROR, quantity, tol,
                       ["grooved roller: only fe2d solves the land and groove film"])
    r = closed.solve_case(case, ClosedFormOptions(), raise_on_failure=False)
    no_answer = closed.no_answer(r)    # never returned: it is not an answer
    if case.beta > BETA_MAX:   # beyond the FE meshes: the web rests on its asperities
        if no_answer:
            raise NoAdmissibleSolution(f"no admissible closed-form answer: {no_answer}")
        return _answer(r, None, quantity, tol,
                       [f"the wrap is {case.beta:.4g} entry lengths long (> {BETA_MAX:g}), "
                        "beyond the FE models; the air film is negligible: closed form"])
    est, text = (None, f"closed form has no answer: {no_answer}") if no_answer else \
        _closed_estimate(case, r, quantity)
    why.append(text)
    if est is None or est > tol:
        r = fe1d.solve_case(case, fe_options(options, FE1DOptions),
                            raise_on_failure=raise_on_failure)
        est, text = _fe1d_estimate(case, r, quantity)
        why.append(text)
        if est > tol:
            r = fe2d.solve_case(case, fe_options(options, FE2DOptions),
                                raise_on_failure=raise_on_failure)
            est = FE2D_ERROR
            why.append(f"fe2d: the reference; mesh error about {FE2D_ERROR:g}")
    return _answer(r, est, quantity, tol, why)


def _answer(r: Result, est, quantity, tol, why) -> Result:
    """The chosen model's result, saying which model answered and why."""
    used = r["model"]
    summary = r.summary.replace(model=NAME, model_used=used, estimated_error=est,
                                quantity=quantity, tolerance=tol,
                                why="; ".join(why) + f" -> {used}")
    return dataclasses.replace(r, summary=summary)


def solve(case: Case, options: AutoOptions | None = None, *, initial=None,
          raise_on_failure: bool = True, **values) -> Result:
    """:func:`solve_case` with the options as keywords (``quantity``, ``tol``, and any FE
    option for the model used)."""
    options = options.replace(**values) if options is not None else \
        AutoOptions.from_mapping(values)
    return solve_case(case, options, initial=initial, raise_on_failure=raise_on_failure)
