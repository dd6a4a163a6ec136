"""Model dispatch: ``solve(case, model=...)`` and ``sweep(sweep, model=...)``."""

from __future__ import annotations

from typing import Callable, Iterator

from .case import Case, CaseError, Sweep
from .errors import ConvergenceError, ValidityWarning  # noqa: F401  (re-exported)
from .models import closed
from .result import Result

__all__ = ["MODELS", "solve", "sweep"]


def _fe1d(case: Case, **options) -> Result:
    from .models import fe1d
    return fe1d.solve(case, **options)


def _fe2d(case: Case, **options) -> Result:
    from .models import fe2d
    return fe2d.solve(case, **options)


def _auto(case: Case, **options) -> Result:
    from .models import auto
    return auto.solve(case, **options)


#: Model names accepted by :func:`solve`, ``--model`` and sweeps.
MODELS: dict[str, Callable[..., Result]] = {"closed-form": closed.solve, "fe1d": _fe1d,
                                            "fe2d": _fe2d, "auto": _auto}


def _model(name: str) -> Callable[..., Result]:
    if name not in MODELS:
        raise CaseError(f"model = {name!r} is not valid: must be one of "
                        + ", ".join(repr(m) for m in MODELS))
    return MODELS[name]


def solve(case: Case, model: str = "closed-form", **options) -> Result:
    """Solve one case with the named model (see :data:`MODELS`).

    ``mesh=PATH`` (FE models): start from the x nodes of a mesh file (metres; e.g. one of
    ``meshes/``) instead of webfem's graded mesh.
    """
    if "mesh" in options:
        from .io.meshes import read_x_nodes
        options = dict(options)
        options["nodes"] = read_x_nodes(options.pop("mesh")) / case.x_scale
    result = _model(model)(case, **options)
    _flag_validity(result)
    return result


#: Mean free path of air at 101325 Pa and 23 C [m]; it scales as 1/p_a.
MEAN_FREE_PATH = 68e-9


def _flag_validity(result: Result) -> None:
    """Add the slip-flow warning where the film is thin against the mean free path, then
    issue every warning of the result as a :class:`ValidityWarning`."""
    import warnings

    s = result.summary
    mfp = MEAN_FREE_PATH * 101325.0 / result.case.air.ambient_pressure
    if 0.0 < s["h_min"] < 10.0 * mfp:
        s.setdefault("warnings", []).append(
            f"h_min = {s['h_min']:.3g} m is below 10 mean free paths of air ({10 * mfp:.3g} m): "
            "slip flow, where the continuum Reynolds equation overestimates the film pressure")
    for text in s.get("warnings", []):
        warnings.warn(text, ValidityWarning, stacklevel=3)


def sweep(spec: Sweep, model: str = "closed-form", progress: Callable | None = None,
          **options) -> Iterator[tuple[str, float, Result]]:
    """Yield ``(series_label, value, result)`` over a sweep.

    The closed form is evaluated for all points of a series at once; FE models solve point by
    point, each started from the previous converged point of its series (continuation). A
    point that fails to converge is yielded with ``converged = False`` (its summary says why)
    and the sweep goes on.
    """
    points = list(spec.points())
    if model == "closed-form":
        results = closed.solve_many([c for _, _, c in points])
        for i, ((label, value, _), res) in enumerate(zip(points, results)):
            if progress:
                progress(i + 1, len(points))
            yield label, value, res
        return
    fn = _model(model)
    previous: dict[str, Result] = {}
    for i, (label, value, case) in enumerate(points):
        try:
            res = fn(case, initial=previous.get(label), **options)
            previous[label] = res
        except ConvergenceError as err:
            # keep the point (marked converged = False) and go on from a cold start
            res = err.result
            previous.pop(label, None)
        if progress:
            progress(i + 1, len(points))
        yield label, value, res
