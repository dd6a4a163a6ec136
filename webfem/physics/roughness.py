"""The web's roughness seen by the asperities and by the air: expectations over the asperity
heights z (physics.md, "Webs that rest on the roller" and "Air through the roughness").

With the roller at h above the web's mean plane, an asperity of height z > h is pressed down
by z - h, and the air gap over a point of height z < h is h - z. Two height densities, as
:mod:`webfem.physics.contact`: the paper's two-sided exponential phi(z) = exp(-|z|/sigma) /
(2 sigma) (Eq. 2) and the Gaussian of RMS sigma (Eq. 1). Every function broadcasts and holds
for any h, negative included (the web's mean plane below the roller's crest: its asperities
and surface layer compressed).

* :func:`mean_excess` E[(z - h)+], the mean asperity compression: the contact pressure is
  (E_b / t) times it. Exponential: (sigma/2) exp(-h/sigma) for h >= 0, -h + (sigma/2)
  exp(h/sigma) for h < 0, smooth to the second derivative at 0 and unbounded as h falls;
* :func:`mean_gap` E[(h - z)+] = h + E[(z - h)+], the flow gap: always positive, h to within
  2.5 % of sigma above 3 sigma, sigma/2 at h = 0 (exponential);
* :func:`wet_share` P(z < h), the share of the surface the air wets: d mean_gap / dh;
* :func:`shear_factor` E[1 / ((h - z) + l); z < h]: the film's mean Couette shear over
  eta U_s, the air sheared only where it wets the roller, over its local gap plus the slip
  length l (which cuts off the logarithmic singularity at contact). It tends to 1/(h + l) for
  h >> sigma (as 1 + 2 sigma^2/h^2 for the exponential density) and to zero like
  exp(h/sigma) as the web compresses.

Examples
--------
>>> float(mean_gap(0.0, 4e-6)), float(mean_excess(-1e-6, 4e-6) - mean_excess(-1e-6, 4e-6, "gaussian")) > 0
(2e-06, True)
>>> round(float(shear_factor(1e-3, 4e-6, 0.13e-6) * (1e-3 + 0.13e-6)), 6)   # h >> sigma
1.000032
"""

from __future__ import annotations

import numpy as np
from scipy.special import erfc, erfcx, exp1, expi

__all__ = ["mean_excess", "mean_gap", "wet_share", "shear_factor", "log_mean_excess",
           "DENSITIES"]

#: The asperity height densities (as :data:`webfem.physics.contact.DISTRIBUTIONS`).
DENSITIES = ("exponential", "gaussian")
_SQ2, _SQ2PI = np.sqrt(2.0), np.sqrt(2.0 * np.pi)


def _check(distribution: str) -> None:
    if distribution not in DENSITIES:
        raise ValueError(f"distribution = {distribution!r} is not valid: must be one of "
                         + ", ".join(repr(d) for d in DENSITIES))


def _gauss_tail(x):
    """phi(x) g(x), g(x) and R(x) for x >= 0: phi the standard normal density, R(x) =
    Q(x) / phi(x) the Mills ratio (Q = P(Z > x)) and g(x) = 1 - x R(x) = E[(Z - x)+] /
    phi(x).

    The textbook phi(x) - x Q(x) loses 2 digits by x = 10 and underflows to 0 at x = 38,
    where a stiff surface's contact gap can sit; R = sqrt(pi/2) erfcx(x / sqrt 2) keeps 13
    digits of g to x = 30, and beyond, the asymptotic series g(x) = x^-2 (1 - 3/x^2 +
    15/x^4 - ...) and x R(x) = 1 - 1/x^2 + 3/x^4 - ... (truncated below 3e-13 relative).
    Only phi(x) itself underflows (x > 38); :func:`log_mean_excess` has no such limit."""
    x = np.asarray(x, dtype=float)
    far = x > _SERIES_FROM
    xs = np.where(far, 1.0, x)
    mills = np.sqrt(0.5 * np.pi) * erfcx(xs / _SQ2)
    y = 1.0 / np.where(far, x, 1.0) ** 2
    g = np.where(far, np.polyval(_G_SERIES, y) * y, 1.0 - xs * mills)
    mills = np.where(far, np.polyval(_R_SERIES, y) * np.sqrt(y), mills)
    with np.errstate(under="ignore"):
        return np.exp(-0.5 * x * x) / _SQ2PI * g, g, mills


#: Above this many sigma the Gaussian tail comes from its asymptotic series.
_SERIES_FROM = 30.0
#: g(x) x^2 = 1 - 3 y + 15 y^2 - 105 y^3 + 945 y^4 - 10395 y^5 + 135135 y^6, y = 1/x^2
#: (highest power first, for numpy.polyval); the next term is below 3e-13 at x = 30.
_G_SERIES = np.array([135135.0, -10395.0, 945.0, -105.0, 15.0, -3.0, 1.0])
#: x R(x) = 1 - y + 3 y^2 - 15 y^3 + 105 y^4 - 945 y^5 + 10395 y^6 (R the Mills ratio).
_R_SERIES = np.array([10395.0, -945.0, 105.0, -15.0, 3.0, -1.0, 1.0])


