"""Messages that point a user to what was meant (a new-user trial, user38): a Case built
with plain tables, a groove pitch given without its unit, a study asked of a grooved case."""

import pytest

import webfem
from webfem.cli import main


def test_a_case_of_plain_tables_points_to_from_dict():
    with pytest.raises(webfem.InputError) as err:
        webfem.Case(roller={"radius": 0.05})
    text = str(err.value)
    assert "not a dict" in text and "Case.from_dict({'roller': {...}})" in text


def test_a_bare_pitch_that_fits_in_millimetres_is_asked_about(capsys):
    assert main(["grooves", "base", "--mu-min", "0.2", "--pitches", "1.27"]) == 2
    assert "(a bare number is metres: '1.27 mm'?)" in capsys.readouterr().err
    # a number too large even in millimetres gets no such guess
    assert main(["grooves", "base", "--mu-min", "0.2", "--pitches", "500"]) == 2
    assert "a bare number is metres" not in capsys.readouterr().err


def test_a_study_of_a_grooved_case_says_studies_are_of_smooth_rollers(tmp_path, capsys):
    out = tmp_path / "study"
    assert main(["study", "convergence", "base_grooved", "--quick", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "studies smooth rollers" in err and "roller.groove_width=0" in err
    assert not out.exists()


@pytest.mark.parametrize("model", ["closed-form", "fitted", "fe1d"])
def test_a_pitch_without_a_width_is_solved_smooth_and_says_so(model):
    """roller.groove_pitch alone gave a smooth roller's answer with no word of the grooves."""
    r = webfem.solve(webfem.Case().updated({"roller.groove_pitch": 1.27e-3}), model=model)
    said = [w for w in r["warnings"] if "solved smooth" in w]
    assert said and "roller.groove_pitch = 0.00127 m set, but roller.groove_width = 0" in said[0]
    assert not any("solved smooth" in w for w in webfem.solve("base", model=model)["warnings"])
