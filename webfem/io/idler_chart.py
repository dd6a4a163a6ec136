"""Chart of an idler's slip check against line speed (matplotlib, off screen)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .charts import save_figure  # noqa: E402

__all__ = ["idler_chart"]


def idler_chart(curve, path, title: str = "") -> Path:
    """Left: tension difference required and available [N/m] against line speed [m/s];
    right: the slip margin (available / required, log scale) with the slip line at 1.
    ``curve`` is a :class:`webfem.idler.MarginCurve`."""
    u = np.asarray(curve.speeds, float)
    req, avail = np.asarray(curve.delta_T_required), np.asarray(curve.delta_T_available)
    margin = np.asarray(curve.slip_margin, float)
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.8), constrained_layout=True)
    a.plot(u, req, "k--", lw=1.2, label="required (drag + J a / R)")
    a.plot(u, avail, "o-", ms=3.5, label=f"available ({curve.model})")
    a.set_xlabel("line speed U_r = U_w [m/s]")
    a.set_ylabel("tension difference delta_T [N/m]")
    a.set_ylim(0.0, max(2.5 * req.max(), 1.05 * np.nanmax(avail[:1])))
    a.grid(True, alpha=0.3)
    a.legend(fontsize=8, loc="upper right")
    b.semilogy(u, np.maximum(margin, 1e-6), "o-", ms=3.5, color="C1")
    b.axhline(1.0, color="k", lw=0.9)
    b.fill_between(u, 1e-6, 1.0, color="C3", alpha=0.08)
    b.text(u[0], 0.5, "slips", color="C3", fontsize=8, va="top")
    b.text(u[0], 2.0, "holds", color="C2", fontsize=8, va="bottom")
    slip = curve.slip_speed()
    if slip is not None:
        b.axvline(slip, color="C3", lw=0.8, ls=":")
        b.annotate(f"slips above {slip:.3g} m/s", (slip, 1.0), xytext=(6, 12),
                   textcoords="offset points", fontsize=8, color="C3")
    b.set_ylim(max(np.nanmin(margin) / 3, 1e-4), max(3 * np.nanmax(margin), 10.0))
    b.set_xlabel("line speed U_r = U_w [m/s]")
    b.set_ylabel("slip margin = available / required [-]")
    b.grid(True, which="both", alpha=0.3)
    if title:
        fig.suptitle(title, fontsize=10)
    return save_figure(fig, path)
