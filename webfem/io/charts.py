"""Charts in the style of the paper's Figs. 10-13 (matplotlib, off screen)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

__all__ = ["sweep_chart"]

_GAP_STYLES = (("h_inlet", "inlet", (0, (6, 2))), ("h_center", "centre", (0, (3, 2))),
               ("h_outlet", "exit", (0, (1, 1.5))))


def sweep_chart(rows: list[dict], path: str | Path, title: str = "",
                reference: list[dict] | None = None) -> Path:
    """mu against roller speed per series, with the gaps (dashed) on a second axis.

    ``reference``: rows of another model (the closed form beside an FE sweep), drawn as thin
    solid lines in the series' colours, mu only.

    The regime boundaries h = h_c and h = 3 sigma are drawn as grey horizontal lines on the
    gap axis (one per distinct value among the series).
    """
    series = list(dict.fromkeys(r["series"] for r in rows))
    fig, ax = plt.subplots(figsize=(7.5, 5.0), constrained_layout=True)
    ax2 = ax.twinx()
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    levels = {}
    for i, label in enumerate(series):
        sel = [r for r in rows if r["series"] == label]
        U = [r["value"] for r in sel]
        colour = colours[i % len(colours)]
        model = sel[0]["model"]
        ax.plot(U, [r["mu"] if r["converged"] else np.nan for r in sel], "-", color=colour,
                lw=1.8, label=f"{label} ({model})" if len(series) > 1 or reference
                else f"mu ({model})")
        bad = [r for r in sel if not r["converged"]]
        if bad:
            ax.plot([r["value"] for r in bad], [0.0] * len(bad), "x", color=colour,
                    label="not converged")
        for key, name, dash in _GAP_STYLES:
            ax2.plot(U, [r[key] * 1e6 for r in sel], linestyle=dash, color=colour, lw=1.0,
                     label=f"h {name}" if i == 0 else None)
        if reference:
            ref = [r for r in reference if r["series"] == label]
            ax.plot([r["value"] for r in ref], [r["mu"] for r in ref], "-", color=colour,
                    lw=0.9, alpha=0.6,
                    label=f"{label} ({ref[0]['model']})" if ref else None)
        levels.setdefault(round(sel[0]["h_c"] * 1e6, 3), "h = h_c")
        levels.setdefault(round(3 * sel[0]["sigma"] * 1e6, 3), "h = 3 sigma")
    for level, name in levels.items():
        ax2.axhline(level, color="0.55", lw=0.8, ls="-", zorder=0)
        ax2.annotate(f"{name} = {level:.2f} um", (0.01, level), xycoords=("axes fraction", "data"),
                     fontsize=7, color="0.35", va="bottom")
    ax.set_xlabel("roller speed U_r [m/s]" if rows[0]["parameter"] == "roller.speed"
                  else rows[0]["parameter"])
    ax.set_ylabel("friction coefficient mu [-]")
    ax2.set_ylabel("web spacing h [um] (dashed)")
    ax.set_ylim(0.0, max(0.4, 1.1 * max((r["mu"] for r in rows if isinstance(r["mu"], float)), default=0)))
    ax2.set_ylim(0.0, None)
    ax.grid(True, alpha=0.3)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=7, loc="upper right", ncol=2 if reference else 1)
    if title:
        ax.set_title(title, fontsize=10)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.stem, suffix=".png", dir=path.parent)
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=120)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise
    finally:
        plt.close(fig)
    return path
