"""The CLI contract: JSON keys, sweep outputs, error exit codes; every case file runs."""

import csv
import json
from pathlib import Path

import pytest

from webfem import SUMMARY_KEYS, load_sweep
from webfem.cli import main

CASES = sorted((Path(__file__).parent.parent / "cases").glob("*.toml"))


def test_solve_json_keys(capsys):
    assert main(["solve", "cases/base.toml", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    for key in SUMMARY_KEYS:
        assert key in data
    assert data["model"] == "closed-form" and data["converged"] is True
    assert 0.0 < data["mu"] < 0.35


def test_solve_set_override(capsys):
    main(["solve", "cases/base.toml", "--json", "--set", "roller.speed=40"])
    fast = json.loads(capsys.readouterr().out)
    main(["solve", "cases/base.toml", "--json", "--set", "roller.speed=5"])
    slow = json.loads(capsys.readouterr().out)
    assert fast["h_inlet"] > slow["h_inlet"]
    assert fast["mu"] < 0.03 < slow["mu"]


def test_bad_input_exits_2_with_message(capsys):
    assert main(["solve", "cases/base.toml", "--set", "web.width=-2"]) == 2
    err = capsys.readouterr().err
    assert "web.width = -2.0" in err and "> 0" in err


@pytest.mark.parametrize("case", CASES, ids=[c.stem for c in CASES])
def test_every_case_file_sweeps(case, tmp_path, capsys):
    assert main(["sweep", str(case), "--out", str(tmp_path), "--quiet"]) == 0
    csv_path = tmp_path / f"{case.stem}_closed-form.csv"
    png = tmp_path / f"{case.stem}_closed-form.png"
    assert png.stat().st_size > 10_000
    rows = list(csv.DictReader(csv_path.open()))
    spec = load_sweep(case)
    assert len(rows) == len(spec.values) * len(spec.series)
    assert set(SUMMARY_KEYS) <= set(rows[0])


def test_base_case_shows_paper_trend(tmp_path):
    """The base case rises to about 0.3 at low speed, falls through mixed, ends below 0.03."""
    main(["sweep", "cases/base.toml", "--out", str(tmp_path), "--quiet"])
    rows = list(csv.DictReader((tmp_path / "base_closed-form.csv").open()))
    mu = [float(r["mu"]) for r in rows]
    speed = [float(r["value"]) for r in rows]
    peak = max(mu)
    assert 0.27 < peak <= 0.3
    assert speed[mu.index(peak)] < 10.0
    assert mu[-1] < 0.03
    assert {"boundary", "mixed", "fluid"} >= {r["regime"] for r in rows}
    assert "fluid" in {r["regime"] for r in rows} and "boundary" in {r["regime"] for r in rows}
