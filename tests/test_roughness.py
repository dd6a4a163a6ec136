"""Webs that rest on the roller and air through the roughness (issue 22): the continued contact
law, the flow gap and the film's shear over the wetted area, against their exact forms and
limits (physics.md, "Webs that rest on the roller", "Air through the roughness")."""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import exp1, expi

import webfem
from webfem.physics.contact import contact_gap, contact_pressure
from webfem.physics.roughness import mean_excess, mean_gap, shear_factor, wet_share

from conftest import BASE

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")

SIGMA, ELL = 4e-6, 0.13e-6           # the base web's roughness, 2 a lambda at 1 atm
DENSITIES = ("exponential", "gaussian")


def laplace_shear(h):
    """E[1/((h - z) + l); z < h] for phi(z) = exp(-|z|/s)/(2 s), in closed form."""
    a = (h + ELL) / SIGMA
    if h >= 0.0:
        return (np.exp(-a) * (expi(a) - expi(ELL / SIGMA)) + np.exp(a) * exp1(a)) / (2 * SIGMA)
    return np.exp(a) * exp1(ELL / SIGMA) / (2 * SIGMA)


@pytest.mark.parametrize("h", [-8e-6, -1e-7, 0.0, 1e-7, 1e-6, 4e-6, 12e-6, 40e-6, 100e-6])
def test_the_shear_factor_is_the_exact_integral(h):
    """Exponential heights: the quadrature against the exponential-integral form (1e-12);
    Gaussian heights: against scipy's adaptive quadrature."""
    assert shear_factor(h, SIGMA, ELL) == pytest.approx(laplace_shear(h), rel=1e-11)

    def integrand(z):
        return np.exp(-0.5 * (z / SIGMA) ** 2) / (SIGMA * np.sqrt(2 * np.pi)) / (h - z + ELL)
    ref = quad(integrand, -15 * SIGMA, h, points=[h - 1e-9], limit=500)[0]
    assert shear_factor(h, SIGMA, ELL, "gaussian") == pytest.approx(ref, rel=1e-9)


@pytest.mark.parametrize("h", [-3e-5, 0.0, 1e-8, 2e-5, 1.5e-4, 2.39e-3, 2.41e-3, 1e-2, 1.0])
def test_the_exponential_shear_is_the_integral_far_from_contact_too(h):
    """The closed form (scaled exponential integrals, their asymptotic series past 600 sigma)
    against an adaptive quadrature in units of sigma, the neighbourhood of h cut into pieces:
    rounding (1e-13) at every gap, on both sides of the series' switch (2.4 mm here) and where
    the 80-point quadrature it replaced missed by 7.5e-9 (37 sigma); the old quadrature (kept
    for the Gaussian heights) agrees within that."""
    from webfem.physics import roughness

    hs, ls = h / SIGMA, ELL / SIGMA
    kw = dict(epsabs=0.0, epsrel=1e-13, limit=1000)
    below = quad(lambda t: np.exp(t) / 2 / (hs - t + ls), -np.inf, min(hs, 0.0), **kw)[0]
    cuts = [hs - k for k in (40, 20, 10, 5, 2, 1) if hs - k > 0.0] or None
    above = quad(lambda y: np.exp(y - hs) / 2 / (y + ls), 0.0, hs, points=cuts, **kw)[0] \
        if hs > 0.0 else 0.0
    ref = (below + above) / SIGMA
    assert shear_factor(h, SIGMA, ELL) == pytest.approx(ref, rel=1e-13)
    old = roughness._shear_factor(*np.broadcast_arrays(np.array(h), SIGMA, ELL), "exponential")
    assert float(old) == pytest.approx(ref, rel=1e-8)


@pytest.mark.parametrize("density", DENSITIES)
def test_far_from_contact_the_smooth_film_returns(density):
    """h >> sigma: the flow gap is h, the shear eta U_s / (h + 2 a lambda), approached as
    1 + 2 sigma^2/h^2 for the exponential heights (physics.md: +2.4 % at 10 sigma)."""
    for h in (50 * SIGMA, 200 * SIGMA):
        assert mean_gap(h, SIGMA, density) == pytest.approx(h, rel=1e-12)
        assert shear_factor(h, SIGMA, ELL, density) * (h + ELL) == pytest.approx(1.0, abs=1e-3)
    ratio = shear_factor(10 * SIGMA, SIGMA, ELL) * (10 * SIGMA + ELL)
    assert ratio == pytest.approx(1.024, abs=2e-3)
    assert shear_factor(3 * SIGMA, SIGMA, ELL) * (3 * SIGMA + ELL) == pytest.approx(1.34,
                                                                                   abs=0.01)


@pytest.mark.parametrize("density", DENSITIES)
def test_below_the_crest_the_flow_and_shear_fade_smoothly(density):
    """h << 0: the flow gap, the wetted share and the shear tend to zero, monotonically and
    without a floor (exp(h/sigma) for the exponential heights)."""
    h = -np.linspace(0.0, 12.0 if density == "exponential" else 7.0, 49) * SIGMA
    for f in (mean_gap(h, SIGMA, density), wet_share(h, SIGMA, density),
              shear_factor(h, SIGMA, ELL, density)):
        assert np.all(np.diff(f) < 0.0) and np.all(f > 0.0)
        assert f[-1] / f[0] < 1e-4
    if density == "exponential":
        assert mean_gap(-3 * SIGMA, SIGMA) == pytest.approx(0.5 * SIGMA * np.exp(-3.0))


