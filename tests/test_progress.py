"""Progress of long solves (issue 13 item 6): the solvers report each iteration, the driver
names its stages, the command line shows them with an estimate of the time left on a
terminal only, and nothing is reported (or printed) otherwise."""

import io
import math
import threading

import numpy as np
import pytest
import scipy.sparse as sp

import webfem
from webfem import progress
from webfem.cli import main
from webfem.cli.common import Ticker, progress_line
from webfem.fem.newton import newton
from webfem.fem.picard import picard
from webfem.progress import Step, iterations_left, report, reporting, stage


def test_report_reaches_the_reporter_with_the_stages():
    seen = []
    with reporting(seen.append):
        report("newton", 0, 1.0, 1e-9)
        with stage("outer"):
            with stage("inner"):
                report("newton", 1, 0.1, 1e-9)
            report("picard", 2, 0.01, 1e-9)
        with pytest.raises(RuntimeError), stage("failing"):
            raise RuntimeError
        report("newton", 3, 0.001, 1e-9)   # a stage left by an exception is left
    assert [s.stage for s in seen] == [(), ("outer", "inner"), ("outer",), ()]
    assert seen[1] == Step(("outer", "inner"), "newton", 1, 0.1, 1e-9)
    with stage("without a reporter"):       # records nothing, reports to no one
        report("newton", 1, 0.1, 1e-9)
    assert progress._STAGE.get() == () and progress._REPORTER.get() is None


def test_reporters_do_not_leak_into_other_threads():
    seen, other = [], []
    with reporting(seen.append):
        t = threading.Thread(target=lambda: other.append(progress._REPORTER.get()))
        t.start()
        t.join()
    assert other == [None]


def test_newton_and_picard_report_every_iteration():
    seen = []
    with reporting(seen.append):
        out = newton(lambda u: u ** 3 - 8.0, lambda u: sp.diags(3 * u ** 2), np.array([1.0]),
                     tol=1e-12)
    assert [s.iteration for s in seen] == list(range(out.iterations + 1))
    assert [s.residual for s in seen] == pytest.approx(out.history)
    assert {s.solver for s in seen} == {"newton"} and seen[0].tol == 1e-12
    seen.clear()
    with reporting(seen.append):
        out = picard(np.cos, np.array([1.0]), omega=1.0, tol=1e-10)
    assert [s.solver for s in seen] == ["picard"] * len(out.history)
    assert seen[-1].residual <= 1e-10


def test_the_fe_driver_names_its_stages():
    seen = []
    with reporting(seen.append):
        webfem.solve(webfem.Case(), model="fe1d")
    stages = list(dict.fromkeys(s.stage for s in seen))
    assert stages[0][0].startswith("fe1d newton, ") and stages[0][0].endswith(" unknowns")
    assert any(s[0].startswith("fe1d refinement round 1, ") for s in stages)
    assert all(s[0].startswith(("fe1d newton, ", "fe1d refinement round ",
                                "fe1d safe start", "fe1d error estimate")) for s in stages)
    assert any(s[0] == "fe1d error estimate on the coarser mesh" for s in stages)


def test_the_continuation_names_its_steps_inside_the_solve_it_serves():
    """The 1-D model's continuation (its safe start) reports each step inside its stage."""
    from webfem.fem.scaling import FoilParameters
    from webfem.models import fe1d
    from webfem.progress import stage

    case = webfem.Case()
    prm = FoilParameters.from_case(case)
    problem = fe1d.LINE.start(case, prm, fe1d.FE1DOptions(), None).problem
    seen = []
    with reporting(seen.append), stage("fe1d safe start"):
        problem.solve_continued(prm)
    stages = list(dict.fromkeys(s.stage for s in seen))
    assert ("fe1d safe start", "Eshel-Elrod continuation, s = 0") in stages
    assert all(len(s) == 1 or s[1].startswith("Eshel-Elrod continuation, s = ")
               for s in stages)


def test_fe2d_reports_its_1d_start_inside_its_own_stage():
    seen = []
    case = webfem.Case().updated({"web.width": 0.025, "wrap.angle_deg": 30.0,
                                  "roller.speed": 30.0})
    with reporting(seen.append):
        webfem.solve(case, model="fe2d")
    stages = list(dict.fromkeys(s.stage for s in seen))
    assert stages[0][:1] == ("fe2d start",) and stages[0][1].startswith("fe1d newton")
    assert any(s[0].startswith("fe2d newton, ") for s in stages)


@pytest.mark.parametrize("residuals,tol,order,n", [
    ([1e-1, 1e-2, 1e-4], 1e-9, None, 2),     # quadratic: 1e-8, 1e-16
    ([1e-1, 1e-2, 1e-3], 1e-9, None, 6),     # linear, a decade per iteration
    ([1e-1, 1e-2, 1e-3], 1e-9, 1.0, 6),
    ([1.0, 0.5], 1e-3, 1.0, 9),              # halving: 2^-10 < 1e-3
    ([1e-2, 1e-12], 1e-9, None, 0),          # converged
    ([1e-2, 1e-1], 1e-9, None, None),        # growing: no rate to extrapolate
    ([1e-2], 1e-9, None, None),              # one residual: no rate yet
    ([float("nan")], 1e-9, None, None),
])
def test_iterations_left_extrapolates_the_observed_rate(residuals, tol, order, n):
    assert iterations_left(residuals, tol, order) == n


