"""Case description: defaults, validation messages, TOML round trip."""

import math

import numpy as np
import pytest

from webfem import Case, InputError, load_case, load_sweep
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
    ("web.width", -0.01, ["web.width", "-0.01", ">= 0.001 and <= 10 [m]"]),
    ("web.tension", 0.0, ["web.tension", "> 0 and <= 100000"]),
    ("roller.radius", float("nan"), ["roller.radius", "nan"]),
    ("wrap.angle_deg", 400.0, ["wrap.angle_deg", "400", "< 360"]),
    ("wrap.angle_deg", 0.0, ["wrap.angle_deg", ">= 0.1"]),
    ("roller.speed", -1.0, ["roller.speed", ">= 0"]),
    ("web.permeability", float("inf"), ["web.permeability", "inf"]),
    ("air.viscosity", "thick", ["air.viscosity", "not a number"]),
    ("friction.variant", "smooth", ["friction.variant", "'paper'", "'continuous'"]),
])
def test_bad_values_name_key_value_and_range(key, value, words):
    with pytest.raises(InputError) as err:
        Case().updated({key: value})
    for w in words:
        assert w in str(err.value)


def test_both_speeds_zero_rejected():
    with pytest.raises(InputError, match="roller.speed = 0 and web.speed = 0"):
        Case().updated({"roller.speed": 0.0, "web.speed": 0.0})
    assert Case().updated({"roller.speed": 0.0, "web.speed": 3.0}).U == 3.0


