"""Asperity contact between a rough web and a roller (paper's Eqs. 1-2, 10-13).

Rigid asperities sit on a linear-spring base of stiffness E_b / t; the mean contact pressure
at separation h is p_c(h) = (E_b / t) int_h^inf (z - h) phi(z) dz. Two height densities:

* ``"exponential"`` (Eq. 2, the paper's choice): phi = exp(-z/sigma) / (2 sigma), giving
  p_c = E_b sigma / (2 t) exp(-h/sigma) (Eq. 10) and h_c = sigma ln(E_b sigma / (2 t pbar))
  (Eq. 11);
* ``"gaussian"`` (Eq. 1): phi = exp(-z^2 / (2 sigma^2)) / (sigma sqrt(2 pi)), giving exactly
  p_c = (E_b / t) [sigma / sqrt(2 pi) exp(-h^2 / (2 sigma^2)) - (h / 2) erfc(h / (sigma sqrt 2))]
  and h_c from p_c(h_c) = pbar by Newton's method on ln p_c (a stiff surface's h_c is a
  few sigma, where p_c is many orders below its value at h = 0: in log space nothing
  underflows).

Both hold for h < 0 too (:mod:`webfem.physics.roughness`): a web whose wrap pressure exceeds
what the asperities carry at h = 0 rests on the roller with its surface compressed.

All functions broadcast over numpy arrays.

Examples
--------
>>> round(float(contact_gap(80 / 0.055, 175e3, 4e-6, 70e-6)) * 1e6, 3)   # h_c in micrometres
4.939
"""

from __future__ import annotations

import numpy as np

from .roughness import log_mean_excess, mean_excess, wet_share

__all__ = ["contact_pressure", "contact_pressure_derivative", "contact_gap", "load_ratio",
           "REGIMES", "DISTRIBUTIONS", "regime_code"]

#: Asperity height densities: the paper's Eq. 2 (default) and Eq. 1.
DISTRIBUTIONS = ("exponential", "gaussian")
_SQ2, _SQ2PI = np.sqrt(2.0), np.sqrt(2.0 * np.pi)


def _check(distribution):
    if distribution not in DISTRIBUTIONS:
        raise ValueError(f"distribution = {distribution!r} is not valid: must be one of "
                         + ", ".join(repr(d) for d in DISTRIBUTIONS))

#: Regime names by code: 0 boundary (h < h_c), 1 mixed (h_c <= h <= 3 sigma), 2 fluid film.
REGIMES = ("boundary", "mixed", "fluid")


def contact_pressure(h, E_b, sigma, t, distribution="exponential"):
    """Mean asperity contact pressure p_c(h) = (E_b / t) E[(z - h)+] [Pa] (Eq. 10 for the
    exponential density and h >= 0), continued past full asperity compression: for h < 0
    (the web's mean surface plane below the roller's crest) the exponential density gives
    (E_b / t)(-h + (sigma/2) exp(h/sigma)), smooth to the second derivative at h = 0 and
    unbounded as h falls, so every wrap pressure has an equilibrium (physics.md, "Webs that
    rest on the roller"; :func:`webfem.physics.roughness.mean_excess`).

    Eq. 8 as printed integrates (h - z); the load is positive for (z - h), which gives Eq. 10.
    """
    return E_b / t * mean_excess(h, sigma, distribution)


def contact_pressure_derivative(h, E_b, sigma, t, distribution="exponential"):
    """d p_c / d h = -(E_b / t) P(z > h) [Pa/m] (negative: contact relaxes as the gap
    opens)."""
    return -E_b / t * (1.0 - wet_share(h, sigma, distribution))


