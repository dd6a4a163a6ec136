"""Circumferential grooves in scaled units: the gap's groove depth across the width.

A roller with grooves of pitch p (land a plus groove g) and depth Delta adds Delta(Z) to the
film gap, H(X, Z) = H_web(X) + Delta(Z) with Delta = depth in a groove and 0 on a land
(physics.md, "Grooved rollers"). A land is centred at Z = 0 (the web's centreline over a
land centre), so the periodic cell of a wide web is Z in [0, p/2]: land centre to groove
centre, both sides symmetry lines. Units: Z as X (R eps^(1/3)), depth as H (R eps^(2/3)).

Examples
--------
>>> g = GroovePattern(pitch=1.0, width=0.25, depth=10.0)
>>> [float(v) for v in g.depth_at(np.array([0.0, 0.3, 0.45, 0.6, 1.1]))]
[0.0, 0.0, 10.0, 10.0, 0.0]
>>> [float(z) for z in g.edges(0.0, 2.0)]
[0.375, 0.625, 1.375, 1.625]
>>> g.land_share(0.0, 0.5)
0.75
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["GroovePattern", "groove_nodes", "choose_domain", "CELL_PITCHES"]


@dataclass(frozen=True)
class GroovePattern:
    """Grooves of ``pitch``, ``width`` (scaled like Z) and ``depth`` (scaled like H); lands
    centred at Z = k pitch."""

    pitch: float
    width: float
    depth: float

    @property
    def land(self) -> float:
        """Land width a = pitch - width."""
        return self.pitch - self.width

    def depth_at(self, Z) -> np.ndarray:
        """Delta(Z): ``depth`` inside a groove, 0 on a land (an edge counts as land)."""
        Z = np.asarray(Z, float)
        off = np.abs(Z - self.pitch * np.round(Z / self.pitch))
        return np.where(off > 0.5 * self.land * (1.0 + 1e-12), self.depth, 0.0)

    def edges(self, z0: float, z1: float) -> np.ndarray:
        """Land/groove edges k pitch +- land/2 strictly inside (z0, z1)."""
        k = np.arange(math.floor(z0 / self.pitch) - 1, math.ceil(z1 / self.pitch) + 2)
        e = np.sort(np.concatenate([k * self.pitch - 0.5 * self.land,
                                    k * self.pitch + 0.5 * self.land]))
        tol = 1e-9 * self.pitch
        return e[(e > z0 + tol) & (e < z1 - tol)]

    def land_share(self, z0: float, z1: float, n: int = 20001) -> float:
        """Share of [z0, z1] that is land (exact at the edges, midpoint sums between)."""
        b = np.concatenate([[z0], self.edges(z0, z1), [z1]])
        mid = 0.5 * (b[1:] + b[:-1])
        return float(np.sum(np.diff(b) * (self.depth_at(mid) == 0.0)) / (z1 - z0))


def groove_nodes(pattern: GroovePattern, z0: float, z1: float, fine: float = 0.25,
                 level: int = 0, cells: int = 2) -> np.ndarray:
    """Nodes on [z0, z1] with one on every land/groove edge (the step in the gap lies on
    element edges): each land or groove piece is cut into equal cells no longer than
    ``fine`` and at least ``cells`` of them; ``level`` bisects every cell."""
    b = np.concatenate([[z0], pattern.edges(z0, z1), [z1]])
    parts = []
    for a, c in zip(b[:-1], b[1:]):
        n = max(cells, int(math.ceil((c - a) / fine - 1e-9))) * 2 ** level
        parts.append(np.linspace(a, c, n + 1)[:-1])
    return np.concatenate(parts + [[z1]])


#: A wide web is solved on the periodic groove cell from this many groove pitches across it
#: (``grooves = "auto"``).
CELL_PITCHES = 10.0


def choose_domain(pitches: float, choice: str = "auto") -> str:
    """The domain across the width of a grooved roller: "cell" (the periodic cell land centre
    to groove centre) or "full" (the web's width with its edge lands). ``pitches``: groove
    pitches the web spans; ``choice``: "auto" (the cell from :data:`CELL_PITCHES` pitches),
    "cell" or "full".

    >>> choose_domain(27.6), choose_domain(6.3), choose_domain(6.3, "cell")
    ('cell', 'full', 'cell')
    """
    if choice != "auto":
        return choice
    return "cell" if pitches >= CELL_PITCHES else "full"
