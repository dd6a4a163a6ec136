"""Small things a new user meets first: webfem.load_case takes a bundled case's name as
webfem.solve does, a misspelt case name gets a suggestion, and the README's case-file block
and VTU figure are what the code does and writes."""

import dataclasses
import re
from pathlib import Path

import numpy as np
import pytest

import webfem
from webfem.cli import main
from webfem.errors import InputError
from webfem.sections import Wrap

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text()


def test_load_case_and_sweep_take_bundled_names():
    assert webfem.load_case("base") == webfem.load_case(ROOT / "cases" / "base.toml")
    assert webfem.load_case("base", {"web.tension": 100.0}).web.tension == 100.0
    assert len(webfem.load_sweep("fig10_wrap").values) > 1


@pytest.mark.parametrize("name, meant", [("basee", "'base'"),
                                         ("cases/basee.toml", "'cases/base.toml'")])
def test_misspelt_case_name_suggests_the_closest(name, meant, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    with pytest.raises(InputError, match=f"did you mean {meant}"):
        webfem.load_case(name)
    assert main(["solve", name, "--model", "closed-form"]) == 2
    assert f"did you mean {meant}?" in capsys.readouterr().err


def test_readme_wrap_block_names_every_wrap_key_with_its_default():
    block = re.search(r"^\[wrap\](.*?)^\[air\]", README, re.S | re.M).group(1)
    for f in dataclasses.fields(Wrap):
        if f.name.startswith("_"):
            continue
        assert f.name in block
    assert f"default {Wrap().span:g}" in block and f'"{Wrap().ends}", the default' in block
    assert "left out" not in block


def test_readme_vtu_node_minimum_is_what_the_file_holds(tmp_path):
    meshio = pytest.importorskip("meshio")
    from webfem.io.vtu import write_result
    result = webfem.solve(ROOT / "cases" / "base.toml", model="fe2d")
    path = [p for p in write_result(result, tmp_path, "base") if p.name.endswith("_film.vtu")]
    data = meshio.read(path[0]).field_data
    nodes = float(np.ravel(data["h_min of the nodes in this file [m]"])[0])
    reported = float(np.ravel(data["h_min [m]"])[0])
    assert f"{nodes * 1e6:.4f} um at the nearest node, {reported * 1e6:.4f} um reported" \
        in " ".join(README.split())
