"""Reduced studies (the full ones run with `make studies`), the findings they pin, their files
and the `webfem study` command."""

import csv
import math
import subprocess
import sys

import pytest

from webfem import Case, solve
from webfem.io import studies as study_io
from webfem.studies import convergence, lambda_table, pareto, stability, variants
from webfem.studies.report import StudiesReport

from conftest import FLYING


@pytest.fixture(scope="module")
def conv():
    return convergence.run(FLYING, quick=True)


@pytest.fixture(scope="module")
def par():
    return pareto.run(FLYING, quick=True, repeats=1)


@pytest.fixture(scope="module")
def stab():
    return stability.run(Case(), quick=True)


def test_convergence_study_quick(conv):
    assert conv.order("fe2d", 1, "h_center")["observed_order"] == pytest.approx(2.0, abs=0.3)
    assert conv.order("fe1d", 1, "h_center")["observed_order"] == pytest.approx(2.0, abs=0.3)
    assert conv.order("fe2d", 2, "h_center")["relative_error_coarsest"] < 1e-3
    assert any(not g["eq21_valid"] for g in conv.eq21)       # outside the range too


def test_convergence_files(conv, tmp_path):
    paths = study_io.write(conv, tmp_path)
    assert sorted(p.name for p in paths) == sorted(
        ["convergence_refinement.csv", "convergence_eq21.csv", "convergence.png",
         "convergence.md"])
    with (tmp_path / "convergence_refinement.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(conv.refinement)
    assert float(rows[-1]["mu"]) == conv.refinement[-1]["mu"]    # full precision
    text = (tmp_path / "convergence.md").read_text()
    q2 = conv.order("fe2d", 2, "h_center")
    assert f"| fe2d | Q2 | h_center | {q2['observed_order']:.2f} |" in text
    assert (tmp_path / "convergence.png").stat().st_size > 10_000


def test_richardson_on_a_known_sequence():
    p, ext, err = convergence.richardson([1 + 1 / 4, 1 + 1 / 16, 1 + 1 / 64])
    assert p == pytest.approx(2.0) and ext == pytest.approx(1.0) and err == pytest.approx(1 / 64)


def test_richardson_not_monotone():
    p, ext, err = convergence.richardson([1.0, 2.0, 1.5])
    assert math.isnan(p) and ext == 1.5 and err == 0.5


def test_pareto_study_quick(par, tmp_path):
    # the cheapest is on the front (the closed form or the fitted model: they take about
    # the same time, and the fitted model is the more accurate)
    fastest = min((r for r in par.rows if r["same_case"]), key=lambda r: r["time_s"])
    assert fastest["pareto_mu"] and fastest["model"] in ("closed-form", "fitted")
    assert par.row("fe2d Q2 level 0")["error_mu"] < par.row("fe1d P2 level 0")["error_mu"]
    assert par.row("closed form")["time_s"] < par.row("fe1d P2 level 0")["time_s"]
    study_io.write(par, tmp_path)
    assert (tmp_path / "pareto.png").stat().st_size > 10_000
    assert "| closed form |" in (tmp_path / "pareto.md").read_text()


def test_pareto_front():
    pts = [(1.0, 1.0), (2.0, 0.5), (3.0, 0.6), (0.5, 2.0)]
    assert pareto.pareto_front(pts) == [0, 1, 3]


def test_stability_findings_quick(stab, tmp_path):
    """Pinned findings (the web held through its spans, the default): plain Picard with
    omega = 1 fails on the base case at 20 m/s where Newton converges (with the ends held at
    the zones it diverged at 20 and 40 m/s; the lift mode's correction, which the spans
    need, converges it at 40); Newton converges everywhere in the reduced map; the default
    Picard (Anderson) converges at every speed (held: it stalled at 20 m/s); the staggered
    Picard fails at 40 m/s."""
    assert stab.status("Newton", 20.0) == "converged"
    assert stab.status("Picard omega 1", 20.0) in ("diverged", "stalled")
    assert stab.status("Picard staggered", 40.0) in ("diverged", "stalled")
    for speed in (2.0, 20.0, 40.0):
        assert stab.status("Picard Anderson (default)", speed) == "converged"
    assert stab.count("Newton", "converged") == stab.count("Newton") > 0
    study_io.write(stab, tmp_path)
    with (tmp_path / "stability.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(stab.rows)
    assert "h_min" in rows[0]                   # a column some rows (failures) lack


def test_report_markdown_from_the_studies(conv, par, stab, tmp_path):
    report = StudiesReport(conv, par, stab, 90.0, quick=True)
    paths = study_io.write(report, tmp_path, source="cases/base.toml")
    assert paths[-1].name == "studies.md" and len(paths) == 11
    text = paths[-1].read_text()
    q2 = conv.order("fe2d", 2, "h_center")
    assert f"converges at order\n{q2['observed_order']:.2f} with Q2" in text
    assert "`webfem study report cases/base.toml --quick`" in text
    assert f"Newton converged at\n{stab.count('Newton')} of {stab.count('Newton')}" in text
    assert text.endswith(study_io.stability_markdown(stab) + "\n")


def test_lambda_table_one_width(tmp_path):
    """Eq. 21's central gap lies below the 2-D one at lambda = 10 (README: 9 % to 21 %), with
    and without permeation; the 2-D mesh error is far smaller than that."""
    table = lambda_table.run(Case(), lambdas=(10.0,))
    assert [r["permeability"] for r in table.rows] == [5e-15, 0.0]
    for r in table.rows:
        assert -25.0 < r["eq21_error_pct"] < -5.0
        assert r["fe2d_mesh_error_pct"] < 0.1
    study_io.write(table, tmp_path)
    assert "| impermeable | 10 |" in (tmp_path / "lambda_table.md").read_text()


@pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")
def test_variants_continue_along_speed():
    """The curves walk each speed path with continuation; the closed form's equal its
    point solves and the FE model's the cold solves."""
    study = variants.run(Case(), model="fe1d", num=3)
    assert len(study.mu) == 8 and study.failed == 0
    u = study.speeds[-1]
    key = ("continuous", "gaussian")
    case = Case().updated({"friction.variant": key[0], "friction.distribution": key[1],
                           "roller.speed": u})
    assert study.mu[key + ("closed-form",)][-1] == solve(case, model="closed-form")["mu"]
    assert study.mu[key + ("fe1d",)][-1] == pytest.approx(solve(case, "fe1d")["mu"], rel=1e-6)
    # the curves in two processes: the same keys in the same order, the same values
    both = variants.run(Case(), model="fe1d", num=3, workers=2)
    assert list(both.mu) == list(study.mu)
    for k in study.mu:
        assert both.mu[k] == pytest.approx(study.mu[k], rel=1e-9)


def test_studies_compute_only():
    """Studies sit below io: importing them loads neither webfem.io nor matplotlib."""
    code = ("import sys, webfem.studies.report, webfem.studies.variants, "
            "webfem.studies.lambda_table; "
            "print(sorted(m for m in sys.modules if m.startswith(('webfem.io', 'webfem.cli', "
            "'matplotlib'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


def test_study_cli(tmp_path, capsys):
    from webfem.cli import main
    assert main(["study", "pareto", "cases/base.toml", "--out", str(tmp_path), "--quick",
                 "--quiet", "--set", "roller.speed=40", "--repeats", "1"]) == 0
    captured = capsys.readouterr()
    assert "| closed form |" in captured.out
    assert "reference fe2d" not in captured.err               # --quiet: no progress
    assert (tmp_path / "pareto.csv").exists()


def test_study_cli_progress_on_stderr(tmp_path, capsys):
    from webfem.cli import main
    assert main(["study", "variants", "cases/base.toml", "--out", str(tmp_path),
                 "--model", "fe1d", "--num", "2"]) == 0
    captured = capsys.readouterr()
    assert "paper      exponential fe1d        done" in captured.err
    assert "done" not in captured.out and "| fe1d | paper | exponential |" in captured.out
    assert {p.name for p in tmp_path.iterdir()} == {"variants.csv", "variants.png",
                                                    "variants.md"}


@pytest.mark.parametrize("argv", [
    ["study", "variants", "cases/base.toml", "--out", "OUT", "--num", "0"],
    ["study", "pareto", "cases/base.toml", "--out", "OUT", "--model", "fe1d"],
    ["study", "sideways", "cases/base.toml", "--out", "OUT"],
])
def test_study_cli_usage_errors(argv, tmp_path, capsys):
    from webfem.cli import main
    with pytest.raises(SystemExit) as err:
        main([str(tmp_path) if a == "OUT" else a for a in argv])
    assert err.value.code == 2
    assert not any(tmp_path.iterdir())


def test_study_cli_out_is_a_file(tmp_path, capsys):
    from webfem.cli import main
    target = tmp_path / "file"
    target.write_text("x")
    assert main(["study", "stability", "cases/base.toml", "--out", str(target)]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "is a file" in err and "Traceback" not in err


def test_pareto_has_the_fitted_models_point(par):
    r = par.row("fitted")
    assert r["model"] == "fitted" and r["same_case"]
    assert r["time_s"] < par.row("fe1d P2 level 0")["time_s"]


def test_pareto_measures_the_fitted_model_on_the_default_physics_where_it_refuses_the_case():
    from conftest import PAPER
    on, name = pareto._fitted_case(PAPER, "fitted")
    assert name == "fitted (default physics)" and on.model.physics == "full"
    assert on.updated({"model.physics": "paper"}) == PAPER
    on, why = pareto._fitted_case(PAPER.updated({"web.width": 0.002}), "fitted")
    assert on is None and "model.physics" in why
