"""Bad inputs beyond the case keys: mesh files, model options; validity warnings."""

import warnings

import pytest

import webfem
from webfem import Case, CaseError
from webfem.cli import main
from webfem.errors import ValidityWarning


def test_mesh_file_missing_or_not_a_mesh(tmp_path):
    with pytest.raises(CaseError, match="mesh file '.*nothere.vtu' does not exist"):
        webfem.solve(Case(), model="fe1d", mesh=tmp_path / "nothere.vtu")
    bad = tmp_path / "bad.vtu"
    bad.write_text("this is not a mesh")
    with pytest.raises(CaseError, match="is not a mesh meshio can read"):
        webfem.solve(Case(), model="fe1d", mesh=bad)


def test_mesh_file_is_used(capsys):
    """A stored mesh gives the answer of the generated one (it is the same mesh)."""
    a = webfem.solve(Case(), model="fe1d", mesh="meshes/base_web.vtu")
    b = webfem.solve(Case(), model="fe1d")
    assert a["h_center"] == pytest.approx(b["h_center"], rel=1e-9)
    assert a["mesh"].startswith("user line")


def test_mesh_not_covering_the_wrap(tmp_path):
    import meshio
    import numpy as np
    x = np.linspace(-0.01, 0.01, 20)   # shorter than the wrap (57.6 mm)
    meshio.write(tmp_path / "short.vtu", meshio.Mesh(
        np.column_stack([x, 0 * x, 0 * x]), [("line", np.column_stack([np.arange(19),
                                                                        np.arange(1, 20)]))]))
    with pytest.raises(CaseError, match="does not cover the wrap"):
        webfem.solve(Case(), model="fe1d", mesh=tmp_path / "short.vtu")


def test_validity_warnings():
    with pytest.warns(ValidityWarning, match="outside Eq. 21"):
        webfem.solve(Case().updated({"roller.speed": 40.0, "web.width": 0.02}))
    with pytest.warns(ValidityWarning, match="incompressible film"):
        webfem.solve(Case().updated({"roller.speed": 40.0, "web.tension": 200.0}),
                     model="fe1d", compressible=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ValidityWarning)
        r = webfem.solve(Case().updated({"roller.speed": 40.0}))   # inside every range
    assert r["warnings"] == []


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
