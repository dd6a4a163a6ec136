"""Chart of an idler's slip check against line speed (matplotlib, off screen)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..units import convert, display, unit_label  # noqa: E402
from .charts import display_values, save_figure  # noqa: E402

__all__ = ["idler_chart"]


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
    b.semilogy(u, np.maximum(margin, 1e-6), "o-", ms=3.5, color="C1")
    b.axhline(1.0, color="k", lw=0.9)
    b.fill_between(u, 1e-6, 1.0, color="C3", alpha=0.08)
    b.text(u[0], 0.5, "slips", color="C3", fontsize=8, va="top")
    b.text(u[0], 2.0, "holds", color="C2", fontsize=8, va="bottom")
    slip = curve.slip_speed()
    if curve.slip_extent() in ("every", "lowest"):   # no speed tried marks where it starts
        b.annotate("slips at the lowest speed tried", (u[0], 1.0), xytext=(6, 12),
                   textcoords="offset points", fontsize=8, color="C3")
    elif slip is not None:
        at = convert(slip, "speed", units)
        b.axvline(at, color="C3", lw=0.8, ls=":")
        b.annotate(f"slips above {display(slip, 'speed', units, 3)}", (at, 1.0), xytext=(6, 12),
                   textcoords="offset points", fontsize=8, color="C3")
    b.set_ylim(max(np.nanmin(margin) / 3, 1e-4), max(3 * np.nanmax(margin), 10.0))
    b.set_xlabel(f"line speed U_r = U_w [{speed}]")
    b.set_ylabel("slip margin = available / required [-]")
    b.grid(True, which="both", alpha=0.3)
    if title:
        fig.suptitle(title, fontsize=10)
    return save_figure(fig, path)
