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

__all__ = ["GroovePattern", "groove_nodes", "graded_groove_nodes", "strip_width",
           "strip_start", "edge_effect", "choose_domain", "web_sag", "SAG_SHARE", "POISSON",
           "STRIP_PITCHES", "STRIP_SCALED", "STRIP_UNVENTED", "EDGE_ZONE",
           "EDGE_MARGIN_VENTED", "EDGE_MARGIN_UNVENTED", "FILM_SHARE_MIN"]


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
    ``fine`` and at least ``cells`` of them; ``level`` bisects every cell. The periodic
    cell's nodes."""
    b = np.concatenate([[z0], pattern.edges(z0, z1), [z1]])
    parts = []
    for a, c in zip(b[:-1], b[1:]):
        n = max(cells, int(math.ceil((c - a) / fine - 1e-9))) * 2 ** level
        parts.append(np.linspace(a, c, n + 1)[:-1])
    return np.concatenate(parts + [[z1]])


#: Growth of the cells of :func:`graded_groove_nodes` per unit distance from a land/groove
#: edge and from a web edge (scaled units).
EDGE_GROWTH, WEB_GROWTH = 0.5, 0.25


def graded_groove_nodes(pattern: GroovePattern, z0: float, z1: float, web_edges, fine=0.25,
                        level: int = 0, cells: int = 2) -> np.ndarray:
    """Nodes across a finite web on a grooved roller: one on every land/groove edge, cells
    ``fine`` at the land/groove edges and at the ``web_edges`` (a list of Z), growing by
    :data:`EDGE_GROWTH` per unit distance from the former and :data:`WEB_GROWTH` from the
    latter, each piece cut into at least ``cells``; ``level`` bisects every cell.

    Why: across a land the film's pressure rises from the groove's at the land's edges to a
    plateau, so the cells follow the edges; the lands far from the web's edges are alike
    (the periodic cell's), those at its edges are not, so the cells there stay ``fine``
    across. Measured on the 33 webs of 5-20 mm of benchmarks/groove_scan.py against
    :func:`groove_nodes`' uniform cells: 0-55 % fewer unknowns (a 20 mm PET web at 2.4 m/s:
    55 -> 37 cells across, 25.6 -> 13.5 s, 2.6 -> 1.8 GB), the answers within 1.3e-3 (all
    but one within 3e-4) and each within its own stated error.
    """
    b = np.concatenate([[z0], pattern.edges(z0, z1), [z1]])
    steps = b[1:-1]
    ends = np.asarray(list(web_edges), float)
    parts = []
    for a, c in zip(b[:-1], b[1:]):
        s = np.linspace(a, c, 401)
        size = np.full(s.shape, (c - a) / cells)
        if steps.size:
            d = np.min(np.abs(s[:, None] - steps[None, :]), axis=1)
            size = np.minimum(size, fine + EDGE_GROWTH * d)
        if ends.size:
            d = np.min(np.abs(s[:, None] - ends[None, :]), axis=1)
            size = np.minimum(size, fine + WEB_GROWTH * d)
        density = 1.0 / size
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1])
                                               * np.diff(s))])
        n = max(cells, int(math.ceil(cum[-1] - 1e-9)))
        nodes = np.interp(np.linspace(0.0, cum[-1], n + 1), cum, s)
        nodes[0], nodes[-1] = a, c
        for _ in range(level):
            nodes = np.sort(np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1])]))
        parts.append(nodes[:-1])
    return np.concatenate(parts + [[z1]])


#: An edge strip spans at least this many pitches and this many scaled units (R eps^(1/3))
#: in from the web's edge, plus :data:`STRIP_UNVENTED` units times the share of the groove
#: pressure that the grooves do not vent: against the full width on 10 designs 30.5
#: pitches wide (benchmarks/groove_scan.py's), a strip of 8 units answered within 1.3e-4
#: where the grooves vent (their pressure below half the lands'), but 1.9 % and 11 % off
#: where they do not (a groove pressure 0.96-0.99 of the lands': the film's edge zone then
#: reaches across the wrap as on a smooth web), and exactly with 24.
STRIP_PITCHES, STRIP_SCALED, STRIP_UNVENTED = 4.0, 8.0, 16.0

#: The edge zone of a web whose grooves do not vent, in scaled units (the smooth web's edge
#: leakage lowers its gap by about 1.5/lambda).
EDGE_ZONE = 1.5

#: The margin of :func:`edge_effect` over what it sums, where the grooves vent and where
#: they do not (in proportion between): measured on 20 designs at 12 and 30.5 pitches
#: across (benchmarks/groove_scan.py's, cell against full width), the largest effect of the
#: edges on h_center, h_min, mu (against max(|mu|, 0.03)) and the contact share was 0.86
#: times the sum where the grooves vent (>= 84 % of the lands' pressure) and 3.84 times
#: where they do not (a flying foil web: its mu follows the gap the edges lower). Issue 38
#: measured more (benchmarks/groove_edges.py: base_grooved and pet_idler_grooved, depths
#: 1-250 um, pitches, widths, speeds): grooves 1 and 5 um deep on base_grooved, which do not
#: vent, changed mu by 5.3 and 5.0 times the sum (1.18 and 1.12 times the estimate with
#: 4.5), so the unvented margin is 6: the estimate itself bounds every change measured, and
#: the stated error doubles it (:func:`webfem.models.groove_domain.edge_error`).
EDGE_MARGIN_VENTED, EDGE_MARGIN_UNVENTED = 1.5, 6.0

