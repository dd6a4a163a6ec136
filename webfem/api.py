"""The public entry points: :func:`solve` one case, :func:`solve_along` a path of cases with
continuation, :func:`sweep` a :class:`webfem.sweepspec.Sweep`.

Models and their options come from :data:`webfem.models.registry.MODELS`; ``model="auto"``,
the default everywhere, picks the cheapest model whose stated errors meet its tolerance. A
case may be given as a :class:`~webfem.case.Case`, a case file or a bundled case's name
(a file in the current folder first). Nothing here writes files.

Examples
--------
>>> import webfem
>>> case = webfem.Case()
>>> [round(r["mu"], 4) for r in solve_along([case.updated({"roller.speed": u})
...                                           for u in (30.0, 40.0)], "closed-form")]
[0.0706, 0.0265]
"""

from __future__ import annotations

import os
import warnings
from typing import Callable, Iterable, Iterator

from .bundled import as_case, find_case
from .case import Case
from .sweepspec import Sweep, load_sweep
from .errors import ConvergenceError, NoAdmissibleSolution, ValidityWarning
from .models.options import Options
from .models.registry import MODELS, make_options, model_spec
from .physics.validity import grooves_text
from .result import Result, refused

__all__ = ["MODELS", "solve", "solve_along", "solve_many", "sweep"]


def solve(case: Case | str | os.PathLike, model: str = "auto", *,
          initial: Result | None = None, options: Options | dict | None = None,
          **values) -> Result:
    """Solve one operating point with the named model.

    Parameters
    ----------
    case : Case, str or path
        The operating point (SI units): a Case, a case file or a bundled case's name.
    model : str
        ``"auto"`` (default: the cheapest model whose stated errors in h_center, h_min, mu
        and the contact share meet ``tol``, 1 %), ``"closed-form"`` (the paper's Eq. 21,
        about 0.5 ms a case), ``"fitted"`` (a fit of fe2d's answers, about 0.6 ms a case;
        smooth rollers inside its domain), ``"fe1d"`` (infinitely wide film + web, 10-100
        ms) or ``"fe2d"`` (2-D film with edge leakage + web, 0.1-0.5 s on realistic cases).
    initial : Result, optional
        A converged result of the same model at a nearby point to start from (continuation).
        The cost depends on it; the answer only within its stated mesh error (fe2d may keep
        the previous point's mesh, moved: :mod:`webfem.models.continued`).
    options : Options or dict, optional
        The model's options (:class:`~webfem.models.options.FE1DOptions`, ...); keywords
        (``level=2, method="picard"``) are the same. Unknown names are errors.

    Returns
    -------
    Result
        ``result["mu"]``, ``result.summary`` (every JSON key), ``result.fields``.

    Raises
    ------
    webfem.errors.InputError
        An unknown model or option, or an option out of its range.
    webfem.errors.ConvergenceError
        No converged, admissible solution; ``err.result`` holds the last iterate.

    Examples
    --------
    >>> import webfem
    >>> r = webfem.solve(webfem.Case(), model="closed-form")
    >>> r["model"], round(r["mu"], 3)
    ('closed-form', 0.219)
    """
    spec = model_spec(model)
    opts = make_options(model, options, **values)
    result = spec.solve(as_case(case), opts, initial=initial)
    for text in result.summary.warnings:
        warnings.warn(text, ValidityWarning, stacklevel=2)
    return result


def solve_along(cases: Iterable[Case], model: str = "auto", options=None, *,
                keep_failures: bool = True, initial: Result | None = None,
                **values) -> Iterator[Result]:
    """Solve cases in order, each started from the previous converged result.

    This is webfem's one continuation loop: sweeps, traction-loss scans and studies walk
    their paths through it. A point that does not converge is yielded as its unconverged
    result (``converged = False``; with ``keep_failures=False`` the ConvergenceError is
    raised instead) and the next point starts cold.
    """
    opts = make_options(model, options, **values)
    previous = initial
    for case in cases:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)   # carried in the result
                result = solve(case, model, initial=previous, options=opts)
        except ConvergenceError as err:
            if not keep_failures or err.result is None:
                raise
            previous = None
            yield err.result
            continue
        previous = result
        yield result


