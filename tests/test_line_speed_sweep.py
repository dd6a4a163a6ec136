"""A sweep of the line's speed (``line.speed``): roller and web together at the case's
U_w/U_r, in TOML [sweep] tables and on the command line (--parameter, --start, --stop, with
units); a sweep of roller.speed alone on an idler or a moving web says in one line that the
web speed is held (issue: the bundled idler's sweep slid its roller 5 m/s under the web)."""

import csv

import pytest

from webfem import Case, load_sweep
from webfem.cli import main
from webfem.errors import InputError
from webfem.line_speed import LINE_SPEED, line_at
from webfem.sweepspec import Sweep

IDLER = Case().updated({"roller.speed": 10.0, "web.speed": 10.0, "roller.drag_torque": 0.05})
DRAW = Case().updated({"roller.speed": 20.0, "web.speed": 19.8})


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_line_speed_moves_roller_and_web_at_the_case_ratio():
    sweep = Sweep(LINE_SPEED, (5.0, 15.0), (("idler", IDLER), ("draw", DRAW)))
    points = {(label, v): c for label, v, c in sweep.points()}
    assert points["idler", 15.0].roller.speed == points["idler", 15.0].web.speed == 15.0
    assert points["draw", 5.0].roller.speed == 5.0
    assert points["draw", 5.0].web.speed == pytest.approx(4.95)
    # a roller at rest has no ratio: the line's speed is the web's, the roller stays still
    bar = Case().updated({"roller.speed": 0.0, "web.speed": 5.0})
    assert (line_at(bar, 8.0).roller.speed, line_at(bar, 8.0).web.speed) == (0.0, 8.0)
    # every point is checked up front, as any sweep's: a web too fast for its tension
    with pytest.raises(InputError, match="cannot be held"):
        Sweep(LINE_SPEED, (10.0, 60.0), (("idler", IDLER),))
    assert sweep.held_web_speed() is None


def test_a_toml_sweep_of_the_line_with_units(tmp_path, capsys):
    path = tmp_path / "line.toml"
    path.write_text('[roller]\nspeed = 10.0\ndrag_torque = 0.05\n[web]\nspeed = 10.0\n'
                    '[sweep]\nparameter = "line.speed"\n'
                    'values = ["300 m/min", "600 m/min", 15.0]\n')
    assert load_sweep(path).values == (5.0, 10.0, 15.0)
    assert main(["sweep", str(path), "--model", "closed-form", "--out", str(tmp_path),
                 "--quiet"]) == 0
    assert "warning" not in capsys.readouterr().err
    rows = _rows(tmp_path / "line_closed-form.csv")
    assert [r["parameter"] for r in rows] == [LINE_SPEED] * 3
    assert [float(r["U_slide"]) for r in rows] == [0.0, 0.0, 0.0]     # nothing slides
    assert [float(r["U"]) for r in rows] == [10.0, 20.0, 30.0]        # U_r + U_w


def test_the_command_line_sweeps_the_line_and_warns_of_a_held_web(tmp_path, capsys):
    held = tmp_path / "held"
    assert main(["sweep", "idler", "--model", "closed-form", "--out", str(held),
                 "--quiet"]) == 0
    err = capsys.readouterr().err
    warning = [line for line in err.splitlines() if "warning" in line]
    assert len(warning) == 1 and "on an idler" in warning[0]
    assert "web speed is held at 10 m/s" in warning[0] and "line.speed" in warning[0]
    line = tmp_path / "line"
    assert main(["sweep", "idler", "--model", "closed-form", "--out", str(line),
                 "--parameter", "line.speed", "--quiet"]) == 0
    assert "warning" not in capsys.readouterr().err
    a, b = _rows(held / "idler_closed-form.csv"), _rows(line / "idler_closed-form.csv")
    assert [r["value"] for r in a] == [r["value"] for r in b]       # the table's 5..15 m/s
    assert float(a[0]["U_slide"]) == 5.0 and float(b[0]["U_slide"]) == 0.0
    assert float(b[5]["mu"]) == float(a[5]["mu"])                     # at 10 m/s: the same
    ranged = tmp_path / "ranged"
    assert main(["sweep", "idler", "--model", "closed-form", "--out", str(ranged),
                 "--parameter", "line.speed", "--start", "300 m/min", "--stop", "15",
                 "--num", "3", "--units", "metric", "--quiet"]) == 0
    capsys.readouterr()
    assert [float(r["value"]) for r in _rows(ranged / "idler_closed-form.csv")] \
        == [5.0, 10.0, 15.0]
    assert _rows(ranged / "idler_closed-form_metric.csv")[0]["value_m_per_min"] == "300.0"
    # a moving web on a driven roller: held too, said in its own words
    assert main(["sweep", "driven_roller", "--model", "closed-form", "--num", "2", "--out",
                 str(tmp_path / "driven"), "--quiet"]) == 0
    assert "with web.speed = 15 m/s: the web speed is held" in capsys.readouterr().err


@pytest.mark.parametrize("args, words", [
    (["--parameter", "web.tension"], "are values of roller.speed, not of web.tension"),
    (["--parameter", "line.sped"], "did you mean 'line.speed'"),
    (["--parameter", "line.speed", "--start", "5"], "--start and --stop go together"),
    (["--parameter", "line.speed", "--start", "5", "--stop", "3 m"], "--stop = '3 m'"),
])
def test_command_line_sweep_parameters_are_checked(tmp_path, capsys, args, words):
    assert main(["sweep", "idler", "--model", "closed-form", "--out", str(tmp_path),
                 *args]) == 2
    assert words in capsys.readouterr().err


def test_keys_lists_the_line_speed(capsys):
    assert main(["keys"]) == 0
    assert '"line.speed" [m/s]' in capsys.readouterr().out


def test_a_range_on_the_command_line_over_a_values_table_takes_the_default_count(tmp_path):
    """--start/--stop over a [sweep] with a values list: the list's length is no count for
    the range (values = [10.0] made --start 5 --stop 15 one point, --stop dropped); the
    table's num where it has one, else the default 40."""
    path = tmp_path / "one.toml"
    path.write_text('[sweep]\nparameter = "roller.speed"\nvalues = [10.0]\n')
    spec = load_sweep(path, start="5", stop="15")
    assert len(spec.values) == 40 and spec.values[0] == 5.0 and spec.values[-1] == 15.0
