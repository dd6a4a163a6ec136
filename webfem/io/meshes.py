"""Mesh files: the starting meshes of a case as VTU (what ``webfem mesh`` writes).

``STEM_web.vtu`` is the web as a polyline of the x nodes (y = z = 0); ``STEM_film.vtu`` the
film as quadrilaterals over the x nodes times the width nodes, the width along y. All
coordinates are in metres: x is the arc position from the wrap centre (air dragged to +x),
y the position across the width from the web's centre line. (meshio's VTU writer drops
field data, so the meaning is stated here rather than in the files.)

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

from ..files import replacing

__all__ = ["web_line_mesh", "film_quad_mesh", "write_meshes"]


def web_line_mesh(x):
    """The web polyline: points (x, 0, 0) [m], one line cell per interval."""
    import meshio

    x = np.asarray(x, float)
    return meshio.Mesh(np.column_stack([x, 0 * x, 0 * x]),
                       [("line", np.column_stack([np.arange(x.size - 1),
                                                  np.arange(1, x.size)]))])


def film_quad_mesh(x, z):
    """The film: points (x, z, 0) [m] of the tensor grid, counter-clockwise quadrilaterals."""
    import meshio

    x, z = np.asarray(x, float), np.asarray(z, float)
    xx, zz = np.meshgrid(x, z, indexing="ij")
    idx = np.arange(x.size * z.size).reshape(x.size, z.size)
    quads = np.column_stack([idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(),
                             idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()])
    return meshio.Mesh(np.column_stack([xx.ravel(), zz.ravel(), 0 * xx.ravel()]),
                       [("quad", quads)])


def _write_atomic(mesh, path: Path) -> Path:
    import meshio

    with replacing(path) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")
    return path


def write_meshes(x, z, folder, stem: str) -> list[Path]:
    """Write ``STEM_web.vtu`` (nodes ``x`` [m]) and ``STEM_film.vtu`` (``x`` times the width
    nodes ``z`` [m]) into ``folder`` (created if missing); returns the two paths."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    return [_write_atomic(web_line_mesh(x), folder / f"{stem}_web.vtu"),
            _write_atomic(film_quad_mesh(x, z), folder / f"{stem}_film.vtu")]
