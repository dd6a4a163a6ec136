"""Traction: loss speed, the paper's trends, sliding speed, calibration from synthetic data."""

import json

import numpy as np
import pytest

import webfem
from webfem import Case
from webfem.calibrate import calibrate, read_measurements
from webfem.cli import main
from webfem.models.closed import case_arrays, evaluate
from webfem.traction import traction_loss_speed


def test_traction_loss_speed_is_a_crossing():
    out = traction_loss_speed(Case(), 0.1)
    u = out["speed"]
    assert out["bracket"][0] <= u <= out["bracket"][1]
    mu = lambda s: webfem.solve(Case().updated({"roller.speed": s}))["mu"]  # noqa: E731
    assert mu(u * 0.99) > 0.1 > mu(u * 1.01)
    assert out["speed_peak"] < u


def test_traction_loss_none_when_never_reached():
    out = traction_loss_speed(Case(), 0.5)
    assert out["speed"] is None and "below" in out["message"]


TRENDS = [("web.tension", 40.0, 120.0), ("wrap.angle_deg", 20.0, 60.0),
          ("web.width", 0.100, 0.020), ("roller.radius", 0.055, 0.035)]


@pytest.mark.parametrize("model,key,low,high", [("closed-form",) + t for t in TRENDS]
                         + [("fe2d", "web.width", 0.100, 0.020)])
def test_paper_trends(model, key, low, high):
    """Larger tension, larger wrap, narrower web and smaller roller each keep traction to a
    higher speed (the paper's Figs. 10-13): the closed form for all four, the 2-D FE model for
    the width (edge leakage; the other three are in the slow tests)."""
    a = traction_loss_speed(Case().updated({key: low}), 0.1, model, n_scan=12)["speed"]
    b = traction_loss_speed(Case().updated({key: high}), 0.1, model, n_scan=12)["speed"]
    assert b > a


@pytest.mark.slow
@pytest.mark.parametrize("key,low,high", [("web.tension", 40.0, 120.0),
                                          ("wrap.angle_deg", 20.0, 60.0),
                                          ("roller.radius", 0.055, 0.035)])
def test_paper_trends_fe2d(key, low, high):
    a = traction_loss_speed(Case().updated({key: low}), 0.1, "fe2d", n_scan=12)["speed"]
    b = traction_loss_speed(Case().updated({key: high}), 0.1, "fe2d", n_scan=12)["speed"]
    assert b > a


def test_cli_traction_loss_json(capsys):
    assert main(["traction-loss", "cases/base.toml", "--mu-min", "0.1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == "closed-form" and 20.0 < out["speed"] < 35.0


def test_viscous_shear_vanishes_without_sliding():
    """An idler at web speed: U = 2 U_w still entrains air, but U_s = 0 leaves no film shear."""
    case = webfem.load_case("cases/idler.toml").updated({"roller.speed": 20.0})
    for model in ("closed-form", "fe1d"):
        r = webfem.solve(case, model=model)
        assert r["U_slide"] == 0.0 and r["U"] == 40.0
        assert np.all(r.fields["mu_f"][np.isfinite(r.fields["mu_f"])] == 0.0)
        assert np.all(r.fields["mu"] == r.fields["mu_c"] * r.fields["chi_c"])


def synthetic(case, speeds, tensions, mu_cc, C, noise, seed=3, model="closed-form"):
    rng = np.random.default_rng(seed)
    rows = []
    truth = case.updated({"friction.mu_cc": mu_cc, "friction.speed_constant": C})
    for u in speeds:
        for T in tensions:
            r = webfem.solve(truth.updated({"roller.speed": u, "web.tension": T}), model=model)
            rows.append({"roller.speed": u, "web.tension": T,
                         "delta_T": r["delta_T"] + noise * rng.standard_normal()})
    return rows


def test_calibration_recovers_constants_closed_form():
    rows = synthetic(Case(), np.geomspace(0.3, 30, 12), (40.0, 80.0, 120.0), 0.36, 0.7, 0.3)
    fit = calibrate(rows, Case())   # starts from the paper's 0.3 and 0.4
    for name, true in (("mu_cc", 0.36), ("speed_constant", 0.7)):
        assert abs(fit["estimates"][name] - true) <= fit["ci95"][name], (name, fit)
        assert fit["ci95"][name] < 0.1 * true
    assert fit["rms"] == pytest.approx(0.3, rel=0.3)


def test_calibration_recovers_constants_fe1d():
    rows = synthetic(Case(), (0.5, 1.0, 2.0, 4.0, 8.0, 12.0, 16.0), (80.0,), 0.25, 0.3, 0.2,
                     model="fe1d")
    fit = calibrate(rows, Case(), model="fe1d")
    for name, true in (("mu_cc", 0.25), ("speed_constant", 0.3)):
        assert abs(fit["estimates"][name] - true) <= fit["ci95"][name], (name, fit)


def test_calibration_cli_and_file(tmp_path, capsys):
    rows = synthetic(Case(), np.geomspace(0.3, 30, 10), (80.0,), 0.33, 0.5, 0.2)
    p = tmp_path / "measured.csv"
    p.write_text("# tension increase measured on the rig\nroller_speed,tension,delta_T\n" +
                 "\n".join(f"{r['roller.speed']},{r['web.tension']},{r['delta_T']}"
                           for r in rows))
    assert len(read_measurements(p)) == 10
    assert main(["calibrate", str(p), "--case", "cases/base.toml", "--json", "--out",
                 str(tmp_path)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert abs(out["estimates"]["mu_cc"] - 0.33) <= out["ci95"]["mu_cc"]
    assert (tmp_path / "measured_calibration.png").stat().st_size > 10_000
    p.write_text("roller_speed,tension,torque\n1,80,3\n")
    assert main(["calibrate", str(p), "--case", "cases/base.toml"]) == 2
    assert "unknown column 'torque'" in capsys.readouterr().err


def test_vectorised_friction_constants():
    """evaluate() takes the friction constants as arrays too (the calibration relies on it)."""
    arr = case_arrays([Case(), Case()])
    arr.update(mu_cc=np.array([0.3, 0.4]), C=np.array([0.4, 0.4]))
    mu = evaluate(**arr)["mu"]
    assert mu[1] > mu[0]
