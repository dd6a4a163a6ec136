"""The stored meshes of meshes/ are what webfem generates for the cases."""

from pathlib import Path

import meshio
import numpy as np
import pytest

from webfem.cli import main

ROOT = Path(__file__).resolve().parents[1]
STORED = sorted((ROOT / "meshes").glob("*_film.vtu"))


@pytest.mark.parametrize("film", STORED, ids=[p.stem for p in STORED])
def test_stored_mesh_regenerates(film, tmp_path):
    stem = film.stem.removesuffix("_film")
    assert main(["mesh", str(ROOT / "cases" / f"{stem}.toml"), "--out", str(tmp_path)]) == 0
    for part in ("film", "web"):
        old = meshio.read(ROOT / "meshes" / f"{stem}_{part}.vtu")
        new = meshio.read(tmp_path / f"{stem}_{part}.vtu")
        assert np.allclose(old.points, new.points, rtol=1e-12, atol=1e-15)
        assert np.array_equal(old.cells[0].data, new.cells[0].data)


def test_meshes_are_stored():
    assert {p.stem for p in STORED} >= {"base_film", "fig10_wrap_film"}
