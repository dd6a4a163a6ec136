"""Result of one solve: the summary numbers (the JSON keys), fields along x, diagnostics.

Every model (closed form, 1-D, 2-D, auto) answers through the same summary keys:

========== ==========================================================================
key        meaning
========== ==========================================================================
model      model that produced the numbers ("closed-form", "fe1d", ...)
h_center   gap at the wrap centre x = 0 [m]
h_inlet    gap at the inlet edge x = -RB/2 [m]
h_outlet   gap at the outlet edge x = +RB/2 [m]
h_min      smallest gap anywhere in the solved domain [m]
mu         wrap-averaged friction coefficient [-]
delta_T    tension increase the roller carries before slip, Eq. 31 [N/m]
regime     lubrication regime covering most of the wrap: boundary, mixed or fluid
lambda     width parameter L/(2 R eps^(1/3))
beta       wrap parameter B/eps^(1/3)
eq21_valid True inside Eq. 21's stated range (beta > 6 and lambda > 7)
converged  True when the solver met its tolerance (always True for the closed form)
iterations nonlinear iterations (0 for the closed form)
n_dofs     unknowns of the discrete problem (0 for the closed form)
solve_time_s wall time of the solve [s]
========== ==========================================================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .case import Case

__all__ = ["Result", "SUMMARY_KEYS"]

#: The contract: keys every model's summary carries (others may be added, none removed).
SUMMARY_KEYS = ("model", "h_center", "h_inlet", "h_outlet", "h_min", "mu", "delta_T", "regime",
                "lambda", "beta", "eq21_valid", "converged", "iterations", "n_dofs",
                "solve_time_s")


def _plain(value: Any) -> Any:
    """JSON-safe scalar: numpy to Python, non-finite floats to None."""
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (np.floating, float)):
        value = float(value)
        return value if math.isfinite(value) else None
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


@dataclass
class Result:
    """What a model returns.

    Attributes
    ----------
    case : Case
        The operating point solved.
    summary : dict
        The JSON keys of :data:`SUMMARY_KEYS` and more (``h_c``, ``sigma``, regime shares,
        ``residual``, ``warnings`` ...). Also reachable as ``result["mu"]``.
    fields : dict of numpy arrays
        Fields along the web: ``x`` [m] and ``h`` [m] at least, ``mu``, ``chi_c`` ...
    diagnostics : dict
        Solver history and settings (free form).
    film : dict or None
        2-D models: the film mesh (``points`` [m], ``quads``) and its vertex fields.
    """

    case: Case
    summary: dict[str, Any]
    fields: dict[str, np.ndarray] = field(default_factory=dict)
    diagnostics: dict[str, Any] = field(default_factory=dict)
    film: dict[str, np.ndarray] | None = None

    def slim(self) -> "Result":
        """A copy without the solver's internal objects (mesh bases, state vector): small
        and picklable, for worker processes and storage."""
        heavy = {"problem", "state", "line_result"}
        diag = {k: v for k, v in self.diagnostics.items() if k not in heavy}
        return Result(self.case, dict(self.summary), dict(self.fields), diag, self.film)

    def save_vtu(self, folder, stem: str | None = None) -> list:
        """Write the web (and, for 2-D models, the film) as VTU files; returns the paths."""
        from .io.vtu import write_result
        return write_result(self, folder, stem)

    def __post_init__(self):
        missing = [k for k in SUMMARY_KEYS if k not in self.summary]
        if missing:
            raise ValueError(f"result summary lacks the keys {missing}")

    def __getitem__(self, key: str) -> Any:
        return self.summary[key]

    def get(self, key: str, default: Any = None) -> Any:
        """A summary value, or ``default`` when the model does not report that key."""
        return self.summary.get(key, default)

    def to_json(self) -> dict[str, Any]:
        """The summary as a JSON-safe dict (non-finite numbers become null)."""
        keys = list(SUMMARY_KEYS) + [k for k in self.summary if k not in SUMMARY_KEYS]
        return {k: _plain(self.summary[k]) for k in keys}

    def describe(self) -> str:
        """A readable multi-line summary for the terminal."""
        s, c = self.summary, self.case
        um = 1e6
        lines = [
            f"webfem {s['model']}: R = {c.roller.radius:g} m, L = {c.web.width:g} m, "
            f"T = {c.web.tension:g} N/m, B = {c.wrap.angle_deg:g} deg, "
            f"U_r = {c.roller.speed:g} m/s, U_w = {c.web.speed:g} m/s",
            f"  lambda = {s['lambda']:.3g}, beta = {s['beta']:.3g}, Eq. 21 range "
            + ("met" if s["eq21_valid"] else "NOT met (beta > 6 and lambda > 7)"),
            f"  gap: inlet {s['h_inlet'] * um:.3f} um, centre {s['h_center'] * um:.3f} um, "
            f"outlet {s['h_outlet'] * um:.3f} um, minimum {s['h_min'] * um:.3f} um",
            f"  h_c = {s['h_c'] * um:.3f} um, 3 sigma = {3 * s['sigma'] * um:.3f} um; "
            f"regime {s['regime']} (wrap shares: boundary {s['share_boundary']:.2f}, "
            f"mixed {s['share_mixed']:.2f}, fluid {s['share_fluid']:.2f})",
            f"  mu = {s['mu']:.4f}, tension increase before slip delta_T = "
            f"{s['delta_T']:.3f} N/m",
            f"  converged = {s['converged']}, iterations = {s['iterations']}, "
            f"n_dofs = {s['n_dofs']}, time = {s['solve_time_s'] * 1e3:.3f} ms",
        ]
        if "mesh" in s:
            lines.append(f"  {s.get('method', '')} on {s['mesh']}; residual "
                         f"{s.get('residual', float('nan')):.2e}; contact carries "
                         f"{100 * s.get('contact_share', 0.0):.1f} % of the wrap load")
        if "why" in s:
            lines.append(f"  model used: {s['model_used']} (estimated {s['quantity']} error "
                         f"{s['estimated_error']:.2g} <= {s['tolerance']:g}): {s['why']}")
        for w in s.get("warnings", []):
            lines.append(f"  warning: {w}")
        return "\n".join(lines)
