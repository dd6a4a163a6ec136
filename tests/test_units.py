"""Units at the edges (issue 13 item 2): text with units -> SI, named dimension errors,
roller.diameter, display units, and no pint for plain numbers."""

import subprocess
import sys

import pytest

from webfem.case import Case, load_case, parse_assignment
from webfem.errors import InputError
from webfem.units import convert, display, to_si

# (key, text) -> the SI value the key stores
GOOD = [
    ("roller.speed", "1200 m/min", 20.0),
    ("roller.speed", "1200m/min", 20.0),
    ("roller.speed", "3937 ft/min", 3937 * 0.3048 / 60),
    ("roller.speed", "100 fpm", 100 * 0.3048 / 60),
    ("web.tension", "0.5 pli", 0.5 * 4.4482216152605 / 0.0254),
    ("web.tension", "0.5PLI", 0.5 * 4.4482216152605 / 0.0254),
    ("web.tension", "0.08 kN/m", 80.0),
    ("web.tension", "2 lbf/in", 2 * 4.4482216152605 / 0.0254),
    ("web.roughness", "4 um", 4e-6),
    ("web.roughness", "4 µm", 4e-6),
    ("web.thickness", "2 mil", 2 * 2.54e-5),      # a thousandth of an inch, not an angle
    ("web.width", "2.5 in", 0.0635),
    ("web.width", "35 mm", 0.035),
    ("wrap.angle_deg", "60 deg", 60.0),
    ("wrap.angle_deg", "0.5 rad", 28.64788975654116),
    ("web.bending_stiffness", "1.27e-4 N*m", 1.27e-4),
    ("web.bending_stiffness", "1.27e-4 N m", 1.27e-4),
    ("air.viscosity", "0.0181 cP", 1.81e-5),
    ("air.ambient_pressure", "14.7 psi", 14.7 * 6894.757293168361),
    ("web.density", "40 lb/ft^3", 40 * 0.45359237 / 0.3048**3),
    ("web.permeability", "5e-9 mm^2", 5e-15),
    ("friction.mu_cc", "30 %", 0.3),
    ("roller.inertia", "0.002 kg*m^2", 0.002),
    ("web.acceleration", "1 ft/s^2", 0.3048),
]


@pytest.mark.parametrize("key,text,si", GOOD, ids=[f"{k}={t}" for k, t, _ in GOOD])
def test_text_with_units_becomes_si(key, text, si):
    assert Case().updated({key: text}).get(key) == pytest.approx(si, rel=1e-12)


# (key, text) -> words the one-line message must hold
BAD = [
    ("web.tension", "3 m", ["web.tension = '3 m' has dimension length",
                            "expected force/length, e.g. '80 N/m' or '0.45 pli'"]),
    ("roller.speed", "20 m", ["roller.speed = '20 m'", "dimension length", "expected speed"]),
    ("roller.radius", "3 N", ["dimension force", "expected length"]),
    ("web.width", "60 deg", ["dimension angle", "expected length"]),
    ("wrap.angle_deg", "4 um", ["dimension length", "expected angle", "'60 deg'"]),
    ("friction.mu_cc", "30 deg", ["dimension angle", "expected no unit"]),
    ("web.roughness", "4 furlongz", ["'4 furlongz' is not a number with a unit",
                                     "unknown unit 'furlongz'"]),
    ("web.roughness", "um", ["'um' is not a number", "give a number and a unit"]),
    ("web.tension", "80", ["'80' is not a number", "quoted text needs a unit",
                           "unquoted, in N/m"]),
    ("roller.speed", "-5 m/s", ["roller.speed = '-5 m/s' = -5 m/s is out of range", ">= 0"]),
    ("roller.speed", "-5 m/min", ["roller.speed = '-5 m/min' = -0.0833333 m/s is out of range",
                                  "<= 300 [m/s]"]),
    ("web.width", "1e400 m", ["web.width = '1e400 m' = inf m is out of range"]),
    ("web.tension", "0.5 pli pli", ["has dimension", "force/length"]),
    # pint would read these as 15 m/s, 150 m/s and 500 m/min
    ("roller.speed", "1,5 m/s", ["'1,5 m/s' has a comma or a space between digits",
                                 "decimal point"]),
    ("roller.speed", "1,50 m/s", ["decimal comma or a thousands separator"]),
    ("roller.speed", "1 500 m/min", ["'1 500 m/min' has a comma or a space"]),
    ("web.thickness", "0,07 mm", ["has a comma", "e.g."]),
]


