"""Bad inputs beyond the case keys: sweep tables and respacing, case files on the command
line, mesh files, model options; validity warnings."""

import warnings

import pytest

import webfem
from webfem import Case
from webfem.sweepspec import Sweep, load_sweep
from webfem.cli import main
from webfem.errors import InputError, ValidityWarning


def test_mesh_file_missing_or_not_a_mesh(tmp_path):
    with pytest.raises(InputError, match="mesh file '.*nothere.vtu' does not exist"):
        webfem.solve(Case(), model="fe1d", mesh=tmp_path / "nothere.vtu")
    bad = tmp_path / "bad.vtu"
    bad.write_text("this is not a mesh")
    with pytest.raises(InputError, match="is not a mesh meshio can read"):
        webfem.solve(Case(), model="fe1d", mesh=bad)


def test_mesh_file_is_used(capsys):
    """A stored mesh (fe2d's start mesh of the case, meshes/) gives the answer of the
    generated one within their stated errors: the two are refined apart (with the web held
    through its spans, the generated one is bisected once more)."""
    a = webfem.solve(Case(), model="fe1d", mesh="meshes/base_web.vtu")
    b = webfem.solve(Case(), model="fe1d")
    change = abs(a["h_center"] - b["h_center"]) / b["h_center"]
    assert 0.0 < change <= max(a["error_h_center"], b["error_h_center"])
    assert a["mesh"].startswith("user mesh")


def test_mesh_not_covering_the_wrap(tmp_path):
    import meshio
    import numpy as np
    x = np.linspace(-0.01, 0.01, 20)   # shorter than the wrap (57.6 mm)
    meshio.write(tmp_path / "short.vtu", meshio.Mesh(
        np.column_stack([x, 0 * x, 0 * x]), [("line", np.column_stack([np.arange(19),
                                                                        np.arange(1, 20)]))]))
    with pytest.raises(InputError, match="does not cover the wrap"):
        webfem.solve(Case(), model="fe1d", mesh=tmp_path / "short.vtu")


def test_validity_warnings(flying):
    with pytest.warns(ValidityWarning, match="outside Eq. 21"):
        webfem.solve(flying.updated({"web.width": 0.02}),
                     model="closed-form")
    with pytest.warns(ValidityWarning, match="incompressible film"):
        webfem.solve(flying.updated({"web.tension": 150.0}),
                     model="fe1d", compressible=False)
    with pytest.warns(ValidityWarning, match="closed form leaves out bending"):
        webfem.solve(flying, model="closed-form")
    with warnings.catch_warnings():
        warnings.simplefilter("error", ValidityWarning)
        r = webfem.solve(Case().updated({"roller.speed": 40.0,     # inside every range
                                         "model.physics": "paper"}),
                         model="closed-form")
    assert list(r["warnings"]) == []


def test_cli_bad_option_exit_code(capsys):
    assert main(["solve", "cases/base.toml", "--model", "fe1d", "--opt", "method=secant"]) == 2
    assert "method = 'secant'" in capsys.readouterr().err
    assert main(["solve", "cases/base.toml", "--model", "fe1d", "--opt", "mesh=none.vtu"]) == 2
    assert "does not exist" in capsys.readouterr().err


def test_unconverged_solve_exits_3_and_writes_marked_vtu(tmp_path, capsys):
    code = main(["solve", "cases/base.toml", "--model", "fe1d", "--opt", "max_iter=1",
                 "--opt", "adapt=0", "--json", "--vtu", str(tmp_path)])
    assert code == 3
    out = capsys.readouterr()
    assert '"converged": false' in out.out
    assert list(tmp_path.glob("*NOT_CONVERGED*_web.vtu"))


# -- [sweep] and [[series]] tables: strict types, counts and spacing -------------------

BIG = "1" + "0" * 400   # a TOML integer beyond float range


def _series(n, label="s{}"):
    return "".join(f'[[series]]\nlabel = "{label.format(i)}"\n' for i in range(n))


