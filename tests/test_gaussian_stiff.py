"""The Gaussian asperity heights on stiff surfaces (issue: gauss37): the contact gap h_c of
a stiff surface lies a few sigma above its mean plane, where p_c is orders of magnitude
below its value at contact and, beyond 38 sigma, zero in floating point. h_c, the tail
E[(z - h)+] and its logarithm must stay finite and exact there, with no numpy warning, and
the CLI must answer (or refuse for the real reason), never print nan or a RuntimeWarning."""

import warnings

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import log_ndtr

from webfem.cli import main
from webfem.physics.contact import contact_gap, contact_pressure
from webfem.physics.roughness import log_mean_excess, mean_excess, mean_gap

SIGMA = 4e-6


def log_tail(x):
    """ln E[(Z - x)+] for a standard normal Z, independently: ln of int_x^inf Q(z) dz, the
    integrand scaled by Q(x) (scipy's log_ndtr: no underflow)."""
    lq = log_ndtr(-x)
    scaled = quad(lambda u: np.exp(log_ndtr(-(x + u)) - lq), 0.0, np.inf, epsabs=0.0,
                  epsrel=1e-13, limit=200)[0]
    return lq + np.log(scaled)


@pytest.mark.parametrize("x", [0.0, 0.5, 3.0, 9.9, 29.0, 31.0, 37.0, 45.0, 200.0])
def test_the_gaussian_tail_and_its_log_are_exact_far_above_the_asperities(x):
    """Against the independent integral: E to 1e-12 where it is representable, its log and
    the log's slope -Q/E to 1e-10 everywhere (the textbook phi - x Q underflows to 0 at
    38 sigma and has lost 3 digits by 30), and below the mean plane too."""
    ref = log_tail(x) + np.log(SIGMA)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        log, slope = log_mean_excess(x * SIGMA, SIGMA, "gaussian")
        e = mean_excess(x * SIGMA, SIGMA, "gaussian")
        below = mean_excess(-x * SIGMA, SIGMA, "gaussian")
        log_below, _ = log_mean_excess(-x * SIGMA, SIGMA, "gaussian")
    assert float(log) == pytest.approx(ref, rel=1e-12, abs=1e-12)
    assert float(slope) * SIGMA == pytest.approx(-np.exp(log_ndtr(-x) - log_tail(x)),
                                                 rel=1e-10)
    if ref > -650.0:
        assert float(e) == pytest.approx(np.exp(ref), rel=1e-12)
    # E[(z - h)+] below the plane is -h + E[(z + h)+] (symmetric heights); the flow gap at h
    # is E[(z - |h|)+] above it
    assert float(below) == pytest.approx(x * SIGMA + np.exp(ref), rel=1e-13)
    assert float(log_below) == pytest.approx(np.log(x * SIGMA + np.exp(ref)), rel=1e-13)
    assert float(mean_gap(-x * SIGMA, SIGMA, "gaussian")) == pytest.approx(np.exp(ref),
                                                                           rel=1e-12)


@pytest.mark.parametrize("E_b, sigma, t, p_bar", [
    (1e9, 4e-6, 70e-6, 1455.0),        # base web, stiff surface: h_c 3.7 sigma (main: nan)
    (3e8, 4e-6, 70e-6, 1455.0),        # 3.4 sigma (main: nan)
    (1e9, 4.0003e-6, 12e-6, 1167.0),   # the trial's 12 um PET on a 4 um roller (main: nan)
    (1e12, 1e-3, 1e-6, 1.0),           # as stiff as the keys allow: 7.7 sigma
    (175e3, 4e-6, 70e-6, 1455.0),      # the paper's newsprint: 0.69 sigma
    (1e3, 4e-6, 70e-6, 1455.0),        # a soft surface, pressed 25 sigma into it
])
def test_the_gaussian_contact_gap_carries_the_wrap_pressure(E_b, sigma, t, p_bar):
    """p_c(h_c) = p_bar to 1e-12, without a warning, for any stiffness; and h_c is below the
    exponential law's (its tail is thinner) while above 0."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        h_c = contact_gap(p_bar, E_b, sigma, t, "gaussian")
        h_e = contact_gap(p_bar, E_b, sigma, t)
    assert np.isfinite(h_c)
    log, _ = log_mean_excess(h_c, sigma, "gaussian")
    assert float(log) + np.log(E_b / t) == pytest.approx(np.log(p_bar), abs=1e-12)
    assert float(contact_pressure(h_c, E_b, sigma, t, "gaussian")) == pytest.approx(
        p_bar, rel=1e-12)
    if h_e > 0.0:
        assert h_c < h_e


def test_a_stiff_gaussian_surface_answers_cleanly(capsys):
    """The trial's commands: the base case with a 300 MPa (closed form) surface and Gaussian
    heights answers, with no RuntimeWarning, no nan and no blame on air.roughness_flow (on
    main: a refusal naming air.roughness_flow = none, which the case leaves at mean-gap)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        code = main(["solve", "base", "--model", "closed-form", "--set",
                     "friction.distribution=gaussian", "--set", "web.modulus_thickness=3e8"])
    out = capsys.readouterr()
    assert code == 0, out.err
    text = out.out + out.err
    assert "nan" not in text and "RuntimeWarning" not in text
    assert "roughness_flow" not in text
