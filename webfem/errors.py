"""What webfem raises: bad input, no converged solution, and warnings on legal inputs.

* :class:`InputError` (a ``ValueError``; ``CaseError`` is the same class under its old
  name): an input webfem rejects. The message names the key or option, its value and what
  is valid. The command line exits with status 2.
* :class:`ConvergenceError`: no converged, admissible solution was found. The command line
  exits with status 3.
* :class:`ValidityWarning`: a legal input outside a model's validity; the result carries
  the same text in its ``warnings``.
"""

from __future__ import annotations

import difflib
import math
import reprlib
from typing import Any

__all__ = ["InputError", "CaseError", "NoAdmissibleSolution", "ConvergenceError",
           "ValidityWarning", "show", "unknown_name"]


class InputError(ValueError):
    """An input that webfem rejects; the message names the key, its value and the valid range."""


#: The name this error had before options were typed; kept for scripts that catch it.
CaseError = InputError


class NoAdmissibleSolution(InputError):
    """A valid operating point the models cannot answer: no admissible solution exists
    (e.g. contact cannot carry T/R at any h >= 0) or it lies outside the physics' range
    (a film thicker than R/100, a wrap too long to mesh). In a sweep the point is kept as
    not converged, with this message, and the sweep goes on."""


_repr = reprlib.Repr()
_repr.maxlist = _repr.maxtuple = _repr.maxdict = 6
_repr.maxstring = _repr.maxother = 60


def show(value: Any) -> str:
    """A value as messages show it: ``repr``, with long lists and strings cut and huge
    integers as ``1.00e+400`` (a TOML file may hold 10**400; its 401 digits would bury the
    message).

    >>> show(3.5), show("m/s"), show(10**400), show(list(range(100)))
    ('3.5', "'m/s'", '1.00e+400', '[0, 1, 2, 3, 4, 5, ...]')
    """
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**20:
        exp = int(math.log10(abs(value)))
        lead = abs(value) // 10 ** (exp - 2)
        if lead >= 1000:  # log10 rounded down across a power of ten
            exp, lead = exp + 1, lead // 10
        return f"{'-' if value < 0 else ''}{lead / 100:.2f}e+{exp}"
    try:
        return _repr.repr(value)
    except ValueError:  # an integer beyond Python's digit limit inside a container
        return f"<{type(value).__name__} holding a number too large to print>"


def unknown_name(kind: str, name: str, valid, where: str = "") -> InputError:
    """The error for a misspelt name: ``kind`` ('key', 'fe1d option' ...) with the closest
    valid name, else the list of valid ones.

    >>> str(unknown_name("fe1d option", "levle", ["level", "entry"]))
    "unknown fe1d option 'levle'; did you mean 'level'?"
    """
    valid = list(valid)
    close = difflib.get_close_matches(str(name), valid, n=1, cutoff=0.5)
    hint = (f"; did you mean '{close[0]}'?" if close
            else "; valid: " + ", ".join(valid) if valid else "; it takes none")
    return InputError(f"unknown {kind} '{name}'{where}{hint}")


class ValidityWarning(UserWarning):
    """A legal input outside a model's validity (Eq. 21's range, incompressibility, slip
    flow); the result is computed and carries the same text in its ``warnings`` key."""


class ConvergenceError(RuntimeError):
    """A solve did not produce a converged, admissible solution.

    ``result`` is the last iterate as a :class:`webfem.result.Result` with
    ``converged = False`` (for inspection only, never an answer) and ``history`` the
    residual norms per iteration.
    """

    def __init__(self, message: str, result=None, history=None):
        super().__init__(message)
        self.result = result
        self.history = list(history or [])
