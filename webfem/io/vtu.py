"""VTU files for ParaView (meshio): the web as a polyline, the film as quadrilaterals.

Files are written to a temporary name in the target folder and renamed, so a failure never
leaves a half-written file. A sweep's files are tied together by a ``.pvd`` collection
indexed by the swept value.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from xml.sax.saxutils import quoteattr

import meshio
import numpy as np

__all__ = ["WEB_FIELDS", "FILM_FIELDS", "web_mesh", "film_mesh", "write_result", "write_pvd"]

#: Point data of the web polyline.
WEB_FIELDS = ("w", "h", "p_rel", "p", "p_contact", "chi_c", "mu", "regime", "in_wrap")
#: Point data of the film surface (2-D models).
FILM_FIELDS = ("p", "p_rel", "h", "p_contact", "chi_c", "mu", "regime")


def _atomic_write(mesh: meshio.Mesh, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.stem + ".", suffix=".vtu", dir=path.parent)
    os.close(fd)
    try:
        meshio.write(tmp, mesh, file_format="vtu")
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise
    return path


def web_mesh(result) -> meshio.Mesh:
    """The web as a polyline along x [m] with its fields (width-averaged film pressure)."""
    f = result.fields
    x = np.asarray(f["x"], float)
    pts = np.column_stack([x, np.zeros_like(x), np.zeros_like(x)])
    cells = [("line", np.column_stack([np.arange(x.size - 1), np.arange(1, x.size)]))]
    data = {k: np.asarray(f[k], float) for k in WEB_FIELDS if k in f}
    return meshio.Mesh(pts, cells, point_data=data)


def film_mesh(result) -> meshio.Mesh:
    """The film surface (x, z) [m] with its vertex fields."""
    film = result.film
    data = {k: np.asarray(film[k], float) for k in FILM_FIELDS if k in film}
    return meshio.Mesh(film["points"], [("quad", film["quads"])], point_data=data)


def write_result(result, folder, stem: str | None = None) -> list[Path]:
    """Write ``STEM_web.vtu`` (and ``STEM_film.vtu`` for 2-D models); returns the paths.

    An unconverged result is written with ``_NOT_CONVERGED`` in the names, for inspection.
    """
    folder = Path(folder)
    stem = stem or result["model"]
    if not result["converged"]:
        stem += "_NOT_CONVERGED"
    paths = [_atomic_write(web_mesh(result), folder / f"{stem}_web.vtu")]
    if result.film is not None:
        paths.append(_atomic_write(film_mesh(result), folder / f"{stem}_film.vtu"))
    return paths


def write_pvd(entries, path) -> Path:
    """A ParaView collection: ``entries`` are ``(value, file)`` pairs (files relative to the
    .pvd's folder or absolute); the swept value becomes the collection's time."""
    path = Path(path)
    lines = ['<?xml version="1.0"?>',
             '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
             "  <Collection>"]
    for value, file in entries:
        rel = os.path.relpath(Path(file), path.parent)
        lines.append(f'    <DataSet timestep="{float(value)!r}" part="0" file={quoteattr(rel)}/>')
    lines += ["  </Collection>", "</VTKFile>", ""]
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.stem + ".", suffix=".pvd", dir=path.parent)
    with os.fdopen(fd, "w") as fh:
        fh.write("\n".join(lines))
    os.replace(tmp, path)
    return path
