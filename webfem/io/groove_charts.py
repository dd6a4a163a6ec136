"""Charts of grooved-roller sizing (matplotlib, off screen): the traction map and the
traction-loss speed against groove geometry."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

from ..units import convert, unit_label  # noqa: E402
from .charts import save_figure  # noqa: E402

__all__ = ["groove_chart", "loss_speed_chart"]


def _rows(items) -> list[dict]:
    return [d.to_dict() if hasattr(d, "to_dict") else dict(d) for d in items]


def _sizes(units: str):
    """(unit of groove sizes, their formatter) in ``units``."""
    return unit_label("position", units), lambda v: f"{convert(v, 'position', units):.3g}"


def groove_chart(designs, mu_min: float, path, best: dict | None = None,
                 units: str = "si") -> Path:
    """Groove sizing map: mu against land fraction, one line per groove pitch (and depth),
    one panel per roller speed; the mu_min line, feasible designs filled, a flagged design
    (``flag``: the web sags into its grooves) open with a "!" in it, the best ringed,
    a design without an answer (not converged, no admissible solution) a cross on the
    bottom edge. The legend sits below the panels, clear of the data.

    ``designs``: :class:`webfem.groove_sizing.GrooveDesign` objects (or mappings with
    their keys); ``units``: of the pitch, depth and speed named in the legend and titles."""
    rows = _rows(designs)
    size, shown = _sizes(units)
    speeds = list(dict.fromkeys(r["speed"] for r in rows))
    keys = list(dict.fromkeys((r["pitch"], r["depth"]) for r in rows))
    colors = {key: f"C{k % 10}" for k, key in enumerate(keys)}
    # constrained layout keeps the axis label, the tick labels and the legend inside the
    # canvas; a single panel is widened so the legend's two columns fit beside each other
    fig, axes = plt.subplots(1, len(speeds), figsize=(max(8.0, 1.0 + 5.0 * len(speeds)), 5.4),
                             squeeze=False, sharey=True, layout="constrained")
    mus = [r["mu"] for r in rows if r["converged"]] + [mu_min]
    bottom = min(mus) - 0.06 * (max(mus) - min(mus) + 1e-3)
    for ax, speed in zip(axes[0], speeds):
        here = [r for r in rows if r["speed"] == speed]
        for key in keys:
            mine = sorted((r for r in here if (r["pitch"], r["depth"]) == key),
                          key=lambda r: r["land_fraction"])
            line = [r for r in mine if r["converged"]]
            x = [100 * r["land_fraction"] for r in line]
            y = [r["mu"] for r in line]
            ax.plot(x, y, "-", color=colors[key])
            ax.scatter(x, y, color=colors[key], zorder=3, s=46,
                       facecolors=[colors[key] if r["feasible"] else "white" for r in line])
            # a flagged design (its answer outside what the model computes) is open
            # whatever its mu: the mark says why
            for xi, r in zip(x, line):
                if r.get("flag"):
                    ax.annotate("!", (xi, r["mu"]), ha="center", va="center",
                                color=colors[key], fontsize=6.5, fontweight="bold",
                                zorder=5)
            failed = [100 * r["land_fraction"] for r in mine if not r["converged"]]
            if failed:
                # out of the layout: an unclipped mark (an empty one sits at the canvas's
                # corner) would make constrained layout shrink the panels to nothing
                ax.plot(failed, [bottom] * len(failed), "x", color=colors[key], ms=9, mew=2,
                        clip_on=False, zorder=4)[0].set_in_layout(False)
        b = (best or {}).get(speed)
        if b is not None:
            b = b.to_dict() if hasattr(b, "to_dict") else b
            ax.scatter([100 * b["land_fraction"]], [b["mu"]], s=180, facecolors="none",
                       edgecolors="k", zorder=4)
        ax.axhline(mu_min, color="k", ls="--", lw=1)
        ax.set_title(f"roller speed {speed:g} m/s ({60 * speed:.0f} m/min)" if units == "si"
                     else f"roller speed {convert(speed, 'speed', units):.4g} "
                          f"{unit_label('speed', units)}", fontsize=10)
        ax.set_xlabel("land fraction a / pitch [%]  (contact area)")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylim(bottom=bottom)
    axes[0][0].set_ylabel("mu [-]: wrap-averaged friction coefficient")
    handles = [Line2D([], [], color=colors[k], marker="o",
                      label=f"pitch {shown(k[0])} {size}, depth {shown(k[1])} {size}")
               for k in keys]
    handles += [Line2D([], [], color="k", ls="--", lw=1, label=f"mu_min = {mu_min:g}"),
                Line2D([], [], ls="none", marker="o", color="0.4", mfc="white",
                       label="open: mu < mu_min" + (", or flagged" if any(
                           r.get("flag") for r in rows) else "")),
                Line2D([], [], ls="none", marker="o", ms=13, mfc="none", color="k",
                       label="ringed: best (most land with mu >= mu_min)")]
    if any(r.get("flag") for r in rows):
        handles.append(Line2D([], [], ls="none", marker="$!$", color="0.4",
                              label="!: the web sags into its grooves:\nnot what fe2d "
                                    "computes (the CSV's flag)"))
    if any(not r["converged"] for r in rows):
        handles.append(Line2D([], [], ls="none", marker="x", mew=2, color="0.4",
                              label="x: no answer (see the CSV)"))
    ncol = 2 if len(speeds) == 1 else 3
    fig.legend(handles=handles, loc="outside lower center", ncol=ncol, fontsize=8,
               frameon=False)
    fig.suptitle("Grooved roller sizing (fe2d): filled points keep mu >= mu_min"
                 + (" and are within the model" if any(r.get("flag") for r in rows) else ""),
                 fontsize=11)
    return save_figure(fig, path)


def loss_speed_chart(losses, mu_min: float, path, speed_range, title: str = "",
                     units: str = "si") -> Path:
    """Traction-loss speed [m/s] against land fraction, one line per groove pitch (and
    depth), the smooth roller as a horizontal line; a right axis in m/min (in ft/min and
    the groove sizes in inches with ``units="us"``).

    ``losses``: :class:`webfem.groove_sizing.LossSpeed` objects (or mappings with their
    keys), the smooth roller's with pitch 0. A geometry whose mu stays above mu_min up to
    the top of ``speed_range`` is drawn as an upward triangle at that speed, one whose mu
    never reaches mu_min as a downward triangle at the bottom, a failed search as a cross
    on the bottom edge, a scan fe2d refused partway, before a crossing (``scan_limit``), as
    a diamond at the last speed it answered (``scanned_to``), off the lines: nothing is
    known above it; the triangles, diamonds and crosses of different pitches are set
    slightly apart so that none hides another.
    """
    rows = _rows(losses)
    size, shown = _sizes(units)
    lo, hi = (float(v) for v in speed_range)
    found = [r["speed"] for r in rows if r["converged"] and r["speed"] is not None]
    found += [r["scanned_to"] for r in rows if r["converged"] and r["speed"] is None
              and r.get("scan_limit") and r.get("scanned_to") is not None]
    bottom = min(found + [hi]) / 1.6
    fig, ax = plt.subplots(figsize=(6.8, 5.2))

    def where(r):
        if not r["converged"]:
            return bottom, "x"
        if r["speed"] is not None:
            return r["speed"], "o"
        if r.get("scan_limit") and r.get("scanned_to") is not None:
            return r["scanned_to"], "d"
        return (hi, "^") if "above" in r["message"] else (max(lo, bottom), "v")

    for r in rows:
        if r["pitch"] == 0.0 and r["converged"]:
            y, kind = where(r)
            text = (f"smooth roller: {y:.3g} m/s" if kind == "o" else
                    f"smooth roller: none up to {y:.3g} m/s, refused above" if kind == "d"
                    else f"smooth roller: {'above' if kind == '^' else 'below'} {y:g} m/s")
            ax.axhline(y, color="0.3", ls="--", lw=1.2, label=text)
    grooved = [r for r in rows if r["pitch"] > 0.0]
    keys = list(dict.fromkeys((r["pitch"], r["depth"]) for r in grooved))
    for k, key in enumerate(keys):
        line = sorted((r for r in grooved if (r["pitch"], r["depth"]) == key),
                      key=lambda r: r["land_fraction"])
        pts = [(100 * r["land_fraction"], *where(r)) for r in line]
        solved = [p for p in pts if p[2] not in ("x", "d")]
        (h,) = ax.plot([p[0] for p in solved], [p[1] for p in solved], "-",
                       label=f"pitch {shown(key[0])} {size}, depth {shown(key[1])} {size}")
        shift = 0.4 * (k - 0.5 * (len(keys) - 1))   # [% land]: capped markers side by side
        for x, y, m in pts:
            ax.plot([x + (shift if m != "o" else 0.0)], [y], m, color=h.get_color(),
                    ms=7 if m == "o" else 9, mew=2 if m == "x" else 1, zorder=3,
                    clip_on=False)
    ax.set_yscale("log")
    ax.set_ylim(bottom, hi * 1.3)
    ax.set_xlabel("land fraction a / pitch [%]  (contact area)")
    ax.set_ylabel("traction-loss speed U_r [m/s]")
    per = 1.0 / convert(1.0, "speed", "us" if units == "us" else "metric")
    right = ax.secondary_yaxis("right", functions=(lambda v: v / per, lambda v: v * per))
    right.set_ylabel(f"traction-loss speed [{'ft/min' if units == 'us' else 'm/min'}]")
    for axis in (ax.yaxis, right.yaxis):   # plain numbers (20, 50, 100), not 10^x
        axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        axis.set_minor_formatter(NullFormatter())
    ax.grid(alpha=0.3, which="both")
    ax.plot([], [], "^", color="0.4", ls="none", label=f"mu >= mu_min up to {hi:g} m/s")
    if any(where(r)[1] == "x" for r in grooved):
        ax.plot([], [], "x", color="0.4", ls="none", mew=2, label="search failed (see CSV)")
    if any(where(r)[1] == "d" for r in rows if r["converged"]):
        ax.plot([], [], "d", color="0.4", ls="none",
                label="refused partway: no loss speed up to\nthis speed (the CSV's scan_limit)")
    # below the axes: the data fill the plot from the smooth line up to the scan's top
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2,
              frameon=False)
    ax.set_title(title or f"Speed at which mu falls to mu_min = {mu_min:g} (fe2d)",
                 fontsize=10)
    fig.tight_layout()
    return save_figure(fig, path)
