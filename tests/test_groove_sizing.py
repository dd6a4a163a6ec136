"""`webfem grooves` (issue 15, item 4): the map and the traction-loss speeds are resumable
(each design saved as it finishes, a re-run solves only what is missing), show progress,
and chart the traction-loss speed against groove geometry.

The store is tested with the solver replaced by a cheap deterministic stand-in (the
bookkeeping does not depend on the physics); the fe2d answers themselves are tested in
tests/test_grooves.py and, for one traction-loss speed, below (slow).
"""

import csv
import json

import pytest

from webfem import Case
from webfem import groove_sizing as gs
from webfem.cli import main
from webfem.errors import ConvergenceError, InputError
from webfem.io.groove_charts import loss_speed_chart
from webfem.sweeps import SweepInterrupted
from webfem.traction import TractionLoss

from conftest import inspect_before_save

GRID = {"speeds": (20.0, 40.0), "pitches": (1.27e-3, 5e-3), "land_fractions": (0.5, 0.9)}


def fake_mu(case: Case) -> float:
    """Traction that falls with speed and land fraction (the map's trends), exactly
    reproducible from the case."""
    return 0.1 + 0.4 * (1.0 - case.land_fraction) * 20.0 / case.roller.speed \
        + 1e-3 * case.roller.groove_pitch / 1e-3


@pytest.fixture
def calls(monkeypatch):
    """The solves made, by (speed, pitch, land fraction); fe2d replaced by fake_mu."""
    made = []

    def solve(case, model, options):
        assert model == "fe2d"
        made.append((case.roller.speed, case.roller.groove_pitch, round(case.land_fraction, 9)))
        mu = fake_mu(case)
        return {"mu": mu, "h_center": 1e-6 / mu, "contact_share": 0.5}

    monkeypatch.setattr(gs, "solve", solve)
    return made


def stop_after(k: int):
    """A progress callback that interrupts (as Ctrl-C would) once k designs are solved."""
    def progress(done, total):
        if done >= k:
            raise KeyboardInterrupt
    return progress


def test_interrupted_map_resumes_with_the_same_answers(calls, tmp_path):
    store = tmp_path / "base_grooves.csv"
    reference = gs.groove_map(Case(), 0.2, **GRID)          # in memory, uninterrupted
    assert len(calls) == 8 and not list(tmp_path.iterdir())
    calls.clear()
    with pytest.raises(SweepInterrupted) as err:
        gs.groove_map(Case(), 0.2, **GRID, store=store, progress=stop_after(3))
    assert (err.value.saved, err.value.total) == (3, 8)
    assert len(calls) == 3
    with store.open() as fh:
        assert len(list(csv.DictReader(fh))) == 3          # saved as each finished
    assert sorted(p.name for p in tmp_path.iterdir()) == ["base_grooves.csv",
                                                           "base_grooves.sweep.json"]
    seen = []
    designs = gs.groove_map(Case(), 0.2, **GRID, store=store,
                            progress=lambda done, total: seen.append((done, total)))
    assert len(calls) == 8                                   # only the 5 missing
    assert seen[0] == (3, 8) and seen[-1] == (8, 8)
    assert designs == reference                              # exact: floats round-trip
    # done: nothing left to solve, and mu_min only marks (it is not part of the signature)
    again = gs.groove_map(Case(), 0.3, **GRID, store=store)
    assert len(calls) == 8
    assert [d.feasible for d in again] == [d.mu >= 0.3 for d in again]
    assert any(d.feasible for d in designs) and not all(d.feasible for d in designs)


def test_changed_map_starts_over(calls, tmp_path):
    store = tmp_path / "m.csv"
    gs.groove_map(Case(), 0.2, **GRID, store=store)
    gs.groove_map(Case().updated({"web.tension": 100.0}), 0.2, **GRID, store=store)
    assert len(calls) == 16
    gs.groove_map(Case(), 0.2, **{**GRID, "pitches": (1.27e-3,)}, store=store)
    assert len(calls) == 20
    with store.open() as fh:
        assert len(list(csv.DictReader(fh))) == 4


