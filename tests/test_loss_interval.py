"""The traction-loss speed states its error: the speeds between which mu's stated error
band reaches mu_min (a new-user trial found the answer given without one)."""

import pytest

from webfem import Case
from webfem.traction import speed_interval, traction_loss_speed

from conftest import FakeResult


def results(points, error=0.05):
    return [FakeResult(Case().updated({"roller.speed": u}), m, error_mu=error)
            for u, m in points]


def test_the_band_brackets_the_crossing_and_widens_with_the_error():
    pts = [(5.0, 0.28), (10.0, 0.25), (20.0, 0.15), (30.0, 0.05)]
    narrow = speed_interval(results(pts, 0.01), 0.1, 5.0)
    wide = speed_interval(results(pts, 0.2), 0.1, 5.0)
    assert narrow[0] < 25.0 < narrow[1]           # mu crosses 0.1 at 25 m/s (linear)
    assert wide[0] < narrow[0] and wide[1] > narrow[1]


@pytest.mark.parametrize("why,pts,error,expected", [
    ("no stated error on the way", [(5.0, 0.3), (20.0, 0.15), (30.0, 0.05)], None,
     (None, None)),
    ("the band reaches mu_min at the peak", [(5.0, 0.12), (20.0, 0.11), (30.0, 0.05)], 0.5,
     (None, "known")),
    ("the band's high side above mu_min at the last speed",
     [(5.0, 0.3), (20.0, 0.15), (30.0, 0.09)], 0.5, ("known", None)),
])
def test_an_end_the_solved_speeds_do_not_show_is_none(why, pts, error, expected):
    low, high = speed_interval(results(pts, error), 0.1, 5.0)
    for got, want in zip((low, high), expected):
        assert (got is None) == (want is None), why


def test_the_closed_form_says_it_states_no_speed_error_where_its_band_stays_open():
    """Eq. 21 on the base case: mu's stated error (0.5 of 0.1 at the crossing) keeps the
    band above 0.1 to the scan's last speed, so the high end is unknown: no error stated,
    the low end given (fe2d's 23.38 m/s lies above it)."""
    out = traction_loss_speed(Case(), 0.1, "closed-form")
    low, high = out.speed_interval
    assert high is None and out.error_speed is None
    assert low < 23.38 < out.speed
    assert "no stated error" in out.message
    assert f"anywhere from {low:.4g} m/s to above the last speed solved" in out.message
    assert out.to_dict()["speed_interval"] == [low, None]


def test_the_speed_found_lies_inside_its_stated_interval():
    """Brent stops within 1e-3 of its bracket, 20 times wider than fe2d's band on the base
    case (the review found 23.37915 m/s reported with an interval of 23.38308..23.38421):
    the speed is mu's crossing interpolated between the root find's nearest solves."""
    from webfem.traction import interpolated_crossing

    cache = {u: FakeResult(Case().updated({"roller.speed": u}), 0.3 - 0.01 * u,
                           error_mu=1e-4) for u in (19.0, 20.0, 20.02, 25.0)}
    speed = interpolated_crossing(cache, 0.1, 20.005)   # Brent's answer, 0.005 off
    assert speed == pytest.approx(20.0)
    low, high = speed_interval(list(cache.values()), 0.1, 19.0)
    assert low <= speed <= high
    full = traction_loss_speed(Case(), 0.1, "closed-form", full_scan=True)
    low, high = full.speed_interval
    assert low <= full.speed <= high and full.error_speed == pytest.approx(
        max(full.speed - low, high - full.speed) / full.speed)
