"""Reduced studies (the full ones run with `make studies`) and the findings they pin."""

import csv
import warnings

import pytest

from webfem import Case
from webfem.errors import ValidityWarning
from webfem.studies import convergence, pareto, stability

warnings.filterwarnings("ignore", category=ValidityWarning)
CASE = Case().updated({"roller.speed": 40.0})


def test_convergence_study_quick(tmp_path):
    out = convergence.run(CASE, tmp_path, quick=True, progress=None)
    for name in ("convergence_refinement.csv", "convergence_eq21.csv", "convergence.png",
                 "convergence.md"):
        assert (tmp_path / name).stat().st_size > 100
    s = {(r["model"], r["order"], r["quantity"]): r for r in out["summary"]}
    assert s[("fe2d", 1, "h_center")]["observed_order"] == pytest.approx(2.0, abs=0.3)
    assert s[("fe1d", 1, "h_center")]["observed_order"] == pytest.approx(2.0, abs=0.3)
    assert s[("fe2d", 2, "h_center")]["relative_error_coarsest"] < 1e-3
    assert any(not g["eq21_valid"] for g in out["eq21"])       # outside the range too


def test_richardson_on_a_known_sequence():
    p, ext, err = convergence.richardson([1 + 1 / 4, 1 + 1 / 16, 1 + 1 / 64])
    assert p == pytest.approx(2.0) and ext == pytest.approx(1.0) and err == pytest.approx(1 / 64)


def test_pareto_study_quick(tmp_path):
    out = pareto.run(CASE, tmp_path, quick=True, repeats=1, progress=None)
    rows = {r["method"]: r for r in out["rows"]}
    assert rows["closed form"]["pareto_mu"]                       # cheapest is on the front
    assert rows["fe2d Q2 level 0"]["error_mu"] < rows["fe1d P2 level 0"]["error_mu"]
    assert rows["closed form"]["time_s"] < rows["fe1d P2 level 0"]["time_s"]
    assert (tmp_path / "pareto.png").stat().st_size > 10_000


def test_pareto_front():
    pts = [(1.0, 1.0), (2.0, 0.5), (3.0, 0.6), (0.5, 2.0)]
    assert pareto.pareto_front(pts) == [0, 1, 3]


def test_stability_findings_quick(tmp_path):
    """Pinned findings: plain Picard with omega = 1 fails on the base case at 40 m/s where
    Newton converges; Newton converges everywhere in the reduced map; the staggered Picard
    fails at 40 m/s."""
    out = stability.run(Case(), tmp_path, quick=True, progress=None)
    rows = out["rows"]

    def status(method, speed):
        return next(r["status"] for r in rows if r["method"] == method
                    and r["speed"] == speed and r["study"] == "coupling")

    assert status("Newton", 40.0) == "converged"
    assert status("Picard omega 1", 40.0) in ("diverged", "stalled")
    assert status("Picard staggered", 40.0) in ("diverged", "stalled")
    assert status("Picard Anderson (default)", 40.0) == "converged"
    assert all(r["status"] == "converged" for r in rows if r["method"] == "Newton")
    with (tmp_path / "stability.csv").open() as fh:
        assert len(list(csv.DictReader(fh))) == len(rows)


def test_study_cli(tmp_path, capsys):
    from webfem.cli import main
    assert main(["study", "pareto", "cases/base.toml", "--out", str(tmp_path), "--quick",
                 "--quiet", "--set", "roller.speed=40"]) == 0
    assert "| closed form |" in capsys.readouterr().out
