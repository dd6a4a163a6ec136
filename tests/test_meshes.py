"""The stored meshes of meshes/ are what ``webfem mesh CASE`` writes now, for every case of
cases/ (``make meshes`` writes them), and they are what meshes/README.md says they are."""

from pathlib import Path

import meshio
import numpy as np
import pytest

from webfem import load_case
from webfem.cli import main
from webfem.io.vtu import read_field_data

ROOT = Path(__file__).resolve().parents[1]
MESHES = ROOT / "meshes"
STEMS = sorted(p.stem for p in (ROOT / "cases").glob("*.toml"))
PARTS = ("web", "film")
#: Coordinates to 1e-12 of the mesh's extent: the grading (cumulative sums, interpolation)
#: may round differently on another platform, never by more.
RTOL = 1e-12
REMEDY = "the stored meshes are stale: run `make meshes`"

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")


def stored(name: str) -> meshio.Mesh:
    """``meshes/NAME`` (a clear failure when it is missing)."""
    if not (MESHES / name).is_file():
        pytest.fail(f"meshes/{name} is missing: {REMEDY}")
    return meshio.read(MESHES / name)


@pytest.fixture(scope="module")
def written(tmp_path_factory) -> Path:
    """What ``webfem mesh`` writes now for every case, in a temporary folder."""
    out = tmp_path_factory.mktemp("meshes")
    for stem in STEMS:
        assert main(["mesh", str(ROOT / "cases" / f"{stem}.toml"), "--out", str(out)]) == 0
    return out


def test_every_case_has_its_stored_meshes_and_no_other():
    stored = {p.name for p in MESHES.glob("*.vtu")}
    expected = {f"{stem}_{part}.vtu" for stem in STEMS for part in PARTS}
    assert stored == expected, (f"missing {sorted(expected - stored)}, without a case "
                                f"{sorted(stored - expected)}: {REMEDY}")


@pytest.mark.parametrize("part", PARTS)
@pytest.mark.parametrize("stem", STEMS)
def test_stored_mesh_is_what_webfem_writes_now(stem, part, written):
    """Node count, coordinates, cells, point arrays and the field data that says what the
    coordinates mean: each as ``webfem mesh`` writes it today."""
    name = f"{stem}_{part}.vtu"
    old, new = stored(name), meshio.read(written / name)
    assert len(old.points) == len(new.points), (
        f"{name}: {len(old.points)} nodes stored, {len(new.points)} written now: {REMEDY}")
    atol = RTOL * np.max(np.abs(new.points))
    assert np.allclose(old.points, new.points, rtol=0.0, atol=atol), f"{name}: {REMEDY}"
    assert [c.type for c in old.cells] == [c.type for c in new.cells]
    for a, b in zip(old.cells, new.cells):
        assert np.array_equal(a.data, b.data), f"{name}: cells differ: {REMEDY}"
    assert sorted(old.point_data) == sorted(new.point_data), f"{name}: {REMEDY}"
    for key, values in new.point_data.items():
        assert np.allclose(old.point_data[key], values, rtol=0.0, atol=atol), (name, key)
    assert read_field_data(MESHES / name) == read_field_data(written / name), name


@pytest.mark.parametrize("stem", STEMS)
def test_stored_meshes_are_what_the_readme_says(stem):
    """The web line: sorted nodes over the wrap plus 40 R eps^(1/3) each side, nodes on
    the wrap edges; the film: the web's nodes times nodes across the half width (a grooved
    roller's periodic cell, land centre to groove centre), one quadrilateral per pair of
    intervals. Checked on the files themselves, so a generator
    that went wrong with its stored copy would still be caught."""
    case = load_case(ROOT / "cases" / f"{stem}.toml")
    web, film = (stored(f"{stem}_{part}.vtu") for part in PARTS)
    x = web.points[:, 0]
    assert np.all(np.diff(x) > 0) and not np.any(web.points[:, 1:])
    half_wrap, entry = case.roller.radius * case.B / 2, 40.0 * case.x_scale
    assert x[0] == pytest.approx(-half_wrap - entry, rel=1e-12)
    assert x[-1] == pytest.approx(half_wrap + entry, rel=1e-12)
    for edge in (-half_wrap, half_wrap):
        assert np.min(np.abs(x - edge)) <= 1e-12 * half_wrap, f"no node at x = {edge:g} m"
    assert [c.type for c in web.cells] == ["line"] and len(web.cells[0].data) == x.size - 1
    y = np.unique(film.points[:, 1])
    assert np.array_equal(np.unique(film.points[:, 0]), x) and not np.any(film.points[:, 2])
    # a grooved roller's film: the periodic cell fe2d solves first (issue 38: it was the
    # smooth half width, a mesh no grooved solve uses)
    across = case.roller.groove_pitch if case.grooved else case.web.width
    assert y[0] == 0.0 and y[-1] == pytest.approx(across / 2, rel=1e-12)
    assert len(film.points) == x.size * y.size
    assert [c.type for c in film.cells] == ["quad"]
    assert len(film.cells[0].data) == (x.size - 1) * (y.size - 1)
