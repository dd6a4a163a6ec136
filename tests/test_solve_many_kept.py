"""webfem.solve_many keeps every point, whatever the model: a point the model refuses comes
back in its place with converged False and the reason in solver_message and warnings; the
other points keep their answers (README: points outside the domain are kept, named)."""

import math
import warnings

import pytest

import webfem
from webfem import Case

BASE = Case()
#: the base web far softer across its thickness at 300 N/m: contact alone would compress it
#: through its thickness; outside the fit's domain and without an FE or closed-form answer
CRUSHED = BASE.updated({"web.modulus_thickness": 1e3, "web.tension": 300.0})


@pytest.mark.parametrize("model", ["closed-form", "fitted", "fe1d"])
def test_one_refused_point_loses_no_other_answer(model):
    cases = [BASE, CRUSHED, BASE.updated({"roller.speed": 30.0})]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        many = webfem.solve_many(cases, model=model)
        alone = [webfem.solve(c, model=model) for c in (cases[0], cases[2])]
    assert len(many) == 3
    assert [r["converged"] for r in many] == [True, False, True]
    why = many[1]["solver_message"]
    assert why and any(why in w for w in many[1]["warnings"])
    for r, one in zip((many[0], many[2]), alone):
        assert math.isclose(r["mu"], one["mu"], rel_tol=1e-9)
    with pytest.raises(webfem.errors.NoAdmissibleSolution):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            webfem.solve(CRUSHED, model=model)


@pytest.mark.parametrize("model", ["closed-form", "fe1d"])
def test_a_grooved_point_is_refused_in_place_by_the_smooth_roller_models(model):
    """A grooved roller is a valid point the closed form and fe1d cannot solve: solve_many
    kept none of a batch holding one (an InputError for all); now it is refused in place."""
    grooved = webfem.load_case("base_grooved")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        many = webfem.solve_many([BASE, grooved], model=model)
        alone = webfem.solve(BASE, model=model)
    assert [r["converged"] for r in many] == [True, False]
    assert "cannot solve a grooved roller" in many[1]["solver_message"]
    assert math.isnan(many[1]["mu"])
    assert many[0]["mu"] == pytest.approx(alone["mu"], rel=1e-9)
    with pytest.raises(webfem.InputError, match="cannot solve a grooved roller"):
        webfem.solve(grooved, model=model)
