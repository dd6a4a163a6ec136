"""Case description: defaults, validation messages, TOML round trip."""

import math

import pytest

from webfem import Case, CaseError, load_case, load_sweep
from webfem.case import parse_assignment, valid_keys


def test_defaults_are_paper_newsprint():
    c = Case()
    assert (c.roller.radius, c.web.width, c.web.tension, c.wrap.angle_deg) == \
        (0.055, 0.035, 80.0, 60.0)
    assert c.web.permeability == 5e-15 and c.web.modulus_thickness == 175e3
    assert c.sigma == 4e-6
    assert Case().updated({"friction.roughness": "composite"}).sigma == \
        pytest.approx(math.hypot(0.6e-6, 4e-6))


@pytest.mark.parametrize("key,value,words", [
    ("web.width", -0.01, ["web.width", "-0.01", "> 0"]),
    ("web.tension", 0.0, ["web.tension", "> 0"]),
    ("roller.radius", float("nan"), ["roller.radius", "nan"]),
    ("wrap.angle_deg", 400.0, ["wrap.angle_deg", "400", "< 360"]),
    ("wrap.angle_deg", 0.0, ["wrap.angle_deg", "> 0"]),
    ("roller.speed", -1.0, ["roller.speed", ">= 0"]),
    ("web.permeability", float("inf"), ["web.permeability", "inf"]),
    ("air.viscosity", "thick", ["air.viscosity", "not a number"]),
    ("friction.variant", "smooth", ["friction.variant", "'paper'", "'continuous'"]),
])
def test_bad_values_name_key_value_and_range(key, value, words):
    with pytest.raises(CaseError) as err:
        Case().updated({key: value})
    for w in words:
        assert w in str(err.value)


def test_both_speeds_zero_rejected():
    with pytest.raises(CaseError, match="roller.speed = 0 and web.speed = 0"):
        Case().updated({"roller.speed": 0.0, "web.speed": 0.0})
    assert Case().updated({"roller.speed": 0.0, "web.speed": 3.0}).U == 3.0


def test_unknown_key_suggests_closest(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text("[web]\nwidht = 0.03\n")
    with pytest.raises(CaseError, match="did you mean 'web.width'"):
        load_case(p)
    p.write_text("[rollr]\nradius = 0.03\n")
    with pytest.raises(CaseError, match="did you mean 'roller'"):
        load_case(p)


def test_malformed_toml_names_file_and_line(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text("[web]\nwidth = 0.03\ntension = = 80\n")
    with pytest.raises(CaseError, match=r"bad.toml.*line 3"):
        load_case(p)
    with pytest.raises(CaseError, match="does not exist"):
        load_case(tmp_path / "missing.toml")


def test_toml_round_trip(tmp_path):
    c = Case().updated({"roller.speed": 12.3456789, "web.bending_stiffness": 1.3e-4,
                        "friction.variant": "continuous", "wrap.angle_deg": 37.5})
    p = tmp_path / "rt.toml"
    p.write_text(c.to_toml())
    assert load_case(p) == c


def test_sweep_table_and_series(tmp_path):
    p = tmp_path / "s.toml"
    p.write_text('[sweep]\nparameter = "roller.speed"\nvalues = [1, 2, 3]\n'
                 '[[series]]\nlabel = "a"\nweb = { tension = 40 }\n'
                 '[[series]]\nlabel = "b"\nweb = { tension = 120 }\n')
    s = load_sweep(p)
    pts = list(s.points())
    assert len(pts) == 6
    assert pts[0][2].web.tension == 40.0 and pts[-1][2].roller.speed == 3.0
    p.write_text('[sweep]\nparameter = "roller.sped"\nvalues = [1]\n')
    with pytest.raises(CaseError, match="roller.speed"):
        load_sweep(p)
    p.write_text('[sweep]\nvalues = [-1, 2]\n')   # a bad point fails before any work
    with pytest.raises(CaseError, match="roller.speed = -1"):
        load_sweep(p)


def test_cli_assignment():
    assert parse_assignment("web.tension=120") == ("web.tension", 120)
    assert parse_assignment("friction.variant=continuous") == ("friction.variant", "continuous")
    with pytest.raises(CaseError, match="web.tension"):
        parse_assignment("web.tensoin=1")
    assert "web.bending_stiffness" in valid_keys()