def mean_excess(h, sigma, distribution: str = "exponential"):
    """E[(z - h)+] [same unit as h]: the mean compression of the asperities at separation h.

    Both densities are symmetric, so E[(z - h)+] = max(-h, 0) + E[(z - |h|)+]: the tail is
    evaluated only at |h| (no cancellation of h against -h below 0)."""
    h = np.asarray(h, dtype=float)
    if distribution == "exponential":
        with np.errstate(over="ignore"):
            tail = 0.5 * sigma * np.exp(-np.abs(h) / sigma)
        return np.where(h >= 0.0, tail, tail - h)
    _check(distribution)
    tail, _, _ = _gauss_tail(np.abs(h) / sigma)
    return np.maximum(-h, 0.0) + sigma * tail


def log_mean_excess(h, sigma, distribution: str = "exponential"):
    """ln E[(z - h)+] [ln m for h in m] and its derivative in h, -P(z > h) / E[(z - h)+]
    [1/m]: finite at every h, however far above the asperities (the Gaussian's
    E[(z - h)+] underflows past h = 38 sigma; its logarithm does not). Both are concave in
    h (the densities are log-concave), so Newton's method on them steps monotonically.

    Returns
    -------
    (log, slope): arrays shaped as ``h``.

    >>> log, slope = log_mean_excess(80e-6, 2e-6, "gaussian")   # 40 sigma: E underflows
    >>> round(float(log), 3), round(float(slope * 2e-6), 4)
    (-821.421, -40.0499)
    """
    h = np.asarray(h, dtype=float)
    up = h >= 0.0
    if distribution == "exponential":
        hd = np.where(up, 0.0, h)
        down = -hd + 0.5 * sigma * np.exp(hd / sigma)
        log = np.where(up, np.log(0.5 * sigma) - np.where(up, h, 0.0) / sigma, np.log(down))
        slope = np.where(up, -1.0 / sigma, -(1.0 - 0.5 * np.exp(hd / sigma)) / down)
        return log, slope
    _check(distribution)
    x = np.abs(h) / sigma
    tail, g, mills = _gauss_tail(x)
    # above the mean plane: ln sigma + ln phi(x) + ln g(x); -Q/E = -R(x) / (sigma g(x))
    log_up = np.log(sigma) - 0.5 * x * x - np.log(_SQ2PI) + np.log(g)
    # below it: E = -h + sigma phi g (no underflow), P(z > h) = P(z < |h|)
    below = np.where(up, 1.0, np.maximum(-h, 0.0) + sigma * tail)
    log = np.where(up, log_up, np.log(below))
    slope = np.where(up, -mills / (sigma * g),
                     -wet_share(np.abs(h), sigma, distribution) / below)
    return log, slope


def mean_gap(h, sigma, distribution: str = "exponential"):
    """E[(h - z)+] [same unit as h]: the flow gap, the mean local air gap over the heights."""
    h = np.asarray(h, dtype=float)
    if distribution == "exponential":
        tail = 0.5 * sigma * np.exp(-np.abs(h) / sigma)
        return np.where(h >= 0.0, h + tail, tail)
    _check(distribution)
    # E[(h - z)+] = h + E[(z - h)+] = max(h, 0) + E[(z - |h|)+]: positive, no cancellation
    tail, _, _ = _gauss_tail(np.abs(h) / sigma)
    return np.maximum(h, 0.0) + sigma * tail


def wet_share(h, sigma, distribution: str = "exponential"):
    """P(z < h): the share of the surface below the roller's level, d E[(h - z)+] / dh."""
    h = np.asarray(h, dtype=float)
    if distribution == "exponential":
        half = 0.5 * np.exp(-np.abs(h) / sigma)
        return np.where(h >= 0.0, 1.0 - half, half)
    _check(distribution)
    return 0.5 * erfc(-h / (sigma * _SQ2))


def _density(z, sigma, distribution):
    if distribution == "exponential":
        return np.exp(-np.abs(z) / sigma) / (2.0 * sigma)
    return np.exp(-0.5 * (z / sigma) ** 2) / (sigma * _SQ2PI)


#: Gauss-Legendre points of each piece of :func:`shear_factor`'s integral (the Gaussian
#: heights'; :func:`_shear_factor` takes the exponential too, the closed form's check).
_NODES = np.polynomial.legendre.leggauss(40)
#: The heights beyond which the densities are negligible, in units of sigma (exp(-40) and
#: exp(-12.5^2 / 2) of the peak).
_REACH = {"exponential": 40.0, "gaussian": 12.5}
#: Gaps per block of :func:`shear_factor`'s quadrature (its arrays then fit in cache).
_BLOCK = 2048


