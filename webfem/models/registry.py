"""The models webfem offers: name -> (solve function, options type, one-line summary).

The API (:func:`webfem.solve`), the command line's ``--model``/``--opt`` and ``--help`` all
read :data:`MODELS`, so a model's options and defaults are written once, in its options type.

Every solve function has the signature ``solve(case, options, *, initial=None)`` and returns
a :class:`webfem.result.Result` or raises :class:`webfem.errors.ConvergenceError`.

Examples
--------
>>> sorted(MODELS)
['auto', 'closed-form', 'fe1d', 'fe2d', 'fitted']
>>> MODELS["fe1d"].options().level
0
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from ..errors import InputError
from . import auto, closed, fe1d, fe2d, fitted
from .options import (AutoOptions, ClosedFormOptions, FE1DOptions, FE2DOptions,
                      FittedOptions, Options)

__all__ = ["ModelSpec", "MODELS", "model_spec", "make_options"]


@dataclass(frozen=True)
class ModelSpec:
    """One model: its ``name``, ``solve(case, options, *, initial=None)``, its ``options``
    type and a one-line ``summary`` for help texts."""

    name: str
    solve: Callable
    options: type[Options]
    summary: str


MODELS: dict[str, ModelSpec] = {spec.name: spec for spec in (
    ModelSpec("closed-form", closed.solve_case, ClosedFormOptions,
              "the paper's Eq. 21 gap with Eqs. 10-13, 28-31 (~0.5 ms a case; microseconds a "
              "point in solve_many)"),
    ModelSpec("fitted", fitted.solve_case, FittedOptions,
              "a fit of fe2d solutions in the dimensionless groups, errors from a hold-out "
              "set (smooth rollers, inside its domain; ~0.6 ms a case)"),
    ModelSpec("fe1d", fe1d.solve_case, FE1DOptions,
              "1-D finite elements: infinitely wide film coupled to the web (10-100 ms)"),
    ModelSpec("fe2d", fe2d.solve_case, FE2DOptions,
              "2-D film over the wrap with edge leakage, coupled to the 1-D web (0.1-0.5 s)"),
    ModelSpec("auto", auto.solve_case, AutoOptions,
              "the cheapest of the above whose estimated error meets a tolerance"),
)}


def model_spec(name: str) -> ModelSpec:
    """The registered model ``name``, or an input error listing the valid names."""
    if name not in MODELS:
        raise InputError(f"model = {name!r} is not valid: must be one of "
                         + ", ".join(repr(m) for m in MODELS))
    return MODELS[name]


def make_options(model: str, options: Options | dict | None = None, **values) -> Options:
    """The options object of ``model`` from an options object, a dict or keywords."""
    spec = model_spec(model)
    if isinstance(options, Options):
        if not isinstance(options, spec.options):
            raise InputError(f"options of type {type(options).__name__} given for model "
                             f"{model!r}, which takes {spec.options.__name__}")
        return options.replace(**values) if values else options
    return spec.options.from_mapping({**(options or {}), **values})
