"""The domain across the width of a grooved roller, chosen by what the web's edges do, and
what a grooved answer says of its web (its sag into the grooves).

With ``grooves = "auto"`` (the default) :func:`solve_grooved` solves

* the **full width** of a web too narrow for an edge strip (:func:`webfem.fem.grooves.
  strip_width` in from each edge: at least 4 pitches and 8 entry lengths R eps^(1/3), 24
  where the grooves do not vent), started from the periodic cell's web;
* otherwise the **periodic cell** first (cheap) and reads from it how much the grooves vent
  (their pressure against the lands') and how much of the load the film carries; from these
  :func:`webfem.fem.grooves.edge_effect` estimates how much the web's edges would change the
  cell's answer. The cell's stated errors include that estimate doubled (:func:`edge_error`,
  the convention of every model error, :data:`~webfem.models.model_error.SAFETY`), so the
  cell answers where the doubled estimate and the mesh error it may keep (``error_tol``)
  are within ``edge_tol`` together (auto's ``tol``, 1 %: :func:`cell_answers`); else the
  **edge strip**: the outer lands and grooves of each half solved, the periodic
  interior standing in as the strip's innermost land and groove, weighted (:class:`webfem.
  fem.film_problem.FilmConfig`), so a web of any width costs what a narrow one does.

The summary's ``groove_domain`` says which, the estimate and its parts, and for the strip the
change from the cell's answer it measured.
"""

from __future__ import annotations

import dataclasses
import math
import time
from typing import Callable

import numpy as np

from ..case import Case
from ..errors import NoAdmissibleSolution
from ..fem.grooves import EDGE_ZONE, POISSON, SAG_SHARE, GroovePattern, choose_domain, \
    edge_effect, strip_start, strip_width, web_sag
from ..result import Result
from .model_error import SAFETY
from .options import FE2DOptions
from .readout import read_out

__all__ = ["solve_grooved", "sag_warning", "domain_text", "venting", "edge_error",
           "cell_answers"]


def edge_error(estimate: float) -> float:
    """The model error a periodic cell's stated errors include for the web's edges it
    leaves out: :func:`~webfem.fem.grooves.edge_effect`'s ``estimate`` times
    :data:`~webfem.models.model_error.SAFETY`, alike for h_center, h_min, mu and the contact
    share (the estimate was measured against the largest change of the four). As fe1d's
    edge leakage: the estimate is a measured law, doubled for what it was not measured on.

    >>> edge_error(0.004)
    0.008
    """
    return SAFETY * estimate


def cell_answers(estimate: float, options: FE2DOptions) -> bool:
    """Whether the periodic cell answers under ``grooves = "auto"``: its stated error, the
    edges' :func:`edge_error` plus a mesh error up to ``error_tol``, within ``edge_tol``.
    Why not the estimate alone against ``edge_tol``: the cell then answered with stated
    errors that left the edges out (base_grooved: 2.6e-4 stated in h_min, 0.9 % off the
    full width's)."""
    return edge_error(estimate) <= options.edge_tol - options.error_tol


def venting(case: Case, result: Result) -> float:
    """1 - the groove pressure over the land pressure over the wrap, of a solved grooved
    ``result`` (1: the grooves are at ambient, 0: they hold the lands' pressure)."""
    return _venting(case, result.state("problem"), result.state("state"))


def _venting(case: Case, problem, u) -> float:
    X = np.linspace(-0.5 * case.beta, 0.5 * case.beta, 201)
    return 1.0 - problem.groove_pressure_ratio(u, X)


def _cell_estimated(case: Case, pattern: GroovePattern, options: FE2DOptions, narrow: bool):
    """Whether the periodic cell's answer (``problem``, ``u``) gets its mesh error estimate:
    only where it is the answer, i.e. the web is not narrow and the edges' estimate from
    that state (:func:`edge_effect`, as :func:`solve_grooved` reads it from the result) is
    within ``edge_tol``. Elsewhere the cell only starts the strip or the full width and
    its estimate, refining towards ``error_tol``, is work for nothing: 45-50 s of a PET
    and a board cell (bisected up to 0.19-0.21 M unknowns) before strips that started from
    the cell's web on their own, coarser x meshes anyway."""
    def wanted(problem, u, prm) -> bool:
        return not narrow and _domain(case, pattern, options, _venting(case, problem, u),
                                      read_out(case, problem, u, prm).contact_share)[0] == "cell"
    return wanted


