"""The physics of a real line (issue 12), each effect against a limit derived by hand.

Web inertia, slip flow, isothermal permeation, bending from the material, friction from the
solved loads, the paper switch, and the idler slip check (physics.md, "Beyond the paper" and
"Will an idler slip?"). The exact Jacobians with every effect on and the convergence orders
are in tests/test_jacobians.py.
"""

import math

import numpy as np
import pytest

import webfem
from webfem import Case
from webfem.errors import InputError
from webfem.fem.scaling import FoilParameters
from webfem.models import fe1d, fe2d
from webfem.physics.effects import EFFECTS, SWITCH_OFF, idler_check, included

from conftest import FLYING

MODELS = [fe1d, fe2d]
KEYS = ("h_center", "h_min", "h_inlet", "h_outlet", "mu", "delta_T")


def rel(a, b):
    return abs(a / b - 1.0)


# -- web inertia ---------------------------------------------------------------------------

#: A moving web on a driven roller: U = 40 m/s entrains, U_s = 10 m/s slides,
#: rho_w t U_w^2 = 650 * 70e-6 * 15^2 = 10.24 N/m of the 80 N/m turns the web.
MOVING = Case().updated({"roller.speed": 25.0, "web.speed": 15.0})


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.NAME)
def test_inertia_is_the_effective_tension(model):
    """The web equation, the wrap pressure, the scaling and the belt formula see only
    T_eff = T - rho_w t U_w^2. So the case (T, rho_w, U_w) and the case (T_eff, rho_w = 0,
    the same U_w: the same entrainment U and sliding U_s) are the same problem: gaps, mu and
    delta_T agree to the solver tolerance (1e-8 relative; measured: bit for bit), and
    delta_T = T_eff (exp(mu B) - 1), not T (exp(mu B) - 1)."""
    T_eff = 80.0 - 650.0 * 70e-6 * 15.0**2
    assert MOVING.tension_eff == pytest.approx(T_eff, rel=1e-14)
    same = MOVING.updated({"web.tension": T_eff, "web.density": 0.0})
    a, b = model.solve(MOVING), model.solve(same)
    assert a["T_eff"] == pytest.approx(T_eff, rel=1e-14) and "inertia" in a["effects"]
    assert "inertia" not in b["effects"]
    for key in KEYS:
        assert rel(a[key], b[key]) < 1e-8, (key, a[key], b[key])
    assert a["delta_T"] == pytest.approx(T_eff * math.expm1(a["mu"] * MOVING.B), rel=1e-12)
    # and inertia matters: at the full tension T the gaps are smaller (h ~ T^(-2/3))
    held = model.solve(MOVING.updated({"web.density": 0.0}))
    assert held["h_center"] < a["h_center"] and held["h_min"] < a["h_min"]


def test_inertia_scaled_gap_depends_on_entrainment_only():
    """In the scaled problem U_w enters only through U = U_r + U_w and T_eff: the web still
    (U_w = 0) on a roller at U_r + U_w under the tension T_eff has the same gaps (same
    FoilParameters), while mu differs (U_s = 10 m/s against 40 m/s)."""
    still = Case().updated({"roller.speed": 40.0, "web.speed": 0.0,
                            "web.tension": MOVING.tension_eff})
    assert FoilParameters.from_case(still) == FoilParameters.from_case(MOVING)
    a, b = fe1d.solve(MOVING), fe1d.solve(still)
    for key in ("h_center", "h_min"):
        assert rel(a[key], b[key]) < 1e-8, (key, a[key], b[key])
    assert a["mu"] < b["mu"]


def test_web_too_fast_to_hold_is_an_input_error():
    """T_eff <= 0: 80 N/m is spent turning newsprint (650 kg/m^3, 70 um) at
    U_w = sqrt(80 / (650 * 70e-6)) = 41.9 m/s; faster is an input error naming web.speed."""
    limit = math.sqrt(80.0 / (650.0 * 70e-6))
    Case().updated({"web.speed": 0.99 * limit})
    with pytest.raises(InputError, match=r"web\.speed"):
        Case().updated({"web.speed": 1.01 * limit})
    with pytest.raises(InputError, match=r"web\.speed"):
        Case().updated({"web.speed": limit})


# -- slip flow -----------------------------------------------------------------------------

#: Impermeable flying web: the fluid film everywhere, the gap shift from slip is clean. The
#: smooth film's shear (air.roughness_flow = "none"): through the roughness the shear is cut
#: off at 2 a lambda whether or not the film carries slip, which would mix into the slip terms.
IMPERMEABLE = FLYING.updated({"web.permeability": 0.0, "air.roughness_flow": "none"})


