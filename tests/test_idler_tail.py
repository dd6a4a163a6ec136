"""`webfem idler` applies the exponential-tail rule speed by speed (issue tail38, 2): a speed
whose answer rests on asperities the exponential heights put beyond 5 sigma reads "unsure"
and carries the warning `webfem solve` gives at that speed. On main the sweep judged only the
margin's range: "holds" where the single solve says "unsure".

The case: the bundled idler with E_b = 7.3e6 Pa. Its h_c grows with line speed (T_eff falls
by rho t U^2): 4.97 sigma at 1 m/s, 5.01 at 8.6 m/s; the tail rule fires from about 8 m/s,
where the margin still holds (6.6), and not below, so the rows that hold, the rows the tail
makes unsure, the rows mu's stated error makes unsure and the rows that slip all appear."""

import csv
import json
import warnings

import pytest

from webfem import solve
from webfem.cli import main
from webfem.describe import idler_verdict
from webfem.errors import ValidityWarning
from webfem.idler import margin_curve
from webfem.line_speed import at_speed

from conftest import IDLER

CASE = IDLER.updated({"web.modulus_thickness": 7.3e6})
SPEEDS = [1.0 + 21.0 * i / 11 for i in range(12)]      # --min-speed 1 --max-speed 22 --num 12
ARGV = ["idler", "idler", "--model", "closed-form", "--set", "web.modulus_thickness=7.3e6",
        "--min-speed", "1", "--max-speed", "22", "--num", "12"]
WORD = {"holds": "holds", "slips": "SLIPS", "unsure": "unsure", "not judged": "no answer"}


def alone(speed, model):
    """A single solve at the line speed: its verdict's word and its tail warning."""
    case = at_speed(CASE, speed, ratio=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        s = solve(case, model=model).summary
    tail = [w for w in s.warnings if w.startswith("the asperities carry")]
    return WORD[idler_verdict(s, case)[0]], tail[0] if tail else None


@pytest.mark.parametrize("model", ["closed-form", "fitted"])
def test_each_row_is_the_verdict_and_warning_of_a_single_solve(model):
    curve = margin_curve(CASE, SPEEDS, model)
    single = [alone(u, model) for u in SPEEDS]
    assert curve.verdicts() == [word for word, _ in single]
    assert list(curve.tail_warnings) == [tail for _, tail in single]
    assert list(curve.exponential_tail) == [tail is not None for _, tail in single]
    if model == "closed-form":
        # the rule fires at some speeds and not at others, and turns holds into unsure
        assert any(curve.exponential_tail) and not all(curve.exponential_tail)
        assert "holds" in curve.verdicts() and any(curve.tail_unsure())
        assert set(curve.verdicts()) == {"holds", "unsure", "SLIPS"}


def test_the_table_csv_and_json_say_it(tmp_path, capsys):
    assert main([*ARGV, "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    curve = margin_curve(CASE, SPEEDS, "closed-form")
    by_tail = [u for u, t in zip(SPEEDS, curve.tail_unsure()) if t]
    rows = [line.split() for line in out.splitlines()[3:3 + len(SPEEDS)]]
    assert [r[-1] for r in rows] == curve.verdicts()
    assert f"unsure at {by_tail[0]:.3g} m/s" in out and "exponential heights' tail" in out
    first = curve.exponential_tail.index(True)
    assert f"warning at {SPEEDS[first]:.3g} m/s: {curve.tail_warnings[first]}" in out
    with open(tmp_path / "idler_idler.csv", newline="") as f:
        table = list(csv.DictReader(f))
    assert [r["verdict"] for r in table] == curve.verdicts()
    assert [r["exponential_tail"] == "True" for r in table] == list(curve.exponential_tail)
    assert main([*ARGV, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["verdicts"] == curve.verdicts()
    assert data["tail_warnings"] == list(curve.tail_warnings)
    assert data["exponential_tail"] == list(curve.exponential_tail)
    for key in ("speeds", "slip_margin", "margin_low", "margin_high", "slip_speed"):
        assert key in data       # the keys before stay