def test_failed_designs_are_kept_and_torn_ones_solved_again(calls, tmp_path, monkeypatch):
    """A design without an answer is final (solved from cold, it would fail again the same
    way, and proving it can cost minutes); a row torn by a kill is solved again."""
    store = tmp_path / "m.csv"
    solve = gs.solve

    def flaky(case, model, options):
        if case.roller.groove_pitch == 5e-3 and case.roller.speed == 40.0:
            raise ConvergenceError("fe2d (newton) did not converge: test")
        return solve(case, model, options)

    monkeypatch.setattr(gs, "solve", flaky)
    first = gs.groove_map(Case(), 0.2, **GRID, store=store)
    failed = [d for d in first if not d.converged]
    assert len(failed) == 2 and not any(d.feasible for d in failed)
    assert all(d.mu is None for d in failed)
    monkeypatch.setattr(gs, "solve", solve)
    lines = store.read_text().splitlines(keepends=True)
    torn = lines.pop(2)              # a kill in mid-write: this design's row cut short
    store.write_text("".join(lines) + torn[:len(torn) // 2])
    n = len(calls)
    again = gs.groove_map(Case(), 0.2, **GRID, store=store)
    assert len(calls) - n == 1                    # the torn row only
    assert again == first
    assert "did not converge: test" in again[-1].message


def test_map_arguments_are_checked_before_any_solve(calls, tmp_path):
    for kwargs, words in [({"speeds": (0.0,)}, "roller speed = 0.0"),
                          ({"land_fractions": (1.0,)}, "land fraction = 1.0"),
                          ({"pitches": (-1e-3,)}, "groove pitch = -0.001")]:
        with pytest.raises(InputError, match=words):
            gs.groove_map(Case(), 0.2, **kwargs, store=tmp_path / "m.csv")
    with pytest.raises(InputError, match="mu_min = 0"):
        gs.loss_speed_map(Case(), 0, store=tmp_path / "l.csv")
    assert calls == [] and not list(tmp_path.iterdir())


def test_default_speeds_are_the_case_speed_and_twice_it(calls):
    designs = gs.groove_map(Case(), 0.2, pitches=(1.27e-3,), land_fractions=(0.9,))
    assert [d.speed for d in designs] == [Case().roller.speed, 2 * Case().roller.speed]


# -- traction-loss speed against groove geometry ----------------------------------------------
@pytest.fixture
def loss_calls(monkeypatch):
    """traction_loss_speed replaced: a loss speed rising with the groove share, none above
    100 m/s (the 90 % land of the fine pitch loses traction, the 50 % never does)."""
    made = []

    def loss(case, mu_min, model, speed_range, n_scan, xtol, options):
        made.append((case.roller.groove_pitch, round(case.land_fraction, 9)))
        speed = 15.0 + 400.0 * (1.0 - case.land_fraction) * 1.27e-3 / max(
            case.roller.groove_pitch, 1.27e-3) if case.grooved else 15.0
        found = speed <= speed_range[1]
        return TractionLoss(speed if found else None, model, mu_min, 0.4, 1.0,
                            (speed * 0.9, speed) if found else None, 12,
                            f"mu falls below {mu_min:g} at U_r = {speed:.4g} m/s" if found
                            else f"mu stays above {mu_min:g} up to {speed_range[1]:g} m/s")

    monkeypatch.setattr(gs, "traction_loss_speed", loss)
    return made


def test_loss_speeds_resume_and_start_with_the_smooth_roller(loss_calls, tmp_path):
    store = tmp_path / "l.csv"
    grid = {"pitches": (1.27e-3, 5e-3), "land_fractions": (0.5, 0.9)}
    with pytest.raises(SweepInterrupted):
        gs.loss_speed_map(Case(), 0.2, **grid, store=store, progress=stop_after(2))
    assert len(loss_calls) == 2
    out = gs.loss_speed_map(Case(), 0.2, **grid, store=store)
    assert len(loss_calls) == 5
    smooth, *grooved = out
    assert (smooth.pitch, smooth.land_fraction, smooth.speed) == (0.0, 1.0, 15.0)
    assert [x.land_fraction for x in grooved] == pytest.approx([0.5, 0.9, 0.5, 0.9])
    assert grooved[0].speed is None and "stays above" in grooved[0].message
    assert grooved[1].speed == pytest.approx(15.0 + 40.0 * 1.27e-3 / 1.27e-3)
    assert all(x.converged and x.evaluations == 12 for x in out)
    # another mu_min is another question: solved again
    gs.loss_speed_map(Case(), 0.25, **grid, store=store)
    assert len(loss_calls) == 10


def test_loss_speed_chart_draws_every_kind_of_answer(tmp_path):
    rows = [{"pitch": 0.0, "depth": 0.0, "land_fraction": 1.0, "speed": 12.0,
             "converged": True, "message": ""}]
    for pitch in (1.27e-3, 5e-3):
        for land, speed, msg in ((0.5, None, "mu stays above 0.2 up to 100 m/s"),
                                 (0.8, 40.0, ""), (0.9, 25.0, "")):
            rows.append({"pitch": pitch, "depth": 2.5e-4, "land_fraction": land,
                         "speed": speed, "converged": True, "message": msg})
    rows.append({"pitch": 5e-3, "depth": 2.5e-4, "land_fraction": 0.65, "speed": None,
                 "converged": False, "message": "no admissible solution"})
    path = loss_speed_chart(rows, 0.2, tmp_path / "loss.png", (1.0, 100.0))
    assert path.stat().st_size > 10_000


def test_cli_loss_speed_prints_writes_and_resumes(calls, loss_calls, tmp_path, capsys):
    args = ["grooves", "cases/base.toml", "--mu-min", "0.2", "--pitches", "1.27e-3",
            "--lands", "0.5,0.9", "--loss-speed", "--loss-pitches", "1.27e-3",
            "--loss-lands", "0.5,0.9", "--out", str(tmp_path), "--quiet", "--workers", "1"]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "roller speed 20 m/s" in out and "roller speed 40 m/s" in out
    assert "traction-loss speed (mu falls to 0.2)" in out and "smooth roller" in out
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["base_grooves.csv", "base_grooves.png", "base_grooves.sweep.json",
                     "base_grooves_loss.csv", "base_grooves_loss.png",
                     "base_grooves_loss.sweep.json"]
    assert (len(calls), len(loss_calls)) == (4, 3)
    assert main(args + ["--json"]) == 0                      # resumed: nothing solved again
    assert (len(calls), len(loss_calls)) == (4, 3)
    data = json.loads(capsys.readouterr().out)
    assert [x["pitch"] for x in data["loss_speeds"]] == [0.0, 1.27e-3, 1.27e-3]


def test_cli_ctrl_c_says_what_is_saved(calls, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("webfem.cli.grooves.Progress", lambda quiet, what: stop_after(1))
    args = ["grooves", "cases/base.toml", "--mu-min", "0.2", "--out", str(tmp_path)]
    assert main(args) == 130
    err = capsys.readouterr().err
    assert "interrupted: 1 of 32 designs saved" in err and "run the same command" in err
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]   # no lock left


def test_map_in_worker_processes_is_the_serial_map(calls, tmp_path):
    """Designs solved in 2 processes (the command's default on 2 cores): the same rows, in
    the same order, as in this process, and a resumed map solves only what is missing."""
    reference = gs.groove_map(Case(), 0.2, **GRID)
    store = tmp_path / "m.csv"
    seen = []
    designs = gs.groove_map(Case(), 0.2, **GRID, store=store, workers=2,
                            progress=lambda done, total: seen.append(done))
    assert designs == reference and seen == list(range(1, 9))
    assert [r["speed"] for r in csv.DictReader(store.open())] == ["20.0"] * 4 + ["40.0"] * 4
    assert gs.groove_map(Case(), 0.2, **GRID, workers=2) == reference      # in memory
    seen.clear()
    assert gs.groove_map(Case(), 0.2, **GRID, store=store, workers=2,
                         progress=lambda done, total: seen.append(done)) == reference
    assert seen == [8]                      # resumed: nothing solved again
    with pytest.raises(InputError, match="workers = 0"):
        gs.groove_map(Case(), 0.2, **GRID, workers=0)


def test_cli_help_names_the_options(capsys):
    with pytest.raises(SystemExit):
        main(["grooves", "--help"])
    text = " ".join(capsys.readouterr().out.split())     # argparse wraps the lines
    for word in ("--loss-speed", "--loss-pitches", "--loss-lands", "times 1 and 2",
                 "continues where", "--workers"):
        assert word in text


# -- the real thing -----------------------------------------------------------------------------
@pytest.mark.slow
def test_grooves_raise_the_traction_loss_speed():
    """fe2d: on the base case the smooth roller loses mu = 0.2 at a lower speed than a
    1.27 mm pitch with 80 % land (whose lands carry the web on its asperities)."""
    smooth, grooved = gs.loss_speed_map(Case(), 0.2, pitches=(1.27e-3,),
                                        land_fractions=(0.8,))
    assert smooth.converged and smooth.speed is not None
    assert grooved.converged
    assert grooved.speed is None or grooved.speed > 1.5 * smooth.speed


def test_cli_refuses_bad_values_before_creating_the_folder(calls, tmp_path, capsys):
    for bad, words in ((["--loss-lands", "0.9,1.5"],
                        "--loss-lands = '0.9,1.5': 1.5 is out of range"),
                       (["--speed", "0"], "roller speed = 0.0"),
                       (["--mu-min", "-1"], "mu_min = -1.0")):
        out = tmp_path / "new"
        args = ["grooves", "cases/base.toml", "--mu-min", "0.2", "--out", str(out)] + bad
        assert main(args) == 2
        assert words in capsys.readouterr().err and not out.exists()
    assert calls == []


def test_groove_chart_of_one_speed_keeps_its_labels_on_the_canvas(tmp_path, monkeypatch):
    """The new-user trial's one-speed map: the y axis names mu and what it is, and the
    legend, the axis labels and the tick labels lie inside the canvas (the legend was cut
    at both edges, the y label and the ticks' first digits off the left edge); a design
    without an answer does not collapse the layout."""
    from webfem.io import groove_charts

    designs = [gs.GrooveDesign(25.0, p, p * (1 - lf), 3e-4, lf, mu, 3e-6, 2 * mu, True,
                               mu >= 0.2) for p, lf, mu in
               [(1e-3, 0.6, 0.485), (1e-3, 0.85, 0.469), (3e-3, 0.6, 0.457),
                (3e-3, 0.85, 0.414)]]
    designs.append(gs.GrooveDesign(25.0, 3e-3, 1.5e-3, 3e-4, 0.5, None, None, None, False,
                                   False, "not converged"))
    seen = {}

    def measure(fig, renderer):
        ax = fig.axes[0]
        lo, hi = ax.get_ylim()
        shown = [t for t, y in zip(ax.get_yticklabels(), ax.get_yticks()) if lo <= y <= hi]
        parts = [fig.legends[0], ax.yaxis.label, ax.xaxis.label, *shown]
        seen.update(ylabel=ax.get_ylabel(), width=ax.get_position().width, canvas=fig.bbox,
                    boxes=[(p, p.get_window_extent(renderer)) for p in parts])

    inspect_before_save(monkeypatch, groove_charts, measure)
    groove_charts.groove_chart(designs, 0.2, tmp_path / "g.png",
                               gs.best_designs(designs))
    assert "mu" in seen["ylabel"] and "friction coefficient" in seen["ylabel"]
    canvas = seen["canvas"]
    for part, box in seen["boxes"]:
        assert canvas.x0 - 1 <= box.x0 and box.x1 <= canvas.x1 + 1, part
        assert canvas.y0 - 1 <= box.y0 and box.y1 <= canvas.y1 + 1, part
    assert seen["width"] > 0.5      # the panel is not squeezed away