@pytest.fixture(scope="module", params=MODELS, ids=lambda m: m.NAME)
def no_slip(request):
    model = request.param
    return model, model.solve(IMPERMEABLE.updated({"air.slip": "none"}))


def test_vanishing_mean_free_path_is_no_slip(no_slip):
    """lambda_a -> 0 (1e-15 m) removes the slip terms: the gaps and mu equal air.slip =
    "none" to 1e-9 (the slip terms are O(lambda_a / h) = 3e-11; measured < 1e-10)."""
    model, none = no_slip
    tiny = model.solve(IMPERMEABLE.updated({"air.mean_free_path": 1e-15}))
    assert "slip" in tiny["effects"] and "slip" not in none["effects"]
    for key in ("h_center", "h_min", "mu"):
        assert rel(tiny[key], none[key]) < 1e-9, (key, tiny[key], none[key])


def test_slip_shifts_the_gap_by_two_mean_free_paths(no_slip):
    """First-order slip turns the Poiseuille conductance p h^3 into p h^3 + 6 a lambda_a p_a
    h^2 ~ p (h + 2 a lambda)^3 with the local mean free path lambda = lambda_a p_a / p: to
    first order the film behaves like the no-slip film of gap h + 2 a lambda, so the gap
    shifts by -2 a lambda = -2 lambda_a p_a / p (a = 1).

    Against the brief's -2 lambda_a: within 0.03 (measured, lambda_a = 5 and 1 nm: -1.974
    central, -1.992 minimum with fe1d; -1.974 and -1.993 with fe2d). The 1.3 % at the
    centre is the film pressure: there p = p_a + T/R = 1.0144 p_a, lambda is 1.4 % shorter
    and -2 p_a / p = -1.972; at the exit minimum p = 1.005 p_a. Against -2 p_a / p with p the
    solved film pressure at the centre and at the minimum: within 0.3 % (measured 0.07 % to
    0.14 %; the rest is the Couette flux, which slip leaves as it is, and the web's ends).
    Linear in lambda_a: the two shifts per lambda_a agree within 0.1 %.
    """
    model, none = no_slip
    p_a = IMPERMEABLE.air.ambient_pressure
    f = none.fields
    p_centre = np.interp(0.0, f["x"], f["p"])
    p_min = np.interp(none["x_min"], f["x"], f["p"])
    shifts = []
    for lam in (5e-9, 1e-9):
        r = model.solve(IMPERMEABLE.updated({"air.mean_free_path": lam}))
        centre = (r["h_center"] - none["h_center"]) / lam
        low = (r["h_min"] - none["h_min"]) / lam
        assert centre == pytest.approx(-2.0, abs=0.03), centre
        assert low == pytest.approx(-2.0, abs=0.03), low
        assert centre == pytest.approx(-2.0 * p_a / p_centre, rel=3e-3)
        assert low == pytest.approx(-2.0 * p_a / p_min, rel=3e-3)
        shifts.append((centre, low))
    assert shifts[0] == pytest.approx(shifts[1], rel=1e-3)


# -- permeation ----------------------------------------------------------------------------


def test_isothermal_and_paper_permeation_differ_at_first_order_in_d():
    """The isothermal sink (12 k/t)((p + p_a)/2)(p - p_a) and the paper's (12 k/t) p (p - p_a)
    differ by (12 k/t)(p - p_a)^2/2: in scaled form K (1 + ds P) P with ds = d/2 against
    ds = d, d = T/(R p_a). The two agree to O((p - p_a)^2/p_a^2) in the sink (over p_a^2),
    i.e. the sinks differ by a fraction d P/2 of themselves, and the gaps by O(d): the
    relative difference of h_min, divided by d, tends to a constant as d -> 0.

    Measured (fe1d, base case at 40 m/s, permeable): p_a = 1 atm, d = 0.01436:
    h_min +0.344 % (physics.md: 0.3 %); p_a = 2 atm, d = 0.00718: +0.173 %; observed order
    in d log2(0.344/0.173) = 0.99 (asserted 1 +- 0.05, i.e. not d^2); difference / d =
    0.239 and 0.241 (asserted equal within 2 %). h_center: +0.136 % and +0.068 %.
    """
    out = []
    for p_a in (101325.0, 2 * 101325.0):
        case = Case().updated({"roller.speed": 40.0, "air.ambient_pressure": p_a})
        iso = fe1d.solve(case)
        paper = fe1d.solve(case.updated({"web.permeation": "paper"}))
        assert "isothermal-permeation" in iso["effects"]
        assert "isothermal-permeation" not in paper["effects"]
        d = case.p_bar / p_a
        out.append((d, iso["h_min"] / paper["h_min"] - 1.0,
                    iso["h_center"] / paper["h_center"] - 1.0))
    (d1, m1, c1), (d2, m2, c2) = out
    assert d1 / d2 == pytest.approx(2.0, rel=1e-12)
    assert 2e-3 < m1 < 5e-3, m1                   # the size physics.md quotes
    assert math.log2(m1 / m2) == pytest.approx(1.0, abs=0.05), (m1, m2)
    assert math.log2(c1 / c2) == pytest.approx(1.0, abs=0.05), (c1, c2)
    assert m1 / d1 == pytest.approx(m2 / d2, rel=0.02)