def _domain(case: Case, pattern: GroovePattern, options: FE2DOptions, vent: float,
            contact_share: float | None) -> tuple[str, dict]:
    """The domain auto solves after a converged periodic cell whose venting is ``vent`` and
    contact share ``contact_share``, and why (:func:`domain_text`'s keywords): the cell
    where its stated error with the edges' estimate (:func:`edge_effect`) is within
    ``edge_tol`` (:func:`cell_answers`)."""
    vent = min(max(vent, 0.0), 1.0)
    film = 1.0 - (contact_share or 0.0)
    why = {"vent": vent, "film": film, "tol": options.edge_tol, "error_tol": options.error_tol,
           "estimate": edge_effect(case.lam, pattern.pitch, vent, film)}
    if cell_answers(why["estimate"], options):
        return "cell", why
    return choose_domain("strip", pattern, case.lam, vent), why


def domain_text(case: Case, domain: str, pattern: GroovePattern, **why) -> str:
    """The summary's ``groove_domain``: the domain and why (``why``: ``estimate``, ``vent``,
    ``film``, ``tol`` (edge_tol), ``error_tol`` (auto's choice: why the cell did not answer),
    ``width`` (the strip's, scaled), ``cell`` (the cell's result))."""
    pitch = case.roller.groove_pitch
    spans = f"the web spans {case.web.width / pitch:.3g} groove pitches"
    est = why.get("estimate")
    said = "" if est is None else (
        f"the web's edges estimated to change the periodic cell's answer by {est:.3g} "
        f"(edge zone {_zone_mm(case, pattern, why['vent']):.3g} mm, the grooves venting "
        f"{100 * why['vent']:.0f} % of the lands' pressure, the film carrying "
        f"{100 * why['film']:.0f} % of the load)")
    if said and domain != "cell" and why.get("error_tol") is not None:
        said += (f"; twice it ({edge_error(est):.3g}) with error_tol = {why['error_tol']:g} "
                 f"above edge_tol = {why['tol']:g}: the cell's stated errors would miss it")
    elif said:
        said += f"; edge_tol = {why['tol']:g}"
    if domain == "cell":
        return (f"periodic cell: {spans}; " + (
            said + f": left out, and {edge_error(est):.3g} (twice the estimate) added to "
            "each stated error" if said else "the web's edges are left out") +
                " (grooves = \"strip\" or \"full\" solves them)")
    if domain == "strip":
        width = why["width"] * case.x_scale
        z_c = strip_start(pattern, case.lam, why["width"]) * case.x_scale
        text = (f"edge strip: {spans}; the outer {1e3 * (0.5 * case.web.width - z_c):.3g} mm "
                f"of each half solved with its edge lands (at least {1e3 * width:.3g} mm), "
                "the periodic interior as its innermost land and groove, weighted")
        cell = why.get("cell")
        if said:
            text += "; " + said
        if cell is not None:
            text += "; " + _change(cell, why["answer"])
        return text
    full = f"full width: {spans}, edge lands included"
    if why.get("narrow"):
        return full + " (too narrow for an edge strip)" + (
            f"; {_change(why['cell'], why['answer'])}" if why.get("cell") is not None else "")
    return full + (f"; {said}" if said else "") + (
        f"; {_change(why['cell'], why['answer'])}" if why.get("cell") is not None else "")


def _zone_mm(case: Case, pattern: GroovePattern, vent: float) -> float:
    return 1e3 * case.x_scale * (EDGE_ZONE * (1.0 - vent) + pattern.pitch * vent)


def _change(cell: Result, answer: Result) -> str:
    """What the edges changed, measured: the strip's answer against the cell's."""
    parts = []
    for key in ("h_center", "h_min"):
        parts.append(f"{key} {100 * (answer[key] / cell[key] - 1):+.2g} %")
    scale = max(abs(cell["mu"]), 0.1 * cell.case.friction.mu_cc)
    parts.append(f"mu {100 * (answer['mu'] - cell['mu']) / scale:+.2g} %")
    return "against the periodic cell: " + ", ".join(parts)


def solve_grooved(case: Case, pattern: GroovePattern, options: FE2DOptions,
                  solve: Callable[..., Result]) -> Result:
    """``grooves = "auto"``: the domain chosen as the module text says, solved with
    ``solve(options, raise_on_failure[, cell])`` (``cell``: the periodic cell's answer, which
    may start the strip's or the full width's solve). The result's ``groove_domain`` says
    which and why; its ``solve_time_s`` includes the periodic cell's solve."""
    t0 = time.perf_counter()
    narrow = choose_domain("auto", pattern, case.lam) == "full" and \
        choose_domain("auto", pattern, case.lam, vent=1.0) == "full"
    try:
        # a narrow web's full width too starts from the cell's web (issue 23: on the groove
        # map's narrow designs at 40 m/s the direct Newton from the 1-D web failed and the
        # depth continuation took 8-13 s; from the cell's web 2-5 s, the same answers)
        cell = solve(options.replace(grooves="cell"), False,
                     estimate_if=_cell_estimated(case, pattern, options, narrow))
    except NoAdmissibleSolution:
        cell = None           # the strip or the full width decide
    if narrow:
        r = solve(options.replace(grooves="full"), True, cell)
        return _said(r, domain_text(case, "full", pattern, narrow=True, cell=_converged(cell),
                                    answer=r), t0)
    if cell is not None and cell.summary.converged:
        domain, why = _domain(case, pattern, options, venting(case, cell),
                              cell["contact_share"])
    else:
        cell, why = None, {"vent": 0.0}
        domain = choose_domain("auto", pattern, case.lam, 0.0, None, options.edge_tol)
    if domain == "cell":
        return _said(cell, domain_text(case, "cell", pattern, **why), t0)
    width = strip_width(pattern.pitch, why["vent"])
    r = solve(options.replace(grooves=domain, strip_width=width if domain == "strip"
                              else None), True, cell)
    return _said(r, domain_text(case, domain, pattern, width=width, cell=cell, answer=r,
                                **why), t0)


