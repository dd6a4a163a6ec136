"""Stability map: where each method converges, diverges or stalls.

1. Coupling schemes on the 1-D model over roller speed x wrap angle x mesh level: Newton with
   and without its continuation fallback; Picard with fixed relaxation (omega 1, 0.5, 0.2; no
   acceleration, no safeguard), Picard with Anderson acceleration and its safeguard (the
   default), and the staggered Picard (film, then web).
2. The low-speed contact regime with and without asperity contact in the web equilibrium.
3. The 2-D model (Newton) over speed x web width.
4. The closed form's stated range (beta > 6, lambda > 7) over speed x width x wrap.

Each point: ``converged``, ``diverged`` or ``stalled``, with iterations and final residual.
Computes only; :func:`webfem.io.studies.write` writes the CSV, chart and markdown.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass
from typing import Callable, ClassVar

import numpy as np

from ..api import solve
from ..case import Case
from ..errors import ConvergenceError, ValidityWarning
from ..line_speed import at_speed

__all__ = ["SCHEMES", "STATUS", "StabilityStudy", "classify", "attempt", "run"]

SCHEMES = (("Newton", {"method": "newton"}),
           ("Newton, no continuation", {"method": "newton", "continuation": False}),
           ("Picard omega 1", {"method": "picard", "omega": 1.0, "aitken": False,
                               "anderson": 0, "backtrack": 0}),
           ("Picard omega 0.5", {"method": "picard", "omega": 0.5, "aitken": False,
                                 "anderson": 0, "backtrack": 0}),
           ("Picard omega 0.2", {"method": "picard", "omega": 0.2, "aitken": False,
                                 "anderson": 0, "backtrack": 0}),
           ("Picard Anderson (default)", {"method": "picard"}),
           ("Picard staggered", {"method": "picard-staggered", "omega": 0.5}))
STATUS = ("converged", "stalled", "diverged")


@dataclass(frozen=True)
class StabilityStudy:
    """Where each method converged, stalled or diverged.

    Attributes
    ----------
    rows : tuple of dict
        Per point: ``study`` (coupling, contact, 2-D, closed form), ``method``, ``model``,
        ``speed``, ``wrap_deg``, ``width``, ``level``, ``status`` (one of :data:`STATUS`, or
        "outside range" for the closed form), ``iterations``, ``residual``, ``message``,
        ``time_s`` and, when a result came back, ``h_min``.
    quick : bool
        The reduced map.
    """

    kind: ClassVar[str] = "stability"
    rows: tuple
    quick: bool = False

    def count(self, method: str, status: str | None = None) -> int:
        """Points of ``method`` (with ``status``, when given)."""
        return sum(r["method"] == method and (status is None or r["status"] == status)
                   for r in self.rows)

    def status(self, method: str, speed: float, study: str = "coupling") -> str:
        """Status of the first point of ``method`` at ``speed`` in ``study``."""
        return next(r["status"] for r in self.rows if r["method"] == method
                    and r["speed"] == speed and r["study"] == study)


def classify(result) -> str:
    """converged, diverged or stalled, from the result's flag and solver message."""
    if result["converged"]:
        return "converged"
    msg = str(result.get("solver_message", "")).lower()
    if any(w in msg for w in ("diverg", "not finite", "linear solve failed", "map failed")):
        return "diverged"
    return "stalled"


def attempt(case: Case, model: str, opts: dict) -> dict:
    """Solve once and classify; a solver that raises counts as diverged."""
    t0 = time.perf_counter()
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", ValidityWarning)   # the map crosses ranges on purpose
        warnings.simplefilter("ignore", RuntimeWarning)    # diverging iterates overflow
        try:
            # the schemes on the given mesh: no error estimate (its solves would be Newton's)
            r = solve(case, model=model, **{"estimate": False, "adapt_settle": False, **opts})
        except ConvergenceError as err:
            r = err.result
        except (FloatingPointError, ValueError, RuntimeError, np.linalg.LinAlgError) as err:
            return {"status": "diverged", "iterations": -1, "residual": float("nan"),
                    "message": f"{type(err).__name__}: {err}",
                    "time_s": time.perf_counter() - t0}
    return {"status": classify(r), "iterations": r["iterations"], "residual": r["residual"],
            "message": r.get("solver_message", ""), "time_s": time.perf_counter() - t0,
            "h_min": r["h_min"]}


def run(case: Case, quick: bool = False,
        progress: Callable[[str], None] | None = None) -> StabilityStudy:
    """Map the methods over the case's neighbourhood (``quick``: 3 speeds, one wrap angle,
    level 0, about a minute; else about ten). ``progress`` receives one line of text per
    coupling scheme and one for the rest."""
    speeds = (2.0, 20.0, 40.0) if quick else (0.5, 2.0, 5.0, 10.0, 20.0, 30.0, 40.0)
    wraps = (60.0,) if quick else (20.0, 60.0, 120.0)
    levels = (0,) if quick else (0, 1, 2)
    picard_iter = 60 if quick else 300
    rows = []
    for name, opts in SCHEMES:
        for level in levels:
            for wrap in wraps:
                for u in speeds:
                    c = at_speed(case, u).updated({"wrap.angle_deg": wrap})
                    o = dict(opts, level=level, picard_max_iter=picard_iter, adapt=0)
                    rows.append({"study": "coupling", "method": name, "model": "fe1d",
                                 "speed": u, "wrap_deg": wrap, "width": case.web.width,
                                 "level": level, **attempt(c, "fe1d", o)})
        if progress:
            progress(f"{name}: done")
    for contact in (True, False):
        for u in speeds:
            c = at_speed(case, u)
            method = f"Newton, contact {'on' if contact else 'off'}"
            rows.append({"study": "contact", "method": method, "model": "fe1d", "speed": u,
                         "wrap_deg": case.wrap.angle_deg, "width": case.web.width, "level": 0,
                         **attempt(c, "fe1d", {"contact": contact})})
    widths = (0.02, 0.1) if quick else (0.01, 0.02, 0.035, 0.1, 0.3)
    for width in widths:
        for u in speeds[::2] if not quick else speeds:
            c = at_speed(case, u).updated({"web.width": width})
            rows.append({"study": "2-D", "method": "fe2d Newton", "model": "fe2d", "speed": u,
                         "wrap_deg": case.wrap.angle_deg, "width": width, "level": 0,
                         **attempt(c, "fe2d", {})})
    if progress:
        progress("contact and 2-D: done")
    for width in widths:
        for wrap in (10.0, 20.0, 60.0, 120.0):
            for u in speeds:
                c = at_speed(case, u).updated({"web.width": width, "wrap.angle_deg": wrap})
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", ValidityWarning)   # the range is mapped
                    r = solve(c, model="closed-form")
                rows.append({"study": "closed form", "method": "Eq. 21", "model": "closed-form",
                             "speed": u, "wrap_deg": wrap, "width": width, "level": 0,
                             "status": "converged" if r["eq21_valid"] else "outside range",
                             "iterations": 0, "residual": 0.0,
                             "message": f"beta = {r['beta']:.3g}, lambda = {r['lambda']:.3g}",
                             "time_s": r["solve_time_s"], "h_min": r["h_min"]})
    return StabilityStudy(tuple(rows), quick)
