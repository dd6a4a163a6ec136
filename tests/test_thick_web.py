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


@pytest.mark.parametrize("factor, refused", [(0.99, False), (1.01, True)])
def test_a_web_too_thick_to_bend_round_its_roller_is_refused(factor, refused):
    """A 5 mm web on a 2 mm roller was answered "fe1d, stated error 0.0018", its own warning
    saying the wrap pressure was 125 % off; beyond t/(2R) = THICK_WEB_LIMIT no answer is
    given, for any model."""
    from webfem import InputError
    from webfem.physics.validity import THICK_WEB_LIMIT
    values = {"roller.radius": 0.01, "web.thickness": factor * 2 * THICK_WEB_LIMIT * 0.01}
    if not refused:
        assert BASE.updated(values).web.thickness == values["web.thickness"]
        return
    with pytest.raises(InputError) as err:
        BASE.updated(values)
    text = str(err.value)
    assert "web.thickness = 0.00202 m on roller.radius = 0.01 m" in text
    assert f"valid: t/(2R) <= {THICK_WEB_LIMIT:g}" in text and "web.thickness <= 0.002 m" in text
