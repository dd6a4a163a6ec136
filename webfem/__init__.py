"""webfem: air entrainment and traction between a moving web and a roller.

Public face: :class:`Case`, :func:`load_case`, :func:`solve`, :func:`sweep`.

>>> import webfem
>>> r = webfem.solve(webfem.Case(), model="closed-form")
>>> sorted(webfem.SUMMARY_KEYS)[:3]
['beta', 'converged', 'delta_T']
"""

from .case import Case, CaseError
from .sweepspec import Sweep
# a case file or a bundled case's name ("base"), as webfem.solve takes
from .bundled import load_case, load_sweep
from .errors import ConvergenceError, InputError, ValidityWarning
from .result import Result, SUMMARY_KEYS
from .api import MODELS, solve, solve_along, solve_many, sweep

__all__ = ["Case", "CaseError", "InputError", "ConvergenceError", "ValidityWarning",
           "load_case", "load_sweep", "Sweep", "Result", "SUMMARY_KEYS", "MODELS", "solve",
           "solve_along", "solve_many", "sweep"]
__version__ = "0.2.0"
