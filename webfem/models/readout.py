"""What a user reads off a solved discrete state: the gaps, the friction and the contact share.

One function, :func:`read_out`, used by the driver for the summary and by the error estimate
(:mod:`webfem.models.mesh_error`) to compare the same quantities on two meshes.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..case import Case
from ..fem import forms
from ..fem.scaling import FoilParameters
from ..physics.effects import MU_SCALE, traction_summary
from ..physics.friction import friction_for, jump_gaps
from .refine import minimum, wrap_samples

__all__ = ["ReadOut", "read_out", "read_moved", "jump_crossings", "pressure_and_gradient",
           "READ_QUANTITIES"]

#: The quantities whose error every result states (``error_<name>`` summary keys).
READ_QUANTITIES = ("h_center", "h_min", "mu", "contact_share")


@dataclass(frozen=True)
class ReadOut:
    """The gaps [m] at the wrap centre and edges, the smallest gap and where [m], the
    headline friction ``mu`` (where nothing slides the traction at the onset of slip,
    :func:`~webfem.physics.effects.traction_summary`, whose keys ``traction`` holds), the
    regime shares, the share of the wrap load carried by asperity contact, the wrap
    quadrature (points, weights, gaps, pressure and its gradient) the summary and
    diagnostics keep, the web's largest ``compression`` -h [m] where it rests below the
    roller's crest (0 elsewhere) and the ``cuts`` splitting the quadrature's cells (scaled
    x: :func:`jump_crossings`)."""

    h_center: float
    h_inlet: float
    h_outlet: float
    h_min: float
    x_min: float
    mu: float
    shares: tuple[float, float, float]
    contact_share: float
    pts: np.ndarray
    wts: np.ndarray
    h: np.ndarray
    p: np.ndarray
    dpdx: np.ndarray
    traction: dict
    compression: float = 0.0
    #: the points (scaled) where the gap crosses a jump of the local friction
    #: (:func:`jump_crossings`), which split the quadrature's cells
    cuts: np.ndarray | None = None

    def value(self, name: str) -> float:
        """One of :data:`READ_QUANTITIES` by name."""
        return float(getattr(self, name))


def pressure_and_gradient(case: Case, problem, u, X) -> tuple[np.ndarray, np.ndarray]:
    """Absolute (width-averaged) film pressure [Pa] and its x-derivative [Pa/m] at scaled
    points X inside cells: the five-point central difference, exact for a polynomial of
    degree 4, over steps inside the point's cell (the pressure is a polynomial there) of
    up to 1e-3 (scaled). A point on a node: steps of 1e-7 across it. Why not 1e-7 steps
    throughout: the pressure's values carry noise of about 1e-10 (scaled; base case), which
    made dp/dx 1e-3 (relative) noisy, enough for points 5e-13 apart to read mu 6e-9 apart."""
    X = np.asarray(X, float)
    stencil, delta = _stencil(problem, X)
    P = problem.pressure(u, stencil)
    n = len(X)
    dPdX = (8.0 * (P[2 * n:3 * n] - P[n:2 * n]) - (P[4 * n:] - P[3 * n:4 * n])) / \
        (12.0 * delta)
    return (case.air.ambient_pressure + P[:n] * case.p_bar,
            dPdX * case.p_bar / case.x_scale)


def _stencil(problem, X) -> tuple[np.ndarray, np.ndarray]:
    """The points :func:`pressure_and_gradient` evaluates at for the points X (X first,
    then X -/+ delta, X -/+ 2 delta) and its steps delta. A function of the mesh and X
    alone: the gap read at the same points (its first ``len(X)``) reuses the basis
    functions' table the pressure built (:class:`webfem.fem.hermite.LineProbes` keeps the
    last point sets), each point's value the same to the bit as read alone."""
    nodes = np.asarray(problem.X, float)
    j = np.clip(np.searchsorted(nodes, X), 1, nodes.size - 1)
    room = np.minimum(X - nodes[j - 1], nodes[j] - X)
    delta = np.where(room > 0.0, np.minimum(1e-3, 0.45 * room), 1e-7)
    return np.concatenate([X, X - delta, X + delta, X - 2 * delta, X + 2 * delta]), delta