def test_the_contact_law_continues_smoothly_and_carries_any_load():
    """p_c = (E_b/t)(-h + (sigma/2) exp(h/sigma)) for h < 0: equal to Eq. 10 at h = 0 in value,
    slope and curvature; unbounded as h falls; h_c solves p_c(h_c) = T/R for any T."""
    E_b, t = 175e3, 70e-6
    p = lambda h: contact_pressure(h, E_b, SIGMA, t)       # noqa: E731
    d = 1e-4 * SIGMA
    # value, slope and curvature on both sides of h = 0 (one-sided differences)
    for side in (-1.0, 1.0):
        h1, h2 = side * d, side * 2 * d
        assert p(0.0) == pytest.approx(E_b * SIGMA / (2 * t), rel=1e-15)
        assert (p(h1) - p(0.0)) / h1 == pytest.approx(-E_b / (2 * t), rel=1e-3)
        assert (p(h2) - 2 * p(h1) + p(0.0)) / d**2 == pytest.approx(E_b / (2 * t * SIGMA),
                                                                    rel=1e-3)
    assert p(-10 * t) > 300 * p(0.0)        # unbounded: (E_b/t) |h| far below the crest
    assert p(-1e-6) == pytest.approx(E_b / t * (1e-6 + 0.5 * SIGMA * np.exp(-0.25)))
    for T in (80.0, 300.0, 1e4):
        for density in DENSITIES:
            h_c = contact_gap(T / 0.055, E_b, SIGMA, t, density)
            assert contact_pressure(h_c, E_b, SIGMA, t, density) == pytest.approx(T / 0.055)
    assert mean_excess(-1e-6, SIGMA) - mean_excess(1e-6, SIGMA) == pytest.approx(1e-6)


@pytest.mark.parametrize("model", ["closed-form", "fe1d", "fe2d"])
def test_a_heavily_tensioned_newsprint_rests_with_mu_near_mu_c(model):
    """T = 300 N/m on the 55 mm base roller (T/R = 5455 Pa above E_b sigma/(2t) = 5000 Pa):
    refused before (issue 22); the web rests compressed, boundary lubrication, mu within 3 %
    of mu_c = (2/pi) 0.3 atan(20/0.4) = 0.296 (the shear of the air through the roughness
    fades as the web comes to rest; eta U_s / h_f would grow without bound)."""
    r = webfem.solve(BASE.updated({"web.tension": 300.0}), model=model)
    mu_c = 2.0 / np.pi * 0.3 * np.arctan(20.0 / 0.4)
    assert r["resting"] and r["compression"] > 0.0 and r["regime"] == "boundary"
    assert r["mu"] == pytest.approx(mu_c, rel=0.03)
    heavier = webfem.solve(BASE.updated({"web.tension": 2000.0}), model=model)
    assert abs(heavier["mu"] / mu_c - 1.0) < abs(r["mu"] / mu_c - 1.0) + 1e-9


def test_the_roughness_flow_switches_off_with_the_papers_physics():
    """air.roughness_flow = "none" restores the floor and the smooth film's shear, and the
    paper's physics sets it; the effect is named in every result that includes it."""
    full = BASE
    assert full.roughness_flow_model == "mean-gap"
    assert BASE.updated({"model.physics": "paper"}).roughness_flow_model == "none"
    r = webfem.solve(full, model="fe1d")
    off = webfem.solve(full.updated({"air.roughness_flow": "none"}), model="fe1d")
    assert "roughness-flow" in r["effects"] and "roughness-flow" not in off["effects"]
    assert r["mu"] > off["mu"] and r["h_min"] != off["h_min"]


@pytest.mark.parametrize("model", ["closed-form", "fe1d", "fe2d", "auto"])
def test_a_web_compressed_through_its_thickness_is_refused_by_name(model):
    """A web far softer across its thickness than the wrap pressure (E_b = 1 kPa at T = 300
    N/m: contact alone would compress it by 0.38 mm, its thickness is 70 um) has no
    admissible equilibrium: every model refuses it up front with the keys that change it,
    instead of iterating to "did not converge"."""
    case = BASE.updated({"web.tension": 300.0, "web.modulus_thickness": 1e3})
    with pytest.raises(webfem.errors.NoAdmissibleSolution,
                       match="through its thickness web.thickness = 7e-05 m"):
        webfem.solve(case, model=model)
    # the same soft web where the film holds it off the roller is an answer
    r = webfem.solve(BASE.updated({"web.modulus_thickness": 1e3, "web.tension": 20.0}),
                     model="fe1d")
    assert r["converged"] and not r["resting"]


@pytest.mark.parametrize("c", [0.03, 13.0, 200.0, 2000.0])
@pytest.mark.parametrize("hs", [-3.0, 0.0, 0.5, 50.0])
def test_the_exponential_shear_holds_for_slip_lengths_far_above_sigma(c, hs):
    """A slip length 2 a lambda of hundreds of sigma (a smooth film at low ambient pressure,
    or pet_idler's 0.14 um roughness with the mean free path at its 1e-4 m limit): e^c and
    Ei(c) overflow past c = 709, and the closed form returned NaN (review38a); against the
    adaptive quadrature of the same integral."""
    sigma = 1e-6
    ls = c
    kw = dict(epsabs=0.0, epsrel=1e-12, limit=1000)
    below = quad(lambda t: np.exp(t) / 2 / (hs - t + ls), -np.inf, min(hs, 0.0), **kw)[0]
    above = quad(lambda y: np.exp(y - hs) / 2 / (y + ls), 0.0, hs, **kw)[0] if hs > 0 else 0.0
    ref = (below + above) / sigma
    with np.errstate(all="raise"):
        got = shear_factor(hs * sigma, sigma, c * sigma)
    assert np.isfinite(got) and got == pytest.approx(ref, rel=1e-10)
