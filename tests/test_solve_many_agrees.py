"""webfem.solve_many takes what webfem.solve takes (a Case, a case file, a bundled case's
name) with every model, and a point a model cannot answer comes back as the README says:
``converged = False``, its numbers NaN (null in JSON) and the reason first in ``warnings``
-- the closed form too, which used to keep its numbers (h_center 0.95 mm, mu 0.0) and put
the reason last."""

import math
from pathlib import Path

import pytest

pytestmark = pytest.mark.filterwarnings("ignore::webfem.ValidityWarning")

import webfem
from webfem.cli import main
from webfem.errors import InputError

ROOT = Path(__file__).resolve().parents[1]
MODELS = ("closed-form", "fitted", "fe1d", "fe2d", "auto")
#: 12 um PET at 600 m/min over a 100 mm roller, 90 deg, impermeable, at T = 2 N/m: the film
#: would be R eps^(2/3) = 1.75 mm thick, beyond the thin-film model (no model answers)
NO_ANSWER = {"web.thickness": 12e-6, "roller.speed": 10.0, "web.speed": 10.0,
             "web.tension": 2.0}


@pytest.mark.parametrize("model", ("closed-form", "fitted", "fe1d"))
def test_names_and_paths_as_solve_takes_them(model):
    by_name, by_path, by_case = webfem.solve_many(
        ["base", ROOT / "cases" / "base.toml", webfem.load_case("base")], model=model)
    one = webfem.solve("base", model)["mu"]
    # fe1d walks them with continuation: the same answer to its solver's 1e-9
    assert [by_name["mu"], by_path["mu"], by_case["mu"]] == pytest.approx([one] * 3, rel=1e-9)


@pytest.mark.parametrize("model", MODELS)
def test_a_bad_name_is_solves_input_error(model):
    with pytest.raises(InputError) as many:
        webfem.solve_many(["bse"], model=model)
    with pytest.raises(InputError) as one:
        webfem.solve("bse", model=model)
    assert str(many.value) == str(one.value) and "did you mean 'base'?" in str(one.value)


@pytest.mark.parametrize("model", MODELS)
def test_no_answer_is_nan_with_the_reason_first(model):
    case = webfem.load_case("pet_idler", NO_ANSWER)
    r = webfem.solve_many([webfem.Case(), case], model=model)[1]
    assert r["converged"] is False and r["regime"] == "none"
    for key in ("h_center", "h_inlet", "h_outlet", "h_min", "mu", "delta_T", "h_c"):
        assert math.isnan(r[key]), (key, r[key])
    assert r.to_dict()["mu"] is None and r.to_dict()["h_center"] is None
    assert r["solver_message"] and r["solver_message"] in r["warnings"][0]
    assert r["lambda"] == pytest.approx(case.lam)      # where the point is, kept


def test_closed_form_single_solve_flags_it_the_same_way():
    from webfem.models import closed
    from webfem.models.options import ClosedFormOptions
    case = webfem.load_case("pet_idler", NO_ANSWER)
    r = closed.solve_case(case, ClosedFormOptions(), raise_on_failure=False)
    assert not r["converged"] and math.isnan(r["h_center"]) and len(r.fields.x) == 0
    assert r["warnings"][0] == "no closed-form answer: " + r["solver_message"]
    many = closed.solve_many([case])[0].to_dict()
    one = r.to_dict()
    assert {k: v for k, v in one.items() if k != "solve_time_s"} == \
        {k: v for k, v in many.items() if k != "solve_time_s"}


@pytest.mark.parametrize("model", ("closed-form", "fitted"))
def test_solve_json_of_the_point_is_no_answer(tmp_path, capsys, model):
    """`webfem solve --json` on the point: exit 2, the reason on stderr and nothing on
    stdout a script could take for an answer (as test_closed_no_answer states it)."""
    sets = [f"--set={k}={v}" for k, v in NO_ANSWER.items()]
    assert main(["solve", "pet_idler", "--model", model, "--json", *sets]) == 2
    out, err = capsys.readouterr()
    assert out == "" and ("R/100" in err or "outside the fitted model's domain" in err)
