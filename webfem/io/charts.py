"""Charts in the style of the paper's Figs. 10-13 (matplotlib, off screen)."""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..files import replacing

__all__ = ["sweep_chart", "traction_loss_chart", "calibration_chart"]

_GAP_STYLES = (("h_inlet", "inlet", (0, (6, 2))), ("h_center", "centre", (0, (3, 2))),
               ("h_outlet", "exit", (0, (1, 1.5))))


def _f(row: dict, key: str) -> float:
    """A row's number, NaN where it is missing (a failed point, a null in JSON or CSV)."""
    value = row.get(key)
    try:
        return float(value)
    except (TypeError, ValueError):
        return np.nan


def sweep_chart(rows: list[dict], path: str | Path, title: str = "",
                reference: list[dict] | None = None) -> Path:
    """mu against roller speed per series, with the gaps (dashed) on a second axis.

    ``reference``: rows of another model (the closed form beside an FE sweep), drawn as thin
    solid lines in the series' colours, mu only. Points that did not converge are marked x
    on the axis and left out of the lines.

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
        good = [r for r in sel if r.get("converged") is True]
        ok = [r.get("converged") is True for r in sel]
        U = [r["value"] for r in sel]
        colour = colours[i % len(colours)]
        model = sel[0]["model"]
        ax.plot(U, [_f(r, "mu") if k else np.nan for r, k in zip(sel, ok)], "-", color=colour,
                lw=1.8, label=f"{label} ({model})" if len(series) > 1 or reference
                else f"mu ({model})")
        bad = [r for r, k in zip(sel, ok) if not k]
        if bad:
            ax.plot([r["value"] for r in bad], [0.0] * len(bad), "x", color=colour,
                    label="not converged")
        for key, name, dash in _GAP_STYLES:
            ax2.plot(U, [_f(r, key) * 1e6 if k else np.nan for r, k in zip(sel, ok)],
                     linestyle=dash, color=colour, lw=1.0,
                     label=f"h {name}" if i == 0 else None)
        if reference:
            ref = [r for r in reference if r["series"] == label]
            ax.plot([r["value"] for r in ref], [_f(r, "mu") for r in ref], "-", color=colour,
                    lw=0.9, alpha=0.6,
                    label=f"{label} ({ref[0]['model']})" if ref else None)
        for key, factor, name in (("h_c", 1.0, "h = h_c"), ("sigma", 3.0, "h = 3 sigma")):
            known = [_f(r, key) for r in good if np.isfinite(_f(r, key))]
            if known:
                levels.setdefault(round(factor * known[0] * 1e6, 3), name)
    for level, name in levels.items():
        ax2.axhline(level, color="0.55", lw=0.8, ls="-", zorder=0)
        ax2.annotate(f"{name} = {level:.2f} um", (0.01, level),
                     xycoords=("axes fraction", "data"), fontsize=7, color="0.35",
                     va="bottom")
    ax.set_xlabel("roller speed U_r [m/s]" if rows[0]["parameter"] == "roller.speed"
                  else rows[0]["parameter"])
    ax.set_ylabel("friction coefficient mu [-]")
    ax2.set_ylabel("web spacing h [um] (dashed)")
    mu = [_f(r, "mu") for r in rows if r.get("converged") is True]
    ax.set_ylim(0.0, max([0.4] + [1.1 * m for m in mu if np.isfinite(m)]))
    ax2.set_ylim(0.0, None)
    ax.grid(True, alpha=0.3)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=7, loc="upper right", ncol=2 if reference else 1)
    if title:
        ax.set_title(title, fontsize=10)
    return _save(fig, path)


def traction_loss_chart(rows: list[dict], mu_curves: dict, mu_min: float, path,
                        parameters) -> Path:
    """Panels: mu against roller speed with the threshold (the traction-loss speed is where
    each curve falls through it), then the traction-loss speed against each parameter, one
    line per model.

    ``rows``: ``model``, ``parameter``, ``value``, ``speed`` (None: no loss); ``mu_curves``:
    model -> (speeds, mu); ``parameters``: ``(key, axis label, range)`` per panel, e.g.
    :data:`webfem.traction.CHART_PARAMETERS`.
    """
    parameters = list(parameters)
    fig, axes = plt.subplots(1, 1 + len(parameters), figsize=(3.4 * (1 + len(parameters)), 3.8),
                             constrained_layout=True, squeeze=False)
    axes = axes[0]
    ax = axes[0]
    for model, (u, mu) in mu_curves.items():
        ax.plot(u, mu, label=model)
    ax.axhline(mu_min, color="k", lw=0.8, ls="--", label=f"mu_min = {mu_min:g}")
    ax.set_xlabel("roller speed U_r [m/s]")
    ax.set_ylabel("mu [-]")
    ax.set_title("base case", fontsize=9)
    ax.legend(fontsize=7)
    for ax, (key, label, *_) in zip(axes[1:], parameters):
        for model in dict.fromkeys(r["model"] for r in rows):
            sel = [r for r in rows if r["model"] == model and r["parameter"] == key]
            ax.plot([r["value"] for r in sel],
                    [np.nan if r["speed"] is None else r["speed"] for r in sel], "o-",
                    label=model, ms=3)
        ax.set_xlabel(label)
        ax.set_ylabel("traction-loss speed [m/s]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"Roller speed at which mu falls below {mu_min:g}", fontsize=10)
    return _save(fig, path)


def _save(fig, path) -> Path:
    """Save as PNG under a hidden temporary name, then rename: never a half-written chart;
    created by os.open so the user's umask sets the mode (0644 by default)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        with replacing(path) as tmp:
            fig.savefig(tmp, dpi=110, format="png")
    finally:
        plt.close(fig)
    return path


def _pm(value, half) -> str:
    """``value +- half`` or, when the data cannot bound it, the value alone."""
    return f"{value:.4g} +- {half:.2g}" if half is not None else f"{value:.4g} (not identified)"


def calibration_chart(fit: dict, path) -> Path:
    """Measured against predicted (with the 1:1 line) and the residuals against roller speed.

    ``fit``: a :class:`webfem.calibrate.Calibration` (or a mapping with its keys).
    """
    obs, pred = np.asarray(fit["observed"]), np.asarray(fit["predicted"])
    speed = [c.roller.speed for c in fit["cases"]]
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    a.plot(obs, pred, "o", ms=4)
    lim = [min(obs.min(), pred.min()), max(obs.max(), pred.max())]
    a.plot(lim, lim, "k-", lw=0.8)
    name = "delta_T [N/m]" if fit["measured"] == "delta_T" else "mu [-]"
    a.set_xlabel(f"measured {name}")
    a.set_ylabel(f"predicted {name} ({fit['model']})")
    est = ", ".join(f"{k} = {_pm(v, fit['ci95'][k])}" for k, v in fit["estimates"].items()
                    if v is not None)
    a.set_title(est + " (95 %)", fontsize=8)
    b.plot(speed, fit["residuals"], "o", ms=4)
    b.axhline(0.0, color="k", lw=0.8)
    b.set_xlabel("roller speed [m/s]")
    b.set_ylabel(f"predicted - measured {name}")
    b.set_title(f"rms {fit['rms']:.3g}, {fit['dof']} degrees of freedom", fontsize=8)
    for ax in (a, b):
        ax.grid(True, alpha=0.3)
    return _save(fig, path)
