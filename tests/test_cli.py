"""The CLI contract: JSON keys, sweep outputs, error exit codes; every case file runs."""

import csv
import json
from pathlib import Path

import pytest

import webfem
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
    """With the paper's physics the base case rises to about 0.3 at low speed, falls
    through mixed, ends below 0.03."""
    main(["sweep", "cases/base.toml", "--out", str(tmp_path), "--quiet", "--set",
          "model.physics=paper"])
    rows = list(csv.DictReader((tmp_path / "base_closed-form.csv").open()))
    mu = [float(r["mu"]) for r in rows]
    speed = [float(r["value"]) for r in rows]
    peak = max(mu)
    assert 0.27 < peak <= 0.3
    assert speed[mu.index(peak)] < 10.0
    assert mu[-1] < 0.03
    assert {"boundary", "mixed", "fluid"} >= {r["regime"] for r in rows}
    assert "fluid" in {r["regime"] for r in rows} and "boundary" in {r["regime"] for r in rows}


# -- every failure a message (issue 11 item 4) ----------------------------------------------

def _one_line(err: str) -> str:
    """The single stderr line of a failed command (and never a traceback)."""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    assert lines[0].startswith("webfem: error: "), err
    return lines[0]


@pytest.mark.parametrize("argv,words", [
    (["--model", "fe1d", "--opt", "level=abc"], ["level=abc", "integer"]),
    (["--model", "fe1d", "--opt", "levle=2"], ["'levle'", "did you mean 'level'"]),
    (["--model", "fe1d", "--opt", "adapt=yes"], ["adapt", "integer"]),
    (["--model", "fe2d", "--opt", "symmetry=maybe"], ["symmetry", "true or false"]),
    (["--model", "fe1d", "--opt", "tol=nan"], ["tol", "out of range"]),
    (["--model", "fe1d", "--opt", "level"], ["expected name=value"]),
    (["--model", "auto", "--opt", "levle=1"], ["unknown auto option 'levle'"]),
])
def test_bad_option_is_one_line_exit_2(argv, words, capsys):
    assert main(["solve", "cases/base.toml", *argv]) == 2
    out = capsys.readouterr()
    line = _one_line(out.err)
    assert out.out == ""
    for word in words:
        assert word in line


def test_solve_help_lists_every_models_options(capsys):
    from webfem.models.registry import MODELS

    with pytest.raises(SystemExit) as exit_:
        main(["solve", "--help"])
    assert exit_.value.code == 0
    text = " ".join(capsys.readouterr().out.split())
    for name, spec in MODELS.items():
        assert f"{name}: {spec.summary}" in text
    # fe1d's options with their defaults and ranges, as the options type describes them
    for line in MODELS["fe1d"].options.describe().splitlines():
        assert " ".join(line.split()) in text
    assert "level = 0: uniform refinement level" in text


def test_plot_without_a_film_is_refused_before_solving(tmp_path, capsys):
    for model in ("fe1d", "closed-form"):
        assert main(["solve", "cases/base.toml", "--model", model, "--plot", "--vtu",
                     str(tmp_path / "v")]) == 2
        out = capsys.readouterr()
        assert "--model fe2d" in _one_line(out.err) and out.out == ""
    assert not (tmp_path / "v").exists() or not any((tmp_path / "v").iterdir())


@pytest.mark.parametrize("command", [
    ["solve", "cases/base.toml", "--model", "fe1d", "--vtu"],
    ["sweep", "cases/base.toml", "--out"],
    ["mesh", "cases/base.toml", "--out"],
    ["traction-loss", "cases/base.toml", "--mu-min", "0.1", "--chart"],
])
@pytest.mark.parametrize("where", ["file", "under a file"])
def test_unwritable_output_fails_before_solving(command, where, tmp_path, capsys):
    blocker = tmp_path / "taken"
    blocker.write_text("not a folder")
    target = blocker if where == "file" else blocker / "sub"
    assert main([*command, str(target)]) == 2
    out = capsys.readouterr()
    line = _one_line(out.err)
    assert str(target) in line and where.split()[-1] in line
    assert out.out == ""   # nothing solved, nothing printed
    assert blocker.read_text() == "not a folder"


def test_sweep_spacing_flags_are_checked(tmp_path, capsys):
    out = str(tmp_path / "o")
    assert main(["sweep", "cases/base.toml", "--out", out, "--log"]) == 2
    assert "--log needs --num" in _one_line(capsys.readouterr().err)
    assert main(["sweep", "cases/base.toml", "--out", out, "--num", "0"]) == 2
    assert "--num" in _one_line(capsys.readouterr().err)
    assert not Path(out).exists()   # input checked before any folder is made