@pytest.mark.parametrize("key,text,words", BAD, ids=[f"{k}={t}" for k, t, _ in BAD])
def test_bad_text_is_one_line_naming_key_and_dimension(key, text, words):
    with pytest.raises(InputError) as err:
        Case().updated({key: text})
    msg = str(err.value)
    assert "\n" not in msg and len(msg) < 300
    for w in words:
        assert w in msg


def test_toml_and_set_read_units(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text('[roller]\nspeed = "1200 m/min"\ndiameter = "110 mm"\n'
                 '[web]\ntension = "0.5 pli"\nroughness = "4 um"\n')
    case = load_case(p, dict([parse_assignment("web.width=2.5in")]))
    assert case.roller.speed == pytest.approx(20.0)
    assert case.roller.radius == pytest.approx(0.055)
    assert case.web.tension == pytest.approx(87.5634176)
    assert case.web.width == pytest.approx(0.0635)
    p.write_text('[web]\ntension = "3 m"\n')
    with pytest.raises(InputError, match=r"web.tension = '3 m' has dimension length.* in "):
        load_case(p)


def test_diameter_or_radius_not_both(tmp_path):
    assert Case().updated({"roller.diameter": 0.2}).roller.radius == 0.1
    assert Case().updated({"roller.diameter": "4 in"}).roller.radius == pytest.approx(0.0508)
    with pytest.raises(InputError, match="give one of them, not both"):
        Case().updated({"roller.radius": 0.1, "roller.diameter": 0.2})
    with pytest.raises(InputError, match=r"roller.diameter = -0.2 is out of range"):
        Case().updated({"roller.diameter": -0.2})
    p = tmp_path / "c.toml"
    p.write_text("[roller]\nradius = 0.05\ndiameter = 0.1\n")
    with pytest.raises(InputError, match="not both"):
        load_case(p)
    # a --set diameter overrides the file's radius: one per source
    p.write_text("[roller]\nradius = 0.05\n")
    assert load_case(p, {"roller.diameter": "0.3 m"}).roller.radius == pytest.approx(0.15)
    assert parse_assignment("roller.diameter=110mm") == ("roller.diameter", "110mm")


def test_display_factors_match_pint():
    import pint
    ureg = pint.UnitRegistry()
    for value, role, system, unit in [(20.0, "speed", "us", "ft/min"),
                                      (20.0, "speed", "metric", "m/min"),
                                      (80.0, "tension", "us", "lbf/in"),
                                      (0.055, "length", "us", "in"),
                                      (4e-6, "thin", "us", "thou"),
                                      (101325.0, "pressure", "us", "psi"),
                                      (1.27e-4, "torque", "us", "lbf*in"),
                                      (1.27e-3, "position", "us", "in"),
                                      (1.27e-3, "position", "si", "mm"),
                                      (101325.0, "pressure", "metric", "kPa")]:
        si = {"speed": "m/s", "tension": "N/m", "length": "m", "thin": "m",
              "pressure": "Pa", "torque": "N*m", "position": "m"}[role]
        expected = ureg.Quantity(value, si).to(unit).magnitude
        assert convert(value, role, system) == pytest.approx(expected, rel=1e-12)
    assert display(20.0, "speed", "metric") == "1200 m/min"
    with pytest.raises(InputError, match="units = 'imperial'"):
        display(1.0, "speed", "imperial")


def test_plain_numbers_never_import_pint():
    code = ("import sys, webfem\n"
            "from webfem.case import Case\n"
            "Case().updated({'roller.speed': 12.0, 'web.tension': 90})\n"
            "webfem.solve(Case(), model='closed-form')\n"
            "assert 'pint' not in sys.modules, 'pint imported'\n"
            "Case().updated({'roller.speed': '12 m/s'})\n"
            "assert 'pint' in sys.modules\n")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_to_si_direct():
    assert to_si("roller.speed", "72 km/h", "m/s") == pytest.approx(20.0)
