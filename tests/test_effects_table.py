"""`webfem effects` and `webfem idler`: what each effect does, and whether an idler slips."""

import json

import pytest

import webfem
from webfem.cli import main
from webfem.effects import effects_table
from webfem.idler import margin_curve
from webfem.physics.effects import SWITCH_OFF

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")


def test_effects_table_switches_each_effect_off(idler):
    """One row per effect the case includes; each row is the case solved with that effect's
    key switched off (checked against a direct solve)."""
    case = idler
    table = effects_table(case, "fe1d")
    assert [r.effect for r in table.rows] == ["all included", "inertia", "bending", "slip",
                                              "isothermal-permeation", "load-friction",
                                              "roughness-flow", "spans"]
    direct = webfem.solve(case.updated(SWITCH_OFF["inertia"]), model="fe1d")
    row = table.rows[1]
    # two solves of one case agree to round-off (the linear solver reuses orderings)
    assert row.h_min == pytest.approx(direct["h_min"], rel=1e-12)
    assert row.slip_margin == pytest.approx(direct["slip_margin"], rel=1e-9)
    assert row.d_h_min == pytest.approx(direct["h_min"] / table.rows[0].h_min - 1.0)
    # the moving web turns at the cost of rho t U^2: without it the film is thinner
    assert row.d_h_center < 0.0


