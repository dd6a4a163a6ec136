"""A web thick against its roller, or pressed deep into itself, is outside the thin-web
model (issue: gauss37): 70 um newsprint over a 1 mm roller was answered, "pressed 60 um"
into a 70 um web, with no warning. The answer now says which assumption fails."""

import pytest

from webfem.cli import main
from webfem.physics.validity import COMPRESSION_RATIO, THICK_WEB_RATIO, thick_web_warning

from conftest import BASE


def test_a_one_millimetre_roller_is_warned(capsys):
    assert main(["solve", "base", "--model", "closed-form", "--set",
                 "roller.radius=0.001"]) == 0
    out = capsys.readouterr().out
    line = next(x for x in out.splitlines() if "outside the model's assumptions" in x)
    assert "web.thickness / (2 roller.radius) = 0.035" in line
    assert "compressed by 3.2e-05 m, 46 % of its thickness" in line


def test_the_base_case_is_not_warned(capsys):
    assert main(["solve", "base", "--model", "closed-form"]) == 0
    assert "outside the model's assumptions" not in capsys.readouterr().out


@pytest.mark.parametrize("radius, h_min, warned", [
    (1.01 * 70e-6 / (2 * THICK_WEB_RATIO), 1e-6, False),     # t/(2R) just below 1 %
    (0.99 * 70e-6 / (2 * THICK_WEB_RATIO), 1e-6, True),
    (0.055, -0.99 * COMPRESSION_RATIO * 70e-6, False),
    (0.055, -1.01 * COMPRESSION_RATIO * 70e-6, True),
])
def test_the_edges(radius, h_min, warned):
    case = BASE.updated({"roller.radius": radius})
    assert (thick_web_warning(case, h_min) is not None) is warned