def _converged(cell: Result | None) -> Result | None:
    return cell if cell is not None and cell.summary.converged else None


def _said(r: Result, text: str, t0: float) -> Result:
    summary = r.summary.replace(groove_domain=text, solve_time_s=time.perf_counter() - t0)
    return dataclasses.replace(r, summary=summary)


def sag_warning(case: Case, h_min: float) -> str:
    """The warning of a web that sags into its grooves by more than :data:`~webfem.fem.
    grooves.SAG_SHARE` of the larger of the smallest land gap ``h_min`` [m] and the
    roughness sigma ("" otherwise): webfem holds the web flat across the width. The sag is
    :func:`~webfem.fem.grooves.web_sag` under the wrap pressure T_eff/R, with E =
    web.modulus_md (the only modulus a case gives). h_min, not the wrap's mean land gap: the
    smallest gap is where the asperities, and so the traction, are most sensitive to a change
    of the gap. The scale is never below sigma: a gap below the roughness matters through the
    contact, which changes on the scale of sigma (webfem's error measures take gaps against
    max(h, sigma) for the same reason), and the rule is continuous in h_min: a web 0.01 um
    above its asperities and one resting at -0.01 um are judged alike (a resting web sagging
    1.1 um into 2.5 mm grooves, h_min -0.03 um, sigma 4 um, is warned of)."""
    w, g = case.web, case.roller.groove_width
    sag = web_sag(case.p_bar, g, w.modulus_md, w.thickness)
    # a gap that is not a number (no answer) is judged against sigma alone
    scale = max(h_min, case.sigma) if math.isfinite(h_min) else case.sigma
    if not (scale > 0.0) or sag <= SAG_SHARE * scale:
        return ""
    D = w.modulus_md * w.thickness ** 3 / (12.0 * (1.0 - POISSON ** 2))
    where = (f"the web resting on its asperities (h_min = {h_min * 1e6:.3g} um)"
             if h_min <= 0.0 else f"above the smallest land gap h_min = {h_min * 1e6:.3g} um")
    against = (f"the smallest land gap h_min = {h_min * 1e6:.3g} um" if h_min > case.sigma
               else f"the roughness sigma = {case.sigma * 1e6:.3g} um, {where}")
    return (f"the web sags into its {g * 1e3:.3g} mm grooves by about {sag * 1e6:.2g} um "
            f"({100 * sag / scale:.3g} % of {against}, "
            f"> {100 * SAG_SHARE:.0f} %): p g^4/(384 D) under the wrap pressure T/R = "
            f"{case.p_bar:.4g} Pa, held flat on the lands (free to turn there: "
            f"{5 * sag * 1e6:.2g} um), D = E t^3/(12(1 - nu^2)) = {D:.3g} N m with "
            f"E = web.modulus_md = {w.modulus_md:.3g} Pa, t = {w.thickness * 1e6:.3g} um, "
            f"nu = {POISSON:g}; webfem holds the web flat across the width and does not model "
            "it bending into its grooves: the film over the land edges is not what it "
            "computes (narrower grooves or a thicker web keep the sag small)"
            + _floor_text(sag, case.roller.groove_depth,
                          max(h_min, 0.0) if math.isfinite(h_min) else 0.0))


def _floor_text(sag: float, depth: float, gap: float) -> str:
    """What a sag at least the way down to the groove's floor means (its ``depth`` [m] below
    the lands, plus the web's ``gap`` above them), clamped (``sag``) or free to turn on the
    lands (5 x): the web reaches the floor and the groove no longer vents ("" when it stays
    above the floor either way)."""
    room = depth + gap
    if 5.0 * sag < room:
        return ""
    how = "held flat on the lands" if sag >= room else "if free to turn on the lands"
    return (f"; {how} the web would reach the groove's floor ({room * 1e6:.3g} um down: "
            f"roller.groove_depth = {depth * 1e6:.3g} um below the lands, the web "
            f"{gap * 1e6:.3g} um above them): the groove is closed, not a vent, and the "
            "answer does not describe that roller")