#: The models that cannot solve a grooved roller, as their refusals name them.
GROOVES_REFUSED = {"closed-form": "the closed form", "fe1d": "fe1d"}


def solve_many(cases: Iterable[Case], model: str = "auto", options=None,
               **values) -> list[Result]:
    """Solve many cases at once: the closed form and the fitted model evaluate every point
    in one vectorised call (summaries and their wrap profiles, no film fields); the FE
    models and auto walk them with :func:`solve_along`. ``cases`` holds what :func:`solve`
    takes: Cases, case files or bundled cases' names (a name that is none of these is the
    same InputError as :func:`solve`'s).

    Every model keeps every point, in order: a point it cannot answer (outside the fitted
    model's domain, no closed-form answer, no admissible FE solution) comes back with
    ``converged = False``, the reason in ``solver_message`` and first in ``warnings``, and
    its numbers NaN (:func:`webfem.result.refused`; the closed form the same), so one
    refused point does not lose the others' answers. An FE point that did not converge
    comes back as its last iterate (``converged = False``, numbers kept for inspection, as
    ``ConvergenceError.result`` holds it). A grooved roller given to the closed form or
    fe1d, which solve smooth rollers only, is such a refused point. Input errors (an unknown
    option, a case that does not exist) still raise.

    >>> rs = solve_many([Case().updated({"roller.speed": u}) for u in (20.0, 30.0)],
    ...                 model="closed-form")
    >>> [r["model"] for r in rs]
    ['closed-form', 'closed-form']
    """
    # what solve takes, every model: a Case, a case file or a bundled case's name
    cases = [as_case(c) for c in cases]
    if model in GROOVES_REFUSED and any(c.grooved for c in cases):
        # a grooved roller is a valid point these models cannot solve: refused in place
        make_options(model, options, **values)
        smooth = [i for i, c in enumerate(cases) if not c.grooved]
        out = [refused(c, model, grooves_text(c, GROOVES_REFUSED[model])) if c.grooved
               else None for c in cases]
        for i, r in zip(smooth, solve_many([cases[i] for i in smooth], model, options,
                                           **values) if smooth else ()):
            out[i] = r
        return out  # type: ignore[return-value]
    if model == "closed-form":
        from .models.closed import solve_many as closed_many
        make_options(model, options, **values)          # checked, though none apply
        return closed_many(cases)
    if model == "fitted":
        from .models.fitted import solve_many as fitted_many
        return fitted_many(cases, make_options(model, options, **values))
    opts = make_options(model, options, **values)
    out: list[Result] = []
    while len(out) < len(cases):
        # a refused point ends solve_along's walk: keep it and walk on from the next, cold
        try:
            for result in solve_along(cases[len(out):], model, opts):
                out.append(result)
        except NoAdmissibleSolution as err:
            out.append(refused(cases[len(out)], model, str(err)))
    return out


def sweep(spec: Sweep | str | os.PathLike, model: str = "auto",
          progress: Callable | None = None, options=None,
          **values) -> Iterator[tuple[str, float, Result]]:
    """Yield ``(series_label, value, result)`` over a sweep, in memory.

    ``spec``: a :class:`~webfem.sweepspec.Sweep`, or a case file or bundled case's name with a
    ``[sweep]`` table.

    The closed form is evaluated for all points at once; FE models walk each series with
    continuation (:func:`solve_along`). A point that fails is yielded with
    ``converged = False`` and the sweep goes on. For resumable sweeps written to files see
    :func:`webfem.sweeps.run`.
    """
    if not isinstance(spec, Sweep):
        spec = load_sweep(find_case(spec))
    points = list(spec.points())
    total = len(points)
    if model == "closed-form":
        from .models.closed import solve_many
        results = solve_many([c for _, _, c in points])
        for i, ((label, value, _), res) in enumerate(zip(points, results)):
            if progress:
                progress(i + 1, total)
            yield label, value, res
        return
    done = 0
    for label, base in spec.series:
        values_ = list(spec.values)
        cases = [spec.case_at(base, v) for v in values_]
        for value, res in zip(values_, solve_along(cases, model, options, **values)):
            done += 1
            if progress:
                progress(done, total)
            yield label, value, res
