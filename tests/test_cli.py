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
    assert main(["solve", "cases/base.toml", "--json", "--model", "closed-form"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["units"] == "SI"
    for key in SUMMARY_KEYS:
        assert key in data
    assert data["model"] == "closed-form" and data["converged"] is True
    assert 0.0 < data["mu"] < 0.35


def test_solve_set_override(capsys):
    main(["solve", "cases/base.toml", "--json", "--model", "closed-form", "--set",
          "roller.speed=40"])
    fast = json.loads(capsys.readouterr().out)
    main(["solve", "cases/base.toml", "--json", "--model", "closed-form", "--set",
          "roller.speed=5"])
    slow = json.loads(capsys.readouterr().out)
    assert fast["h_inlet"] > slow["h_inlet"]
    assert fast["mu"] < 0.03 < slow["mu"]


def test_bad_input_exits_2_with_message(capsys):
    assert main(["solve", "cases/base.toml", "--set", "web.width=-2"]) == 2
    err = capsys.readouterr().err
    assert "web.width = -2.0" in err and ">= 0.001 and <= 10 [m]" in err


@pytest.mark.parametrize("case", CASES, ids=[c.stem for c in CASES])
def test_every_case_file_sweeps(case, tmp_path, capsys):
    if webfem.load_case(case).grooved:   # only fe2d solves grooves: the closed form refuses
        assert main(["sweep", str(case), "--model", "closed-form", "--out", str(tmp_path),
                     "--quiet"]) == 2
        assert "roller.groove_width" in capsys.readouterr().err
        return
    assert main(["sweep", str(case), "--model", "closed-form", "--out", str(tmp_path),
                 "--quiet"]) == 0
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
    main(["sweep", "cases/base.toml", "--model", "closed-form", "--out", str(tmp_path),
          "--quiet", "--set", "model.physics=paper"])
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
    assert main(["sweep", "cases/base.toml", "--model", "closed-form", "--out", str(tmp_path),
                 "--num", "5", "--log", "--quiet"]) == 0
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


def test_json_is_strict_when_numbers_are_not_finite(flying, monkeypatch, capsys):
    """A summary holding NaN and infinity prints as null, never as NaN or Infinity."""
    import dataclasses

    import webfem.cli.solve as solve_cmd

    real = webfem.solve(flying)
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
    assert main(["sweep", "cases/base.toml", "--model", "closed-form", "--out", str(tmp_path),
                 "--quiet"]) == 130
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert err == (f"webfem: interrupted: 3 of 60 points saved in "
                   f"{tmp_path / 'base_closed-form.csv'}; run the same command to continue")


def test_sigterm_ends_a_sweep_as_ctrl_c_does(tmp_path):
    """`kill PID` (SIGTERM) on a sweep on 2 processes: the lock released, the saved points
    said, exit 143 (it used to die silently, leaving .NAME.csv.lock behind)."""
    import os
    import signal
    import subprocess
    import sys
    import time

    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[1])}
    proc = subprocess.Popen(
        [sys.executable, "-m", "webfem", "sweep", "cases/fig10_wrap.toml", "--model", "fe1d",
         "--out", str(tmp_path), "--workers", "2", "--quiet"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, text=True)
    csv = tmp_path / "fig10_wrap_fe1d.csv"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if csv.exists() and len(csv.read_text().splitlines()) > 3:
            break
        time.sleep(0.2)
    assert proc.poll() is None, "the sweep ended before it could be stopped"
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 143, err
    assert "webfem: interrupted:" in err and "points saved in" in err
    assert "Traceback" not in err
    assert not (tmp_path / ".fig10_wrap_fe1d.csv.lock").exists()


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


# -- the engineer's interface (issue 13 items 1, 2, 3, 6) -------------------------------------

def test_solve_defaults_to_auto_and_says_which_model_and_why(capsys):
    assert main(["solve", "cases/base.toml"]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("webfem auto: ")
    used = first.removeprefix("webfem auto: ").split()[0]
    assert used in ("closed-form", "fe1d", "fe2d") and f"{used} answered" in first
    assert "estimated mu error" in first


def test_units_of_the_printed_summary(capsys):
    argv = ["solve", "base", "--model", "closed-form", "--set", "roller.speed=1200 m/min",
            "--set", "web.tension=0.5 pli"]
    assert main([*argv, "--units", "us"]) == 0
    us = capsys.readouterr().out
    assert "U_r = 3937 ft/min" in us and "T = 0.5 pli" in us and "R = 2.165 in" in us
    assert " um" not in us and " m/s" not in us and "mil" in us
    assert main([*argv, "--units", "metric"]) == 0
    metric = capsys.readouterr().out
    assert "U_r = 1200 m/min" in metric and "R = 55 mm" in metric
    assert main([*argv, "--units", "us", "--json"]) == 0   # JSON stays SI
    data = json.loads(capsys.readouterr().out)
    assert data["units"] == "SI" and data["U"] == pytest.approx(20.0)


def test_unit_errors_from_the_command_line(capsys):
    assert main(["solve", "base", "--set", "web.tension=3 m"]) == 2
    line = _one_line(capsys.readouterr().err)
    assert "web.tension = '3 m' has dimension length; expected force/length" in line


def test_traction_loss_speeds_take_units(capsys):
    assert main(["traction-loss", "base", "--model", "closed-form", "--mu-min", "0.1",
                 "--min-speed", "30 m/min", "--max-speed", "6000 m/min", "--units",
                 "metric"]) == 0
    out = capsys.readouterr().out
    assert "m/min" in out and "m/s" not in out
    with pytest.raises(SystemExit) as exit_:   # a usage error, as for any bad flag value
        main(["traction-loss", "base", "--mu-min", "0.1", "--max-speed", "3 kg"])
    assert exit_.value.code == 2
    assert "'3 kg' has dimension mass; expected speed" in capsys.readouterr().err


def test_bundled_cases_list_init_and_run_from_anywhere(tmp_path, monkeypatch, capsys):
    bundled = Path(webfem.__file__).parent / "cases"
    names = sorted(p.stem for p in bundled.glob("*.toml"))
    assert "base" in names and {c.stem for c in CASES} == set(names)
    monkeypatch.chdir(tmp_path)
    assert main(["cases"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [ln.split()[0] for ln in lines] == names
    assert lines[0].split(None, 1)[1].startswith("Base case")
    assert main(["init", "base"]) == 0
    capsys.readouterr()
    assert (tmp_path / "base.toml").read_text() == (bundled / "base.toml").read_text()
    (tmp_path / "base.toml").write_text("# mine\n")
    assert main(["init", "base"]) == 2   # never overwrites
    assert "exists" in _one_line(capsys.readouterr().err)
    assert (tmp_path / "base.toml").read_text() == "# mine\n"
    assert main(["init", "fig10_wrap", "sub/dir"]) == 0
    assert (tmp_path / "sub" / "dir" / "fig10_wrap.toml").exists()
    capsys.readouterr()
    assert main(["init", "bsae"]) == 2
    assert "did you mean 'base'" in _one_line(capsys.readouterr().err)
    (tmp_path / "base.toml").unlink()
    assert main(["solve", "fig13_radius", "--model", "closed-form", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["model"] == "closed-form"


def test_version_and_keys_show_units(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0 and capsys.readouterr().out.strip() == \
        f"webfem {webfem.__version__}"
    assert main(["keys"]) == 0
    out = capsys.readouterr().out
    assert "[m/s] or e.g. '1200 m/min', '3900 ft/min'" in out
    assert "[N/m] or e.g. '80 N/m', '0.45 pli'" in out
    assert "\n  diameter " in out


def test_no_progress_when_stderr_is_not_a_terminal(tmp_path, capsys):
    assert main(["sweep", "base", "--model", "closed-form", "--out", str(tmp_path)]) == 0
    err = capsys.readouterr().err
    assert "points" not in err.replace("values x", "") and "\r" not in err


def test_progress_on_a_terminal_shows_time_left(monkeypatch, capsys):
    from webfem.cli.common import Progress

    monkeypatch.setattr("sys.stderr.isatty", lambda: True)
    progress = Progress()
    progress(1, 4)
    progress(4, 4)
    err = capsys.readouterr().err
    assert "1/4 points" in err and "left" in err and err.endswith("\n")
    Progress(quiet=True)(1, 4)
    assert capsys.readouterr().err == ""


def test_wheel_installs_and_runs_from_an_empty_folder(tmp_path):
    """Build the wheel, install it (without dependencies: the test venv's own are reached
    through a .pth file) into a fresh venv, and run the bundled case from an empty folder."""
    import os
    import shutil
    import subprocess
    import sys
    import sysconfig

    root = Path(__file__).parent.parent
    src = tmp_path / "src"
    src.mkdir()
    shutil.copy(root / "pyproject.toml", src)
    shutil.copy(root / "README.md", src)
    shutil.copytree(root / "webfem", src / "webfem",
                    ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    build = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet",
                            "-w", str(tmp_path / "dist"), str(src)],
                           capture_output=True, text=True)
    assert build.returncode == 0, build.stderr[-2000:]
    assert "SetuptoolsDeprecationWarning" not in build.stderr
    wheel, = (tmp_path / "dist").glob("webfem-*.whl")
    venv = tmp_path / "venv"
    subprocess.run([sys._base_executable, "-m", "venv", str(venv)], check=True)
    py = venv / "bin" / "python"
    purelib = subprocess.run([py, "-c", "import sysconfig; print(sysconfig.get_paths()"
                                        "['purelib'])"], capture_output=True, text=True,
                             check=True).stdout.strip()
    Path(purelib, "project_deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    subprocess.run([py, "-m", "pip", "install", "--quiet", "--no-deps", "--no-index",
                    str(wheel)], check=True, capture_output=True)
    empty = tmp_path / "empty"
    empty.mkdir()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}

    def webfem_(*argv):
        return subprocess.run([venv / "bin" / "webfem", *argv], cwd=empty, env=env,
                              capture_output=True, text=True)

    listed = webfem_("cases")
    assert listed.returncode == 0 and listed.stdout.startswith("base ")
    assert webfem_("init", "base").returncode == 0 and (empty / "base.toml").exists()
    (empty / "base.toml").unlink()   # the bundled name, not the copy, must answer
    solved = webfem_("solve", "base", "--set", "roller.speed=1200 m/min", "--set",
                     "web.tension=0.5 pli", "--units", "us")
    assert solved.returncode == 0, solved.stderr
    assert solved.stdout.startswith("webfem auto: ") and "U_r = 3937 ft/min" in solved.stdout
    where = subprocess.run([py, "-c", "import webfem; print(webfem.__file__)"], cwd=empty,
                           env=env, capture_output=True, text=True, check=True).stdout
    assert str(venv) in where   # the wheel's copy, not the source tree


def test_a_local_file_beats_the_bundled_name_and_says_so(tmp_path, monkeypatch, capsys):
    """`webfem init base`, edit ./base.toml, `webfem solve base`: the edited file answers,
    and stderr says which file a bare name stood for (issue 20)."""
    monkeypatch.chdir(tmp_path)
    assert main(["solve", "base", "--model", "closed-form", "--json"]) == 0
    out = capsys.readouterr()
    assert json.loads(out.out)["U"] == pytest.approx(20.0)
    assert "case 'base' is the bundled base.toml" in out.err
    assert main(["init", "base"]) == 0
    path = tmp_path / "base.toml"
    path.write_text(path.read_text().replace("speed = 20.0", "speed = 35.0", 1))
    capsys.readouterr()
    for name in ("base", "base.toml"):
        assert main(["solve", name, "--model", "closed-form", "--json"]) == 0
        out = capsys.readouterr()
        assert json.loads(out.out)["U"] == pytest.approx(35.0)
    assert main(["solve", "base", "--model", "closed-form"]) == 0
    err = capsys.readouterr().err
    assert "case 'base' is ./base.toml, the file here (not the bundled case" in err
    assert main(["solve", "base", "--set", "web=80"]) == 2   # a failure stays one line
    _one_line(capsys.readouterr().err)


# -- sweeps and charts (issue 20) ------------------------------------------------------------

def _chart_axes(monkeypatch):
    """Capture the figures sweep_chart saves (their axes, titles and legend texts)."""
    from webfem.io import charts
    seen = []
    real = charts._save

    def save(fig, path):
        ax = fig.axes[0]
        seen.append({"xscale": ax.get_xscale(), "title": ax.get_title(),
                     "legend": [t.get_text() for lg in fig.legends for t in lg.get_texts()]})
        return real(fig, path)
    monkeypatch.setattr(charts, "_save", save)
    return seen


def test_grooved_fe2d_sweep_draws_its_chart_without_the_closed_form(tmp_path, capsys,
                                                                     monkeypatch):
    seen = _chart_axes(monkeypatch)
    assert main(["sweep", "base_grooved", "--model", "fe2d", "--num", "2", "--out",
                 str(tmp_path), "--quiet"]) == 0
    err = capsys.readouterr().err
    assert "no closed-form curve beside fe2d" in err and "grooved roller" in err
    assert (tmp_path / "base_grooved_fe2d.png").stat().st_size > 10_000
    assert "no closed-form curve" in seen[-1]["title"]
    assert not any("closed-form" in t for t in seen[-1]["legend"])


def test_log_sweep_has_a_log_axis_and_auto_rows_name_their_model(tmp_path, capsys,
                                                                  monkeypatch):
    seen = _chart_axes(monkeypatch)
    assert main(["sweep", "base", "--model", "closed-form", "--num", "4", "--log", "--out",
                 str(tmp_path), "--quiet"]) == 0
    assert seen[-1]["xscale"] == "log"
    assert main(["sweep", "base", "--model", "closed-form", "--num", "4", "--out",
                 str(tmp_path / "lin"), "--quiet"]) == 0
    assert seen[-1]["xscale"] == "linear"
    rows = list(csv.DictReader((tmp_path / "base_closed-form.csv").open()))
    assert {r["model_used"] for r in rows} == {"closed-form"} and {r["why"] for r in rows} == {""}
    assert main(["sweep", "base", "--num", "2", "--out", str(tmp_path), "--quiet"]) == 0
    rows = list(csv.DictReader((tmp_path / "base_auto.csv").open()))
    assert {r["model"] for r in rows} == {"auto"}
    assert all(r["model_used"] in ("closed-form", "fe1d", "fe2d") and r["why"] for r in rows)
    title = seen[-1]["title"]
    assert title.startswith("base: auto: ") and rows[0]["model_used"] in title


def test_sweep_into_another_sweeps_csv_says_what_it_does(tmp_path, capsys):
    argv = ["sweep", "cases/base.toml", "--model", "closed-form", "--out", str(tmp_path),
            "--quiet"]
    assert main([*argv, "--num", "3"]) == 0
    csv_path = tmp_path / "base_closed-form.csv"
    before = csv_path.read_text()
    capsys.readouterr()
    assert main([*argv, "--num", "4"]) == 2               # would drop points: refused
    line = _one_line(capsys.readouterr().err)
    assert "holds another sweep" in line and "--replace" in line
    assert csv_path.read_text() == before
    assert main([*argv, "--num", "4", "--replace"]) == 0
    assert "replacing its 3 rows of another sweep" in capsys.readouterr().err
    assert len(list(csv.DictReader(csv_path.open()))) == 4
    assert main([*argv, "--num", "4"]) == 0
    assert "resuming this sweep: 4 of 4 points already there" in capsys.readouterr().err


def test_vtu_states_the_reported_minimum_gap(tmp_path, capsys):
    """The VTU's nodal h does not reach the reported h_min (it lies between nodes): its
    field data give h_min, x_min, the nodal minimum and a note saying they differ."""
    import meshio
    from webfem.io.vtu import H_MIN_KEYS, H_MIN_NOTE, read_field_data
    assert main(["solve", "base", "--model", "fe2d", "--json", "--vtu", str(tmp_path)]) == 0
    data = json.loads(capsys.readouterr().out)
    for part in ("web", "film"):
        path = tmp_path / f"base_fe2d_{part}.vtu"
        fields = read_field_data(path)
        nodal = float(meshio.read(path).point_data["h [m]"].min())
        assert fields["h_min [m]"] == pytest.approx(data["h_min"], rel=1e-12)
        assert fields["x_min [m]"] == pytest.approx(data["x_min"], rel=1e-12)
        assert fields[H_MIN_KEYS[2]] == pytest.approx(nodal, rel=1e-12)
        assert nodal > data["h_min"]                       # 3.35 um against 3.30 um
        assert fields[H_MIN_KEYS[3]] == pytest.approx(nodal / data["h_min"] - 1, rel=1e-9)
        assert fields[H_MIN_NOTE] == 1.0


# -- the fitted model where it pays: sweeps, traction loss, idlers, calibration -------------

def test_sweep_with_the_fitted_model_keeps_points_outside_its_domain(tmp_path, capsys):
    assert main(["sweep", "base", "--model", "fitted", "--out", str(tmp_path),
                 "--quiet"]) in (0, 3)
    rows = list(csv.DictReader((tmp_path / "base_fitted.csv").open()))
    assert len(rows) == len(load_sweep("cases/base.toml").values)
    answered = [r for r in rows if r["converged"] == "True"]
    refused = [r for r in rows if r["converged"] != "True"]
    assert len(answered) >= 0.9 * len(rows)
    assert all(r["model"] == "fitted" and float(r["error_mu"]) > 0 for r in answered)
    # the slowest speeds put the web's permeation outside the fitted domain: named, kept
    assert all("outside the fitted model's domain" in r["solver_message"] for r in refused)


def test_traction_loss_with_the_fitted_model_scans_its_domain(tmp_path, capsys):
    assert main(["traction-loss", "base", "--model", "fitted", "--mu-min", "0.1",
                 "--json", "--chart", str(tmp_path), "--points", "2"]) == 0
    assert (tmp_path / "base_traction_loss.png").stat().st_size > 10_000
    out = json.loads(capsys.readouterr().out)
    assert out["model"] == "fitted" and out["speed"] is not None
    assert "the fitted model's domain limits the scan to" in out["message"]
    at = webfem.solve(webfem.load_case("cases/base.toml").updated(
        {"roller.speed": out["speed"]}), model="fitted")
    assert at["mu"] == pytest.approx(0.1, abs=2e-3)


def test_idler_with_the_fitted_model_answers_inside_its_domain(capsys):
    assert main(["idler", "idler", "--model", "fitted", "--min-speed", "0.05",
                 "--max-speed", "20", "--num", "3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["converged"] == [False, True, True]     # 0.05 m/s: outside the domain
    assert out["slip_margin"][0] is None and out["slip_margin"][1] > 0
    assert main(["idler", "idler", "--model", "fitted", "--min-speed", "0.05",
                 "--num", "3"]) == 0
    assert "no answer" in capsys.readouterr().out


def test_calibration_with_the_fitted_model_recovers_its_constants(tmp_path, capsys):
    """Rows made by the fitted model itself: calibration re-evaluates the friction on the
    fitted profile as the model does (its wrap quadrature), so it finds the constants."""
    base = webfem.load_case("cases/base.toml")
    lines = ["roller_speed,tension,delta_T"]
    for tension in (60.0, 100.0):
        for speed in (3.0, 5.0, 8.0, 12.0, 20.0, 30.0):
            r = webfem.solve(base.updated({"roller.speed": speed, "web.tension": tension,
                                           "friction.mu_cc": 0.35,
                                           "friction.speed_constant": 0.6}), model="fitted")
            lines.append(f"{speed},{tension},{r['delta_T']!r}")
    p = tmp_path / "rig.csv"
    p.write_text("\n".join(lines) + "\n")
    assert main(["calibrate", str(p), "--case", "base", "--model", "fitted", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["estimates"]["mu_cc"] == pytest.approx(0.35, rel=1e-6)
    assert out["estimates"]["speed_constant"] == pytest.approx(0.6, rel=1e-6)
