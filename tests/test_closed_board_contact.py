"""The closed form's stated errors on the board where Eq. 21's film runs out of air before
the wrap's centre, and where a flying board touches only at its exit minimum
(webfem.models.model_error, closed_form_errors: AIR_GONE and EXIT_CONTACT).

* R 0.03 m, 15 m/s (Dn 274): Eq. 21 puts the centre at -1.7 um, above h_c = -11.8 um, the
  film lifting part of the load; its air runs out at 0 (permeation drains it, and the stiff
  web's inlet line load thins the film), and fe2d rests the centre at h_c (-12.0 um). True
  error 3.4 against a stated 0.77 (4.4x) before; the web resting at h_c where Eq. 21's gap
  is at or below 0 (model_error.rested) is now a candidate. On a 40 mm roller at 20 m/s
  the exit rests and dips the same way: h_min 6.25 against a stated 2.99 before.
* R 0.2 m, 30 m/s (flying): Eq. 21's linear gap has no exit constriction, where fe2d's
  contact gathers (its local share 3.4e-5 over about 1.4 entry lengths): the contact share
  1.5e-7 against fe2d's 6.4e-7, true error 4.9e-7 against a stated 3.2e-7 (mu 1.5x short);
  the foil roller at 4.1 m/s, 84 N/m likewise (true 5.5e-7, stated 2.3e-7). The exit
  zone's EDGE_LENGTHS entry lengths at the contact's local share at the lowest minimum the
  h_min error allows are now counted.

The bound is the plain one: the true error (less fe2d's own stated error) within the stated.
"""

import pytest

import webfem
from webfem.bundled import as_case
from webfem.models.readout import READ_QUANTITIES, error_scale

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")


def board(radius, width, speed):
    return as_case("board").updated({"roller.radius": radius, "web.width": width,
                                     "roller.speed": speed, "web.speed": speed})


CASES = {"R 0.03 m, 0.3 m, 15 m/s": board(0.03, 0.3, 15.0),
         "R 0.05 m, 0.1 m, 15 m/s": board(0.05, 0.1, 15.0),
         "R 0.04 m, 0.2 m, 20 m/s": board(0.04, 0.2, 20.0),
         "R 0.2 m, 0.3 m, 30 m/s": board(0.2, 0.3, 30.0),
         # the bundled foil at half its speed and 1.4x its tension: its contact gathers at
         # the exit minimum too (share 6.7e-7 against the closed form's 1.2e-7)
         "foil roller, 4.1 m/s, 84 N/m": as_case("foil_roller").updated(
             {"roller.speed": 4.1, "web.speed": 4.0, "web.tension": 84.0})}


@pytest.fixture(scope="module")
def solved():
    return {name: (webfem.solve(case, model="closed-form"), webfem.solve(case, model="fe2d"))
            for name, case in CASES.items()}


def true_error(r, reference, q):
    """The closed form's error against fe2d, less fe2d's own stated error."""
    return max(abs(r[q] - reference[q]) / error_scale(r.case, q, r[q])
               - reference[f"error_{q}"], 0.0)


@pytest.mark.parametrize("name", list(CASES))
def test_stated_errors_bound_the_truth(name, solved):
    """Every quantity, no factor: before, h_center 3.4 against 0.77 at R 0.03 m and 0.97
    against 0.88 at R 0.05 m; h_min 6.25 against 2.99 at R 0.04 m; mu and the contact share
    1.5x short at R 0.2 m, 30 m/s, the contact share 2.4x on the foil roller."""
    r, reference = solved[name]
    assert r["converged"] and reference["converged"]
    for q in READ_QUANTITIES:
        assert true_error(r, reference, q) <= r[f"error_{q}"], \
            (name, q, r[q], reference[q], r[f"error_{q}"])


def test_the_centre_rests_where_the_air_is_gone(solved):
    """What the new candidate is for: fe2d's centre lies at h_c, far below Eq. 21's, and
    the stated error reaches it (with its factor 2: twice the distance over the scale)."""
    r, reference = solved["R 0.03 m, 0.3 m, 15 m/s"]
    assert r["h_c"] < r["h_center"] <= 0.0
    assert abs(reference["h_center"] - r["h_c"]) < 0.1 * r.case.sigma
    assert r["error_h_center"] >= 2.0 * abs(r["h_c"] - r["h_center"]) / r.case.sigma - 1e-9


def test_flying_contact_sits_at_the_exit_minimum(solved):
    """The flying board's contact share is the exit minimum's: fe2d's several times the
    linear gap's, and the stated error not more than 10x the true one there (6.9x)."""
    r, reference = solved["R 0.2 m, 0.3 m, 30 m/s"]
    assert reference["contact_share"] > 3.0 * r["contact_share"]
    assert r["error_contact_share"] <= 10.0 * true_error(r, reference, "contact_share")


@pytest.mark.slow
@pytest.mark.parametrize("radius", [0.03, 0.05, 0.1, 0.2])
def test_the_board_family_is_bounded(radius):
    """benchmarks/model_error_families.py's ``board`` family, a radius at a time (36 fe2d
    solves in all, about 3 min of CPU): no stated error below the true one (before: 5
    points short in h_center, 3 in mu and the contact share)."""
    short = []
    for width in (0.1, 0.3, 1.0):
        for speed in (5.0, 15.0, 30.0):
            case = board(radius, width, speed)
            r = webfem.solve(case, model="closed-form")
            reference = webfem.solve(case, model="fe2d")
            short += [(width, speed, q) for q in READ_QUANTITIES
                      if true_error(r, reference, q) > r[f"error_{q}"]]
    assert not short
