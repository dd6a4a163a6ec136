"""webfem idler shows progress over its speeds (an fe2d curve takes a while) and takes
--quiet as the other long commands do (user38: 'unrecognized arguments: --quiet')."""

from webfem import load_case
from webfem.cli import main
from webfem.idler import margin_curve


def test_the_margin_curve_reports_each_speed_solved():
    calls = []
    margin_curve(load_case("idler"), [2.0, 4.0, 6.0], "fe1d",
                 progress=lambda done, total: calls.append((done, total)))
    assert calls == [(1, 3), (2, 3), (3, 3)]


def test_idler_shows_progress_on_a_terminal_unless_quiet(capsys, monkeypatch):
    import sys
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)
    args = ["idler", "idler", "--model", "fe1d", "--num", "2", "--max-speed", "4"]
    assert main(args) == 0
    assert "2/2 speeds" in capsys.readouterr().err
    assert main(args + ["--quiet"]) == 0
    out = capsys.readouterr()
    assert "verdict" in out.out and "speeds," not in out.err
