"""The meshes the FE models start from, in metres (what ``webfem mesh`` writes).

The 1-D web mesh is graded towards the wrap edges and the exit constriction
(:func:`webfem.fem.mesh.graded_nodes`); the 2-D film mesh is its tensor product with nodes
across the width graded towards the web edge (:func:`webfem.fem.transfer.width_nodes`), or on
a grooved roller the nodes of the domain fe2d solves (:func:`webfem.models.fe2d.
width_nodes_of`: the periodic groove cell first under ``grooves = "auto"``). Both
are the meshes before the models refine where the film turns out thin, so they depend on the
case and the options only.

Examples
--------
>>> from webfem import Case
>>> from webfem.models.options import FE2DOptions
>>> x, z = start_meshes(Case(), FE2DOptions())
>>> bool(x[0] < 0 < x[-1]), float(z[0]), bool(abs(z[-1] - Case().web.width / 2) < 1e-12)
(True, 0.0, True)
"""

from __future__ import annotations

import numpy as np

from ..case import Case
from ..errors import InputError
from ..fem.mesh import graded_nodes
from ..fem.transfer import width_nodes
from . import fe2d
from .options import FE1DOptions, FE2DOptions

__all__ = ["start_meshes", "film_domain"]


def start_meshes(case: Case, options: FE1DOptions | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Node positions of the starting meshes: ``(x_nodes_m, z_nodes_m)``.

    ``x_nodes_m`` [m]: arc position along the web from the wrap centre, air dragged towards
    +x. ``z_nodes_m`` [m]: position across the width from the web's centre line (0 to L/2
    with ``symmetry``, else -L/2 to L/2); on a grooved roller across the domain fe2d solves
    (:func:`film_domain` says which: the periodic cell, 0 to pitch/2, under "auto").

    ``options``: an :class:`FE2DOptions` (``entry``, ``level``, ``symmetry``,
    ``width_fine``; default: fe2d's defaults); an :class:`FE1DOptions` sets the x nodes
    and leaves the width at fe2d's defaults. The options' bounds (``level`` at most 3 for
    fe2d) keep the meshes to a size that fits in memory.

    Raises
    ------
    InputError
        When the options name a user mesh (``mesh`` or ``nodes``): that mesh is the start.
    """
    opts = FE2DOptions() if options is None else options
    if not isinstance(opts, FE1DOptions):
        raise TypeError(f"options must be FE2DOptions or FE1DOptions, not {type(opts).__name__}")
    for name in ("mesh", "nodes"):
        if getattr(opts, name) is not None:
            raise InputError(f"{opts.model} option {name} is set: the starting mesh is then "
                             "the user's own; the graded meshes are written without it")
    width = opts if isinstance(opts, FE2DOptions) else FE2DOptions()
    X = graded_nodes(case.beta, opts.entry, level=opts.level)
    if case.grooved:
        Z = fe2d.width_nodes_of(case, width, *_grooved_domain(case, width))
    else:
        Z = width_nodes(case.lam, width.level, half=width.symmetry, fine=width.width_fine)
    return X * case.x_scale, Z * case.x_scale


def _grooved_domain(case: Case, options: FE2DOptions):
    """The groove pattern and the domain fe2d solves first: the one ``grooves`` names, and
    under "auto" the periodic cell (:func:`webfem.models.groove_domain.solve_grooved` solves
    it first, on every web, and answers with it or starts the strip or full width from it)."""
    pattern, domain = fe2d.groove_domain(case, options)
    return pattern, "cell" if options.grooves == "auto" else domain


def film_domain(case: Case, options: FE1DOptions | None = None) -> str:
    """What the film mesh of :func:`start_meshes` spans, in words (for ``webfem mesh``)."""
    opts = FE2DOptions() if options is None or not isinstance(options, FE2DOptions) \
        else options
    if not case.grooved:
        return ("the half width, the web's centre line to its edge" if opts.symmetry else
                "the full width, edge to edge")
    _, domain = _grooved_domain(case, opts)
    pitch_mm = case.roller.groove_pitch * 1e3
    if domain == "cell":
        return (f"the periodic groove cell, a land centre to a groove centre (0 to "
                f"{0.5 * pitch_mm:.4g} mm: half of one {pitch_mm:.4g} mm pitch; the web's "
                "edges left out)" + (", which grooves = auto solves first (--opt "
                                     "grooves=full or strip writes those)"
                                     if opts.grooves == "auto" else ""))
    if domain == "strip":
        return "the edge strip, a land centre to the web's edge (its outer lands and grooves)"
    return ("the grooved " + ("half width, the centre line to the edge" if opts.symmetry
                              else "full width, edge to edge") + ", with its edge lands")
