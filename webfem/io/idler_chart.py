"""Chart of an idler's slip check against line speed (matplotlib, off screen)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..units import convert, display, unit_label  # noqa: E402
from .charts import display_values, save_figure  # noqa: E402

__all__ = ["idler_chart", "FLOOR"]

#: The slip margin axis's lowest floor: six decades below the slip line (a margin of 1e-6
#: is no traction at all; deeper decades would squash the ones that matter).
FLOOR = 1e-6


def idler_chart(curve, path, title: str = "", units: str = "si") -> Path:
    """Left: tension difference required and available against line speed; right: the slip
    margin (available / required, log scale) with the slip line at 1. ``curve`` is a
    :class:`webfem.idler.MarginCurve`; ``units``: of the speeds and tension differences."""
    u = display_values(curve.speeds, "speed", units)
    req = display_values(curve.delta_T_required, "tension", units)
    avail = display_values(curve.delta_T_available, "tension", units)
    speed, tension = unit_label("speed", units), unit_label("tension", units)
    margin = np.asarray(curve.slip_margin, float)
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.8), constrained_layout=True)
    a.plot(u, req, "k--", lw=1.2, label="required (drag + J a / R)")
    a.plot(u, avail, "o-", ms=3.5, label=f"available ({curve.answered()})")
    a.set_xlabel(f"line speed U_r = U_w [{speed}]")
    a.set_ylabel(f"tension difference delta_T [{tension}]")
    a.set_ylim(0.0, max(2.5 * req.max(), 1.05 * np.nanmax(avail[:1])))
    a.grid(True, alpha=0.3)
    a.legend(fontsize=8, loc="upper right")
    # the axis spans at most FLOOR..top: a margin of 1e-89 (a web floating clear of its
    # roller) would squash every other number onto one line; margins below the floor are
    # drawn on it as downward triangles and the note says how small they are
    floor = max(np.nanmin(margin) / 3, FLOOR) if np.isfinite(margin).any() else FLOOR
    top = max(3 * np.nanmax(margin), 10.0) if np.isfinite(margin).any() else 10.0
    below = np.isfinite(margin) & (margin < floor)
    b.semilogy(u, np.where(below, floor, margin), "-", color="C1")
    b.semilogy(u[~below], margin[~below], "o", ms=3.5, color="C1")
    if below.any():
        b.plot(u[below], np.full(below.sum(), floor), "v", ms=7, color="C1", clip_on=False,
               label=f"margin below {floor:.0e} (smallest {np.nanmin(margin):.2g}): "
                     "no traction to speak of")
        # clear of the triangles on the floor
        b.legend(fontsize=8, loc="lower right", bbox_to_anchor=(1.0, 0.07))
    b.axhline(1.0, color="k", lw=0.9)
    b.fill_between(u, floor, 1.0, color="C3", alpha=0.08)
    # slips / holds at the left edge, either side of the line; the slip speed's note at
    # the top of the panel, beside its line: they never meet, wherever the slip speed is
    edge = b.get_yaxis_transform()
    b.text(0.02, 0.8, "slips", color="C3", fontsize=8, va="top", transform=edge)
    b.text(0.02, 1.25, "holds", color="C2", fontsize=8, va="bottom", transform=edge)
    slip = curve.slip_speed()
    b.set_xlim(u[0] - 0.04 * (u[-1] - u[0]), u[-1] + 0.04 * (u[-1] - u[0]))
    extent = curve.slip_extent()
    if extent in ("every", "lowest"):   # no speed tried marks where it starts slipping
        b.annotate("slips at every speed shown" if extent == "every" else
                   "slips at the lowest speed shown", (0.02, 0.97), xycoords="axes fraction",
                   fontsize=8, color="C3", va="top", ha="left")
    elif slip is not None:
        at = convert(slip, "speed", units)
        b.axvline(at, color="C3", lw=0.8, ls=":")
        x0, x1 = b.get_xlim()
        right = (at - x0) < 0.6 * (x1 - x0)
        b.annotate(f"slips above {display(slip, 'speed', units, 3)}", (at, 0.97),
                   xycoords=b.get_xaxis_transform(), xytext=(4 if right else -4, 0),
                   textcoords="offset points", fontsize=8, color="C3", va="top",
                   ha="left" if right else "right")
    b.set_ylim(floor, top)
    b.set_xlabel(f"line speed U_r = U_w [{speed}]")
    b.set_ylabel("slip margin = available / required [-]")
    b.grid(True, which="both", alpha=0.3)
    if title:
        fig.suptitle(title, fontsize=10)
    return save_figure(fig, path)
