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


def test_idler_takes_quiet(capsys):
    assert main(["idler", "idler", "--model", "closed-form", "--num", "3", "--quiet"]) == 0
    assert "verdict" in capsys.readouterr().out
