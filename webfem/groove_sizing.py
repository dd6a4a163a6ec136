"""Groove sizing: traction against groove pitch and land fraction at the case's speed(s).

The question users bring (issue 15): which groove keeps mu above ``mu_min`` at a given line
speed, and how much land (contact area, heat transfer, marking) does it cost? For each
design (pitch p_g, land fraction a/p_g, depth delta) at each speed this solves the grooved
2-D film (fe2d) and marks the designs with mu >= mu_min; the recommended one is the feasible
design with the largest land fraction (ties: the larger mu).

Examples
--------
>>> DEFAULT_PITCHES[1], DEFAULT_LAND_FRACTIONS[-1]
(0.00127, 0.9)
"""

from __future__ import annotations

import warnings
from dataclasses import asdict, dataclass
from typing import Callable, Sequence

from .api import solve
from .case import Case
from .errors import ConvergenceError, InputError, ValidityWarning

__all__ = ["GrooveDesign", "groove_map", "best_designs", "DEFAULT_PITCHES",
           "DEFAULT_LAND_FRACTIONS", "DEFAULT_DEPTH"]

#: Pitches [m] of the map: fine to coarse around Walker's 1.27 mm.
DEFAULT_PITCHES = (0.8e-3, 1.27e-3, 2.5e-3, 5e-3)
#: Land fractions a/p_g of the map.
DEFAULT_LAND_FRACTIONS = (0.5, 0.65, 0.8, 0.9)
#: Groove depth [m] of the map (Walker's 0.25 mm).
DEFAULT_DEPTH = 0.25e-3


@dataclass(frozen=True)
class GrooveDesign:
    """One design at one roller speed and what fe2d answers for it (SI units)."""

    speed: float
    pitch: float
    width: float
    depth: float
    land_fraction: float
    mu: float | None
    h_center: float | None
    contact_share: float | None
    converged: bool
    feasible: bool

    def to_dict(self) -> dict:
        return asdict(self)


def groove_map(case: Case, mu_min: float, *, speeds: Sequence[float] | None = None,
               pitches: Sequence[float] = DEFAULT_PITCHES,
               land_fractions: Sequence[float] = DEFAULT_LAND_FRACTIONS,
               depths: Sequence[float] = (DEFAULT_DEPTH,), options=None,
               progress: Callable[[int, int], None] | None = None) -> list[GrooveDesign]:
    """Every design (pitch x land fraction x depth) at every roller speed (default: the
    case's), solved with fe2d; a design that does not converge is kept with
    ``converged = False`` and is never feasible."""
    if not 0.0 < mu_min < 10.0:
        raise InputError(f"mu_min = {mu_min!r} is out of range: must be > 0 and < 10")
    for v in land_fractions:
        if not 0.0 < v < 1.0:
            raise InputError(f"land fraction = {v!r} is out of range: must be > 0 and < 1")
    for name, values in (("groove pitch", pitches), ("groove depth", depths)):
        for v in values:
            if not 0.0 < v < float("inf"):
                raise InputError(f"{name} = {v!r} is out of range: must be > 0 [m]")
    speeds = [case.roller.speed] if speeds is None else list(speeds)
    designs = [(s, p, f, d) for s in speeds for p in pitches for f in land_fractions
               for d in depths]
    out = []
    for i, (speed, pitch, land, depth) in enumerate(designs):
        c = case.updated({"roller.speed": speed, "roller.groove_pitch": pitch,
                          "roller.groove_width": pitch * (1.0 - land),
                          "roller.groove_depth": depth})
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)
                r = solve(c, model="fe2d", options=options)
            mu, hc, cs, ok = r["mu"], r["h_center"], r["contact_share"], True
        except ConvergenceError:
            mu = hc = cs = None
            ok = False
        out.append(GrooveDesign(speed, pitch, pitch * (1.0 - land), depth, c.land_fraction,
                                mu, hc, cs, ok, bool(ok and mu >= mu_min)))
        if progress:
            progress(i + 1, len(designs))
    return out


def best_designs(designs: Sequence[GrooveDesign]) -> dict[float, GrooveDesign | None]:
    """Per speed: the feasible design with the largest land fraction (ties: larger mu), or
    None when no design keeps mu >= mu_min."""
    best: dict[float, GrooveDesign | None] = {}
    for d in designs:
        best.setdefault(d.speed, None)
        if d.feasible:
            b = best[d.speed]
            if b is None or (d.land_fraction, d.mu) > (b.land_fraction, b.mu):
                best[d.speed] = d
    return best