def test_impermeable_web_has_no_permeation_effect():
    """k = 0: no sink, so the permeation law cannot matter (bit for bit) and is not listed."""
    a = fe1d.solve(IMPERMEABLE)
    b = fe1d.solve(IMPERMEABLE.updated({"web.permeation": "paper"}))
    assert "isothermal-permeation" not in a["effects"]
    assert a["h_min"] == b["h_min"] and a["mu"] == b["mu"]


# -- bending -------------------------------------------------------------------------------


def test_bending_from_the_modulus_is_the_explicit_value():
    """web.bending_stiffness absent: D = E_m t^3/12 = 4.46e9 * (70e-6)^3 / 12 = 1.2748e-4
    N m (physics.md: 1.27e-4). The explicit value gives the same scaled problem, bit for bit,
    and the same answer to round-off (two solves in one process may differ in the last
    digits: the linear solver reuses the fill-reducing ordering of a pattern it has seen)."""
    D = 4.46e9 * 70e-6**3 / 12.0
    case = Case().updated({"roller.speed": 30.0})
    assert case.web.bending_stiffness is None
    assert case.bending_used == pytest.approx(D, rel=1e-14)
    assert D == pytest.approx(1.2748e-4, rel=1e-4)
    explicit = case.updated({"web.bending_stiffness": D})
    assert FoilParameters.from_case(case) == FoilParameters.from_case(explicit)
    a = fe1d.solve(case)
    b = fe1d.solve(explicit)
    assert a["bending_stiffness_used"] == pytest.approx(D, rel=1e-14)
    for key in KEYS:
        assert rel(a[key], b[key]) < 1e-10, (key, a[key], b[key])
    membrane = fe1d.solve(case.updated({"web.bending_stiffness": 0.0}))
    assert "bending" in a["effects"] and "bending" not in membrane["effects"]
    assert membrane["bending_stiffness_used"] == 0.0
    assert membrane["h_min"] > a["h_min"]         # physics.md: bending lowers h_min


def test_paper_physics_is_a_membrane_unless_D_is_given():
    paper = Case().updated({"model.physics": "paper"})
    assert paper.bending_used == 0.0 and included(paper) == ()
    beam = paper.updated({"web.bending_stiffness": 2e-4})
    assert beam.bending_used == 2e-4 and included(beam) == ("bending",)
    r = fe1d.solve(paper.updated({"roller.speed": 40.0}))
    assert r["bending_stiffness_used"] == 0.0 and tuple(r["effects"]) == ()


def test_paper_switch_is_every_effect_switched_off():
    """model.physics = "paper" equals the full physics with each effect's own switch
    (physics/effects.SWITCH_OFF) set: gaps, mu and delta_T to 1e-12 (a moving web, a
    permeable web near landing, so that every effect is on in the full model)."""
    full = Case().updated({"roller.speed": 25.0, "web.speed": 5.0})
    assert included(full) == EFFECTS
    off = {}
    for keys in SWITCH_OFF.values():
        off.update(keys)
    a = fe1d.solve(full.updated({"model.physics": "paper"}))
    b = fe1d.solve(full.updated(off))
    assert tuple(b["effects"]) == () and a["T_eff"] == 80.0
    for key in KEYS:
        assert rel(a[key], b[key]) < 1e-12, (key, a[key], b[key])


# -- friction from the solved loads --------------------------------------------------------

