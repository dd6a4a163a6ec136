"""What a user reads off a solved discrete state: the gaps, the friction and the contact share.

One function, :func:`read_out`, used by the driver for the summary and by the error estimate
(:mod:`webfem.models.mesh_error`) to compare the same quantities on two meshes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..case import Case
from ..fem import forms
from ..fem.scaling import FoilParameters
from ..physics.effects import MU_SCALE, traction_summary
from ..physics.friction import friction_for, jump_gaps
from .refine import minimum, wrap_samples

__all__ = ["ReadOut", "read_out", "jump_crossings", "pressure_and_gradient", "READ_QUANTITIES"]

#: The quantities whose error every result states (``error_<name>`` summary keys).
READ_QUANTITIES = ("h_center", "h_min", "mu", "contact_share")


@dataclass(frozen=True)
class ReadOut:
    """The gaps [m] at the wrap centre and edges, the smallest gap and where [m], the
    headline friction ``mu`` (where nothing slides the traction at the onset of slip,
    :func:`~webfem.physics.effects.traction_summary`, whose keys ``traction`` holds), the
    regime shares, the share of the wrap load carried by asperity contact, the wrap
    quadrature (points, weights, gaps, pressure and its gradient) the summary and
    diagnostics keep, and the web's largest ``compression`` -h [m] where it rests below the
    roller's crest (0 elsewhere)."""

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
    nodes = np.asarray(problem.X, float)
    j = np.clip(np.searchsorted(nodes, X), 1, nodes.size - 1)
    room = np.minimum(X - nodes[j - 1], nodes[j] - X)
    delta = np.where(room > 0.0, np.minimum(1e-3, 0.45 * room), 1e-7)
    P = problem.pressure(u, np.concatenate([X, X - delta, X + delta, X - 2 * delta,
                                            X + 2 * delta]))
    n = len(X)
    dPdX = (8.0 * (P[2 * n:3 * n] - P[n:2 * n]) - (P[4 * n:] - P[3 * n:4 * n])) / \
        (12.0 * delta)
    return (case.air.ambient_pressure + P[:n] * case.p_bar,
            dPdX * case.p_bar / case.x_scale)


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
    found = []
    for level in np.atleast_1d(levels):
        above = H > level
        i = np.nonzero(above[1:] != above[:-1])[0]
        if i.size == 0:
            continue
        lo, hi, Hlo, Hhi = xs[i], xs[i + 1], H[i], H[i + 1]
        t = np.linspace(0.0, 1.0, 17)
        for _ in range(4):      # each round cuts the brackets 16-fold: 6.6e4 in all
            x = lo[:, None] + (hi - lo)[:, None] * t[None, :]
            Hx = problem.gap(u, prm, x.ravel()).reshape(x.shape)
            Hx[:, 0], Hx[:, -1] = Hlo, Hhi
            k = np.argmax((Hx[:, 1:] > level) != (Hx[:, :1] > level), axis=1)
            r = np.arange(k.size)
            lo, hi, Hlo, Hhi = x[r, k], x[r, k + 1], Hx[r, k], Hx[r, k + 1]
        # the gap is smooth inside a bracket this short: linear to rounding
        with np.errstate(all="ignore"):
            w = np.clip(np.nan_to_num((level - Hlo) / (Hhi - Hlo), nan=0.5), 0.0, 1.0)
        found.append(lo + w * (hi - lo))
    return np.sort(np.concatenate(found)) if found else np.empty(0)


def read_out(case: Case, problem, u, prm: FoilParameters) -> ReadOut:
    """The quantities of a solved state ``u`` of ``problem`` (SI units). The last one read
    of a problem is kept on it: the error estimate and the result read the same answer
    (a pure function of its arguments; about 10 ms on a 2-D mesh of 2e4 unknowns)."""
    kept = getattr(problem, "_read_out", None)
    if kept is not None and kept[0] is case and kept[1] is prm and kept[2].shape == \
            np.shape(u) and np.array_equal(kept[2], u):
        return kept[3]
    out = _read_out(case, problem, u, prm)
    try:
        problem._read_out = (case, prm, np.array(u, float, copy=True), out)
    except AttributeError:      # a problem without a __dict__: nothing kept
        pass
    return out


def _read_out(case: Case, problem, u, prm: FoilParameters) -> ReadOut:
    Hs = case.h_scale
    pts, wts = wrap_samples(problem.X, prm.beta,
                            cuts=jump_crossings(problem, u, prm, np.array(jump_gaps(case, True))
                                                / Hs))
    h = problem.gap(u, prm, pts) * Hs
    p, dpdx = pressure_and_gradient(case, problem, u, pts)
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
                   compression=max(0.0, -min(float(np.min(h)), Hmin * Hs)))


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
