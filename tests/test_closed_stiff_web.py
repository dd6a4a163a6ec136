"""The closed form's stated errors on a stiff web bound its true error against fe2d
(webfem.models.model_error: bending_drop, bending_dip, bending_edge_share).

Eq. 21 is a membrane result. The bundled board on a 50 mm roller, 0.3 m wide (Dn 99),
rests compressed at its exit dip 10.9 um below h_c, and its wrap ends carry the line loads
sqrt(D T)/R on its asperities: fe2d's mu 0.187 against the closed form's 0.082 (true error
1.29), h_min -17.8 um against -4.9 um (2.66), the contact share 0.535 against 0.234. The
closed form stated 0.41, 0.61 and 0.096, and left bending out of its error basis.
"""

import pytest

import webfem
from webfem.bundled import as_case
from webfem.models import model_error
from webfem.models.readout import READ_QUANTITIES, error_scale

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")

BOARD = as_case("board")


def board(radius, width, speed):
    return BOARD.updated({"roller.radius": radius, "web.width": width,
                          "roller.speed": speed, "web.speed": speed})


#: the headline point, a resting one, a flying one, and a mildly stiff flying one
CASES = {"R 0.05 m, 0.3 m, 15 m/s": board(0.05, 0.3, 15.0),
         "R 0.03 m, 0.3 m, 5 m/s": board(0.03, 0.3, 5.0),
         "R 0.03 m, 0.3 m, 30 m/s": board(0.03, 0.3, 30.0),
         "R 0.1 m, 1.0 m, 15 m/s": board(0.1, 1.0, 15.0)}


@pytest.fixture(scope="module")
def solved():
    return {name: (webfem.solve(case, model="closed-form"), webfem.solve(case, model="fe2d"))
            for name, case in CASES.items()}


def true_error(r, reference, q):
    return abs(r[q] - reference[q]) / error_scale(r.case, q, r[q])


@pytest.mark.parametrize("name", list(CASES))
def test_closed_form_stated_errors_bound_the_truth_on_the_board(name, solved):
    """Within the README's factor 2, the reference's own stated error allowed for (the old
    basis fell 3.2-4.4x short at the headline point, 2.3-3.8x at rest)."""
    r, reference = solved[name]
    assert r["converged"] and reference["converged"]
    for q in READ_QUANTITIES:
        assert true_error(r, reference, q) <= 2.0 * r[f"error_{q}"] + reference[f"error_{q}"], \
            (name, q, r[q], reference[q], r[f"error_{q}"])


def test_the_headline_point_is_bounded_without_the_factor_2(solved):
    """mu's true error 1.29 and h_min's 2.66 at the board on a 50 mm roller: the stated
    errors now reach them (2.1 and 3.35 with the bending terms; 3.28 and 4.61 since the
    web may rest where Eq. 21's gap holds no air, tests/test_closed_board_contact.py)."""
    r, reference = solved["R 0.05 m, 0.3 m, 15 m/s"]
    for q in ("h_min", "mu", "contact_share"):
        assert true_error(r, reference, q) <= r[f"error_{q}"], (q, r[f"error_{q}"])


def test_the_beam_dip_is_the_measured_one_at_rest(solved):
    """The rested board's exit dip below h_c against a tensioned beam on its asperities under
    the line load sqrt(D T)/R: fe2d's within 0.8-1.3x of it."""
    r, reference = solved["R 0.03 m, 0.3 m, 5 m/s"]
    dip = model_error.bending_dip(r.case, r["h_c"])
    assert 0.8 <= (r["h_c"] - reference["h_min"]) / dip <= 1.3


def test_a_membrane_has_no_bending_terms():
    """A membrane (D = 0, as under the paper's physics) keeps Eq. 21's error basis as it
    was."""
    case = board(0.05, 0.3, 15.0).updated({"web.bending_stiffness": 0.0})
    r = webfem.solve(case, model="closed-form")
    assert model_error.bending_drop(case) == 0.0
    assert model_error.bending_dip(case, r["h_c"]) == 0.0
    assert model_error.bending_edge_share(case, r.summary) == 0.0
