"""The printed summary of a solve: which model answered and why, then the numbers in the
units asked for (``--units si|metric|us``; the JSON output stays SI).

The numbers are :meth:`webfem.result.Result.describe`'s, so the summary keeps every line it
has; for metric and US units each ``NUMBER UNIT`` it prints in SI is shown converted.
"""

from __future__ import annotations

import re

from ..describe import judged_text
from ..units import convert, unit_label

__all__ = ["model_line", "summary_text", "in_units"]

#: SI unit as describe() prints it -> display role of webfem.units
_ROLES = {"m/s": "speed", "N/m": "tension", "N m": "torque", "um": "thin", "m": "length",
          "Pa": "pressure"}
_QUANTITY = re.compile(r"(?<![\w.])([-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?) (m/s|N/m|N m|um|m|Pa)"
                       r"(?![\w/^])")


def model_line(result, asked: str) -> str:
    """``webfem auto: fe2d answered (largest stated error 0.00031 <= 0.01, every quantity
    judged); WHY`` for auto,
    else the model named with ``--model``."""
    s = result.summary
    if s.why is not None:
        return f"webfem {asked}: {s.model_used} answered ({judged_text(s)}); {s.why}"
    return f"webfem {s.model}: the model asked for (--model {asked})"


def in_units(text: str, system: str) -> str:
    """``text`` with each SI ``NUMBER UNIT`` shown in ``system``'s unit, 4 digits.

    >>> in_units("U_r = 20 m/s, gap 4.5 um, T = 80 N/m, time = 3 ms", "us")
    'U_r = 3937 ft/min, gap 0.1772 mil, T = 0.4568 pli, time = 3 ms'
    """
    if system == "si":
        return text

    def one(match: re.Match) -> str:
        role = _ROLES[match.group(2)]
        value = float(match.group(1)) * (1e-6 if role == "thin" else 1.0)
        return f"{convert(value, role, system):.4g} {unit_label(role, system)}"

    return _QUANTITY.sub(one, text)


def summary_text(result, asked: str, system: str = "si") -> str:
    """The terminal summary of ``result`` (from ``--model asked``) in ``system`` units: the
    model line first, then :meth:`~webfem.result.Result.describe` without its own model
    label (and without its "model used" line, which the first line now carries)."""
    lines = result.describe().splitlines()
    head = re.sub(r"^webfem [\w-]+: ", "  ", lines[0]) if lines else ""
    body = [head] + [ln for ln in lines[1:] if not ln.startswith("  model used: ")]
    return "\n".join([model_line(result, asked)] + [in_units(ln, system) for ln in body])
