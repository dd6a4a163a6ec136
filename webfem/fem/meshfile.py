"""Reading user meshes (input, like a case file): the x nodes of a web line (or film) mesh file, via meshio."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import InputError

__all__ = ["read_x_nodes"]


def read_x_nodes(path) -> np.ndarray:
    """Distinct x coordinates [m] of the points of a mesh file (any format meshio reads).

    Raises :class:`webfem.case.CaseError` naming the file when it does not exist, is not a
    mesh, or has fewer than 3 distinct x positions.
    """
    import meshio

    path = Path(path)
    if not path.is_file():
        raise InputError(f"mesh file '{path}' does not exist")
    try:
        mesh = meshio.read(path)
    except (Exception, SystemExit) as err:  # meshio raises many kinds (even SystemExit)
        raise InputError(f"mesh file '{path}' is not a mesh meshio can read: {err}") from None
    x = np.unique(np.round(np.asarray(mesh.points, float)[:, 0], 15))
    if x.size < 3 or not np.all(np.isfinite(x)):
        raise InputError(f"mesh file '{path}' has {x.size} distinct finite x positions; "
                         "a web mesh needs at least 3")
    return x
