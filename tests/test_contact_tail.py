"""The exponential asperity heights beyond any real surface (issue: gauss37): Eq. 2 has no
cut-off, so a stiff surface (large E_b sigma / (2 t T/R)) gets its contact gap h_c many sigma
above the mean plane, where no surface has asperities. An answer whose asperities carry load
there says so in its warnings, with the Gaussian law's h_c, and an idler's "holds" becomes
"unsure"; the default law is unchanged."""

import numpy as np
import pytest

from webfem import solve, solve_many
from webfem.cli import main
from webfem.physics import contact
from webfem.physics.contact import (TAIL_SHARE, TAIL_SIGMAS, beyond_the_surface, contact_gap,
                                    tail_gaussian_gaps, tail_warning)

from conftest import IDLER

#: The bundled idler with a surface 114x stiffer: h_c = 6.03 sigma, the web resting there.
STIFF = ["--set", "web.modulus_thickness=2e7"]


def solve_cli(capsys, *argv):
    assert main(["solve", "idler", "--model", "closed-form", *argv]) == 0
    return capsys.readouterr().out


def test_contact_beyond_five_sigma_is_warned_and_the_idler_is_unsure(capsys):
    out = solve_cli(capsys, *STIFF)
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
    out = solve_cli(capsys, *argv)
    assert "warning: the asperities carry" not in out and "heights' tail" not in out


def test_the_edge_is_five_sigma_and_half_a_percent_of_the_load():
    s = IDLER.sigma
    assert beyond_the_surface(IDLER, 1.001 * TAIL_SIGMAS * s, 2 * TAIL_SHARE)
    assert not beyond_the_surface(IDLER, 0.999 * TAIL_SIGMAS * s, 1.0)
    assert not beyond_the_surface(IDLER, 10 * s, 0.99 * TAIL_SHARE)
    gauss = IDLER.updated({"friction.distribution": "gaussian"})
    assert not beyond_the_surface(gauss, 10 * s, 1.0)


# --- the batch's tail warnings (issue tail38, 1): one vectorised Gaussian h_c per batch ---

def stiff_batch():
    """The stiff idler from 1 to 20 m/s at 0.6-2 times its tension: the tail fires at most
    of them, not at all (the fast, lightly tensioned ones fly)."""
    case = IDLER.updated({"web.modulus_thickness": 2e7})
    return [case.updated({"roller.speed": u, "web.speed": u, "web.tension": T})
            for T in (48.0, 80.0, 160.0) for u in np.linspace(1.0, 20.0, 12).tolist()]


@pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")
@pytest.mark.parametrize("model", ["closed-form", "fitted"])
def test_a_batch_warns_as_each_point_alone_with_one_gaussian_solve(monkeypatch, model):
    """solve_many's summaries equal a single solve's at every point, warnings and all, and
    the Gaussian h_c of the warnings is solved once for the batch (main: once per warned
    point, which made a stiff closed-form idler batch 1.8x as costly)."""
    cases = stiff_batch()
    alone = [solve(c, model=model).summary for c in cases]
    calls = []
    real = contact._gaussian_gap
    monkeypatch.setattr(contact, "_gaussian_gap",
                        lambda *a, **k: calls.append(np.size(a[0])) or real(*a, **k))
    batch = [r.summary for r in solve_many(cases, model=model)]
    warned = [any("asperities carry" in w for w in s.warnings) for s in alone]
    assert 0 < sum(warned) and (model == "fitted" or sum(warned) < len(cases))
    assert len(calls) == 1 and calls[0] == sum(warned)
    for one, many in zip(alone, batch):
        assert many.warnings == one.warnings
        assert (many.h_c, many.contact_share, many.mu, many.slip_margin) == \
            (one.h_c, one.contact_share, one.mu, one.slip_margin)


def test_the_batch_gaussian_gap_is_each_point_alone_bit_for_bit():
    """per_point stops each point at its own convergence: the bits of a scalar solve, which
    the warning of a single solve prints (the default, stepping every point until all have
    converged, may move a converged one by an ulp)."""
    p_bar = np.array([1e2, 1e3, 1e4, 1e5, 3e6])
    E_b = np.array([1e9, 2e7, 175e3, 1e9, 175e3])
    alone = [float(contact_gap(p, e, 4e-6, 70e-6, "gaussian")) for p, e in zip(p_bar, E_b)]
    batch = contact._gaussian_gap(p_bar, E_b, 4e-6, 70e-6, per_point=True)
    assert batch.tolist() == alone
    case = IDLER.updated({"web.modulus_thickness": 2e7})
    h_e = float(contact_gap(case.p_bar, 2e7, case.sigma, case.web.thickness))
    h_own = float(contact_gap(IDLER.p_bar, IDLER.web.modulus_thickness, IDLER.sigma,
                              IDLER.web.thickness))
    gaps = tail_gaussian_gaps([case, case, IDLER], [h_e, h_e, h_own], [0.5, 0.001, 0.5])
    assert gaps[0] == float(contact_gap(case.p_bar, 2e7, case.sigma, case.web.thickness,
                                        "gaussian"))
    assert np.isnan(gaps[1:]).all()     # too little load; the bundled idler within 5 sigma
    assert tail_warning(case, h_e, 0.5, gaps[0]) == tail_warning(case, h_e, 0.5)
