"""`webfem grooves --loss-speed`: a geometry whose speed scan fe2d refused partway, before mu
crossed mu_min, says so (issue tail38, 4). On main its row read as a converged row without a
speed: the table printed the scan's message as if the range had been answered, the CSV and
JSON had no field for where and why the scan ended, and the chart drew it as "mu >= mu_min
up to 100 m/s". Now ``scan_limit`` (why, as `webfem traction-loss` reports it with exit 4)
and ``scanned_to`` (the last speed answered) are in every row, the table's line says
"refused partway" with both, and the chart puts a diamond at that speed.

The scan is replaced by a stand-in (the bookkeeping does not depend on the physics); the
refused answer it returns is a real one: the light foil's closed-form scan, refused at
5.788 m/s where its h_c outgrows R/100 (tests/test_scan_limit.py)."""

import csv
import json

import pytest

from webfem import Case
from webfem import groove_sizing as gs
from webfem.bundled import load_case
from webfem.cli import main
from webfem.io import groove_charts
from webfem.traction import TractionLoss, traction_loss_speed

from conftest import inspect_before_save

FOIL = ("foil_roller", {"web.tension": 5.0, "web.roughness": 25e-6})


@pytest.fixture(scope="module")
def refused():
    out = traction_loss_speed(load_case(*FOIL), 0.01, "closed-form")
    assert out.speed is None and out.scan_limit and out.scanned[1] < 5.788
    return out


@pytest.fixture
def losses(monkeypatch, refused):
    """The 50 % land refused partway; the smooth roller and the 90 % land answer."""
    def loss(case, mu_min, model, speed_range, n_scan, xtol, options):
        if case.grooved and case.land_fraction < 0.6:
            return refused
        return TractionLoss(20.0, model, mu_min, 0.4, 1.0, (18.0, 20.0), 12,
                            f"mu falls below {mu_min:g} at U_r = 20 m/s", scanned=(1.0, 20.0))

    monkeypatch.setattr(gs, "traction_loss_speed", loss)


@pytest.fixture
def calls(monkeypatch):
    monkeypatch.setattr(gs, "solve", lambda case, model, options: {
        "mu": 0.3, "h_center": 3e-6, "contact_share": 0.5})


def test_the_row_keeps_why_and_where_the_scan_ended(losses, refused, tmp_path):
    store = tmp_path / "l.csv"
    smooth, half, most = gs.loss_speed_map(Case(), 0.01, pitches=(1.27e-3,),
                                           land_fractions=(0.5, 0.9), store=store)
    assert half.refused_partway() and half.converged and half.speed is None
    assert (half.scan_limit, half.scanned_to) == (refused.scan_limit, refused.scanned[1])
    assert not smooth.refused_partway() and smooth.scan_limit is None
    assert smooth.scanned_to == 20.0
    # resumed from the store: the same rows, the reason's text and all
    again = gs.loss_speed_map(Case(), 0.01, pitches=(1.27e-3,), land_fractions=(0.5, 0.9),
                              store=store)
    assert again == [smooth, half, most]


def test_table_csv_json_and_chart_say_refused_partway(calls, losses, refused, tmp_path,
                                                      capsys, monkeypatch):
    args = ["grooves", "cases/base.toml", "--mu-min", "0.01", "--pitches", "1.27e-3",
            "--lands", "0.9", "--loss-speed", "--loss-pitches", "1.27e-3",
            "--loss-lands", "0.5,0.9", "--out", str(tmp_path), "--quiet", "--workers", "1"]
    seen = {}
    inspect_before_save(monkeypatch, groove_charts, lambda fig, renderer: seen.update(
        legend=[t.get_text() for a in fig.axes if a.get_legend()
                for t in a.get_legend().texts]))
    assert main(args) == 0
    out = capsys.readouterr().out
    line = next(x for x in out.splitlines() if "refused partway" in x)
    assert f"no loss speed up to {refused.scanned[1]:.4g} m/s" in line
    assert "mu stays above 0.01" in line
    assert f"the scan ended {refused.scan_limit[:60]}" in line     # cut: the CSV has it
    assert sum("refused partway" in x for x in out.splitlines()) == 1
    assert any("refused partway" in t for t in seen["legend"])
    with open(tmp_path / "base_grooves_loss.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["scan_limit"] for r in rows] == ["", refused.scan_limit, ""]
    assert float(rows[1]["scanned_to"]) == refused.scanned[1]
    assert rows[1]["loss_speed"] == "" and rows[1]["converged"] == "True"
    assert main(args + ["--json"]) == 0
    data = json.loads(capsys.readouterr().out)["loss_speeds"]
    assert data[1]["scan_limit"] == refused.scan_limit
    assert data[1]["scanned_to"] == refused.scanned[1]
    for key in ("pitch", "width", "depth", "land_fraction", "speed", "mu_peak",
                "speed_peak", "evaluations", "converged", "message"):
        assert key in data[1]                      # the keys before stay