def test_a_damped_newton_phase_is_not_extrapolated_as_quadratic():
    # a slow step after a fast one: the order is kept >= 1 (never a slowing-down "order")
    assert iterations_left([1.0, 1e-3, 5e-4], 1e-9) == math.ceil(
        math.log(1e-9 / 5e-4) / math.log(0.5))


def track(*points, solver="newton", stage=("fe1d newton, 543 unknowns",), tol=1e-9):
    it, r = points[-1][2], points[-1][1]
    return (Step(stage, solver, it, r, tol), tuple(points))


def test_progress_line_shows_stage_iteration_residual_and_time_left():
    line = progress_line("solving with fe1d", 3.0,
                         track((0.0, 1.0, 0), (2.0, 1e-1, 1), (4.0, 1e-3, 2)))
    # order 2 observed: 1e-7, then 1e-15: two more iterations of 2 s each
    assert line == ("  solving with fe1d: 3 s | fe1d newton, 543 unknowns | newton 2: residual "
                    "1.0e-03 -> 1e-09, about 4 s left (estimate)")
    assert progress_line("x", 3.0, track((0.0, 1e-2, 0), (1.0, 1e-10, 1))).endswith(
        "residual 1.0e-10 -> 1e-09, converged")
    assert "left" not in progress_line("x", 3.0, track((0.0, 1e-2, 0)))
    assert progress_line("x", 70.0, expected=100.0) == "  x: 1:10 elapsed, about 30 s left"


def test_progress_line_fits_the_terminal():
    deep = ("fe2d start", "fe1d newton, 2,227 unknowns", "Eshel-Elrod continuation, s = 0.25")
    t = track((0.0, 1.0, 0), (2.0, 1e-2, 1), stage=deep)
    full = progress_line("solving with fe2d", 3.0, t)
    assert " > ".join(deep) in full
    for width in (120, 100, 60, 20):
        line = progress_line("solving with fe2d", 3.0, t, width=width)
        assert len(line) <= width
    assert progress_line("solving with fe2d", 3.0, t, width=110).startswith(
        "  3 s | Eshel-Elrod continuation, s = 0.25 | newton 1")


def test_ticker_tracks_one_solve_and_hides_picards_inner_newton():
    ticker = Ticker("solving", quiet=True)
    ticker.record(Step(("a",), "newton", 0, 1.0, 1e-9))
    ticker.record(Step(("a",), "newton", 1, 0.1, 1e-9))
    assert len(ticker.track[1]) == 2
    ticker.record(Step(("a",), "newton", 0, 5.0, 1e-9))   # a new solve: a new track
    assert len(ticker.track[1]) == 1
    ticker.record(Step(("a",), "picard", 1, 1.0, 1e-9))
    ticker.record(Step(("a",), "newton", 3, 1e-3, 1e-11))  # a sub-solve of the Picard step
    assert ticker.track[0].solver == "picard"
    ticker.record(Step(("b",), "newton", 1, 1e-3, 1e-9))   # another stage
    assert ticker.track[0].stage == ("b",)


class FakeTerminal(io.StringIO):
    def isatty(self):
        return True


def test_ticker_on_a_terminal_draws_the_solvers_progress(monkeypatch):
    err = FakeTerminal()
    monkeypatch.setattr("sys.stderr", err)
    with Ticker("solving with fe1d", after=0.0) as ticker:
        assert progress._REPORTER.get() is not None
        webfem.solve(webfem.Case(), model="fe1d")
        seen = ticker.track
        ticker._stop.wait(0.7)   # one more drawing, after the solve's reports
    assert progress._REPORTER.get() is None
    assert seen is not None and seen[0].stage[0].startswith("fe1d")
    text = err.getvalue()
    assert "\r" in text and "residual" in text and "fe1d" in text


@pytest.mark.parametrize("quiet,tty", [(True, True), (False, False)])
def test_no_reporter_and_nothing_drawn_when_quiet_or_not_a_terminal(monkeypatch, quiet, tty):
    err = FakeTerminal() if tty else io.StringIO()
    monkeypatch.setattr("sys.stderr", err)
    with Ticker("solving", quiet=quiet, after=0.0):
        assert progress._REPORTER.get() is None
        webfem.solve(webfem.Case(), model="fe1d")
    assert err.getvalue() == ""


def test_solve_prints_no_progress_when_not_a_terminal(capsys):
    assert main(["solve", "base", "--model", "fe1d"]) == 0
    assert "\r" not in capsys.readouterr().err
    assert main(["report", "base", "--model", "closed-form", "--quiet", "--out",
                 str(__import__("tempfile").mkdtemp())]) == 0
    assert "\r" not in capsys.readouterr().err
