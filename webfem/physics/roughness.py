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
from scipy.special import erfc

__all__ = ["mean_excess", "mean_gap", "wet_share", "shear_factor", "DENSITIES"]

#: The asperity height densities (as :data:`webfem.physics.contact.DISTRIBUTIONS`).
DENSITIES = ("exponential", "gaussian")
_SQ2, _SQ2PI = np.sqrt(2.0), np.sqrt(2.0 * np.pi)


def _check(distribution: str) -> None:
    if distribution not in DENSITIES:
        raise ValueError(f"distribution = {distribution!r} is not valid: must be one of "
                         + ", ".join(repr(d) for d in DENSITIES))


def mean_excess(h, sigma, distribution: str = "exponential"):
    """E[(z - h)+] [same unit as h]: the mean compression of the asperities at separation h."""
    h = np.asarray(h, dtype=float)
    if distribution == "exponential":
        with np.errstate(over="ignore"):
            tail = 0.5 * sigma * np.exp(-np.abs(h) / sigma)
        return np.where(h >= 0.0, tail, tail - h)
    _check(distribution)
    x = h / sigma
    return sigma * (np.exp(-0.5 * x * x) / _SQ2PI - 0.5 * x * erfc(x / _SQ2))


def mean_gap(h, sigma, distribution: str = "exponential"):
    """E[(h - z)+] [same unit as h]: the flow gap, the mean local air gap over the heights."""
    h = np.asarray(h, dtype=float)
    if distribution == "exponential":
        tail = 0.5 * sigma * np.exp(-np.abs(h) / sigma)
        return np.where(h >= 0.0, h + tail, tail)
    _check(distribution)
    # h Phi(h/sigma) + sigma phi(h/sigma): no cancellation of h against -h far below 0
    x = h / sigma
    return h * wet_share(h, sigma, distribution) + sigma * np.exp(-0.5 * x * x) / _SQ2PI


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


#: Gauss-Legendre points of each piece of :func:`shear_factor`'s integral.
_NODES = np.polynomial.legendre.leggauss(40)
#: The heights beyond which the densities are negligible, in units of sigma (exp(-40) and
#: exp(-12.5^2 / 2) of the peak).
_REACH = {"exponential": 40.0, "gaussian": 12.5}
#: Gaps per block of :func:`shear_factor`'s quadrature (its arrays then fit in cache).
_BLOCK = 2048


def shear_factor(h, sigma, slip_length, distribution: str = "exponential"):
    """E[1 / ((h - z) + l); z < h] [1/m for h in m]: the mean Couette shear over eta U_s.

    With y = h - z (the local gap) and u = ln(y + l), dy / (y + l) = du: the integral of the
    density over u, smooth even where the gap closes (y -> 0). Gauss-Legendre in u on two
    pieces, split where z = 0 (the exponential density's kink), over the heights where the
    density is not negligible. ``slip_length`` l > 0 (2 a lambda)."""
    _check(distribution)
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