#: The least film share :func:`edge_effect` takes (where the asperities carry nearly all
#: the load, the edges still move the exit constriction's h_min).
FILM_SHARE_MIN = 0.05


def strip_width(pitch: float, vent: float = 0.0) -> float:
    """The width of an edge strip (scaled, like the pitch): :data:`STRIP_PITCHES` pitches
    and at least :data:`STRIP_SCALED` + :data:`STRIP_UNVENTED` (1 - ``vent``) units.
    ``vent``: 1 - the groove pressure over the land pressure (1: the grooves are at
    ambient; 0: no venting, or not known)."""
    vent = min(max(vent, 0.0), 1.0)
    return max(STRIP_PITCHES * pitch, STRIP_SCALED + STRIP_UNVENTED * (1.0 - vent))


def strip_start(pattern: GroovePattern, lam: float, width: float) -> float:
    """The inner end z_c of an edge strip of at least ``width`` on the half width [0, lam]:
    the land centre k pitch furthest from the edge that leaves ``width`` between it and the
    edge (0: the whole half width).

    >>> strip_start(GroovePattern(1.0, 0.25, 1.0), 20.3, 8.0)
    12.0
    """
    k = math.floor((lam - width) / pattern.pitch + 1e-9)
    return max(k, 0) * pattern.pitch


def edge_effect(lam: float, pitch: float, vent: float, film_share: float) -> float:
    """An estimate of the relative change the web's edges make to the answer of the periodic
    cell: the edge zone's share of the half width ``lam`` times the share of the load the
    film carries (at least :data:`FILM_SHARE_MIN`: the asperities' share does not feel the
    edges), times a margin (:data:`EDGE_MARGIN_VENTED`, :data:`EDGE_MARGIN_UNVENTED`). The
    edge zone and the margin are a pitch and 1.5 where the grooves vent (``vent`` = 1: the
    edge pitch is the one that differs), :data:`EDGE_ZONE` and 6 where they do not (the
    smooth web's edge leakage), in proportion. Scaled lengths.

    >>> round(edge_effect(100.0, 1.0, 1.0, 0.1), 4), round(edge_effect(100.0, 1.0, 0.0, 1.0), 4)
    (0.0015, 0.09)
    """
    vent = min(max(vent, 0.0), 1.0)
    zone = EDGE_ZONE * (1.0 - vent) + pitch * vent
    margin = EDGE_MARGIN_VENTED * vent + EDGE_MARGIN_UNVENTED * (1.0 - vent)
    return margin * zone * max(film_share, FILM_SHARE_MIN) / lam


def choose_domain(choice: str, pattern: GroovePattern, lam: float, vent: float = 0.0,
                  estimate: float | None = None, tol: float = 0.01) -> str:
    """The domain across the width of a grooved roller: "cell" (the periodic cell land
    centre to groove centre), "strip" (the web's edge strip, :func:`strip_start`) or "full"
    (the half width with its edge lands). ``choice``: "cell", "full", "strip" (the full
    width where the web is too narrow for a strip) or "auto": the cell where the edges'
    ``estimate`` (:func:`edge_effect`; None: not known) is within ``tol``, else the strip or
    the full width.

    >>> g = GroovePattern(1.0, 0.25, 1.0)
    >>> choose_domain("auto", g, 100.0, 1.0, 0.004), choose_domain("auto", g, 100.0, 0.0)
    ('cell', 'strip')
    >>> choose_domain("auto", g, 20.0), choose_domain("cell", g, 5.0)
    ('full', 'cell')
    """
    if choice == "cell" or (choice == "auto" and estimate is not None and estimate <= tol):
        return "cell"
    if choice == "full" or strip_start(pattern, lam, strip_width(pattern.pitch, vent)) == 0:
        return "full"
    return "strip"


#: Poisson's ratio of the web across the width in :func:`web_sag` (a case gives none).
POISSON = 0.3

#: A result warns where the web's sag into a groove exceeds this share of the land gap.
SAG_SHARE = 0.1


def web_sag(pressure: float, groove: float, modulus: float, thickness: float,
            poisson: float = POISSON) -> float:
    """Sag of the web into a groove of width ``groove`` under ``pressure``, held flat on the
    lands: the clamped plate strip's p g^4 / (384 D), D = E t^3 / (12 (1 - nu^2)) (free to
    turn on the lands it would sag 5 times that). SI units in, metres out.

    The web is continuous over lands wider than its grooves (land fractions of 50-95 %),
    whose film and asperities hold it flat there: the clamped strip is its sag, the hinged
    one a bound.

    >>> round(web_sag(1455.0, 0.25e-3, 4.46e9, 70e-6) * 1e9, 3)     # base_grooved, nm
    0.106
    """
    D = modulus * thickness ** 3 / (12.0 * (1.0 - poisson ** 2))
    return pressure * groove ** 4 / (384.0 * D)
