"""The exponential asperity heights beyond any real surface (issue: gauss37): Eq. 2 has no
cut-off, so a stiff surface (large E_b sigma / (2 t T/R)) gets its contact gap h_c many sigma
above the mean plane, where no surface has asperities. An answer whose asperities carry load
there says so in its warnings, with the Gaussian law's h_c, and an idler's "holds" becomes
"unsure"; the default law is unchanged."""

import pytest

from webfem.cli import main
from webfem.physics.contact import TAIL_SHARE, TAIL_SIGMAS, beyond_the_surface, contact_gap

from conftest import IDLER

#: The bundled idler with a surface 114x stiffer: h_c = 6.03 sigma, the web resting there.
STIFF = ["--set", "web.modulus_thickness=2e7"]


def solve(capsys, *argv):
    assert main(["solve", "idler", "--model", "closed-form", *argv]) == 0
    return capsys.readouterr().out


def test_contact_beyond_five_sigma_is_warned_and_the_idler_is_unsure(capsys):
    out = solve(capsys, *STIFF)
    assert "idler unsure: margin" in out and "exponential heights' tail" in out
    assert "idler holds" not in out
    warning = [line for line in out.splitlines()
               if line.startswith("  warning: the asperities carry")]
    assert len(warning) == 1
    case = IDLER.updated({"web.modulus_thickness": 2e7})
    w = case.web
    h_e = contact_gap(case.p_bar, w.modulus_thickness, case.sigma, w.thickness)
    h_g = contact_gap(case.p_bar, w.modulus_thickness, case.sigma, w.thickness, "gaussian")
    assert h_e > TAIL_SIGMAS * case.sigma > h_g
    assert f"h_c = {h_e * 1e6:.4g} um = {h_e / case.sigma:.3g} sigma" in warning[0]
    assert f"put h_c at {h_g * 1e6:.4g} um" in warning[0]


@pytest.mark.parametrize("argv", [(), (*STIFF, "--set", "friction.distribution=gaussian")])
def test_a_surface_within_its_heights_is_not_warned(capsys, argv):
    """The bundled idler (h_c 1.2 sigma) and the stiff one with Gaussian heights."""
    out = solve(capsys, *argv)
    assert "warning: the asperities carry" not in out and "heights' tail" not in out


def test_the_edge_is_five_sigma_and_half_a_percent_of_the_load():
    s = IDLER.sigma
    assert beyond_the_surface(IDLER, 1.001 * TAIL_SIGMAS * s, 2 * TAIL_SHARE)
    assert not beyond_the_surface(IDLER, 0.999 * TAIL_SIGMAS * s, 1.0)
    assert not beyond_the_surface(IDLER, 10 * s, 0.99 * TAIL_SHARE)
    gauss = IDLER.updated({"friction.distribution": "gaussian"})
    assert not beyond_the_surface(gauss, 10 * s, 1.0)