#: A flying, impermeable web on a smooth pair (sigma = 0.51 um against h > 25 um: the contact
#: pressure is below 1e-20 T/R) without slip: the film's shear is all the friction.
SMOOTH = IMPERMEABLE.updated({"air.slip": "none", "web.roughness": 0.5e-6,
                         "roller.roughness": 0.1e-6})


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.NAME)
def test_load_friction_is_the_film_shear_where_contact_vanishes(model):
    """Where contact vanishes (chi_c -> 0, chi_f = 1 - chi_c -> 1) Eq. 28 with the continuous
    Eq. 29 is the wrap average of Eq. 30's mu_f = eta R U_s/(h T_eff), and the "loads"
    traction (eta U_s/h - (h/2) dp/dx)/p_bar with p_bar = T_eff/R is the same Couette term
    plus the pressure-driven shear. So mu_loads - mu_continuous = the wrap average of
    -(h/2) dp/dx / p_bar (to round-off), the Couette part of "loads" equals the continuous mu
    to 1e-12, and the pressure-driven part is small: measured -3.0 % of mu (fe1d, mu =
    0.00969 against 0.00998) and -3.1 % (fe2d): it lives in the entry and exit zones, where
    dp/dx ~ p_bar over a length R eps^(1/3) and h/2 ~ h_0/2 (asserted between -5 % and -1 %).
    """
    loads = model.solve(SMOOTH)
    cont = model.solve(SMOOTH.updated({"friction.variant": "continuous"}))
    # friction is read off the same film (two solves: equal to round-off, the linear solver
    # reuses the ordering of a pattern it has seen)
    assert loads["h_center"] == pytest.approx(cont["h_center"], rel=1e-12)
    assert loads["contact_share"] < 1e-15
    g = loads.diagnostics
    p_bar = SMOOTH.p_bar
    couette = float(np.sum(g.wrap_w * SMOOTH.air.viscosity * SMOOTH.U_slide / g.wrap_h)) / p_bar
    pressure = float(np.sum(g.wrap_w * (-0.5 * g.wrap_h * g.wrap_dpdx))) / p_bar
    assert couette == pytest.approx(cont["mu"], rel=1e-12)
    assert loads["mu"] - cont["mu"] == pytest.approx(pressure, rel=1e-9, abs=1e-15)
    assert -0.05 < pressure / loads["mu"] < -0.01, pressure / loads["mu"]
    # the uniform-gap estimate eta R U_s / (h_center T_eff) within 3 % (measured: 1.5 %
    # above fe1d, 1.8 % above fe2d: the wide inlet gap lowers the average more than the exit
    # constriction raises it)
    estimate = (SMOOTH.air.viscosity * SMOOTH.roller.radius * SMOOTH.U_slide
                / (loads["h_center"] * SMOOTH.tension_eff))
    assert cont["mu"] == pytest.approx(estimate, rel=0.03)


# -- will an idler slip? -------------------------------------------------------------------

#: An idler (U_r = U_w, nothing slides) of the base rig: drag M_d = 0.01 N m, J = 0.002
#: kg m^2, the line speeding up at a = 0.5 m/s^2.
IDLER = {"roller.drag_torque": 0.01, "roller.inertia": 0.002, "web.acceleration": 0.5}


@pytest.mark.parametrize("speed,holds", [(2.0, True), (10.0, False)])
def test_idler_holds_at_low_speed_and_slips_when_it_flies(speed, holds):
    """delta_T_required = (M_d + J a / R) / (R L) = (0.01 + 0.002 * 0.5 / 0.055) /
    (0.055 * 0.035) = 0.028182 / 0.001925 = 14.640 N/m at any speed.
    delta_T_available = T_eff (exp(mu_onset B) - 1), mu_onset = mu_cc x contact share, B =
    pi/3:
    - 2 m/s: T_eff = 80 - 650 * 70e-6 * 2^2 = 79.818 N/m; the web rests on its asperities
      (contact share 0.954, fe1d), mu_onset = 0.286, available = 79.818 * 0.3496 = 27.9 N/m,
      margin 1.91: the idler holds;
    - 10 m/s: T_eff = 80 - 4.55 = 75.45 N/m; the film carries most of the wrap (contact share
      0.171), mu_onset = 0.0513, available = 75.45 * 0.0552 = 4.17 N/m, margin 0.28: it slips.
    """
    case = Case().updated({"roller.speed": speed, "web.speed": speed, **IDLER})
    required = (0.01 + 0.002 * 0.5 / 0.055) / (0.055 * 0.035)
    assert required == pytest.approx(14.6399, rel=1e-5)
    r = fe1d.solve(case)
    T_eff = 80.0 - 650.0 * 70e-6 * speed**2
    assert r["T_eff"] == pytest.approx(T_eff, rel=1e-14)
    assert r["delta_T_required"] == pytest.approx(required, rel=1e-12)
    assert r["mu_onset"] == pytest.approx(0.3 * r["contact_share"], rel=1e-12)
    available = T_eff * math.expm1(r["mu_onset"] * math.pi / 3)
    assert r["delta_T_available"] == pytest.approx(available, rel=1e-12)
    assert r["slip_margin"] == pytest.approx(available / required, rel=1e-12)
    if holds:
        assert r["contact_share"] > 0.9 and 1.5 < r["slip_margin"] < 2.5
    else:
        assert r["contact_share"] < 0.3 and r["slip_margin"] < 0.5


