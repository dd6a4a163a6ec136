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


def test_a_sag_past_the_groove_floor_says_the_groove_is_closed():
    """A 10 mm groove under the base web sags 270 um held flat, past its 250 um floor: the
    warning said only 'sags' (user38)."""
    from webfem.models.groove_domain import sag_warning
    case = webfem.load_case("base_grooved").updated(
        {"roller.groove_pitch": 0.04, "roller.groove_width": 0.01})
    text = sag_warning(case, 1.7e-6)
    assert "held flat on the lands the web would reach the groove's floor" in text
    # 2.5 mm grooves sag 1.1 um (5.3 um if free to turn): far above a 250 um floor
    wide = webfem.load_case("base_grooved").updated(
        {"roller.groove_pitch": 5e-3, "roller.groove_width": 2.5e-3})
    assert "floor" not in sag_warning(wide, -0.03e-6)
    deep_enough = case.updated({"roller.groove_depth": 1e-3})
    assert "if free to turn on the lands the web would reach" in sag_warning(deep_enough, 1.7e-6)


def test_the_groove_floor_is_judged_with_the_land_gap():
    """A 1 um deep groove under a web flying 0.78 um above the lands is 1.78 um down: a
    1.35 um sag (free to turn) does not reach it (review38b)."""
    from webfem.models.groove_domain import sag_warning
    case = webfem.load_case("pet_idler_grooved").updated(
        {"roller.groove_width": 1e-3, "roller.groove_depth": 1e-6})
    assert "floor" not in sag_warning(case, 0.78e-6)
    assert "would reach the groove's floor" in sag_warning(case, 0.0)
