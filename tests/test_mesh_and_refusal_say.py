"""`webfem mesh` writes the mesh of the model asked for (fe1d: its web mesh alone; the
closed form and the fitted model have none: refused), and a sweep refused for another
sweep's CSV names the case key that changed, with its old and new values."""

import pytest

from webfem import Case
from webfem.cli import main
from webfem.errors import InputError
from webfem.sweeps import run
from webfem.sweepspec import Sweep


@pytest.mark.parametrize("model", ("closed-form", "fitted"))
def test_mesh_of_a_model_without_one_is_refused(model, tmp_path, capsys):
    assert main(["mesh", "cases/base.toml", "--model", model, "--out", str(tmp_path)]) == 2
    assert f"--model {model} solves no mesh" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_mesh_of_fe1d_is_its_web_mesh_with_its_options(tmp_path, capsys):
    """fe1d at level 3: its own graded web, finer than fe2d's default, and no film."""
    import meshio
    assert main(["mesh", "cases/base.toml", "--model", "fe1d", "--opt", "level=3", "--out",
                 str(tmp_path / "a")]) == 0
    assert main(["mesh", "cases/base.toml", "--out", str(tmp_path / "b")]) == 0
    assert sorted(p.name for p in (tmp_path / "a").iterdir()) == ["base_web.vtu"]
    fine = meshio.read(tmp_path / "a" / "base_web.vtu").points
    coarse = meshio.read(tmp_path / "b" / "base_web.vtu").points
    assert len(fine) > len(coarse)
    assert fine[:, 0].min() == pytest.approx(coarse[:, 0].min())


def test_refused_sweep_names_the_changed_key(tmp_path):
    def spec(tension):
        return Sweep("roller.speed", (20.0, 30.0),
                     (("base", Case().updated({"web.tension": tension})),))
    run(spec(80.0), "closed-form", tmp_path / "s.csv")
    with pytest.raises(InputError, match=r"other case values \(web\.tension 80 -> 120\)"):
        run(spec(120.0), "closed-form", tmp_path / "s.csv")


def test_a_users_case_leaving_out_web_material_says_so(tmp_path, capsys):
    """A case file giving a 12 um film's thickness alone keeps newsprint's E_b, E_m,
    roughness and density: one line on stderr names them (not with --quiet, not for a
    bundled case, not when the file gives them all)."""
    path = tmp_path / "pet.toml"
    path.write_text("[web]\nthickness = 12e-6\npermeability = 0.0\n")
    args = ["solve", str(path), "--model", "closed-form"]
    assert main(args) == 0
    err = capsys.readouterr().err
    assert (f"webfem: {path} leaves out 4 of the web's 6 material keys, which take the "
            "base case's newsprint values: web.modulus_thickness = 175000 Pa, "
            "web.modulus_md = 4.46e+09 Pa, web.roughness = 4e-06 m, web.density = 650 "
            "kg/m^3") in err
    assert main(args + ["--set", "web.roughness=0.1 um", "--set", "web.density=1390",
                        "--set", "web.modulus_md=4.5e9", "--set",
                        "web.modulus_thickness=1e9"]) == 0
    assert "leaves out" not in capsys.readouterr().err
    assert main(args + ["--quiet"]) == 0
    assert "leaves out" not in capsys.readouterr().err
    assert main(["solve", "base", "--model", "closed-form"]) == 0   # no density: on purpose
    assert "leaves out" not in capsys.readouterr().err


def test_a_copy_of_a_bundled_case_is_not_told_it_leaves_out_its_web(tmp_path):
    """`webfem init idler` then `webfem solve idler.toml`: the copy's [web] table is the
    bundled one's, on purpose; only an edited one is a user's own web (the review found the
    line on every command in a fresh folder)."""
    from webfem.cli.common import defaults_note

    assert main(["init", "idler", str(tmp_path)]) == 0
    copy = tmp_path / "idler.toml"
    assert defaults_note(copy, {}) is None
    copy.write_text(copy.read_text().replace("[web]\n", "[web]\nthickness = 12e-6\n", 1))
    assert "5 of the web's 6 material keys" in defaults_note(copy, {})
