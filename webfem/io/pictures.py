"""Pictures of a solved film (matplotlib, off screen): one PNG, panels on a shared arc axis.

For a 2-D result (fe2d, or auto answering with it) the picture has three aligned panels:

a. the film pressure p - p_a over the arc x and the full width z, on a diverging colour map
   centred on 0 (red above ambient, blue below); a half-width solve is mirrored;
b. the gap h along the centre line against the regime levels h_c and 3 sigma, each labelled
   where its words cross no line of the panel (:func:`_level_labels`: the right end, the
   left, or along the wrap; in the panel's legend where nowhere is clear);
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
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from matplotlib.path import Path as LinePath  # noqa: E402
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


#: Where a level's label may sit, in the order tried: (x as a fraction of the axis, the
#: side of the text at it); each above its line, then below it. The ends first (the far
#: entry gaps are off the top there for most films), then along the wrap from the right.
LABEL_SPOTS = ((1.0, "right"), (0.0, "left"),
               *((f, "center") for f in (0.75, 0.6, 0.4, 0.25, 0.85, 0.15, 0.5)))


def _level_labels(ax, levels, curve) -> None:
    """Label each level ``(value, text, colour)`` of the gap axis ``ax`` (its line drawn)
    where its words touch no line of the panel: the gap ``curve`` ``(x, h)`` as drawn, the
    other level lines, the wrap edges, a legend or another label. Tried at
    :data:`LABEL_SPOTS`, above the line then below; a level with no clear spot is named in
    the panel's legend instead, as is a level at or below 0 (a web resting compressed),
    which a log axis cannot show. Positions are measured on the laid-out figure, so nothing
    drawn after this call may move the panel."""
    fig = ax.figure
    fig.draw_without_rendering()   # the layout, the limits and the pixel scale are final
    renderer = fig.canvas.get_renderer()
    x, h = curve
    ok = np.isfinite(x) & np.isfinite(h) & (h > 0)
    obstacles = [(LinePath(ax.transData.transform(np.column_stack([x[ok], h[ok]]))), False)]
    obstacles += [(LinePath(line.get_transform().transform(line.get_xydata())), False)
                  for line in ax.get_lines() if len(line.get_xydata()) == 2]
    # filled areas (the closed form's landed web): a label inside one is on the data too
    obstacles += [(p.transformed(c.get_transform()), True) for c in ax.collections
                  for p in c.get_paths()]
    # a web resting compressed (h_c < 0) has no place on a log axis: named in the legend
    # first, so the labels placed below keep clear of it
    _in_legend(ax, [(f"{text}: below 0, off the log axis", colour)
                    for value, text, colour in levels if value <= 0.0])
    taken = [ax.get_legend().get_window_extent(renderer)] if ax.get_legend() else []
    frame = ax.bbox
    unplaced = []
    for value, text, colour in levels:
        if value <= 0.0:
            continue
        own = ax.transData.transform((0.0, value))[1]
        for (fx, ha), va in ((spot, va) for spot in LABEL_SPOTS for va in ("bottom", "top")):
            label = ax.annotate(text, (fx, value), xycoords=("axes fraction", "data"),
                                xytext=({"left": 3, "right": -3}.get(ha, 0),
                                        1.5 if va == "bottom" else -1.5),
                                textcoords="offset points", ha=ha, va=va, fontsize=7,
                                color=colour)
            label.set_in_layout(False)
            box = label.get_window_extent(renderer).padded(1.0)
            inside = (frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0
                      and box.y1 <= frame.y1)
            # its own line runs just beside the box; every other line must miss it
            crossed = any(path.intersects_bbox(box, filled=filled)
                          for path, filled in obstacles if not _is_level(path, own))
            if inside and not crossed and not any(box.overlaps(t) for t in taken):
                taken.append(box)
                break
            label.remove()
        else:
            unplaced.append((text, colour))
    _in_legend(ax, unplaced)


def _in_legend(ax, named) -> None:
    """Name the levels ``named`` ``(text, colour)`` in the legend of ``ax``, beside what it
    names already (the landed web); "best" keeps it off the lines and labels drawn."""
    if not named:
        return
    handles, _ = ax.get_legend_handles_labels() if ax.get_legend() else ([], [])
    handles += [Line2D([], [], color=colour, lw=0.9, label=text) for text, colour in named]
    ax.legend(handles=handles, loc="best", fontsize=7, framealpha=0.9)


def _is_level(path, y) -> bool:
    """Whether ``path`` (display coordinates) is the horizontal line at height ``y``."""
    v = path.vertices
    return len(v) == 2 and abs(v[0, 1] - y) < 0.5 and abs(v[1, 1] - y) < 0.5


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
    levels = [level for level in levels if math.isfinite(level[0])]
    for value, _, colour in levels:
        if value > 0.0:
            ax.axhline(value, color=colour, lw=0.9, zorder=1)
    gap_axis, drawn = ax, (x[inside] * to_x, h[inside] * to_h)
    # a log axis: the landing zone (a few um) and the entry gaps (tens of um) both show
    shown = h[inside][h[inside] > 0] * to_h
    # the levels above 0 only: a web resting compressed (h_c < 0) has none on a log axis
    drawn_levels = [v for v in (s.h_c * to_h, 3 * s.sigma * to_h) if v > 0]
    low = max(min(drawn_levels + ([shown.min()] if shown.size else [])),
              0.1 * drawn_levels[0])
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
    # last: the labels are placed on the finished layout, clear of every line
    _level_labels(gap_axis, levels, drawn)
    return _save(fig, path)


def film_pictures(result, folder, stem: str | None = None, units: str = "si") -> list[Path]:
    """Write ``STEM_film.png`` (the panels of :func:`film_figure`, in ``units``) into
    ``folder``; returns ``[path]``. The file appears whole or not at all."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    stem = stem or result["model"]
    return [film_figure(result, folder / f"{stem}_film.png", units=units)]
