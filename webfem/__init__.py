"""webfem: air entrainment and traction between a moving web and a roller.

Public face: :class:`Case`, :func:`load_case`, :func:`solve`, :func:`sweep`.

>>> import webfem
>>> r = webfem.solve(webfem.Case(), model="closed-form")
>>> sorted(webfem.SUMMARY_KEYS)[:3]
['beta', 'converged', 'delta_T']
"""

from .case import Case, CaseError, load_case, load_sweep
from .result import Result, SUMMARY_KEYS
from .api import MODELS, solve, sweep

__all__ = ["Case", "CaseError", "load_case", "load_sweep", "Result", "SUMMARY_KEYS", "MODELS",
           "solve", "sweep"]
__version__ = "0.1.0"