def jump_crossings(problem, u, prm: FoilParameters, levels, n: int = 8) -> np.ndarray:
    """The points inside the wrap where the scaled gap crosses one of ``levels``
    (:func:`~webfem.physics.friction.jump_gaps` scaled: where the local friction or the
    regime jumps), to rounding. The wrap average's Gauss rule integrates a jump inside a cell
    to first order in the cell's length only: on the base case with the paper's physics
    (mu's chi_c drops from 0.11 to 0 at 3 sigma) level 1 and 2 shared one 0.49-long cell
    across it and both read mu 4.3e-4 (relative) high, the adapted mesh 5.7e-5 low. The gap
    is sampled at the cells' nodes and ``n`` points inside each; a sign change between
    neighbours is narrowed to the crossing."""
    e = 0.5 * prm.beta
    X = problem.X
    inner = X[(X >= -e - 1e-12) & (X <= e + 1e-12)]
    s = np.linspace(0.0, 1.0, n + 2)[:-1]
    xs = np.append((inner[:-1, None] + np.diff(inner)[:, None] * s[None, :]).ravel(),
                   inner[-1])
    H = problem.gap(u, prm, xs)
    brackets = []
    for level in np.atleast_1d(levels):
        above = H > level
        i = np.nonzero(above[1:] != above[:-1])[0]
        brackets.append((np.full(i.size, float(level)), i))
    level = np.concatenate([b[0] for b in brackets])
    if level.size == 0:
        return np.empty(0)
    i = np.concatenate([b[1] for b in brackets])
    lo, hi, Hlo, Hhi = xs[i], xs[i + 1], H[i], H[i + 1]
    t = np.linspace(0.0, 1.0, 17)
    for _ in range(4):      # each round cuts the brackets 16-fold: 6.6e4 in all
        # every level's brackets in one evaluation (each point's value is its own)
        x = lo[:, None] + (hi - lo)[:, None] * t[None, :]
        Hx = problem.gap(u, prm, x.ravel()).reshape(x.shape)
        Hx[:, 0], Hx[:, -1] = Hlo, Hhi
        k = np.argmax((Hx[:, 1:] > level[:, None]) != (Hx[:, :1] > level[:, None]), axis=1)
        r = np.arange(k.size)
        lo, hi, Hlo, Hhi = x[r, k], x[r, k + 1], Hx[r, k], Hx[r, k + 1]
    # the gap is smooth inside a bracket this short: linear to rounding
    with np.errstate(all="ignore"):
        w = np.clip(np.nan_to_num((level - Hlo) / (Hhi - Hlo), nan=0.5), 0.0, 1.0)
    return np.sort(lo + w * (hi - lo))


def read_out(case: Case, problem, u, prm: FoilParameters, keep: bool = True) -> ReadOut:
    """The quantities of a solved state ``u`` of ``problem`` (SI units). The last one read
    of a problem is kept on it: the error estimate and the result read the same answer
    (a pure function of its arguments; about 3.5 ms on a 2-D mesh of 1.1e4 unknowns).
    ``keep=False``: a trial state's, read without replacing the one kept."""
    kept = getattr(problem, "_read_out", None)
    if kept is not None and kept[0] is case and kept[1] is prm and kept[2].shape == \
            np.shape(u) and np.array_equal(kept[2], u):
        return kept[3]
    out = _read_out(case, problem, u, prm)
    if not keep:
        return out
    try:
        problem._read_out = (case, prm, np.array(u, float, copy=True), out)
    except AttributeError:      # a problem without a __dict__: nothing kept
        pass
    return out


def _read_out(case: Case, problem, u, prm: FoilParameters) -> ReadOut:
    Hs = case.h_scale
    cuts = jump_crossings(problem, u, prm, np.array(jump_gaps(case, True)) / Hs)
    pts, wts = wrap_samples(problem.X, prm.beta, cuts=cuts)
    p, dpdx = pressure_and_gradient(case, problem, u, pts)
    # at the pressure's points (pts first): their table is built once
    h = problem.gap(u, prm, _stencil(problem, pts)[0])[:pts.size] * Hs
    loc = friction_for(case, h, resting=True, p=p, dpdx=dpdx)
    mu = float(np.sum(loc["mu"] * wts) / prm.beta)
    shares = tuple(float(np.sum(wts * (loc["regime"] == k)) / prm.beta) for k in range(3))
    Pf = (p - case.air.ambient_pressure) / case.p_bar
    Pc = prm.land * forms.contact_law(h / Hs, prm.as_form_args())[0]  # lands only
    contact_share = float(np.sum(Pc * wts) / max(np.sum((Pf + Pc) * wts), 1e-300))
    Hmin, Xmin = minimum(problem, u, prm)
    e = 0.5 * prm.beta
    H3 = problem.gap(u, prm, np.array([0.0, -e, e]))
    traction = traction_summary(case, mu, contact_share)
    return ReadOut(h_center=H3[0] * Hs, h_inlet=H3[1] * Hs, h_outlet=H3[2] * Hs,
                   h_min=Hmin * Hs, x_min=Xmin * case.x_scale, mu=traction["mu"],
                   shares=shares, contact_share=contact_share, pts=pts, wts=wts, h=h, p=p,
                   dpdx=dpdx, traction=traction,
                   compression=max(0.0, -min(float(np.min(h)), Hmin * Hs)), cuts=cuts)


#: The gap's slope at a jump crossing is read by a central difference over this step
#: (scaled x): the Hermite gap is smooth there to far below the 1e-9 relative that
#: rounding leaves in the difference.
SLOPE_STEP = 1e-6


