"""Ctrl-C always says how many points a sweep or a groove map saved (README, exit 130),
however it lands: a second SIGINT during the clean-up (``timeout -s INT`` signals the
command and then its process group; a user presses twice), or after the run while the
chart is drawn. A re-run of a groove map says it resumes."""

import os
import signal

import pytest

import webfem.groove_sizing as gs
from webfem import Case
from webfem.cli import main
from webfem.sweeps import SweepInterrupted, run
from webfem.sweeps.store import Store
from webfem.sweepspec import Sweep

SPEEDS = (20.0, 25.0, 30.0, 35.0)


def spec():
    return Sweep("roller.speed", SPEEDS, (("base", Case()),))


def stop_at(k):
    def progress(done, total):
        if done == k:
            raise KeyboardInterrupt
    return progress


@pytest.fixture
def second_sigint(monkeypatch):
    """The store's clean-up receives another SIGINT, as from timeout's second signal."""
    close = Store.close

    def close_and_signal(self):
        if self._fd is not None:
            os.kill(os.getpid(), signal.SIGINT)
        close(self)
    monkeypatch.setattr(Store, "close", close_and_signal)


def raised(call):
    """The exception ``call`` raised, KeyboardInterrupt included (pytest.raises would let a
    plain KeyboardInterrupt end the session)."""
    try:
        call()
    except BaseException as err:   # noqa: BLE001
        return err
    raise AssertionError("nothing raised")


def test_second_ctrl_c_in_the_clean_up_keeps_the_sweeps_count(tmp_path, second_sigint):
    out = tmp_path / "s.csv"
    err = raised(lambda: run(spec(), "closed-form", out, progress=stop_at(2)))
    assert isinstance(err, SweepInterrupted), repr(err)
    assert (err.saved, err.total) == (2, 4)
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler   # restored
    assert not (tmp_path / ".s.csv.lock").exists()


def test_second_ctrl_c_in_the_clean_up_keeps_the_maps_count(tmp_path, second_sigint,
                                                              monkeypatch):
    monkeypatch.setattr(gs, "solve", lambda case, model, options: {
        "mu": 0.3, "h_center": 1e-6, "contact_share": 0.5})
    err = raised(lambda: gs.groove_map(Case(), 0.2, speeds=(20.0,), pitches=(5e-3,),
                                       land_fractions=(0.5, 0.7, 0.9),
                                       store=tmp_path / "g.csv", progress=stop_at(1)))
    assert isinstance(err, SweepInterrupted), repr(err)
    assert str(err) == (f"interrupted: 1 of 3 designs saved in {tmp_path / 'g.csv'}; "
                        "run the same command to continue")


def test_ctrl_c_on_top_of_the_count_still_says_it(capsys, monkeypatch, tmp_path):
    """A KeyboardInterrupt raised while the SweepInterrupted unwinds carries it as its
    context: the command's line still counts."""
    def stop(spec, model, csv_path, **kwargs):
        try:
            raise SweepInterrupted(3, 60, csv_path)
        finally:
            raise KeyboardInterrupt
    monkeypatch.setattr("webfem.sweeps.run", stop)
    assert main(["sweep", "cases/base.toml", "--model", "closed-form", "--out",
                 str(tmp_path), "--quiet"]) == 130
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        f"webfem: interrupted: 3 of 60 points saved in {tmp_path / 'base_closed-form.csv'};"
        " run the same command to continue")


def test_ctrl_c_while_the_chart_is_drawn_says_every_point_is_saved(capsys, monkeypatch,
                                                                   tmp_path):
    def stop(*args, **kwargs):
        raise KeyboardInterrupt
    monkeypatch.setattr("webfem.io.charts.sweep_chart", stop)
    assert main(["sweep", "cases/base.toml", "--model", "closed-form", "--num", "4",
                 "--out", str(tmp_path), "--quiet"]) == 130
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        f"webfem: interrupted: 4 of 4 points saved in {tmp_path / 'base_closed-form.csv'};"
        " run the same command to continue")


GROOVES = ["grooves", "cases/base.toml", "--mu-min", "0.2", "--speed", "20",
           "--pitches", "0.005", "--lands", "0.5,0.7,0.9", "--workers", "1", "--quiet"]


def test_groove_map_interrupted_then_resumed_says_so(capsys, monkeypatch, tmp_path):
    made = []

    def solve(case, model, options):
        made.append(case.land_fraction)
        if len(made) == 3:
            raise KeyboardInterrupt
        return {"mu": 0.3, "h_center": 1e-6, "contact_share": 0.5}
    monkeypatch.setattr(gs, "solve", solve)
    args = GROOVES + ["--out", str(tmp_path)]
    assert main(args) == 130
    csv = tmp_path / "base_grooves.csv"
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        f"webfem: interrupted: 2 of 3 designs saved in {csv}; run the same command to "
        "continue")
    assert main(args) == 0
    err = capsys.readouterr().err
    assert f"webfem: {csv}: resuming: 2 of 3 designs already there, solving the other 1" \
        in err
    assert len(made) == 4


def _designs_answer_at_once(monkeypatch):
    """Every groove design answers at once (a fake solve): the tests interrupt what follows."""
    monkeypatch.setattr(gs, "solve", lambda case, model, options: {
        "mu": 0.3, "h_center": 1e-6, "contact_share": 0.5})


def _ctrl_c(*args, **kwargs):
    raise KeyboardInterrupt


def test_groove_loss_speeds_interrupted_say_the_geometries_saved(capsys, monkeypatch,
                                                                  tmp_path):
    _designs_answer_at_once(monkeypatch)
    monkeypatch.setattr(gs, "traction_loss_speed", _ctrl_c)
    assert main(GROOVES + ["--loss-speed", "--loss-pitches", "0.005", "--loss-lands", "0.5",
                           "--out", str(tmp_path)]) == 130
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        f"webfem: interrupted: 0 of 2 geometries saved in "
        f"{tmp_path / 'base_grooves_loss.csv'}; run the same command to continue")


def test_ctrl_c_while_the_map_is_drawn_says_every_design_is_saved(capsys, monkeypatch,
                                                                  tmp_path):
    _designs_answer_at_once(monkeypatch)
    monkeypatch.setattr("webfem.io.groove_charts.groove_chart", _ctrl_c)
    assert main(GROOVES + ["--out", str(tmp_path)]) == 130
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        f"webfem: interrupted: 3 of 3 designs saved in {tmp_path / 'base_grooves.csv'}; "
        "run the same command to continue")
