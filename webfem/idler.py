"""Will an idler slip? The slip margin of an undriven roller against line speed.

An idler turns with the web (U_r = U_w): :func:`margin_curve` solves the case at line speeds
``speeds`` with both speeds set to each one, through the one continuation loop, and returns
the traction needed and available at each (:func:`webfem.physics.effects.idler_check`), and
where an answer's contact comes from the exponential heights' tail beyond any surface
(:func:`webfem.physics.contact.beyond_the_surface`), its warning: each speed's verdict is
the one ``webfem solve`` gives at that speed (:func:`webfem.describe.idler_verdict`).

Examples
--------
>>> from webfem import load_case
>>> curve = margin_curve(load_case("cases/idler.toml"), [5.0, 15.0], "closed-form")
>>> [round(m, 2) for m in curve.slip_margin]
[6.39, 0.02]
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import Callable
from dataclasses import dataclass

import numpy as np

from .api import solve, solve_along
from .case import Case
from .errors import ConvergenceError, InputError, ValidityWarning
from .line_speed import at_speed
from .physics.contact import beyond_the_surface, tail_gaussian_gaps, tail_warning
from .physics.effects import margin_range, margin_verdict, states_load

__all__ = ["MarginCurve", "margin_curve", "idler_at_web_speed"]


@dataclass(frozen=True)
class MarginCurve:
    """Line speeds [m/s] and, at each, delta_T required and available [N/m], the slip margin
    (available / required), mu at the onset of slip, whether the solve converged and the
    model that answered (``models_used``: auto may choose per speed; ``model``: the one
    model that answered every speed, else the model asked for)."""

    model: str
    speeds: tuple[float, ...]
    delta_T_required: tuple[float, ...]
    delta_T_available: tuple[float, ...]
    slip_margin: tuple[float, ...]
    mu_onset: tuple[float, ...]
    converged: tuple[bool, ...]
    models_used: tuple[str, ...] = ()
    #: The stated error of ``mu_onset`` at each speed (the answer's ``error_mu``: relative to
    #: the larger of |mu| and 0.1 mu_cc) and, from it, the slip margin's range
    #: (:func:`margin_range`); empty for a curve made without them.
    error_mu: tuple[float, ...] = ()
    margin_low: tuple[float, ...] = ()
    margin_high: tuple[float, ...] = ()
    #: Per speed, whether the answer's asperity contact comes from the exponential heights'
    #: tail beyond any surface (:func:`~webfem.physics.contact.beyond_the_surface`: h_c above
    #: 5 sigma carrying at least 0.5 % of the load), and that answer's warning (None where
    #: it does not apply); empty for a curve made without them.
    exponential_tail: tuple[bool, ...] = ()
    tail_warnings: tuple[str | None, ...] = ()

    #: The columns of :meth:`rows` (and of ``webfem idler --out``'s CSV), SI units:
    #: ``verdict`` as :meth:`verdicts`, ``exponential_tail`` as the field.
    COLUMNS = ("speed", "delta_T_required", "delta_T_available", "slip_margin", "mu_onset",
               "converged", "model_used", "error_mu", "margin_low", "margin_high", "verdict",
               "exponential_tail")

    def to_dict(self) -> dict:
        """The fields, JSON-safe (a speed without an answer has None for its numbers)."""
        from .summary import plain
        return {k: plain(v) for k, v in self.__dict__.items()}

    def rows(self) -> list[dict]:
        """One row per line speed, keyed by :attr:`COLUMNS` (``speed`` [m/s] is the line
        speed, U_r = U_w)."""
        used = self.models_used or (self.model,) * len(self.speeds)
        none = (None,) * len(self.speeds)
        return [dict(zip(self.COLUMNS, values)) for values in zip(
            self.speeds, self.delta_T_required, self.delta_T_available, self.slip_margin,
            self.mu_onset, self.converged, used, self.error_mu or none,
            self.margin_low or none, self.margin_high or none, self.verdicts(),
            self.exponential_tail or none)]

    def verdicts(self) -> list[str]:
        """Per speed: ``holds`` (the margin's whole stated range at or above 1), ``SLIPS``
        (all of it below 1), ``unsure`` (the stated error of mu leaves either possible, or
        the margin holds only by the exponential heights' tail: :meth:`tail_unsure`) or
        ``no answer``: the word of a single ``webfem solve`` at that speed
        (:func:`webfem.describe.idler_verdict`)."""
        tail = self.tail_unsure()
        return ["unsure" if t else v for v, t in zip(self._range_verdicts(), tail)]

    def _range_verdicts(self) -> list[str]:
        """Per speed, the verdict of the margin's stated range alone."""
        low = self.margin_low or self.slip_margin
        high = self.margin_high or self.slip_margin
        return [margin_verdict(lo, hi) if ok else "no answer"
                for ok, lo, hi in zip(self.converged, low, high)]

    def tail_unsure(self) -> list[bool]:
        """Per speed, whether it is ``unsure`` only because its margin holds by the
        exponential heights' tail (``exponential_tail``; see ``tail_warnings``): the range
        alone says ``holds``, as :func:`webfem.describe.idler_verdict` judges it."""
        tail = self.exponential_tail or (False,) * len(self.speeds)
        return [v == "holds" and bool(t) for v, t in zip(self._range_verdicts(), tail)]

    def answered(self) -> str:
        """Which model answered: ``fe1d``, or for auto ``auto: fe2d at every speed`` /
        ``auto: fe1d at 3, fe2d at 17 speeds``."""
        used = [m for m in self.models_used if m]
        if not used or set(used) == {self.model}:
            return self.model
        counts = {m: used.count(m) for m in dict.fromkeys(used)}
        if len(counts) == 1:
            return f"{self.model}: {used[0]} at every speed"
        return f"{self.model}: " + ", ".join(f"{m} at {n}" for m, n in counts.items()) \
            + " speeds"

    def slip_extent(self) -> str:
        """Where the answered speeds slip (margin below 1): ``every`` speed tried,
        ``lowest`` (the lowest answered speed, not all of them: where it starts slipping
        lies below the range), ``above`` (it holds at the lowest and slips above
        :meth:`slip_speed`), ``none`` (it holds at every answered speed) or ``unanswered``."""
        ok = np.asarray(self.converged, bool)
        m = np.asarray(self.slip_margin, float)[ok]
        if m.size == 0:
            return "unanswered"
        below = m < 1.0
        return ("every" if below.all() else "lowest" if below[0] else "above" if below.any()
                else "none")

    def slip_speed(self) -> float | None:
        """The first line speed where the margin falls below 1 (linear interpolation), or
        None when the idler holds at every answered speed."""
        # only answers count: an unconverged solve's margin is no evidence either way
        ok = np.asarray(self.converged, bool)
        m = np.asarray(self.slip_margin, float)[ok]
        u = np.asarray(self.speeds, float)[ok]
        below = np.nonzero(m < 1.0)[0]
        if below.size == 0:
            return None
        i = int(below[0])
        if i == 0:
            return float(u[0])
        u0, u1, m0, m1 = u[i - 1], u[i], m[i - 1], m[i]
        return float(u0 + (1.0 - m0) * (u1 - u0) / (m1 - m0))


def margin_curve(case: Case, speeds, model: str = "fe1d", options=None,
                 progress: Callable[[int, int], None] | None = None,
                 **values) -> MarginCurve:
    """The idler's slip margin at each line speed (roller and web at that speed);
    ``progress(done, total)`` is called after each speed the FE models solve."""
    if case.roller.drag_torque <= 0.0 and case.roller.inertia * case.web.acceleration == 0.0:
        raise InputError("the case states no idler load: set roller.drag_torque [N m] or "
                         "roller.inertia [kg m^2] with web.acceleration [m/s^2]")
    speeds = [float(u) for u in speeds]
    # the check is at the onset of slip: the line moves with U_r = U_w (webfem.line_speed)
    cases = [at_speed(case, u, ratio=1.0) for u in speeds]
    keys = ("delta_T_required", "delta_T_available", "slip_margin", "mu_onset")
    if model == "fitted":
        # its domain moves with the speed: a speed outside it has no answer (NaN), the
        # others come from one vectorised evaluation
        from .models import fit_groups as fg
        from .models.fitted import solve_many
        from .models.registry import make_options
        opts = make_options(model, options, **values)
        inside = [fg.outside(c) is None for c in cases]
        answered = iter(solve_many([c for c, ok in zip(cases, inside) if ok], opts))
        results = [next(answered) if ok else None for ok in inside]
    else:
        results = []
        for r in solve_along(cases, model, options, **values):
            results.append(r)
            if progress is not None:
                progress(len(results), len(cases))
    # an unconverged answer, or one made without an estimate, states no error: NaN
    pick = {k: tuple(float(r[k]) if r is not None and r[k] is not None else math.nan
                     for r in results)
            for k in keys + ("error_mu",)}
    ranges = [margin_range(c, r["delta_T_required"], r["mu_onset"], r["error_mu"])
              if r is not None else (math.nan, math.nan) for c, r in zip(cases, results)]
    used = tuple((r.summary.model_used or r["model"]) if r is not None else model
                 for r in results)
    converged = tuple(r is not None and bool(r["converged"]) for r in results)
    tail, said = _tails(cases, results, converged)
    return MarginCurve(model, tuple(speeds), converged=converged,
                       models_used=used, margin_low=tuple(lo for lo, _ in ranges),
                       margin_high=tuple(hi for _, hi in ranges), exponential_tail=tail,
                       tail_warnings=said, **pick)


def _tails(cases, results, converged):
    """Per speed, whether the answer's contact comes from the exponential heights' tail
    (:func:`~webfem.physics.contact.beyond_the_surface`, judged on its h_c and contact share
    as :func:`webfem.describe.idler_verdict` judges a single solve) and its warning, the
    Gaussian h_c of every warning solved at once."""
    def read(r, ok, key):
        return float(r[key]) if ok and r[key] is not None else math.nan
    h_c = [read(r, ok, "h_c") for r, ok in zip(results, converged)]
    share = [read(r, ok, "contact_share") for r, ok in zip(results, converged)]
    tail = tuple(bool(ok and beyond_the_surface(c, h, s))
                 for c, h, s, ok in zip(cases, h_c, share, converged))
    gaps = tail_gaussian_gaps(cases, h_c, share)
    said = tuple(tail_warning(c, h, s, g) if t else None
                 for c, h, s, g, t in zip(cases, h_c, share, gaps, tail))
    return tail, said


def idler_at_web_speed(result, model: str = "auto", options=None):
    """``result`` with the idler keys of an idler at its web speed, where its web slides.

    An idler turns with the web (U_r = U_w) and entrains air at 2 U_w; where the case's
    speeds differ its film is another, and the traction at the onset of slip read from it
    is no idler's (the models leave ``mu_onset``, ``delta_T_available`` and ``slip_margin``
    None there). This solves the case again with ``model`` at U_r = U_w (as costly as the
    first solve for the FE models) and puts that solve's idler keys into the summary, with
    ``error_mu_onset`` its stated mu error and ``idler_basis`` naming it. Where that solve
    finds no answer ``idler_basis`` says so and the keys stay None. Unchanged where nothing
    slides, no idler load is stated or the web stands still.

    Parameters
    ----------
    result : Result
        A solved case.
    model, options
        As for :func:`webfem.solve`: the second solve's model (auto may pick another than
        the first's; ``idler_basis`` names the one that answered).

    Returns
    -------
    Result
        ``result`` itself, or a copy with the summary's idler keys filled.
    """
    case, s = result.case, result.summary
    if case.U_slide == 0.0 or not states_load(case) or case.web.speed <= 0.0:
        return result
    speed = f"U_r = U_w = {case.web.speed:.4g} m/s"
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)   # its own case's warnings
            other = solve(case.updated({"roller.speed": case.web.speed}), model,
                          options=options).summary
    except (ConvergenceError, InputError) as err:   # NoAdmissibleSolution among them
        basis = f"the second {model} solve at {speed} found no answer ({err})"
        return dataclasses.replace(result, summary=s.replace(idler_basis=basis))
    basis = f"a second {other.model_used or other.model} solve at {speed}"
    # the second solve's warning of contact from the exponential law's tail is the idler's
    tail = tail_warning(case, other.h_c, other.contact_share)
    said = s.warnings + ((tail,) if tail and tail not in s.warnings else ())
    return dataclasses.replace(result, summary=s.replace(
        delta_T_available=other.delta_T_available, slip_margin=other.slip_margin,
        mu_onset=other.mu_onset, error_mu_onset=other.error_mu, idler_basis=basis,
        idler_contact_share=other.contact_share, warnings=said))
