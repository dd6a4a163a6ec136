"""`webfem effects` and `webfem idler`: what each effect does, and whether an idler slips."""

import json

import pytest

import webfem
from webfem.cli import main
from webfem.effects import effects_table
from webfem.idler import margin_curve
from webfem.physics.effects import SWITCH_OFF

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")


def test_effects_table_switches_each_effect_off():
    """One row per effect the case includes; each row is the case solved with that effect's
    key switched off (checked against a direct solve)."""
    case = webfem.load_case("cases/idler.toml")
    table = effects_table(case, "fe1d")
    assert [r.effect for r in table.rows] == ["all included", "inertia", "bending", "slip",
                                              "isothermal-permeation", "load-friction"]
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
    for effect in ("bending", "slip", "isothermal-permeation", "load-friction"):
        assert effect in out
    assert main(["effects", "cases/base.toml", "--model", "closed-form", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["not_carried"] == ["bending", "slip", "isothermal-permeation"]


def test_idler_margin_falls_with_line_speed(tmp_path, capsys):
    """The idler of cases/idler.toml holds at 5 m/s and slips at 15 m/s: the film lifts the
    web off its asperities and mu_onset = mu_cc x contact share falls."""
    curve = margin_curve(webfem.load_case("cases/idler.toml"), [5.0, 10.0, 15.0], "fe1d")
    assert curve.slip_margin[0] > 1.0 > curve.slip_margin[-1]
    assert 5.0 < curve.slip_speed() < 15.0
    assert main(["idler", "cases/idler.toml", "--model", "closed-form", "--num", "5",
                 "--out", str(tmp_path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["slip_margin"]) == 5
    assert (tmp_path / "idler_idler.png").stat().st_size > 1000
    with pytest.raises(webfem.InputError, match="no idler load"):
        margin_curve(webfem.Case(), [5.0], "closed-form")