BAD_SWEEPS = [
    ('values = "12"', ["sweep.values = '12'", "list of numbers"]),
    ("values = [true, 2]", ["sweep.values item 1 = True", "not a number"]),
    ('values = ["a"]', ["sweep.values item 1 = 'a'", "not a number"]),
    ("values = 5", ["sweep.values = 5", "list of numbers"]),
    ("values = []", ["sweep.values holds 0", "1 to 10000"]),
    ("values = [1, 2, 1.0]", ["sweep.values holds 1 twice"]),
    ("values = [1, nan]", ["sweep.values item 2 = nan", "finite"]),
    (f"values = [{BIG}]", ["sweep.values item 1 = 1.00e+400", "out of range"]),
    ("values = [" + ", ".join(map(str, range(1, 10_002))) + "]",
     ["sweep.values holds 10001", "1 to 10000"]),
    ("values = [-1, 2]", ["roller.speed = -1", ">= 0", "series 'base'"]),
    ("values = [1, 2]\nnum = 3", ["sweep.values and sweep.num", "cannot be combined"]),
    ("start = 1\nstop = 2\nnum = 2.7", ["sweep.num = 2.7", "whole number", "1 to 10000"]),
    ('start = 1\nstop = 2\nnum = "x"', ["sweep.num = 'x'", "whole number"]),
    ("start = 1\nstop = 2\nnum = 1e11", ["sweep.num = 100000000000.0", "whole number"]),
    ("start = 1\nstop = 2\nnum = 100000000000", ["sweep.num = 100000000000", "out of range",
                                                  "1 to 10000"]),
    ("start = 1\nstop = 2\nnum = 0", ["sweep.num = 0", "out of range"]),
    ("start = 1\nstop = 2\nnum = true", ["sweep.num = True", "whole number"]),
    ('start = 0\nstop = 2\nspacing = "log"', ["sweep.spacing = 'log'", "sweep.start = 0",
                                              "> 0"]),
    ('start = 1\nstop = 2\nspacing = "cubic"', ["sweep.spacing = 'cubic'", "'linear' or 'log'"]),
    ('start = "a"\nstop = 2', ["sweep.start = 'a'", "not a number"]),
    ("start = 1\nstop = nan", ["sweep.stop = nan", "finite"]),
    (f"start = 1\nstop = {BIG}", ["sweep.stop = 1.00e+400", "out of range"]),
    ("start = 1\nnum = 3", ["needs 'values' or 'start' and 'stop'"]),
    ("start = 5\nstop = 5\nnum = 3", ["sweep.start = sweep.stop = 5", "num = 1"]),
    ("parameter = 5\nvalues = [1]", ["sweep.parameter = 5", "case key"]),
    ('parameter = "friction.variant"\nvalues = [1]', ["sweep.parameter = 'friction.variant'",
                                                      "not a numeric key", "roller.speed"]),
    ('parameter = "roller.sped"\nvalues = [1]', ["roller.sped", "did you mean 'roller.speed'"]),
    ("nmu = 4\nvalues = [1]", ["sweep.nmu", "did you mean 'num'"]),
    ("values = [1]\n" + _series(2, "a"), ["series label 'a' is used twice", "series 1 and 2"]),
    ('values = [1]\n[[series]]\nlabel = ""', ["series label = ''", "non-empty"]),
    ("values = [1]\n[[series]]\nlabel = 5", ["series label = 5", "non-empty"]),
    ("values = [1]\n" + _series(101), ["[[series]]", "101 tables", "at most 100"]),
    ('values = [1]\n[[series]]\nlabel = "a"\nroller = { speed = 3 }',
     ["roller.speed = 3", "series 'a'", "swept parameter"]),
    ('values = [1]\n[[series]]\nlabel = "a"\nweb = { tension = -1 }',
     ["web.tension = -1.0", "> 0", "series 'a'"]),
    ("values = [" + ", ".join(map(str, range(1, 2001))) + "]\n" + _series(51),
     ["2000 values x 51 series = 102000 points", "at most 100000"]),
]


@pytest.mark.parametrize("body,words", BAD_SWEEPS, ids=[w[0] for _, w in BAD_SWEEPS])
def test_bad_sweep_table_names_key_value_and_rule(tmp_path, body, words):
    p = tmp_path / "s.toml"
    head, _, tail = body.partition("[[series]]")
    p.write_text("[sweep]\n" + head + ("\n[[series]]" + tail if tail else ""))
    with pytest.raises(InputError) as err:
        load_sweep(p)
    msg = str(err.value)
    assert "\n" not in msg and "s.toml" in msg
    for w in words:
        assert w in msg