def contact_gap(p_bar, E_b, sigma, t, distribution="exponential"):
    """Gap h_c at which contact alone carries the wrap pressure p_bar = T/R [m]: Eq. 11,
    sigma ln(E_b sigma / (2 t p_bar)), while p_bar <= E_b sigma / (2 t); beyond, the web
    rests compressed (h_c < 0) on the continued law, solved by Newton's method (p_c is
    convex and decreasing in h: monotone steps). The Gaussian heights: p_c(h_c) = p_bar by
    Newton's method on ln p_c (:func:`_gaussian_gap`), finite for every stiffness."""
    p_bar = np.asarray(p_bar, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        h = sigma * np.log(E_b * sigma / (2.0 * t * p_bar))
    if distribution == "exponential":
        over = p_bar > E_b * sigma / (2.0 * t)
        if not np.any(over):
            return h
        # start below the root: the linear part -h alone carries p_bar there
        g = np.where(over, -p_bar * t / E_b, 0.0)
        for _ in range(60):
            f = E_b / t * mean_excess(g, sigma) - p_bar
            step = f / contact_pressure_derivative(g, E_b, sigma, t)
            g = np.where(over, g - step, g)
            if np.all(np.abs(np.where(over, step, 0.0)) <= 1e-14 * sigma):
                break
        return np.where(over, g, h)
    _check(distribution)
    return _gaussian_gap(p_bar, E_b, sigma, t)


def _gaussian_gap(p_bar, E_b, sigma, t, per_point=False):
    """h_c of the Gaussian heights: Newton's method on ln E[(z - h)+] = ln(p_bar t / E_b).

    In log space (:func:`~webfem.physics.roughness.log_mean_excess`) nothing underflows,
    however stiff the surface: a stiff one (E_b sigma / (t p_bar) = 1e5) rests a few sigma
    above its mean plane (3.9), where p_c itself is 2.5e-5 of its value at h = 0; beyond
    38 sigma it is 0 in floating point. ln p_c is concave and decreasing, so after
    at most one step the iterates fall monotonically to the root. The start: where the
    density phi(h / sigma) / sigma = p_bar t / (E_b sigma), above the root (E = sigma phi
    g < sigma phi there), or, for a load the asperities carry only compressed (h_c < 0),
    h = -p_bar t / E_b, where the linear part alone carries p_bar.

    Arrays step together until every point has converged; ``per_point`` stops each point at
    its own convergence instead, so its h_c is the bits a solve of that point alone gives
    (:func:`tail_gaussian_gaps`)."""
    p_bar, E_b, sigma, t = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                                 for v in (p_bar, E_b, sigma, t)))
    target = np.log(p_bar * t / E_b)
    ratio = np.exp(np.log(E_b * sigma / (t * p_bar)) - np.log(_SQ2PI))
    h = np.where(ratio > 1.0, sigma * np.sqrt(2.0 * np.log(np.maximum(ratio, 1.0))),
                 -p_bar * t / E_b)
    going = np.ones(h.shape, dtype=bool)
    for _ in range(100):
        log, slope = log_mean_excess(h, sigma, "gaussian")
        step = (log - target) / slope
        if per_point:
            step = np.where(going, step, 0.0)
        h = h - step
        going &= ~(np.abs(step) <= 1e-14 * np.maximum(sigma, np.abs(h)))
        if not np.any(going):
            break
    return h[()] if h.ndim == 0 else h


#: A web rests on its asperities where contact carries at least this share of the wrap
#: pressure T/R. The FE models hold a landed web at the gap where contact and film together
#: carry T/R, i.e. within round-off of h_c; judging "h < h_c" there would let round-off pick
#: the regime (and the paper's jump in Eq. 29). 0.999 moves the edge by sigma ln(1/0.999) =
#: 0.001 sigma (4 nm for newsprint) above h_c.
RESTING_SHARE = 0.999


def resting_gap(p_bar, E_b, sigma, t, distribution="exponential", share=RESTING_SHARE):
    """The gap below which contact carries at least ``share`` of p_bar: the edge of the
    boundary regime for a web resting on its asperities (``share = 1`` gives h_c)."""
    return contact_gap(share * np.asarray(p_bar, float), E_b, sigma, t, distribution)


def load_ratio(h, p_bar, E_b, sigma, t, variant="paper", distribution="exponential",
               h_edge=None):
    """Share chi_c of the wrap load carried by asperity contact (Eq. 13); chi_f = 1 - chi_c.

    ``variant="paper"``: 1 below h_c, p_c/p_bar up to 3 sigma, 0 above (jumps at 3 sigma).
    ``variant="continuous"``: min(1, p_c/p_bar) for every h (no cut at 3 sigma).
    A landed web (h <= 0) is in full contact in both. ``h_edge`` replaces h_c as the edge
    of full contact (see :func:`resting_gap`).
    """
    h = np.asarray(h, dtype=float)
    ratio = np.minimum(contact_pressure(h, E_b, sigma, t, distribution) / p_bar, 1.0)
    if variant == "continuous":
        chi = ratio
    elif variant == "paper":
        h_c = contact_gap(p_bar, E_b, sigma, t, distribution) if h_edge is None else h_edge
        chi = np.where(h < h_c, 1.0, np.where(h <= 3.0 * sigma, ratio, 0.0))
    else:
        raise ValueError(f"variant = {variant!r} is not valid: must be 'paper' or 'continuous'")
    return np.where(h <= 0.0, 1.0, chi)


