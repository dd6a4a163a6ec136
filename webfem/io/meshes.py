"""Mesh files: the starting meshes of a case as VTU (what ``webfem mesh`` writes).

``STEM_web.vtu`` is the web as a polyline of the x nodes (y = z = 0); ``STEM_film.vtu`` the
film as quadrilaterals over the x nodes times the width nodes, the width along y. All
coordinates are in metres: x is the arc position from the wrap centre (air dragged to +x),
y the position across the width from the web's centre line. The files say so themselves:
their field data name the coordinates (and, given the wrap's half length, where the wrap
ends), and point arrays ``"arc x [m]"`` (and ``"across width y [m]"``) plus ``in_wrap`` (1 on
the roller) let ParaView colour by them.

Files are written under a hidden temporary name in the target folder and renamed, so a
failure never leaves a half-written mesh, and created with the user's umask.

Examples
--------
>>> import tempfile, numpy as np
>>> with tempfile.TemporaryDirectory() as d:
...     paths = write_meshes(np.linspace(-1e-2, 1e-2, 5), np.linspace(0.0, 5e-3, 3), d, "demo")
...     [p.name for p in paths]
['demo_web.vtu', 'demo_film.vtu']
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .vtu import write_mesh

__all__ = ["web_line_mesh", "film_quad_mesh", "write_meshes", "write_web_mesh"]


#: What the coordinates mean (field data of every mesh file: the names carry the text).
COORDINATES = {"X = arc from the wrap centre [m], air dragged to +X": 0.0,
               "Y = across the width from the centre line [m] (film)": 0.0,
               "Z = 0 (the roller surface unrolled)": 0.0}


def _point_data(points, half_wrap):
    data = {"arc x [m]": points[:, 0].copy()}
    if np.any(points[:, 1]):
        data["across width y [m]"] = points[:, 1].copy()
    if half_wrap is not None:
        data["in_wrap"] = (np.abs(points[:, 0]) <= half_wrap * (1 + 1e-12)).astype(np.int32)
    return data


def web_line_mesh(x, half_wrap: float | None = None):
    """The web polyline: points (x, 0, 0) [m], one line cell per interval; ``half_wrap``
    (R B / 2 [m]) adds the in-wrap flag."""
    import meshio

    x = np.asarray(x, float)
    pts = np.column_stack([x, 0 * x, 0 * x])
    return meshio.Mesh(pts, [("line", np.column_stack([np.arange(x.size - 1),
                                                       np.arange(1, x.size)]))],
                       point_data=_point_data(pts, half_wrap))


def film_quad_mesh(x, z, half_wrap: float | None = None):
    """The film: points (x, z, 0) [m] of the tensor grid, counter-clockwise quadrilaterals."""
    import meshio

    x, z = np.asarray(x, float), np.asarray(z, float)
    xx, zz = np.meshgrid(x, z, indexing="ij")
    idx = np.arange(x.size * z.size).reshape(x.size, z.size)
    quads = np.column_stack([idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(),
                             idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()])
    pts = np.column_stack([xx.ravel(), zz.ravel(), 0 * xx.ravel()])
    return meshio.Mesh(pts, [("quad", quads)], point_data=_point_data(pts, half_wrap))


#: The film's Y on a periodic groove cell (field data, replacing :data:`COORDINATES`'s).
CELL_Y = ("Y = across one periodic groove cell from a land centre (0) to a groove centre "
          "(pitch/2) [m] (film; the web's edges left out)")


def write_meshes(x, z, folder, stem: str, half_wrap: float | None = None,
                 cell: bool = False) -> list[Path]:
    """Write ``STEM_web.vtu`` (nodes ``x`` [m]) and ``STEM_film.vtu`` (``x`` times the width
    nodes ``z`` [m]) into ``folder`` (created if missing); returns the two paths.

    ``half_wrap``: the wrap's half length R B / 2 [m], if known, adds the in-wrap flag and
    the wrap edges to the files. ``cell``: ``z`` spans a periodic groove cell, not the
    width (the field data say so)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    meaning = dict(COORDINATES)
    if cell:
        meaning = {(CELL_Y if k.startswith("Y =") else k): v for k, v in meaning.items()}
    if half_wrap is not None:
        meaning[f"wrap edges at X = -+{half_wrap:.6g} m (R B / 2)"] = float(half_wrap)
    return [write_mesh(web_line_mesh(x, half_wrap), folder / f"{stem}_web.vtu", meaning),
            write_mesh(film_quad_mesh(x, z, half_wrap), folder / f"{stem}_film.vtu", meaning)]


def write_web_mesh(x, folder, stem: str) -> Path:
    """Write ``STEM_web.vtu`` (nodes ``x`` [m]) alone into ``folder``: fe1d's mesh, which
    has no film across the width."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    return write_mesh(web_line_mesh(x), folder / f"{stem}_web.vtu", dict(COORDINATES))
