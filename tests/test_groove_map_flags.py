"""The groove map keeps what each design's answer says: h_min, the stated errors and the
warnings in its CSV and JSON; a design whose answer warns that its film is not what fe2d
computes (the web sagging into wide grooves) is flagged, not feasible."""

import csv
import json

import pytest

from webfem.bundled import as_case
from webfem.cli import main
from webfem.groove_sizing import MAP_COLUMNS, SAG_FLAG, best_designs, groove_map

NEW = ("h_min", "error_h_center", "error_h_min", "error_mu", "error_contact_share",
       "warnings", "flag")


@pytest.fixture(scope="module")
def sagging(tmp_path_factory):
    """5 mm pitch, 2.5 mm grooves on the base case at 20 m/s: mu 0.32 but the web sags
    about 1.1 um into its grooves, 6 x the smallest land gap."""
    store = tmp_path_factory.mktemp("map") / "base_grooves.csv"
    designs = groove_map(as_case("base"), 0.2, speeds=[20.0], pitches=[5e-3],
                         land_fractions=[0.5], store=store)
    return designs, store


def test_sagging_design_is_flagged_not_feasible(sagging):
    (d,), _ = sagging
    assert d.converged and d.mu >= 0.2
    assert d.flag == SAG_FLAG and not d.feasible
    assert any("sags into its" in w for w in d.warnings)
    assert best_designs([d]) == {20.0: None}


def test_csv_and_json_carry_h_min_errors_and_warnings(sagging):
    (d,), store = sagging
    assert set(NEW) <= set(MAP_COLUMNS)
    with open(store, newline="") as fh:
        (row,) = list(csv.DictReader(fh))
    assert float(row["h_min"]) == pytest.approx(d.h_min) and 0 < d.h_min < d.h_center
    for key in ("error_h_center", "error_h_min", "error_mu", "error_contact_share"):
        assert float(row[key]) == pytest.approx(getattr(d, key)) and getattr(d, key) > 0
    assert "sags into its" in row["warnings"] and row["flag"] == SAG_FLAG
    data = json.loads(json.dumps(d.to_dict()))
    assert set(NEW) <= set(data) and data["warnings"] == list(d.warnings)


def test_map_prints_the_flag(sagging, capsys):
    _, store = sagging
    # the same map resumed from its store: nothing solved again
    assert main(["grooves", "base", "--mu-min", "0.2", "--speed", "20", "--pitches",
                 "0.005", "--lands", "0.5", "--out", str(store.parent), "--quiet"]) == 4
    out = capsys.readouterr().out
    assert "! mu >= mu_min but flagged" in out and f"! 5 mm / 2.5 mm groove: {SAG_FLAG}" in out
    assert "\n*" not in out