def regime_code(h, h_c, sigma):
    """0 boundary (h < h_c or landed), 1 mixed (h_c <= h <= 3 sigma), 2 fluid (h > 3 sigma)."""
    h = np.asarray(h, dtype=float)
    return np.where((h < h_c) | (h <= 0.0), 0, np.where(h <= 3.0 * sigma, 1, 2))


#: Above this many sigma the exponential heights (Eq. 2) no longer describe a surface: a
#: surface's peak-to-valley height Rmax is about 7 sigma (the paper's newsprint, Table 1:
#: 27.6 um = 6.9 sigma), so its tallest asperities stand about 3.5 sigma above the mean
#: plane, and the tallest of 1e5 Gaussian summits about sqrt(2 ln 1e5) = 4.8 sigma; Eq. 2's
#: tail has no end (it puts 0.5 exp(-5) = 0.34 % of the heights above 5 sigma, the Gaussian
#: 2.9e-7).
TAIL_SIGMAS = 5.0
#: The contact load share below which the tail is not worth a warning (as the summary's
#: :data:`webfem.describe.CONTACT_NOTED`).
TAIL_SHARE = 0.005


def beyond_the_surface(case, h_c, contact_share) -> bool:
    """Whether an answer's asperity contact comes from the exponential law's tail above any
    real surface: Eq. 2's heights, h_c above :data:`TAIL_SIGMAS` sigma and the asperities
    carrying at least :data:`TAIL_SHARE` of the wrap load (``case`` a
    :class:`webfem.case.Case`)."""
    return (case.friction.distribution == "exponential" and h_c is not None
            and contact_share is not None and h_c > TAIL_SIGMAS * case.sigma
            and contact_share >= TAIL_SHARE)


def tail_gaussian_gaps(cases, h_c, contact_share) -> np.ndarray:
    """The Gaussian heights' h_c (Eq. 1) of every case :func:`beyond_the_surface`, NaN at
    the others, in one vectorised Newton solve: what :func:`tail_warning` computes point by
    point, bit for bit (:func:`_gaussian_gap` stops each point at its own convergence), for
    a batch (``h_c``, ``contact_share``: arrays or sequences beside ``cases``). A stiff
    batch's warnings then cost what its other numbers do, not one scalar Newton solve each.
    """
    cases = list(cases)
    h_c, contact_share = (np.broadcast_to(np.asarray(v, float), (len(cases),)).tolist()
                          for v in (h_c, contact_share))
    beyond = np.array([beyond_the_surface(c, h, s)
                       for c, h, s in zip(cases, h_c, contact_share)], dtype=bool)
    out = np.full(len(cases), np.nan)
    if np.any(beyond):
        at = [c for c, b in zip(cases, beyond) if b]
        out[beyond] = _gaussian_gap(
            np.array([c.p_bar for c in at]), np.array([c.web.modulus_thickness for c in at]),
            np.array([c.sigma for c in at]), np.array([c.web.thickness for c in at]),
            per_point=True)
    return out


def tail_warning(case, h_c, contact_share, gaussian_gap=None) -> str | None:
    """The warning of :func:`beyond_the_surface` (None where it does not apply), with what
    the Gaussian heights (Eq. 1) give for h_c: cheap, and where it lies far below the solved
    gaps the contact, mu and an idler's margin rest on the tail alone. ``gaussian_gap``: that
    h_c where a batch has it already (:func:`tail_gaussian_gaps`); None solves it here."""
    if not beyond_the_surface(case, h_c, contact_share):
        return None
    w, s = case.web, case.sigma
    h_g = (float(contact_gap(case.p_bar, w.modulus_thickness, s, w.thickness, "gaussian"))
           if gaussian_gap is None else float(gaussian_gap))
    return (f"the asperities carry {100 * contact_share:.1f} % of the wrap load, at gaps "
            f"where the exponential heights (friction.distribution = \"exponential\", the "
            f"paper's Eq. 2) put h_c = {h_c * 1e6:.4g} um = {h_c / s:.3g} sigma above the mean "
            f"plane (E_b sigma / (2 t T_eff/R) = "
            f"{w.modulus_thickness * s / (2 * w.thickness * case.p_bar):.3g}): beyond "
            f"{TAIL_SIGMAS:g} sigma no real surface has asperities (a surface's peak-to-valley "
            "height is about 7 sigma, the paper's newsprint 6.9 sigma), so this contact, and "
            "the mu and idler margin it gives, come from the law's unending tail, not the "
            f"surface; the Gaussian heights (friction.distribution = \"gaussian\") put h_c at "
            f"{h_g * 1e6:.4g} um = {h_g / s:.3g} sigma: solve with them to compare")
