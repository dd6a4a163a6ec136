"""Pictures of a solved film (matplotlib, off screen): one PNG, panels on a shared arc axis.

For a 2-D result (fe2d, or auto answering with it) the picture has three aligned panels:

a. the film pressure p - p_a over the arc x and the full width z, on a diverging colour map
   centred on 0 (red above ambient, blue below); a half-width solve is mirrored;
b. the gap h along the centre line against the regime levels h_c and 3 sigma;
c. the local friction coefficient mu(x) in the wrap, over bands showing the local regime,
   and the headline mu as a dashed line: the wrap average where the web slides; where
   nothing slides (an idler) the traction available at the onset of slip, mu_onset, which
   the local friction at the stated speeds (the film's drag, near 0) does not average to.

Results without a film (closed form, fe1d) get panels b and c only. The wrap edges
x = -+RB/2 are marked in every panel; air is dragged towards +x. Coordinates are drawn in
millimetres, gaps in micrometres and pressures in Pa; with ``units="metric"`` pressures in
kPa, with ``units="us"`` coordinates in inches, gaps in mils and pressures in psi
(:data:`webfem.units.SYSTEMS`). Nothing here solves: it reads a :class:`~webfem.Result`.

Examples
--------
>>> import tempfile, webfem
>>> result = webfem.solve(webfem.Case(), model="closed-form")
>>> with tempfile.TemporaryDirectory() as d:
...     [p.name for p in film_pictures(result, d, "demo")]
['demo_film.png']
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import CenteredNorm  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from matplotlib.ticker import FormatStrFormatter, NullFormatter  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

from ..units import convert, unit_label  # noqa: E402
from ..describe import level_words  # noqa: E402
from .charts import level_text, save_figure  # noqa: E402

__all__ = ["film_pictures", "film_figure", "REGIME_COLOURS"]

# every picture is saved through this name (a test replaces it to look at the figure)
_save = save_figure

#: Regime code -> (name, band colour), codes as in :data:`webfem.physics.contact.REGIMES`.
REGIME_COLOURS = {0: ("boundary", "#f4a6a6"), 1: ("mixed", "#f9d98c"), 2: ("fluid", "#b9dcf2")}


def _reach(result) -> float:
    """Half the drawn arc [m]: the wrap and a few entry lengths either side (the far entry
    zones are nearly ambient and the gap there grows quadratically)."""
    case = result.case
    half = case.roller.radius * case.B / 2
    x = np.asarray(result.fields["x"], float)
    return min(half + 4.0 * case.x_scale, float(np.max(np.abs(x))))


def _full_width(film):
    """Vertices, triangles and p - p_a over the full width (mirrored when half was solved)."""
    pts = np.asarray(film["points"], float)
    quads = np.asarray(film["quads"], int)
    p = np.asarray(film["p_rel"], float)
    tri = np.vstack([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    if pts[:, 1].min() >= 0.0:   # half width solved: the other half is its mirror image
        n = len(pts)
        pts = np.vstack([pts, pts * [1.0, -1.0, 1.0]])
        tri = np.vstack([tri, tri[:, ::-1] + n])
        p = np.concatenate([p, p])
    return pts, tri, p


def _edges(ax, half, scale, label=False):
    """The wrap edges at x = -+``half`` [m] (drawn ``scale`` units per metre)."""
    for sign, name in ((-1, "inlet edge"), (1, "outlet edge")):
        ax.axvline(sign * half * scale, color="0.2", lw=0.8, ls=(0, (4, 2)))
        if label:
            ax.annotate(f"wrap {name}", (sign * half * scale, 1.0),
                        xycoords=("data", "axes fraction"),
                        xytext=(0, 3), textcoords="offset points", ha="center", va="bottom",
                        fontsize=7, color="0.2")


def _level(ax, value, text, colour):
    """A horizontal level with its label at the left (over the wide inlet gap), just above
    the line."""
    ax.axhline(value, color=colour, lw=0.9, zorder=1)
    ax.annotate(text, (0.0, value), xycoords=("axes fraction", "data"), xytext=(3, 1),
                textcoords="offset points", ha="left", va="bottom", fontsize=7, color=colour)


def _centre_line(result):
    """x and h along the centre line: the film's vertices nearest z = 0, else the web's."""
    film = result.film
    if film is None:
        return np.asarray(result.fields["x"], float), np.asarray(result.fields["h"], float)
    pts = np.asarray(film["points"], float)
    z0 = pts[np.argmin(np.abs(pts[:, 1])), 1]
    on = np.isclose(pts[:, 1], z0)
    order = np.argsort(pts[on, 0])
    return pts[on, 0][order], np.asarray(film["h"], float)[on][order]


def _regime_bands(ax, x, regime, inside, scale):
    """Background bands coloured by the local regime, inside the wrap only (x [m] drawn
    ``scale`` units per metre)."""
    x, regime = np.asarray(x, float), np.asarray(regime, int)
    idx = np.flatnonzero(inside)
    if idx.size == 0:
        return
    start = idx[0]
    for k in range(1, idx.size + 1):
        if k == idx.size or regime[idx[k]] != regime[start] or idx[k] != idx[k - 1] + 1:
            end = idx[k - 1]
            lo = x[start] if start == idx[0] else 0.5 * (x[start - 1] + x[start])
            hi = x[end] if end == idx[-1] else 0.5 * (x[end] + x[end + 1])
            ax.axvspan(lo * scale, hi * scale, color=REGIME_COLOURS[int(regime[start])][1],
                       lw=0, zorder=0)
            if k < idx.size:
                start = idx[k]


def _amount(value: float) -> str:
    """A pressure as labelled: whole numbers from 100 up (Pa), else 3 digits (kPa, psi)."""
    return f"{value:.0f}" if abs(value) >= 100 else f"{value:.3g}"


def film_figure(result, path, title: str | None = None, units: str = "si") -> Path:
    """Draw the panels described in the module docstring into ``path`` (PNG), in ``units``
    (si, metric or us); returns it."""
    s, case = result.summary, result.case
    # display units per SI unit (the conversions are linear)
    to_x, to_h = convert(1.0, "position", units), convert(1.0, "thin", units)
    to_p = convert(1.0, "pressure", units)
    x_unit, h_unit, p_unit = (unit_label(r, units) for r in ("position", "thin", "pressure"))
    half = case.roller.radius * case.B / 2
    reach = _reach(result)
    two_d = result.film is not None
    n = 3 if two_d else 2
    fig = plt.figure(figsize=(7.6, 2.35 * n + 0.5), layout="constrained")
    grid = fig.add_gridspec(n, 2, width_ratios=(1.0, 0.025),
                            height_ratios=(1.15, 1, 0.9)[-n:])
    axes = [fig.add_subplot(grid[0, 0])]
    axes += [fig.add_subplot(grid[i, 0], sharex=axes[0]) for i in range(1, n)]
    used = s.model_used or s.model
    fig.suptitle(title or f"{used}: film over the wrap (air dragged towards +x)", fontsize=10)

    if two_d:
        ax = axes[0]
        pts, tri, p = _full_width(result.film)
        # the suction peak past the outlet edge is several times the wrap pressure T/R:
        # cap the colours at 1.5 T/R so the film in the wrap keeps its shades
        scale = 1.5 * (s.T_eff or case.web.tension) / case.roller.radius
        capped = np.abs(p).max() > scale
        mesh = ax.tripcolor(Triangulation(pts[:, 0] * to_x, pts[:, 1] * to_x, tri),
                            np.clip(p, -scale, scale) * to_p, shading="gouraud", cmap="RdBu_r",
                            norm=CenteredNorm(0.0, halfrange=scale * to_p), rasterized=True)
        bar = fig.colorbar(mesh, cax=fig.add_subplot(grid[0, 1]),
                           extend="both" if capped else "neither")
        bar.set_label(f"p - p_a [{p_unit}]", fontsize=8)
        bar.ax.tick_params(labelsize=7)
        peaks = (f"; colours capped at 1.5 T/R, peaks {_amount(p.min() * to_p)} and "
                 f"{_amount(p.max() * to_p)} {p_unit}"
                 if capped else "")
        ax.set_ylabel(f"z across width [{x_unit}]")
        # the periodic groove cell, mirrored: a land in the middle, half a groove each side
        span = ("one groove pitch" if s.groove_domain and s.groove_domain.startswith(
            "periodic") else "full width")
        ax.set_title(f"a. film pressure above ambient, {span}{peaks}", fontsize=9,
                     loc="left", pad=12)
        _edges(ax, half, to_x, label=True)

    ax = axes[-2]
    x, h = _centre_line(result)
    inside = np.abs(x) <= reach * 1.02
    ax.plot(x[inside] * to_x, h[inside] * to_h, color="k", lw=1.4, label="gap h")
    # the words of the paper's regime by the gap: where h_c lies above 3 sigma there is no
    # mixed band, and "fluid above 3 sigma" under "boundary below h_c" would contradict
    words = level_words(s.h_c, s.sigma)
    levels = [(s.h_c * to_h, f"h_c = {level_text(s.h_c * to_h)} {h_unit} ({words[0]})",
               "tab:orange"),
              (3 * s.sigma * to_h, f"3 sigma = {level_text(3 * s.sigma * to_h)} {h_unit} "
               f"({words[1]})", "tab:blue")]
    for value, text, colour in levels:
        if math.isfinite(value):
            _level(ax, value, text, colour)
    # a log axis: the landing zone (a few um) and the entry gaps (tens of um) both show
    shown = h[inside][h[inside] > 0] * to_h
    low = max(min([s.h_c * to_h, 3 * s.sigma * to_h] + ([shown.min()] if shown.size else [])),
              0.1 * s.h_c * to_h)
    landed = inside & (h * to_h < 0.5 * low)
    if landed.any():   # the closed form lands the web (h = 0), which a log axis cannot show
        ax.fill_between(x * to_x, 0.5 * low, 4.0 * low, where=landed, color="0.6", lw=0,
                        label=f"web landed (h below {0.5 * low:.2g} {h_unit})")
        ax.legend(loc="upper right", fontsize=7, frameon=False)
    high = max([3 * s.sigma * to_h] + [v * to_h for v in (s.h_inlet, s.h_outlet)
                                      if math.isfinite(v)])
    ax.set_yscale("log")
    ax.set_ylim(0.5 * low, 4.0 * high)
    ax.set_yticks([t for t in (0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100,
                               200, 500, 1000)
                   if 0.5 * low <= t <= 4.0 * high])
    ax.yaxis.set_major_formatter(FormatStrFormatter("%g"))
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_ylabel(f"gap h [{h_unit}]")
    ax.set_title(f"{'b' if two_d else 'a'}. gap along the centre line (log scale; the far "
                 "entry gaps run off the top)", fontsize=9, loc="left",
                 pad=3 if two_d else 12)
    _edges(ax, half, to_x, label=not two_d)

    ax = axes[-1]
    f = result.fields
    x = np.asarray(f["x"], float)
    wrap = (np.asarray(f["in_wrap"]) > 0) if "in_wrap" in f else np.abs(x) <= half * (1 + 1e-9)
    if "regime" in f:
        _regime_bands(ax, x, f["regime"], wrap, to_x)
    local = np.asarray(f["mu"], float)[wrap] if "mu" in f else np.zeros(0)
    # where nothing slides (an idler, U_s = 0) the headline mu is the traction available at
    # the onset of slip (mu_cc x contact share), not the average of the local friction at
    # the stated speeds, which is the film's drag near 0: the line says which it is
    idle = s.get("mu_film") is not None
    said = (f"mu_onset = {s.mu:.3f}: traction available at the onset of slip "
            "(mu_cc x contact share)" if idle else f"wrap average mu = {s.mu:.3f}")
    curve = ("local friction at the stated speeds (nothing slides: the film's drag, wrap "
             f"average mu_film = {s.mu_film:.2g})" if idle else "local friction mu(x)")
    if local.size:
        ax.plot(x[wrap] * to_x, local, color="k", lw=1.3, label=curve)
    ax.axhline(s.mu, color="tab:red", lw=0.9, ls=(0, (5, 2)), label=said)
    # the labels go in a legend in head room above every line: none crosses a curve or
    # the panel's title
    top = max([s.mu, *(local[np.isfinite(local)] if local.size else [])])
    low = min([0.0, *(local[np.isfinite(local)] if local.size else [])])
    ax.set_ylim(low, low + 1.6 * (top - low) if top > low else 1.0)
    ax.legend(loc="upper left", fontsize=7, framealpha=0.9, borderaxespad=0.3)
    ax.set_ylabel("friction mu [-]")
    ax.set_xlabel(f"x along the arc from the wrap centre [{x_unit}]")
    # the regime is the paper's label by the gap; the contact model's load share is another
    # number (its asperity heights have no cut-off at 3 sigma): both named, so a fluid band
    # beside a mu carried by contact does not read as a contradiction
    share = s.get("contact_share")
    ax.set_title(f"{'c' if two_d else 'b'}. local friction and regime (by the gap) in the wrap"
                 + (f"; contact carries {100 * share:.1f} % of the wrap load"
                    if share is not None and math.isfinite(share) else ""),
                 fontsize=9, loc="left")
    handles = [Patch(color=c, label=name) for name, c in REGIME_COLOURS.values()]
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=7,
               title="regime bands", title_fontsize=7, frameon=False)
    _edges(ax, half, to_x)
    axes[0].set_xlim(-reach * to_x, reach * to_x)
    for a in axes:
        a.tick_params(labelsize=8)
        a.grid(True, alpha=0.25) if a is not axes[0] or not two_d else None
    for a in axes[:-1]:
        a.tick_params(labelbottom=False)
    return _save(fig, path)


def film_pictures(result, folder, stem: str | None = None, units: str = "si") -> list[Path]:
    """Write ``STEM_film.png`` (the panels of :func:`film_figure`, in ``units``) into
    ``folder``; returns ``[path]``. The file appears whole or not at all."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    stem = stem or result["model"]
    return [film_figure(result, folder / f"{stem}_film.png", units=units)]
