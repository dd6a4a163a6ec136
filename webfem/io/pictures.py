"""Pictures of the film (pyvista, off screen): pressure and gap over the wrap domain.

pyvista is imported only when a picture is asked for, so webfem imports without it. Each
picture is rendered to a hidden temporary name and renamed, so none is ever half written.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import InputError

__all__ = ["film_pictures"]


def film_pictures(result, folder, stem: str | None = None) -> list[Path]:
    """Render ``STEM_p.png`` (p - p_a) and ``STEM_h.png`` (gap) of a 2-D result; returns paths.

    Coordinates are drawn in millimetres, the gap in micrometres.
    """
    import pyvista as pv

    from .vtu import film_mesh

    if result.film is None:
        raise InputError(f"model {result['model']!r} has no 2-D film to draw: use fe2d")
    pv.OFF_SCREEN = True
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    stem = stem or result["model"]
    mesh = pv.from_meshio(film_mesh(result))
    case = result.case
    # the wrap and a few entry lengths either side: the far entry zones are nearly ambient
    reach = case.roller.radius * case.B / 2 + 4 * case.x_scale
    mesh = mesh.clip(normal="x", origin=(reach, 0, 0)).clip(normal="-x", origin=(-reach, 0, 0))
    if mesh.points[:, 1].min() >= 0.0:   # half width solved: mirror for the picture
        mesh = mesh.merge(mesh.reflect((0, 1, 0), point=(0, 0, 0)))
    mesh.points *= 1e3
    mesh.point_data["gap_um"] = mesh.point_data["h"] * 1e6
    out = []
    # the gap grows quadratically off the roller: cap its colour range at twice the gap at
    # the inlet edge so the film's structure in the wrap stays visible
    h_cap = 2e6 * max(result["h_inlet"], result["h_min"])
    for name, title, clim in (("p_rel", "p - p_a [Pa]", None),
                              ("gap_um", "h [um] (colours capped)", (0.0, h_cap))):
        plotter = pv.Plotter(off_screen=True, window_size=(1100, 500))
        plotter.add_mesh(mesh, scalars=name, cmap="viridis", clim=clim,
                         scalar_bar_args={"title": title})
        plotter.view_xy()
        plotter.add_text(f"{result['model']}: {title}; x (arc, air dragged to +x) and z "
                         "(width) in mm; wrap edges at x = -+RB/2", font_size=9)
        plotter.show_bounds(xtitle="x [mm]", ytitle="z [mm]", font_size=9, n_ylabels=3)
        plotter.reset_camera(bounds=mesh.bounds)
        plotter.camera.zoom(1.05)
        path = folder / f"{stem}_{'p' if name == 'p_rel' else 'h'}.png"
        tmp = path.with_name(f".tmp-{os.getpid()}-{path.name}")   # ends .png for VTK
        try:
            plotter.screenshot(str(tmp))
            os.replace(tmp, path)
        finally:
            plotter.close()
            if tmp.exists():
                tmp.unlink()
        out.append(path)
    return out