@pytest.mark.parametrize("text,words", [
    ("sweep = 5\n", ["sweep = 5 in", "[sweep] table"]),
    ("series = 5\n", ["series = 5 in", "[[series]]"]),
    ("series = [1]\n", ["series = [1] in", "[[series]]"]),
])
def test_sweep_and_series_must_be_tables(tmp_path, text, words):
    p = tmp_path / "s.toml"
    p.write_text(text)
    with pytest.raises(InputError) as err:
        load_sweep(p)
    for w in words:
        assert w in str(err.value)


def test_good_sweeps_read_as_before(tmp_path):
    p = tmp_path / "s.toml"
    p.write_text('[sweep]\nstart = 1\nstop = 100\nnum = 3\nspacing = "log"\n')
    assert load_sweep(p).values == (1.0, 10.0, 100.0)
    p.write_text("[sweep]\nstart = 40\nstop = 0.5\n")          # downward, num defaults to 40
    values = load_sweep(p).values
    assert len(values) == 40 and values[0] == 40.0 and values[-1] == 0.5
    p.write_text('[[series]]\nweb = { tension = 40 }\n[[series]]\nlabel = "b"\n')
    s = load_sweep(p)                                           # no [sweep]: the paper's range
    assert s.parameter == "roller.speed" and len(s.values) == 60
    assert [label for label, _ in s.series] == ["series 1", "b"]
    assert load_sweep(p, {"web.width": 0.05}).series[0][1].web.width == 0.05
    with pytest.raises(InputError, match="roller.speed = 5.*swept parameter"):
        load_sweep(p, {"roller.speed": 5})


# -- Sweep.respaced: the command line's --num and --log ---------------------------------
def _sweep(values, **case):
    return Sweep("roller.speed", values, (("a", Case().updated(case)),))


def test_respaced_same_range():
    s = _sweep([5.0, 1.0, 3.0])
    assert s.respaced(3).values == (1.0, 3.0, 5.0)
    assert s.respaced(3, log=True).values == pytest.approx((1.0, 5 ** 0.5, 5.0), rel=1e-15)
    assert s.respaced(1).values == (1.0,)
    assert s.respaced(None) is s
    assert s.respaced(4).series == s.series


@pytest.mark.parametrize("num,log,words", [
    (None, True, ["--log needs --num"]),
    (2.7, False, ["--num = 2.7", "whole number", "1 to 10000"]),
    ("x", False, ["--num = 'x'", "whole number"]),
    (True, False, ["--num = True", "whole number"]),
    (0, False, ["--num = 0", "out of range", "1 to 10000"]),
    (10_001, False, ["--num = 10001", "out of range"]),
])
def test_respaced_rejects_bad_num(num, log, words):
    with pytest.raises(InputError) as err:
        _sweep([1.0, 2.0]).respaced(num, log=log)
    for w in words:
        assert w in str(err.value)


def test_respaced_log_needs_positive_range_and_a_range():
    with pytest.raises(InputError, match=r"--log needs values > 0.*roller.speed = 0 \.\. 4"):
        _sweep([0.0, 4.0], **{"web.speed": 1.0}).respaced(5, log=True)
    with pytest.raises(InputError, match="one value roller.speed = 2"):
        _sweep([2.0]).respaced(5)


def test_sweep_checked_on_creation():
    s = Sweep("roller.speed", [1, 2], [("a", Case())])
    assert s.values == (1.0, 2.0) and isinstance(s.series, tuple)
    with pytest.raises(InputError, match="must hold a webfem.case.Case"):
        Sweep("roller.speed", [1.0], [("a", {"web": {}})])
    with pytest.raises(InputError, match="a sweep has 0 series"):
        Sweep("roller.speed", [1.0], [])


