"""A traction-loss scan that reaches a speed the line or the model cannot answer before mu has
crossed mu_min answers what the speeds below found, with where and why it ended (issue:
the light foil's closed-form scan ended in an error, exit 2, hiding mu >= mu_min up to
5.15 m/s)."""

import json

import pytest


from webfem import Case
from webfem.bundled import load_case
from webfem.cli import main
from webfem.errors import ConvergenceError, NoAdmissibleSolution
from webfem.line_speed import top_speed
from webfem.traction import traction_loss_speed

from conftest import FakeResult

#: A light, rough foil at a low tension: as the line speeds up the web's inertia leaves
#: less of its tension (T_eff) to press it down, and the closed form's contact gap h_c
#: outgrows R/100 at 5.5 m/s, well below the thin-film bound (7.3 m/s).
FOIL = ("foil_roller", {"web.tension": 5.0, "web.roughness": 25e-6})


def test_a_scan_refused_above_some_speed_answers_the_speeds_below():
    case = load_case(*FOIL)
    out = traction_loss_speed(case, 0.01, "closed-form")
    assert out.speed is None and out.mu_peak > 0.01
    # the answer ends at the last scan speed answered, the refusal names the next and h_c
    assert out.scanned[0] == 0.5 and 4.0 < out.scanned[1] < top_speed(case, 100.0)[0]
    assert out.scan_limit.startswith("at U_r = 5.788 m/s, no admissible closed-form answer")
    assert "h_c" in out.scan_limit and "T_eff" in out.scan_limit
    # the two lengths compared are printed until they differ (0.000375 'more than' 0.000375)
    assert "h_c = 0.0003752 m" in out.scan_limit and "R/100 = 0.000375 m" in out.scan_limit
    assert f"mu stays above 0.01 up to {out.scanned[1]:.4g} m/s" in out.message
    assert "the last speed answered" in out.message
    # mu rises all the way (peak 0.058 at the last speed answered): below 0.1 up to there
    below = traction_loss_speed(case, 0.1, "closed-form")
    assert below.scanned == out.scanned and below.scan_limit == out.scan_limit
    assert f"mu stays below 0.1 at every speed in 0.5..{out.scanned[1]:.4g} m/s" \
        in below.message


def test_the_cli_prints_the_answer_with_exit_4_and_the_json_key(capsys):
    name, values = FOIL
    sets = [a for k, v in values.items() for a in ("--set", f"{k}={v}")]
    assert main(["traction-loss", name, *sets, "--mu-min", "0.01", "--model", "closed-form",
                 "--quiet", "--json"]) == 4
    out = json.loads(capsys.readouterr().out)
    assert out["speed"] is None and out["scan_limit"].startswith("at U_r = 5.788 m/s")
    assert out["scanned"][1] < 5.788
    assert main(["traction-loss", name, *sets, "--mu-min", "0.01", "--model", "fe1d",
                 "--quiet", "--json", "--workers", "1"]) == 4
    fe = json.loads(capsys.readouterr().out)
    # the FE model holds the case up to the thin-film bound, where the line ends
    assert fe["scanned"][1] == pytest.approx(top_speed(load_case(*FOIL), 100.0)[0])
    assert "thicker than R/100" in fe["scan_limit"] and "T_eff" in fe["scan_limit"]
    base = main(["traction-loss", "base", "--mu-min", "0.1", "--model", "closed-form",
                 "--json", "--quiet"])
    assert base == 0 and json.loads(capsys.readouterr().out)["scan_limit"] is None


def test_the_line_limit_names_its_quantity():
    """Above the last possible speed: the film thicker than R/100, with the T_eff left."""
    case = load_case(*FOIL)
    top, why = top_speed(case, 100.0)
    assert "R eps^(2/3) is thicker than R/100" in why and "T_eff = " in why
    at_rest = top_speed(Case().updated({"web.tension": 5.0}), 100.0)[1]
    assert "thicker than R/100" in at_rest and "T_eff" not in at_rest   # no inertia
    smooth = load_case("foil_roller", {"web.tension": 5.0})   # its own 0.2 um roughness
    top, why = top_speed(smooth, 100.0)
    out = traction_loss_speed(smooth, 1e-4, "closed-form")
    assert out.scan_limit == f"above U_r = {top:.4g} m/s {why}" and out.scanned[1] == top
    assert "the last possible speed" in out.message




@pytest.fixture
def refusing(monkeypatch):
    """An FE scan whose model refuses (or fails to converge at) every speed above 20 m/s,
    mu 0.3 below it."""
    import webfem.loss_scan as ls

    state = {"error": NoAdmissibleSolution("no admissible solution: made up"),
             "mu": lambda u: 0.3}

    def along(cases, *args, **kwargs):
        for c in cases:
            if c.roller.speed > 20.0:
                raise state["error"]
            yield FakeResult(c, state["mu"](c.roller.speed))
    monkeypatch.setattr(ls, "solve_along", along)
    return state


@pytest.mark.parametrize("workers", [1, 2])
def test_an_fe_scan_ends_at_a_refused_speed_on_one_process_or_two(refusing, workers):
    if workers == 2 and __import__("multiprocessing").get_start_method() != "fork":
        pytest.skip("the worker must inherit the monkeypatched solve")
    out = traction_loss_speed(Case(), 0.1, "fe1d", speed_range=(1.0, 80.0),
                                     n_scan=13, workers=workers)
    assert out.speed is None and out.scanned == (1.0, pytest.approx(80.0 ** (8 / 12)))
    assert out.scan_limit.startswith(f"at U_r = {80.0 ** (9 / 12):.4g} m/s, no admissible")
    # refused at its first speed the scan has nothing to answer: the error says so
    with pytest.raises(NoAdmissibleSolution, match="the scan's first speed"):
        traction_loss_speed(Case(), 0.1, "fe1d", speed_range=(30.0, 80.0),
                                   n_scan=5, workers=workers)
    # a solve that does not converge is still an error, saying what the speeds below found
    refusing["error"] = ConvergenceError("made up")
    with pytest.raises(ConvergenceError, match=r"U_r = 26\.75 m/s did not converge .*; below "
                                               r"it, at 1\.\.18\.57 m/s, mu reaches it"):
        traction_loss_speed(Case(), 0.1, "fe1d", speed_range=(1.0, 80.0),
                                   n_scan=13, workers=workers)


def test_a_full_scan_refused_past_its_crossing_keeps_the_crossing(refusing):
    refusing["mu"] = lambda u: 0.3 if u < 10.0 else 0.05
    out = traction_loss_speed(Case(), 0.1, "fe1d", speed_range=(1.0, 80.0), n_scan=13,
                              full_scan=True, workers=1)
    assert out.bracket[0] < 10.0 < out.bracket[1] and out.speed is not None
    assert out.scanned[1] == pytest.approx(80.0 ** (8 / 12))
    assert out.scan_limit.startswith("at U_r = 26.75 m/s, no admissible solution")
    stopped = traction_loss_speed(Case(), 0.1, "fe1d", speed_range=(1.0, 80.0), n_scan=13,
                                  workers=1)
    assert stopped.speed == out.speed and stopped.scan_limit is None