def test_effects_cli_prints_the_table(capsys):
    assert main(["effects", "cases/base.toml", "--model", "fe1d", "--quiet"]) == 0
    out = capsys.readouterr().out
    for effect in ("bending", "slip", "isothermal-permeation", "load-friction",
                   "roughness-flow", "spans"):
        assert effect in out
    assert main(["effects", "cases/base.toml", "--model", "closed-form", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["not_carried"] == ["bending", "slip", "isothermal-permeation", "spans"]
    # --units as every table command takes it: the gaps in mil, the same numbers
    assert main(["effects", "cases/base.toml", "--model", "closed-form", "--quiet"]) == 0
    si = capsys.readouterr().out.splitlines()
    assert main(["effects", "cases/base.toml", "--model", "closed-form", "--quiet",
                 "--units", "us"]) == 0
    us = capsys.readouterr().out.splitlines()
    assert "h_center um" in si[1] and "h_center mil" in us[1] and "h_min mil" in us[1]
    assert float(us[2].split()[2]) == pytest.approx(float(si[2].split()[2]) / 25.4, abs=1e-3)


def test_idler_margin_falls_with_line_speed(idler, tmp_path, capsys):
    """The idler of cases/idler.toml holds at 5 m/s and slips at 15 m/s: the film lifts the
    web off its asperities and mu_onset = mu_cc x contact share falls."""
    curve = margin_curve(idler, [5.0, 10.0, 15.0], "fe1d")
    assert curve.slip_margin[0] > 1.0 > curve.slip_margin[-1]
    assert 5.0 < curve.slip_speed() < 15.0
    assert main(["idler", "cases/idler.toml", "--model", "closed-form", "--num", "5",
                 "--out", str(tmp_path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["slip_margin"]) == 5
    assert (tmp_path / "idler_idler.png").stat().st_size > 1000
    with pytest.raises(webfem.InputError, match="no idler load"):
        margin_curve(webfem.Case(), [5.0], "closed-form")


# -- one default model: auto, and every output says which model answered (issue 20) ------

def test_every_case_command_defaults_to_auto():
    """report, effects, idler, calibrate answer as solve, sweep and traction-loss do."""
    from webfem.cli.main import build_parser
    parser = build_parser()
    for argv in (["solve", "base"], ["sweep", "base", "--out", "x"], ["report", "base",
                 "--out", "x"], ["effects", "base"], ["idler", "idler"],
                 ["traction-loss", "base", "--mu-min", "0.1"],
                 ["calibrate", "m.csv", "--case", "base"]):
        args = parser.parse_args(argv)
        assert args.model == "auto" and args.model_given is False, argv
    assert parser.parse_args(["report", "base", "--out", "x", "--model", "fe1d"]).model_given


def _auto_as_fe1d(monkeypatch, calls):
    """webfem.effects.solve with auto answering by fe1d (fast and the same whatever auto's
    rules), recording the model each solve asked for."""
    import dataclasses

    import webfem.effects as effects
    real = effects.solve

    def solve(case, model="closed-form", **kw):
        calls.append(model)
        if model != "auto":
            return real(case, model, **kw)
        r = real(case, "fe1d")
        return dataclasses.replace(r, summary=r.summary.replace(
            model="auto", model_used="fe1d", why="test: fe1d is adequate -> fe1d"))
    monkeypatch.setattr(effects, "solve", solve)


def test_effects_with_auto_solve_every_variant_with_autos_choice(monkeypatch, capsys):
    """The full case with auto; each effect switched off with the model auto chose for it
    (fe1d here), so bending is not shown as changing nothing by a closed form."""
    calls = []
    _auto_as_fe1d(monkeypatch, calls)
    table = effects_table(webfem.Case(), "auto")
    assert calls == ["auto"] + ["fe1d"] * (len(table.rows) - 1)
    assert table.model == "fe1d" and table.asked == "auto"
    assert table.rows[1].effect == "bending" and table.rows[1].d_h_min != 0.0
    text = table.text()
    assert text.startswith("effects on fe1d (auto's choice for the full case; every row "
                           "solved with fe1d)")
    assert "why fe1d: test: fe1d is adequate -> fe1d" in text
    assert table.to_dict()["asked"] == "auto" and "fe1d is adequate" in table.to_dict()["why"]
    assert main(["effects", "base", "--json"]) == 0   # the command's default is auto
    data = json.loads(capsys.readouterr().out)
    assert data["asked"] == "auto" and data["model"] == "fe1d"


def test_idler_table_header_csv_and_model_per_row(tmp_path, capsys):
    """The idler table has a header naming columns and units; --out writes the CSV beside
    the chart; a curve auto answered with several models says which at each speed."""
    import csv

    from webfem.idler import MarginCurve
    assert main(["idler", "idler", "--model", "closed-form", "--num", "3",
                 "--out", str(tmp_path)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[1].split() == ["line", "speed", "required", "available", "margin", "range",
                                "verdict"]
    assert lines[2].split() == ["[m/s]", "[N/m]", "[N/m]", "[-]", "[-]"]
    rows = list(csv.DictReader((tmp_path / "idler_idler.csv").open()))
    assert list(rows[0]) == list(MarginCurve.COLUMNS) and len(rows) == 3
    assert {r["model_used"] for r in rows} == {"closed-form"}
    assert float(rows[0]["speed"]) == 1.0 and (tmp_path / "idler_idler.png").exists()
    curve = MarginCurve("auto", (1.0, 2.0, 3.0), (1.0,) * 3, (2.0, 1.5, 0.5), (2.0, 1.5, 0.5),
                        (0.3,) * 3, (True,) * 3, ("fe1d", "fe2d", "fe2d"))
    assert curve.answered() == "auto: fe1d at 1, fe2d at 2 speeds"
    assert [r["model_used"] for r in curve.rows()] == ["fe1d", "fe2d", "fe2d"]
    assert curve.verdicts() == ["holds", "holds", "SLIPS"]     # no stated range: the margin
    from webfem.cli.idler import _table
    text = _table(curve, "si").splitlines()
    assert text[1].split()[-1] == "model" and text[3].split()[-1] == "fe1d"


def test_idler_verdict_is_unsure_where_mu_s_stated_error_straddles_one(capsys):
    """The fitted model's mu on an idler states its error from the contact share's
    (fitted.onset_error): where that range of the margin crosses 1 the verdict says so."""
    from webfem.idler import margin_curve
    curve = margin_curve(webfem.load_case("cases/idler.toml"), [4.8, 12.4], "fitted")
    assert all(lo <= m <= hi for lo, m, hi in zip(curve.margin_low, curve.slip_margin,
                                                  curve.margin_high))
    assert curve.verdicts()[1] == "unsure" and curve.error_mu[1] > 1.0
    fe = margin_curve(webfem.load_case("cases/idler.toml"), [12.4], "fe1d")
    assert fe.verdicts() == ["SLIPS"]      # a finer model decides: fe2d's margin is 0.13
    assert main(["idler", "idler", "--model", "fitted", "--num", "3"]) == 0
    assert "the answer's stated error of mu puts the margin on both sides" in \
        capsys.readouterr().out
    assert main(["solve", "idler", "--set", "roller.speed=12.4", "--set", "web.speed=12.4",
                 "--model", "fitted"]) == 0
    # margin 1.6 before the contact share was fitted in arcsin(sqrt(share)) (docs/fit.md)
    assert "idler unsure: margin 1, but mu's stated error allows 0 to" in \
        capsys.readouterr().out


def test_idler_without_stated_errors_or_answers_says_so(capsys):
    """An unconverged speed or one solved without an estimate states no error: the curve
    keeps its rows (NaN error, the margin itself as its range), and a speed without an
    answer gives no verdict and no slip speed (it once gave 13.6 m/s from two unconverged
    margins)."""
    import math

    from webfem.idler import margin_curve
    case = webfem.load_case("cases/idler.toml")
    curve = margin_curve(case, [1.0, 20.0], "fe1d", estimate=False)
    assert all(math.isnan(e) for e in curve.error_mu)
    assert curve.verdicts() == ["holds", "SLIPS"] and curve.slip_speed() is not None
    failed = margin_curve(case, [1.0, 20.0], "fe1d", max_iter=2)
    assert failed.verdicts() == ["no answer", "no answer"] and failed.slip_speed() is None
    assert main(["idler", "idler", "--model", "fe1d", "--opt", "max_iter=2", "--num", "2"]) == 0
    assert "no speed was answered: no verdict" in capsys.readouterr().out
    assert main(["idler", "idler", "--model", "fitted", "--num", "4", "--min-speed", "1",
                 "--max-speed", "9"]) == 0
    out = capsys.readouterr().out
    # "unsure at 9 m/s" before the contact share was fitted in arcsin(sqrt(share)), "unsure
    # at 6.33 m/s, 9 m/s" until the errors were stated per point (docs/fit.md): at 6.33 m/s
    # the fit's mu 0.199 (fe2d 0.195) now states a range that holds on its own
    assert "unsure at 9 m/s" in out and "holds at every speed tried" not in out


@pytest.mark.parametrize("low,high,said", [
    (1.0, 3.0, "the idler holds at every speed tried (1 m/s to 3 m/s)"),
    (20.0, 30.0, "the idler slips at every speed tried (20 m/s to 30 m/s)"),
    (1.0, 30.0, "the idler slips above about")])
def test_idler_verdict_names_the_speeds_tried(capsys, low, high, said):
    """Slipping at the lowest speed tried is not "slips above about" that speed (it once
    said so of a PET idler slipping at every speed from 60 m/min): where it starts slipping
    lies below the range."""
    assert main(["idler", "idler", "--model", "closed-form", "--num", "4", "--min-speed",
                 str(low), "--max-speed", str(high)]) == 0
    out = capsys.readouterr().out
    assert said in out
    assert (f"slips above about {low:g} m/s" not in out)