def test_sweep_num_log_respaces(tmp_path):
    assert main(["sweep", "cases/base.toml", "--out", str(tmp_path), "--num", "5", "--log",
                 "--quiet"]) == 0
    rows = list(csv.DictReader((tmp_path / "base_closed-form.csv").open()))
    values = [float(r["value"]) for r in rows]
    spec = load_sweep("cases/base.toml")
    assert len(values) == 5
    assert values[0] == pytest.approx(min(spec.values)) and \
        values[-1] == pytest.approx(max(spec.values))
    assert values[2] == pytest.approx((values[0] * values[4]) ** 0.5)   # geometric


def test_mesh_level_is_bounded(tmp_path, capsys):
    assert main(["mesh", "cases/base.toml", "--out", str(tmp_path), "--opt", "level=99"]) == 2
    line = _one_line(capsys.readouterr().err)
    assert "level = 99" in line and "<= 3" in line
    assert not list(tmp_path.iterdir())


def test_mesh_files_follow_the_options(tmp_path, capsys):
    import meshio

    assert main(["mesh", "cases/base.toml", "--out", str(tmp_path / "a")]) == 0
    assert main(["mesh", "cases/base.toml", "--out", str(tmp_path / "b"), "--opt",
                 "symmetry=false"]) == 0
    half = meshio.read(tmp_path / "a" / "base_film.vtu").points
    full = meshio.read(tmp_path / "b" / "base_film.vtu").points
    width = webfem.load_case("cases/base.toml").web.width
    assert half[:, 1].min() == 0.0 and half[:, 1].max() == pytest.approx(width / 2)
    assert full[:, 1].min() == pytest.approx(-width / 2)
    assert not [p for p in tmp_path.rglob(".*")]   # no temporary files left


def test_json_is_strict_when_numbers_are_not_finite(monkeypatch, capsys):
    """A summary holding NaN and infinity prints as null, never as NaN or Infinity."""
    import dataclasses

    import webfem.cli.solve as solve_cmd

    real = webfem.solve(webfem.Case().updated({"roller.speed": 40.0}))
    broken = dataclasses.replace(real, summary=real.summary.replace(mu=float("nan"),
                                                                    delta_T=float("inf")))
    monkeypatch.setattr(solve_cmd, "solve", lambda *a, **k: broken)
    assert main(["solve", "cases/base.toml", "--json"]) == 0

    def refuse(name):
        raise AssertionError(f"{name} in JSON output")
    data = json.loads(capsys.readouterr().out, parse_constant=refuse)
    assert data["mu"] is None and data["delta_T"] is None and data["h_center"] > 0


def test_keyboard_interrupt_is_one_line_exit_130(monkeypatch, capsys):
    import webfem.cli.solve as solve_cmd

    def stop(*args, **kwargs):
        raise KeyboardInterrupt
    monkeypatch.setattr(solve_cmd, "solve", stop)
    assert main(["solve", "cases/base.toml"]) == 130
    err = capsys.readouterr().err
    assert err.strip() == "webfem: interrupted"


def test_interrupted_sweep_says_what_was_saved(monkeypatch, tmp_path, capsys):
    import webfem.sweeps

    def stop(spec, model, csv_path, **kwargs):
        err = KeyboardInterrupt()
        err.saved, err.total, err.csv_path = 3, 60, csv_path
        raise err
    monkeypatch.setattr(webfem.sweeps, "run", stop)
    assert main(["sweep", "cases/base.toml", "--out", str(tmp_path), "--quiet"]) == 130
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert err == (f"webfem: interrupted: 3 of 60 points saved in "
                   f"{tmp_path / 'base_closed-form.csv'}; run the same command to continue")


def test_keys_into_a_closed_pipe_is_quiet():
    """`webfem keys | head -1`: the reader goes away; no BrokenPipeError traceback."""
    import subprocess
    import sys

    proc = subprocess.Popen([sys.executable, "-m", "webfem", "keys"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    proc.stdout.close()   # before webfem writes a line
    err = proc.stderr.read().decode()
    assert proc.wait() == 0 and err == ""
    shell = subprocess.run(f"{sys.executable} -m webfem keys | head -1", shell=True,
                           capture_output=True, text=True)
    assert shell.stdout == "[roller]\n" and "Traceback" not in shell.stderr


def test_keys_describe_the_sweep_tables(capsys):
    assert main(["keys"]) == 0
    out = capsys.readouterr().out
    assert "[roller]" in out and "  speed " in out
    assert "[sweep]" in out and "[[series]]" in out
    for key in ("parameter", "values", "start, stop", "num", "spacing", "label"):
        assert f"\n  {key} " in out