@pytest.mark.parametrize("command,content,words", [
    ("sweep", b'[sweep]\nvalues = "12"\n', ["sweep.values = '12'"]),
    ("sweep", b"[sweep]\nvalues = [1, 1]\n", ["sweep.values holds 1 twice"]),
    ("sweep", b"[sweep]\nstart = 1\nstop = 2\nnum = 1e11\n", ["sweep.num"]),
    ("solve", b"[web]\n# caf\xe9\n", ["not UTF-8"]),
    ("solve", None, ["is a directory"]),
    ("solve", b"[roller]\nspeed = 1" + b"0" * 400 + b"\n", ["roller.speed", "out of range"]),
])
def test_cli_bad_case_file_exits_2_without_traceback(tmp_path, capsys, command, content, words):
    p = tmp_path / "s.toml"
    if content is None:
        p.mkdir()
    else:
        p.write_bytes(content)
    assert main([command, str(p), "--out", str(tmp_path / "out"), "--quiet"]
                if command == "sweep" else [command, str(p)]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1
    for w in words:
        assert w in err


# -- model options: a name of another model says whose it is (issue 20) -------------------

@pytest.mark.parametrize("model,name,words,never", [
    ("fe1d", "symmetry", ["unknown fe1d option 'symmetry' (--opt): it is an option of fe2d "
                          "and auto, not of fe1d",
                          "--model fe2d"], "did you mean"),
    ("closed-form", "level", ["unknown closed-form option 'level' (--opt): it is an option "
                              "of fe1d, fe2d and auto, not of closed-form",
                              "closed-form options: n_points"], "did you mean"),
    ("fe2d", "quantity", ["is an option of auto, not of fe2d"], None),
    ("fe1d", "nodes", ["'nodes' (--opt) is set from Python only"], "did you mean"),
    ("fe1d", "levle", ["unknown fe1d option 'levle' (--opt); did you mean 'level'?"], None),
])
def test_option_of_another_model_names_its_model(model, name, words, never):
    from webfem.models.registry import model_spec
    with pytest.raises(InputError) as err:
        model_spec(model).options.from_strings([f"{name}=1"])
    msg = str(err.value)
    for w in words:
        assert w in msg, msg
    assert never is None or never not in msg, msg


def test_option_of_another_model_through_the_api():
    with pytest.raises(InputError, match=r"unknown fe1d option 'symmetry': it is an option "
                                         r"of fe2d and auto, not of fe1d: give it with that "
                                         r"model \(model='fe2d'\)"):
        webfem.solve(Case(), model="fe1d", symmetry=False)


def test_cli_set_a_section_and_opt_of_another_model(capsys):
    assert main(["solve", "cases/base.toml", "--set", "web=80"]) == 2
    err = capsys.readouterr().err
    assert "'web' (--set) is a section, not a key" in err and "did you mean" not in err
    assert main(["solve", "cases/base.toml", "--model", "fe1d", "--opt", "symmetry=false"]) == 2
    err = capsys.readouterr().err
    assert "an option of fe2d and auto, not of fe1d" in err and "did you mean" not in err


def test_case_error_is_only_an_old_name_for_input_error():
    """``CaseError`` stays importable for users' scripts (webfem, webfem.case,
    webfem.errors) as the very class ``InputError``; webfem itself raises, catches and
    names ``InputError`` only (issue 21)."""
    import ast
    from pathlib import Path

    import webfem.case
    import webfem.errors
    assert webfem.CaseError is webfem.case.CaseError is webfem.errors.CaseError is InputError
    package = Path(webfem.__file__).parent
    # re-exports are imports, not uses: only the alias's own line stores the name
    uses = [f"{path.relative_to(package)}:{node.lineno}"
            for path in sorted(package.rglob("*.py"))
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
            if isinstance(node, ast.Name) and node.id == "CaseError"
            and isinstance(node.ctx, ast.Load)]
    assert not uses, f"CaseError used in {uses}"


def test_sweeps_are_where_users_are_told():
    """``webfem.Sweep`` and ``webfem.load_sweep`` (README, examples) are webfem.sweepspec's;
    webfem.case no longer loads them (the two modules imported each other), and says where
    they are."""
    import webfem.case
    import webfem.sweepspec
    assert webfem.Sweep is webfem.sweepspec.Sweep
    # webfem.load_sweep takes a bundled case's name too: webfem.sweepspec's on the file
    import webfem.bundled
    assert webfem.load_sweep is webfem.bundled.load_sweep
    assert webfem.load_sweep("fig10_wrap") == webfem.sweepspec.load_sweep(
        webfem.bundled.find_case("fig10_wrap"))
    with pytest.raises(AttributeError, match="webfem.case.Sweep is webfem.sweepspec.Sweep"):
        webfem.case.Sweep