def test_unknown_key_suggests_closest(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text("[web]\nwidht = 0.03\n")
    with pytest.raises(InputError, match="did you mean 'web.width'"):
        load_case(p)
    p.write_text("[rollr]\nradius = 0.03\n")
    with pytest.raises(InputError, match="did you mean 'roller'"):
        load_case(p)


def test_malformed_toml_names_file_and_line(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text("[web]\nwidth = 0.03\ntension = = 80\n")
    with pytest.raises(InputError, match=r"bad.toml.*line 3"):
        load_case(p)
    with pytest.raises(InputError, match="does not exist"):
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
    with pytest.raises(InputError, match="roller.speed"):
        load_sweep(p)
    p.write_text('[sweep]\nvalues = [-1, 2]\n')   # a bad point fails before any work
    with pytest.raises(InputError, match="roller.speed = -1"):
        load_sweep(p)


def test_cli_assignment():
    assert parse_assignment("web.tension=120") == ("web.tension", 120)
    assert parse_assignment("friction.variant=continuous") == ("friction.variant", "continuous")
    with pytest.raises(InputError, match="web.tension"):
        parse_assignment("web.tensoin=1")
    assert "web.bending_stiffness" in valid_keys()


@pytest.mark.parametrize("content,words", [
    (b"[web]\n# caf\xe9\nwidth = 0.03\n", ["c.toml", "not UTF-8", "0xe9", "line 2"]),
    (b"[roller]\nspeed = 1" + b"0" * 400 + b"\n", ["roller.speed = 1.00e+400", "out of range",
                                                   ">= 0"]),
    (b"[roller]\nspeed = 1" + b"0" * 5000 + b"\n", ["c.toml", "out of range", "4300 digits"]),
    (b"[roller]\nspeed = true\n", ["roller.speed = True", "not a number"]),
    (b'[roller]\nspeed = "10"\n', ["roller.speed = '10'", "not a number"]),
    (b"[friction]\nvariant = 5\n", ["friction.variant = 5", "'paper'"]),
    (b"roller = 5\n", ["'roller' in", "must be a table"]),
])
def test_bad_case_file_names_file_or_key(tmp_path, content, words):
    p = tmp_path / "c.toml"
    p.write_bytes(content)
    with pytest.raises(InputError) as err:
        load_case(p)
    msg = str(err.value)
    assert "\n" not in msg and len(msg) < 400
    for w in words:
        assert w in msg


def test_case_file_path_checks(tmp_path):
    with pytest.raises(InputError, match="case file '.*' is a directory"):
        load_case(tmp_path)
    bom = tmp_path / "bom.toml"             # some Windows editors start files with a BOM
    bom.write_bytes("\ufeff[web]\nwidth = 0.03\n".encode())
    assert load_case(bom).web.width == 0.03


@pytest.mark.parametrize("text,words", [
    ("roller.speed=1" + "0" * 400, ["roller.speed = 1.00e+400", "out of range"]),
    ("roller.speed=10**400", ["roller.speed = '10**400'", "not a number"]),
    ("roller.speed=1e400", ["roller.speed = inf", "out of range"]),
    ("roller.speed=" + "1" * 5000, ["roller.speed = '1111", "not a number"]),
    ("roller.speed=true", ["roller.speed = True", "not a number"]),
])
def test_cli_assignment_bad_numbers(text, words):
    with pytest.raises(InputError) as err:
        Case().updated(dict([parse_assignment(text)]))
    msg = str(err.value)
    assert len(msg) < 300
    for w in words:
        assert w in msg


def test_cli_assignment_one_line_only():
    with pytest.raises(InputError, match="on one line"):
        parse_assignment("roller.speed=1\nweb.width=3")


def test_numpy_numbers_accepted():
    import numpy as np
    c = Case().updated({"roller.speed": np.int64(3), "web.width": np.float32(0.5)})
    assert c.roller.speed == 3.0 and type(c.roller.speed) is float and c.web.width == 0.5


# -- physical ranges (issue 20): absurd values refused by name, before any solver ----------

#: A value of each numeric key that no real line has, and the words its message must hold.
ABSURD = [
    ("web.roughness", 1.0, ["web.roughness = 1.0", "<= 0.001 [m]", "'4 um'"]),
    ("web.roughness", 1e30, ["web.roughness = 1e+30", ">= 1e-09 and <= 0.001 [m]"]),
    ("friction.mu_cc", 1e30, ["friction.mu_cc = 1e+30", ">= 0 and <= 5"]),
    ("roller.radius", 1e-30, ["roller.radius = 1e-30", ">= 0.001 and <= 10 [m]"]),
    ("web.tension", 1e30, ["web.tension = 1e+30", "> 0 and <= 100000 [N/m]"]),
    ("air.viscosity", 1e3, ["air.viscosity = 1000.0", "<= 0.001 [Pa s]"]),
    ("web.acceleration", -1e30, ["web.acceleration = -1e+30", ">= -1000"]),
    ("roller.diameter", 100.0, ["roller.diameter = 100.0", "<= 20 [m]"]),
]


@pytest.mark.parametrize("key,value,words", ABSURD, ids=[f"{k}={v:g}" for k, v, _ in ABSURD])
def test_absurd_values_get_a_range_error(key, value, words):
    with pytest.raises(InputError) as err:
        Case().updated({key: value})
    msg = str(err.value)
    for w in words:
        assert w in msg, msg


NUMERIC = [k for k in valid_keys() if isinstance(Case().get(k), float)
           or k == "web.bending_stiffness"]


@pytest.mark.parametrize("key", NUMERIC)
def test_every_numeric_key_refuses_1e30_and_keeps_its_default(key):
    """Every numeric key has a finite upper bound (1e30 is refused, naming key, value and
    range) and its default lies inside its range."""
    from webfem.keys import key_range, key_unit
    with pytest.raises(InputError) as err:
        Case().updated({key: 1e30})
    assert f"{key} = 1e+30 is out of range: {key_range(key)} [{key_unit(key)}]" in str(err.value)
    assert "<=" in key_range(key) or "<" in key_range(key)


def test_real_lines_are_accepted():
    """The ends of what real lines have: 5 mm to 3 m wide, 0.01 to 100 m/s, 1 to 5000 N/m,
    5 um to 3 mm thick, roughness to 100 um, radii 5 mm to 2 m, wraps to 359 deg."""
    for values in ({"web.width": 0.005, "roller.speed": 0.01, "web.tension": 1.0,
                    "web.thickness": 5e-6, "roller.radius": 0.005},
                   {"web.width": 3.0, "roller.speed": 100.0, "web.tension": 5000.0,
                    "web.thickness": 3e-3, "roller.radius": 2.0, "web.roughness": 100e-6,
                    "roller.roughness": 100e-6, "wrap.angle_deg": 359.0,
                    "friction.mu_cc": 1.5},
                   {"web.speed": 100.0, "web.thickness": 10e-6}):
        Case().updated(values)


def test_physical_ranges_off_keeps_the_equations_bounds():
    """Dimensional-analysis checks rescale keys beyond real lines; signs still hold."""
    from webfem.sections import physical_ranges
    with physical_ranges(False):
        assert Case().updated({"web.modulus_md": 4.46e21}).web.modulus_md == 4.46e21
        with pytest.raises(InputError, match="web.width = -1.0 is out of range: must be > 0"):
            Case().updated({"web.width": -1.0})
    with pytest.raises(InputError, match="web.modulus_md"):
        Case().updated({"web.modulus_md": 4.46e21})


def test_docs_inputs_lists_every_range():
    """docs/inputs.md states each numeric key's range as the messages do."""
    from pathlib import Path
    from webfem.keys import key_range, key_unit
    from webfem.sections import ALIASES
    text = (Path(__file__).parent.parent / "docs" / "inputs.md").read_text()
    for key in NUMERIC + list(ALIASES):
        rng = key_range(key).removeprefix("must be ")
        assert f"| `{key}` | {rng} | {key_unit(key)} |" in text, key


# -- did-you-mean: only names that exist, where they exist (issue 20) ---------------------

@pytest.mark.parametrize("text,words,never", [
    ("web=80", ["'web'", "is a section, not a key", "web.KEY=VALUE", "tension"], "did you mean"),
    ("roller.tension=3", ["not a key of [roller] but of [web]", "'web.tension'"], "did you mean 'roller"),
    ("roller.width=0.1", ["but of [web]", "'web.width'"], "groove_width"),
    ("air.speed=3", ["[roller] and [web]", "'roller.speed' or 'web.speed'"], None),
    ("tension=3", ["did you mean 'web.tension'"], None),
    ("web.tensoin=3", ["did you mean 'web.tension'"], None),
    ("web.foo=3", ["the keys of [web]: width, tension"], "did you mean"),
    ("rollr.radius=0.05", ["did you mean 'roller.radius'"], None),
])
def test_unknown_key_suggests_only_what_exists(text, words, never):
    with pytest.raises(InputError) as err:
        parse_assignment(text)
    msg = str(err.value)
    for w in words:
        assert w in msg, msg
    assert never is None or never not in msg, msg


def test_unknown_table_suggests_a_section(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text("[webb]\nwidth = 0.03\n")
    with pytest.raises(InputError, match="unknown section 'webb' in .*c.toml; did you mean 'web'"):
        load_case(p)


def test_no_mean_free_path_through_the_roughness_is_refused_naming_both_keys():
    """Without a mean free path nothing cuts off the air's shear between the asperities at
    contact (physics.md, "Air through the roughness"): mu would be infinite for every model,
    and fe1d/fe2d once returned mu = nan as converged."""
    with pytest.raises(InputError) as err:
        Case().updated({"air.mean_free_path": 0.0})
    text = str(err.value)
    assert "air.mean_free_path = 0 m" in text and "air.roughness_flow" in text
    assert "valid: air.mean_free_path > 0 m" in text
    # the paper's Couette shear has its own floor: still a case
    assert Case().updated({"air.mean_free_path": 0.0, "air.roughness_flow": "none"})
    assert Case().updated({"air.mean_free_path": 0.0, "model.physics": "paper"})


def test_overrides_that_mend_a_case_file_apply(tmp_path):
    """A --set that makes a file's case valid must be applied, not refused with the file's
    own error; a bad override still names itself, not the file."""
    path = tmp_path / "c.toml"
    path.write_text('[air]\nmean_free_path = 0.0\n')
    with pytest.raises(InputError, match="air.mean_free_path = 0 m"):
        load_case(path)
    case = load_case(path, {"air.roughness_flow": "none"})
    assert case.air.mean_free_path == 0.0 and case.air.roughness_flow == "none"
    with pytest.raises(InputError) as err:
        load_case(tmp_path / "c.toml", {"air.roughness_flow": "none", "web.tension": -1.0})
    assert "web.tension" in str(err.value) and "c.toml" not in str(err.value)
    # an alias in the file and its key in the override (or the other way) are one key
    thick = tmp_path / "thick.toml"
    thick.write_text('[roller]\ndiameter = 0.002\n[web]\nthickness = 0.0005\n')
    with pytest.raises(InputError, match="t/\\(2R\\)"):
        load_case(thick)
    assert load_case(thick, {"roller.radius": 0.05}).roller.radius == 0.05
    assert load_case(thick, {"roller.diameter": 0.1}).roller.radius == 0.05
    # the file's own fault, with a harmless override, still names the file
    with pytest.raises(InputError, match="c.toml"):
        load_case(path, {"roller.speed": 5.0})


def test_the_valley_shear_bound_without_a_cut_off_is_infinite_and_silent():
    import warnings

    from webfem.physics.friction import valley_shear_bound
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert valley_shear_bound(4e-6, 0.0) == np.inf


def test_series_may_mend_a_base_case_refused_alone(tmp_path):
    """A sweep whose top-level case is refused alone (no mean free path through the
    roughness) but whose every series mends it loads (it did before that check existed);
    a series that does not mend it is refused naming the series."""
    path = tmp_path / "s.toml"
    path.write_text('[air]\nmean_free_path = 0.0\n[sweep]\nparameter = "roller.speed"\n'
                    'values = [10.0, 20.0]\n[[series]]\nlabel = "paper"\n'
                    'model = {physics = "paper"}\n[[series]]\nlabel = "no flow"\n'
                    'air = {roughness_flow = "none"}\n')
    sweep = load_sweep(path)
    assert [label for label, _ in sweep.series] == ["paper", "no flow"]
    path.write_text(path.read_text().replace('air = {roughness_flow = "none"}',
                                             'web = {tension = 90.0}'))
    with pytest.raises(InputError) as err:
        load_sweep(path)
    text = str(err.value)
    assert "air.mean_free_path = 0 m" in text and text.count("s.toml") == 1
    assert "(series 'no flow')" in text


def test_a_sweep_files_own_error_is_not_blamed_on_a_series(tmp_path):
    path = tmp_path / "t.toml"
    path.write_text('[roller]\nspeeed = 3\n[sweep]\nparameter = "roller.speed"\n'
                    'values = [1.0, 2.0]\n[[series]]\nlabel = "paper"\n'
                    'model = {physics = "paper"}\n')
    with pytest.raises(InputError) as err:
        load_sweep(path)
    assert "roller.speeed" in str(err.value) and "series" not in str(err.value)