def shear_factor(h, sigma, slip_length, distribution: str = "exponential"):
    """E[1 / ((h - z) + l); z < h] [1/m for h in m]: the mean Couette shear over eta U_s.

    Exponential heights: in closed form (:func:`_exponential_shear`, exponential integrals
    scaled so that no gap overflows them). Gaussian heights: with y = h - z (the local gap)
    and u = ln(y + l), dy / (y + l) = du, the integral of the density over u, smooth even
    where the gap closes (y -> 0): Gauss-Legendre in u over the heights where the density
    is not negligible. ``slip_length`` l > 0 (2 a lambda)."""
    _check(distribution)
    if distribution == "exponential":
        return _exponential_shear(*(np.asarray(v, float) for v in (h, sigma, slip_length)))
    h, sigma, ell = np.broadcast_arrays(*(np.asarray(v, float) for v in
                                          (h, sigma, slip_length)))
    if h.size <= _BLOCK:
        return _shear_factor(h, sigma, ell, distribution)
    # in blocks of gaps, so the quadrature's arrays stay in cache (each gap's sum is the same)
    shape = h.shape
    h, sigma, ell = (np.ravel(v) for v in (h, sigma, ell))
    out = np.empty(h.shape)
    for i in range(0, h.size, _BLOCK):
        out[i:i + _BLOCK] = _shear_factor(h[i:i + _BLOCK], sigma[i:i + _BLOCK],
                                          ell[i:i + _BLOCK], distribution)
    return out.reshape(shape)


#: Above this argument the scaled exponential integrals come from their asymptotic series
#: (exp(a) overflows past 709); the series' 12 terms leave 12!/600^12 (2e-25) relative.
_SCALED_FROM = 600.0
#: k! for the asymptotic series: e^a E1(a) ~ sum (-1)^k k!/a^(k+1), e^-a Ei(a) ~ sum k!/a^(k+1)
_FACTORIALS = np.cumprod(np.concatenate([[1.0], np.arange(1.0, 12.0)]))


def _scaled_integrals(a):
    """(e^a E1(a), e^-a Ei(a)) for a > 0, finite however large a is."""
    far = a > _SCALED_FROM
    near = np.where(far, 1.0, a)
    with np.errstate(over="ignore", under="ignore"):
        e1, ei = np.exp(near) * exp1(near), np.exp(-near) * expi(near)
    if np.any(far):
        y = 1.0 / np.where(far, a, 1.0)
        terms = _FACTORIALS[:, None] * y ** np.arange(1, _FACTORIALS.size + 1)[:, None]
        signs = (-1.0) ** np.arange(_FACTORIALS.size)[:, None]
        # the smallest terms first
        e1 = np.where(far, np.sum((signs * terms)[::-1], axis=0).reshape(a.shape), e1)
        ei = np.where(far, np.sum(terms[::-1], axis=0).reshape(a.shape), ei)
    return e1, ei


def _exponential_shear(h, sigma, ell):
    """:func:`shear_factor` for the two-sided exponential density, in closed form: with a =
    (h + l)/sigma and c = l/sigma, (e^a E1(a) + e^-a (Ei(a) - Ei(c))) / (2 sigma) for h >= 0
    (the heights below the mean plane, then those between it and h), e^a E1(c) / (2 sigma)
    for h < 0. The integrals of c are taken on ``sigma`` and ``ell`` as given (one value for
    every gap, as a read-out asks). Why: the quadrature it replaces (80 points a gap)
    matched it to 1e-11 (7.5e-9 at 37 sigma) and cost about 4 ms of a cold fe2d base
    solve's read-outs."""
    c = np.asarray(ell / sigma, dtype=float)
    # c's integrals scaled too: a slip length above 709 sigma (a smooth film at low ambient
    # pressure) overflows e^c and Ei(c) (0 x inf: NaN)
    e1_c, ei_c = _scaled_integrals(c)          # e^c E1(c), e^-c Ei(c)
    shape = np.broadcast_shapes(h.shape, c.shape)
    h, sigma, ell, c, ei_c, e1_c = (np.broadcast_to(v, shape).ravel()
                                    for v in (h, sigma, ell, c, ei_c, e1_c))
    a = (np.maximum(h, 0.0) + ell) / sigma
    e1, ei = _scaled_integrals(a)
    with np.errstate(under="ignore"):
        up = e1 + ei - np.exp(c - a) * ei_c           # a >= c: no overflow
        down = np.exp(np.minimum(h, 0.0) / sigma) * e1_c
    return (np.where(h >= 0.0, up, down) / (2.0 * sigma)).reshape(shape)


def _shear_factor(h, sigma, ell, distribution):
    reach = _REACH[distribution] * sigma
    g, w = _NODES
    total = np.zeros(h.shape)
    # y in [max(0, h - reach), max(0, h)]: z in [0, min(h, reach)];
    # y in [max(0, h), h + reach]: z in [-reach, min(0, h)]
    for y0, y1 in ((np.maximum(h - reach, 0.0), np.maximum(h, 0.0)),
                   (np.maximum(h, 0.0), np.maximum(h + reach, 0.0))):
        u0, u1 = np.log(y0 + ell), np.log(y1 + ell)
        half = 0.5 * (u1 - u0)
        u = 0.5 * (u0 + u1)[..., None] + half[..., None] * g
        y = np.exp(u) - ell[..., None]
        dens = _density(h[..., None] - y, sigma[..., None], distribution)
        total = total + half * np.sum(dens * w, axis=-1)
    return total
