"""Contact (Eqs. 10-13) and friction (Eqs. 28-31) at hand-worked points."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from webfem.physics.contact import contact_gap, contact_pressure, load_ratio, regime_code
from webfem.physics.friction import (delta_T_from_mu, local_friction, mu_from_delta_T,
                                     wrap_average_linear_gap)

NEWS = dict(E_b=175e3, sigma=4e-6, t=70e-6)
P_BAR = 80.0 / 0.055
KW = dict(R=0.055, T=80.0, eta=1.81e-5, E_b=175e3, sigma=4e-6, t=70e-6, mu_cc=0.3, C=0.4)


def test_contact_gap_by_hand():
    """h_c = sigma ln(E_b sigma / (2 t T/R)) = 4e-6 ln(0.7 / 0.203636) = 4e-6 * 1.23474
    = 4.939 um (physics.md: about 4.9 um)."""
    assert contact_gap(P_BAR, **NEWS) == pytest.approx(4.9390e-6, rel=1e-4)
    # contact alone carries T/R at h_c
    assert contact_pressure(contact_gap(P_BAR, **NEWS), **NEWS) == pytest.approx(P_BAR)


def test_load_ratio_three_regimes():
    """chi_c: 1 below h_c; at h = 8 um, 3.4375 exp(-2) = 0.46522; 0 above 12 um (paper);
    the continuous variant keeps 3.4375 exp(-3.25) = 0.13329 at 13 um."""
    h = np.array([2e-6, 8e-6, 13e-6])
    assert load_ratio(h, P_BAR, **NEWS) == pytest.approx([1.0, 0.46522, 0.0], abs=1e-5)
    assert load_ratio(h, P_BAR, **NEWS, variant="continuous") == \
        pytest.approx([1.0, 0.46522, 0.13329], abs=1e-5)
    assert list(regime_code(h, 4.939e-6, 4e-6)) == [0, 1, 2]
    # the paper's jump at 3 sigma
    below, above = load_ratio(np.array([12e-6 * (1 - 1e-9), 12e-6 * (1 + 1e-9)]), P_BAR, **NEWS)
    assert below == pytest.approx(3.4375 * math.exp(-3), rel=1e-6) and above == 0.0


def test_local_friction_by_hand():
    """U_s = 20 m/s. mu_f = eta R U_s / (h T) = 1.81e-5 * 0.055 * 20 / (h * 80) = 2.48875e-7 / h.
    h = 2 um: boundary, mu = (2/pi) 0.3 atan(50) = 0.29618.
    h = 8 um: mixed, chi_c = 0.46522, mu = 0.3 * 0.46522 + (2.48875e-7 / 8e-6) * 0.53478
          = 0.139566 + 0.016637 = 0.156203.
    h = 20 um: fluid, mu = 2.48875e-7 / 2e-5 = 0.0124438."""
    out = local_friction(np.array([2e-6, 8e-6, 20e-6]), U_s=20.0, **KW)
    assert out["mu"] == pytest.approx([0.29618, 0.156203, 0.0124438], rel=2e-5)
    assert list(out["regime"]) == [0, 1, 2]


def test_no_viscous_shear_without_sliding():
    """An idler at web speed (U_s = 0) has no film shear and no boundary friction."""
    out = local_friction(np.array([2e-6, 20e-6]), U_s=0.0, **KW)
    assert out["mu"] == pytest.approx([0.0, 0.0])


@pytest.mark.parametrize("variant", ["paper", "continuous"])
@pytest.mark.parametrize("h_in,h_out", [(30e-6, 20e-6), (22e-6, -30e-6), (15e-6, 1e-6),
                                        (3e-6, -1e-6), (9e-6, 9e-6), (-2e-6, -8e-6),
                                        (40e-6, 5e-6)])
def test_exact_wrap_average_matches_quadrature(h_in, h_out, variant):
    """The exact integral over a linear gap equals adaptive quadrature of the local mu."""
    exact = wrap_average_linear_gap(h_in, h_out, U_s=17.0, variant=variant, **KW)

    def mu(s):
        h = max(h_in + (h_out - h_in) * s, 0.0)
        return float(local_friction(h, U_s=17.0, variant=variant, **KW)["mu"])

    brk = [s for s in ((4.939e-6 - h_in) / (h_out - h_in) if h_out != h_in else -1,
                       (12e-6 - h_in) / (h_out - h_in) if h_out != h_in else -1,
                       (0 - h_in) / (h_out - h_in) if h_out != h_in else -1) if 0 < s < 1]
    numeric = quad(mu, 0.0, 1.0, points=brk or None, limit=200)[0]
    assert float(exact["mu"]) == pytest.approx(numeric, rel=1e-7)
    total = exact["share_boundary"] + exact["share_mixed"] + exact["share_fluid"]
    assert float(total) == pytest.approx(1.0)


def test_belt_formula_round_trip():
    """dT = T (exp(mu B) - 1): mu = 0.3, B = 60 deg, T = 80 -> 80 (e^0.314159 - 1) = 80 * 0.369107 = 29.529."""
    assert delta_T_from_mu(0.3, 80.0, math.pi / 3) == pytest.approx(29.529, abs=1e-3)
    mu = np.linspace(0.0, 0.6, 13)
    back = mu_from_delta_T(delta_T_from_mu(mu, 120.0, 1.2), 120.0, 1.2)
    assert back == pytest.approx(mu, abs=1e-14)


def test_exp1_fast_matches_scipy():
    from scipy.special import exp1

    from webfem.physics.friction import exp1_fast
    x = np.concatenate([np.geomspace(1e-9, 3.0, 2000), np.linspace(3.0, 60.0, 500)])
    assert np.max(np.abs(exp1_fast(x) / exp1(x) - 1.0)) < 1e-12


def test_gaussian_contact_matches_quadrature():
    """Eq. 1 heights: p_c = (E_b/t) int_h^inf (z - h) phi_1(z) dz, exact erfc form."""
    E, s, t = 175e3, 4e-6, 70e-6
    for h in (-2e-6, 0.0, 3e-6, 1e-5):
        num = E / t * quad(lambda z: (z - h) * np.exp(-z * z / (2 * s * s))
                           / (s * np.sqrt(2 * np.pi)), h, h + 15 * s, epsabs=0, epsrel=1e-12)[0]
        assert contact_pressure(h, E, s, t, "gaussian") == pytest.approx(num, rel=1e-7)
    h_c = contact_gap(P_BAR, E, s, t, "gaussian")
    assert contact_pressure(h_c, E, s, t, "gaussian") == pytest.approx(P_BAR, rel=1e-10)
    assert 0 < h_c < contact_gap(P_BAR, E, s, t)   # 2.76 um against 4.94 um


def test_numeric_average_agrees_with_exact():
    from webfem.physics.friction import wrap_average_numeric
    for h_in, h_out in [(30e-6, 20e-6), (22e-6, -30e-6), (15e-6, 1e-6)]:
        a = wrap_average_linear_gap(h_in, h_out, U_s=17.0, **KW)
        b = wrap_average_numeric(h_in, h_out, U_s=17.0, **KW)
        assert float(b["mu"]) == pytest.approx(float(a["mu"]), rel=1e-6)
        assert float(b["share_mixed"]) == pytest.approx(float(a["share_mixed"]), abs=1e-9)


@pytest.mark.parametrize("distribution", ["exponential", "gaussian"])
def test_continuous_variant_has_no_jumps(distribution):
    """The paper's mu(h) jumps at h_c and 3 sigma; the continuous variant does not."""
    h_c = float(contact_gap(P_BAR, 175e3, 4e-6, 70e-6, distribution))
    for level in (h_c, 12e-6):
        h = np.array([level * (1 - 1e-9), level * (1 + 1e-9)])
        cont = local_friction(h, U_s=5.0, variant="continuous", distribution=distribution,
                              **KW)["mu"]
        assert cont[0] == pytest.approx(cont[1], abs=1e-6)
    paper = local_friction(np.array([h_c * (1 - 1e-9), h_c * (1 + 1e-9)]), U_s=5.0,
                           distribution=distribution, **KW)["mu"]
    assert abs(paper[1] - paper[0]) > 1e-3
