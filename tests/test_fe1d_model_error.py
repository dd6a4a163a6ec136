"""fe1d's stated error (mesh + the edge leakage it leaves out) bounds its true error against
fe2d within the README's factor 2, on stiff resting webs too (webfem.models.model_error).

The board (0.5 mm board on a 200 mm idler, Dn = 24.7) rests compressed at its exit dip,
where the film still carries 81 % of the load: fe1d used to lower only the local gap by
1.87/lambda there and stated an h_min error of 0.008 (1.0 m wide) and 0.026 (0.3 m) where
fe2d puts the minimum 0.077 and 0.27 away, and auto answered with fe1d at tol = 0.05.

The base web at rest at 0.5 m/s: the film's suction around its exit dip (-160 Pa), which the
2-D film's edges relieve, put fe2d's minimum 1.2e-3 above fe1d's where fe1d stated 4.6e-4.
"""

import pytest

import webfem
from webfem import Case
from webfem.bundled import as_case
from webfem.models import model_error
from webfem.models.readout import READ_QUANTITIES, error_scale

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")

BOARD = as_case("board")

#: stiff resting webs (the board at its bundled 1.0 m and at 0.3 m; a stiffer web on the
#: base rig), a stiff flying one (the board at 300 N/m) and a flexible one (the PET idler)
CASES = {"board": BOARD,
         "board 0.3 m": BOARD.updated({"web.width": 0.3}),
         "board 300 N/m": BOARD.updated({"web.tension": 300.0, "web.width": 0.3}),
         "thick base web": Case().updated({"web.thickness": 300e-6, "roller.speed": 10.0}),
         "pet idler 0.2 m": as_case("pet_idler").updated({"web.width": 0.2}),
         # the base web resting on its asperities at low speeds (Dn 4.3-11: stiff), whose
         # exit dip the film's suction deepens and the 2-D film's edges relieve
         # (model_error.relieved_dip): h_min was 2.6-7x short at 0.3-0.5 m/s
         "base 0.3 m/s": Case().updated({"roller.speed": 0.3}),
         "base 0.5 m/s": Case().updated({"roller.speed": 0.5}),
         "base 0.5 m/s 130 N/m": Case().updated({"roller.speed": 0.5, "web.tension": 130.0}),
         "base 1 m/s": Case().updated({"roller.speed": 1.0}),
         "base 2 m/s": Case().updated({"roller.speed": 2.0})}


@pytest.fixture(scope="module")
def solved():
    return {name: (webfem.solve(case, model="fe1d"), webfem.solve(case, model="fe2d"))
            for name, case in CASES.items()}


def true_error(r, reference, q):
    return abs(r[q] - reference[q]) / error_scale(r.case, q, r[q])


@pytest.mark.parametrize("name", list(CASES))
def test_fe1d_stated_errors_bound_the_truth(name, solved):
    r, reference = solved[name]
    for q in READ_QUANTITIES:
        # the README's promise, the reference's own (stated) mesh error allowed for
        assert true_error(r, reference, q) <= 2.0 * r[f"error_{q}"] + reference[f"error_{q}"], \
            (name, q, r[q], reference[q], r[f"error_{q}"])


@pytest.mark.parametrize("name", ["board", "board 0.3 m"])
def test_fe1d_stated_errors_are_not_far_above_the_truth_on_the_board(name, solved):
    """The bound is a bound, not a blanket: where the truth is sizable (above 0.01) the
    stated error on the board stays within 3x of it."""
    r, reference = solved[name]
    for q in READ_QUANTITIES:
        true = true_error(r, reference, q)
        if true > 0.01:
            assert r[f"error_{q}"] <= 3.0 * true, (name, q, true, r[f"error_{q}"])


def test_the_board_is_treated_as_stiff_and_the_idler_as_flexible(solved):
    assert model_error.stiff(BOARD) and not model_error.stiff(CASES["pet idler 0.2 m"])
    assert "stiff web" in solved["board"][0]["error_basis"]
    assert "stiff web" not in solved["pet idler 0.2 m"][0]["error_basis"]


def test_auto_no_longer_answers_the_narrow_board_with_fe1d():
    """At tol = 0.05 auto took fe1d (stated 0.038; true 0.27 in h_min, 0.13 in mu)."""
    r = webfem.solve(CASES["board 0.3 m"], model="auto", tol=0.05)
    assert r["model_used"] == "fe2d"
    assert "fe1d: estimated h_min error" in r["why"]
