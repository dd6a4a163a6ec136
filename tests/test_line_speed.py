"""A speed scan moves the line (webfem/line_speed.py): the traction-loss search, its mu curve
and the groove map set the roller to each speed and the web to the case's ratio U_w/U_r
times it, as the idler margin sets U_r = U_w. Before, they kept the web speed, so an idler
scanned at 8.81 m/s had its roller sliding 1.2 m/s under a web still at 10 m/s."""

import math

import pytest

import webfem
from webfem import Case
from webfem import groove_sizing as gs
from webfem import loss_scan
from webfem.errors import InputError
from webfem.idler import margin_curve
from webfem.line_speed import at_speed, speed_ratio, top_speed
from webfem.traction import mu_curve, traction_loss_speed

IDLER = Case().updated({"roller.speed": 10.0, "web.speed": 10.0})
DRAW = Case().updated({"roller.speed": 20.0, "web.speed": 19.8})


def test_at_speed_keeps_the_ratio_and_the_rig_web_at_rest():
    assert at_speed(DRAW, 5.0).web.speed == pytest.approx(4.95)
    assert at_speed(IDLER, 30.0).web.speed == 30.0
    assert at_speed(Case(), 30.0).web.speed == 0.0          # the paper's rig
    still = Case().updated({"roller.speed": 0.0, "web.speed": 5.0})
    assert speed_ratio(still) is None and at_speed(still, 3.0).web.speed == 5.0


def test_every_scan_solves_the_line_at_the_case_ratio(monkeypatch):
    """The loss scan's solves see U_w = ratio x U_r (the old scan kept U_w = 10)."""
    seen = []
    real = loss_scan.solve_along

    def spy(cases, *args, **kwargs):
        cases = list(cases)
        seen.extend((c.roller.speed, c.web.speed) for c in cases)
        return real(cases, *args, **kwargs)

    monkeypatch.setattr(loss_scan, "solve_along", spy)
    traction_loss_speed(IDLER, 0.1, "closed-form")
    assert seen and all(w == pytest.approx(r) for r, w in seen)


def test_idler_loss_speed_is_at_the_onset_of_slip():
    """An idler scanned as a line: every point has U_s = 0, so the crossing is where its
    onset traction (mu_cc x contact share) falls to mu_min, as a solve at U_r = U_w says."""
    out = traction_loss_speed(IDLER, 0.1, "closed-form")
    assert out.web_speed_ratio == 1.0 and "web at U_r" in out.message
    u = out.speed
    mu = lambda s: webfem.solve(IDLER.updated({"roller.speed": s, "web.speed": s}),  # noqa
                                model="closed-form")["mu"]
    assert mu(0.99 * u) > 0.1 > mu(1.01 * u)


def test_a_fast_web_ends_the_scan_where_it_can_no_longer_be_held():
    """The web's inertia rises with the scan: the scan ends below top_speed, says so, and
    no solve is asked of a case that cannot exist."""
    top, why = top_speed(IDLER, 100.0)
    assert 10.0 < top < 100.0 and why
    out = traction_loss_speed(IDLER, 1e-4, "closed-form", full_scan=True)
    assert out.scanned[1] == pytest.approx(top) and "the scan ends at" in out.message
    speeds, mu = mu_curve(IDLER, "closed-form", [5.0, 20.0, 0.5 * (top + 100.0)])
    assert math.isfinite(mu[0]) and math.isfinite(mu[1]) and math.isnan(mu[2])
    with pytest.raises(InputError, match="out of range"):
        traction_loss_speed(IDLER, 0.1, "closed-form", speed_range=(top * 1.01, 200.0))


def test_mu_curve_moves_the_web():
    u, mu = mu_curve(IDLER, "closed-form", [20.0])
    assert mu[0] == webfem.solve(IDLER.updated({"roller.speed": 20.0, "web.speed": 20.0}),
                                 model="closed-form")["mu"]


def test_groove_map_moves_the_web(monkeypatch):
    seen = []

    def solve(case, model, options):
        seen.append((case.roller.speed, case.web.speed))
        return {"mu": 0.3, "h_center": 1e-6, "contact_share": 0.5}

    monkeypatch.setattr(gs, "solve", solve)
    gs.groove_map(DRAW, 0.2, pitches=(1.27e-3,), land_fractions=(0.9,))
    assert seen == [(20.0, pytest.approx(19.8)), (40.0, pytest.approx(39.6))]


def test_groove_map_refuses_a_speed_the_web_cannot_hold(monkeypatch):
    monkeypatch.setattr(gs, "solve", lambda *a: pytest.fail("solved"))
    top, _ = top_speed(IDLER, 100.0)
    with pytest.raises(InputError, match="cannot be held"):
        gs.groove_map(IDLER, 0.2, speeds=(1.5 * top,), pitches=(1.27e-3,),
                      land_fractions=(0.9,))


def test_idler_margin_holds_the_onset_whatever_the_ratio():
    """The idler check is at U_r = U_w: a case with a draw is checked at equal speeds."""
    case = DRAW.updated({"roller.drag_torque": 0.05})
    a = margin_curve(case, [10.0], model="closed-form")
    b = margin_curve(case.updated({"web.speed": 20.0}), [10.0], model="closed-form")
    assert a.delta_T_available == b.delta_T_available