def read_moved(case: Case, problem, u, du, prm: FoilParameters,
               here: ReadOut) -> tuple[ReadOut, float] | None:
    """The read quantities of ``u + du`` (a Newton iterate plus a small correction) at about
    two thirds of :func:`read_out`'s price (2.2 ms after its 3.5 at 11,117 unknowns): the
    gaps at the centre and the minimum as :func:`read_out` reads them, mu and the contact
    share on ``here``'s wrap quadrature
    (``here``: :func:`read_out` of ``u``; its cells split where ``u``'s gap crosses the
    friction's jumps, so no search for ``u + du``'s crossings, and the basis functions'
    tables are ``here``'s). Returns that :class:`ReadOut` (the fields not read here are
    ``here``'s) and a bound of what the moved crossings add to mu's change: each crossing
    moves by the gap's change there over its slope (first order), across the jump of the
    local friction there, sum |jump| |shift| / beta (0 where ``mu`` is the onset of slip,
    mu_cc x the contact share, which has no jumps). None where a quadrature point's gap
    crosses a jump level between ``u`` and ``u + du`` (the rule then straddles a jump it
    does not split: :func:`read_out` of ``u + du`` is needed).

    Why it bounds the change :func:`read_out` reads between ``u`` and ``u + du``: on each
    cell of ``here``'s rule the local friction is smooth for both states (no point changed
    side), so the rule reads ``u + du``'s smooth part to the quadrature's order; what it
    misses is the integrand's jump moving with its crossing, which the bound adds."""
    if here.cuts is None:
        return None
    v = u + du
    Hs, e = case.h_scale, 0.5 * prm.beta
    pts, wts = here.pts, here.wts
    p, dpdx = pressure_and_gradient(case, problem, v, pts)
    h = problem.gap(v, prm, _stencil(problem, pts)[0])[:pts.size] * Hs
    levels = np.array(jump_gaps(case, True))
    if np.any((h[:, None] > levels[None, :]) != (here.h[:, None] > levels[None, :])):
        return None
    loc = friction_for(case, h, resting=True, p=p, dpdx=dpdx)
    mu = float(np.sum(loc["mu"] * wts) / prm.beta)
    Pf = (p - case.air.ambient_pressure) / case.p_bar
    Pc = prm.land * forms.contact_law(h / Hs, prm.as_form_args())[0]
    contact_share = float(np.sum(Pc * wts) / max(np.sum((Pf + Pc) * wts), 1e-300))
    Hmin, Xmin = minimum(problem, v, prm)
    H3 = problem.gap(v, prm, np.array([0.0, -e, e]))
    traction = traction_summary(case, mu, contact_share)
    moved = replace(here, h_center=H3[0] * Hs, h_inlet=H3[1] * Hs, h_outlet=H3[2] * Hs,
                    h_min=Hmin * Hs, x_min=Xmin * case.x_scale, mu=traction["mu"],
                    contact_share=contact_share, h=h, p=p, dpdx=dpdx, traction=traction)
    x = here.cuts
    if x.size == 0 or here.traction.get("mu_film") is not None:
        return moved, 0.0
    # the crossings' shifts: the gap's change there over its slope
    at = np.concatenate([x, x - SLOPE_STEP, x + SLOPE_STEP])
    H0, H1 = problem.gap(u, prm, at).reshape(3, -1), problem.gap(v, prm, at).reshape(3, -1)
    slope = np.abs(H0[2] - H0[1]) / (2.0 * SLOPE_STEP)
    with np.errstate(divide="ignore", invalid="ignore"):
        shift = np.abs(H1[0] - H0[0]) / slope
    # the local friction's jump at each crossing: either side of its level, at the
    # pressure of the quadrature point on that side (the cut is a cell end: its nearest
    # points lie 1 % of the cell away; ``here``'s, where the state's own width average
    # is not recomputed)
    level = levels[np.argmin(np.abs(H0[0][:, None] * Hs - levels[None, :]), axis=1)]
    side = 1e-9 * np.maximum(level, case.sigma)
    right = np.clip(np.searchsorted(pts, x), 1, pts.size - 1)
    rises = H0[2] > H0[1]            # the gap below the level on the cut's left
    k = np.concatenate([np.where(rises, right - 1, right), np.where(rises, right, right - 1)])
    f = friction_for(case, np.concatenate([level - side, level + side]), resting=True,
                     p=here.p[k], dpdx=here.dpdx[k])["mu"].reshape(2, -1)
    jump = float(np.sum(np.abs(f[1] - f[0]) * shift) / prm.beta)
    return moved, (jump if np.isfinite(jump) else np.inf)


def error_scale(case: Case, name: str, value: float) -> float:
    """What an error in quantity ``name`` at ``value`` is measured against: the larger of
    the gap and the roughness sigma (a gap below the roughness matters only through the
    contact it implies, which mu and the contact share carry; a web resting compressed has
    a gap near or below 0), mu or :data:`MU_SCALE` mu_cc, and 1 for the contact share (a
    share of the load: its error is absolute)."""
    if name == "contact_share":
        return 1.0
    if name == "mu":
        return max(abs(value), MU_SCALE * case.friction.mu_cc)
    return max(abs(value), case.sigma)


def errors_between(case: Case, answer: ReadOut, other: ReadOut) -> dict[str, float]:
    """|answer - other| per :data:`READ_QUANTITIES`, each against :func:`error_scale` of the
    answer's value."""
    out = {}
    for name in READ_QUANTITIES:
        a = answer.value(name)
        scale = error_scale(case, name, a)
        out[name] = abs(a - other.value(name)) / scale if scale > 0 else float("inf")
    return out
