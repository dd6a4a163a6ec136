"""model="auto": picks the cheapest model within tolerance, and its estimate is honoured."""

import pytest

import webfem
from webfem import Case

# the cases include landed webs and Eq. 21's range edges: the warnings are expected here
pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")

CASES = [Case().updated({"roller.speed": 5.0}),
         Case().updated({"roller.speed": 20.0, "wrap.angle_deg": 20.0}),
         Case().updated({"roller.speed": 40.0, "web.width": 0.3}),
         Case().updated({"roller.speed": 30.0, "web.width": 0.1}),
         Case().updated({"roller.speed": 40.0, "web.width": 0.020}),
         Case().updated({"roller.speed": 5.0, "web.tension": 40.0})]


@pytest.fixture(scope="module")
def references():
    return [webfem.solve(c, model="fe2d", level=1) for c in CASES]


@pytest.mark.parametrize("tol", [0.01, 0.1, 0.3])
def test_estimated_error_is_honoured(tol, references):
    used = set()
    for case, ref in zip(CASES, references):
        r = webfem.solve(case, model="auto", tol=tol)
        assert r["model"] == "auto" and r["estimated_error"] <= tol
        assert abs(r["mu"] / ref["mu"] - 1.0) <= tol, (r["why"], r["mu"], ref["mu"])
        used.add(r["model_used"])
    if tol == 0.01:
        assert used == {"fe2d"}


def test_choices_differ_where_they_should():
    wide_fast = webfem.solve(CASES[2], model="auto", tol=0.3)
    narrow = webfem.solve(CASES[4], model="auto", tol=0.3)
    landed = webfem.solve(CASES[0], model="auto", tol=0.1)
    assert wide_fast["model_used"] == "closed-form"        # inside Eq. 21's range, loose tol
    assert narrow["model_used"] == "fe2d"                   # lambda = 4.8: edge leakage
    assert "outside Eq. 21" in narrow["why"]
    assert landed["model_used"] == "fe1d"                   # web on its asperities
    assert "lands the web" in landed["why"]


def test_auto_through_the_cli(capsys):
    import json
    from webfem.cli import main
    assert main(["solve", "cases/base.toml", "--model", "auto", "--json", "--opt",
                 "tol=0.3", "--set", "web.width=0.3", "--set", "roller.speed=40"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["model"] == "auto" and data["model_used"] == "closed-form"


def test_bad_auto_options():
    with pytest.raises(webfem.CaseError, match="quantity"):
        webfem.solve(Case(), model="auto", quantity="torque")
    with pytest.raises(webfem.CaseError, match="tol"):
        webfem.solve(Case(), model="auto", tol=2.0)