def test_no_drag_no_idler_check():
    """Without drag torque and acceleration the check has nothing to compare: None."""
    out = idler_check(Case(), 0.3)
    assert out == dict(delta_T_required=None, delta_T_available=None, slip_margin=None,
                       mu_onset=None)
    assert fe1d.solve(IMPERMEABLE)["slip_margin"] is None


def test_slip_warning_says_what_the_slip_model_leaves():
    """Below 10 mean free paths the warning follows the slip model: with first-order slip
    (the default) it must not claim the continuum equation is used."""
    from webfem.physics.validity import slip_warning
    base = webfem.load_case("base")
    with_slip = slip_warning(base, 4e-7)
    assert "first-order slip webfem includes" in with_slip and "continuum" not in with_slip
    assert "Kn = 0.17" in with_slip
    without = slip_warning(base.updated({"air.slip": "none"}), 4e-7)
    assert "continuum Reynolds equation overestimates" in without
    assert slip_warning(base, 1e-6) is None and slip_warning(base, -1e-7) is None


@pytest.mark.parametrize("a", [0.5, -0.5, -5.0, -6.05])
def test_idler_load_follows_the_rollers_equation(a):
    """J alpha = R F - M_d with alpha = a/R, F = delta_T L: delta_T_required =
    |M_d + J a/R| / (R L). Slowing down (a < 0) the roller's inertia helps the drag (the old
    J |a| / R counted it against the web); past M_d = J |a| / R (a = -0.275 m/s^2 here) the
    web brakes the roller."""
    from webfem.physics.effects import idler_check

    case = Case().updated({**IDLER, "web.acceleration": a})
    R, L = case.roller.radius, case.web.width
    out = idler_check(case, 0.2)
    assert out["delta_T_required"] == pytest.approx(abs(0.01 + 0.002 * a / R) / (R * L),
                                                    rel=1e-12)
    assert out["slip_margin"] == pytest.approx(out["delta_T_available"]
                                               / out["delta_T_required"], rel=1e-12)


def test_idler_with_drag_and_inertia_cancelling_holds():
    from webfem.physics.effects import idler_check, traction_summaries

    a = -0.01 * 0.055 / 0.002     # J a / R = -M_d
    case = Case().updated({**IDLER, "web.acceleration": a})
    out = idler_check(case, 0.2)
    assert out["delta_T_required"] == pytest.approx(0.0, abs=1e-12)
    assert out["slip_margin"] > 1e6
    many = traction_summaries([case], [0.1], [0.5])[0]
    assert many["delta_T_required"] == pytest.approx(0.0, abs=1e-12)


def test_exactly_cancelling_drag_and_inertia_reach_the_cli_without_a_traceback(capsys):
    """0.05 N m + 0.006 kg m^2 x (-0.5 m/s^2) / 0.06 m is 0.0 to the bit: the stated margin
    range divided by it (a ZeroDivisionError in `webfem solve` and `webfem idler`)."""
    from webfem.cli import main
    from webfem.physics.effects import margin_range

    values = {"roller.radius": 0.06, "roller.drag_torque": 0.05, "roller.inertia": 0.006,
              "web.acceleration": -0.5, "roller.speed": 10.0, "web.speed": 10.0}
    case = Case().updated(values)
    assert margin_range(case, 0.0, 0.1, 0.5) == (math.inf, math.inf)
    sets = [a for k, v in values.items() for a in ("--set", f"{k}={v}")]
    assert main(["solve", "base", "--model", "closed-form", *sets]) == 0
    assert "holds" in capsys.readouterr().out
    assert main(["idler", "base", "--model", "closed-form", "--num", "3", *sets]) == 0
