"""Charts of the studies (matplotlib, off screen): one function per study, each taking the
study's dataclass (:mod:`webfem.studies`) and a path, returning the path."""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

from .charts import save_figure  # noqa: E402

__all__ = ["convergence_chart", "pareto_chart", "stability_chart", "lambda_table_chart",
           "variants_chart"]


_save = save_figure


def _sequence(study, model, order):
    return [r for r in study.refinement if r["model"] == model and r["order"] == order]


def convergence_chart(study, path) -> Path:
    """Error of the central gap against unknowns per sequence, then Eq. 21's central gap and
    mu errors over (lambda, beta) with its stated range marked."""
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.4), constrained_layout=True)
    ax = axes[0]
    for model, order in dict.fromkeys((r["model"], r["order"]) for r in study.refinement):
        sel = _sequence(study, model, order)
        s = study.order(model, order, "h_center")
        p, ext = s["observed_order"], s["richardson"]
        err = [abs(r["h_center"] / ext - 1) for r in sel[:-1]]
        ax.loglog([r["n_dofs"] for r in sel[:-1]], np.maximum(err, 1e-16), "o-",
                  label=f"{model} {'P' if model == 'fe1d' else 'Q'}{order} (order {p:.2f})")
    ax.set_xlabel("unknowns")
    ax.set_ylabel("|h_center / Richardson - 1|")
    ax.set_title("mesh refinement", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    grid = study.eq21
    lams = sorted({g["lambda"] for g in grid})
    betas = sorted({g["beta"] for g in grid})
    for ax, key, title in ((axes[1], "gap_error_pct", "Eq. 21 central gap error [%]"),
                           (axes[2], "mu_error_pct", "Eq. 21 mu error [%]")):
        Z = np.full((len(betas), len(lams)), np.nan)
        for g in grid:
            Z[betas.index(g["beta"]), lams.index(g["lambda"])] = g[key]
        lim = np.nanmax(np.abs(Z))
        im = ax.imshow(Z, origin="lower", cmap="RdBu_r", vmin=-lim, vmax=lim, aspect="auto")
        for i in range(len(betas)):
            for j in range(len(lams)):
                ax.text(j, i, f"{Z[i, j]:.0f}", ha="center", va="center", fontsize=7)
        ax.set_xticks(range(len(lams)), [f"{v:g}" for v in lams])
        ax.set_yticks(range(len(betas)), [f"{v:g}" for v in betas])
        ax.set_xlabel("lambda")
        ax.set_ylabel("beta")
        ax.axvline(lams.index(7.0) + 0.5 if 7.0 in lams else -1, color="k", lw=1)
        ax.axhline(betas.index(6.0) + 0.5 if 6.0 in betas else -1, color="k", lw=1)
        ax.set_title(title + " (Eq. 21's range: upper right of the lines)", fontsize=9)
        fig.colorbar(im, ax=ax)
    return _save(fig, path)


def pareto_chart(study, path) -> Path:
    """Time per solve against the relative errors (log-log), the mu Pareto front filled."""
    rows = study.rows
    fig, ax = plt.subplots(figsize=(8, 5.5), constrained_layout=True)
    markers = {"closed-form": "s", "fitted": "D", "fe1d": "o", "fe2d": "^"}
    for q, colour in (("mu", "C0"), ("h_center", "C1"), ("h_min", "C2")):
        for r in rows:
            ax.loglog(r["time_s"], max(r[f"error_{q}"], 1e-12), markers[r["model"]],
                      color=colour, ms=7 if q == "mu" else 4,
                      mfc=colour if (q == "mu" and r["pareto_mu"]) else "none")
        ax.plot([], [], "o", color=colour, label=f"error in {q}")
    front = sorted((r for r in rows if r["pareto_mu"]), key=lambda r: r["time_s"])
    ax.loglog([r["time_s"] for r in front], [max(r["error_mu"], 1e-12) for r in front], "-",
              color="C0", lw=1, label="Pareto front (mu), filled")
    ax.set_xlabel("time per solve [s] (median)")
    ax.set_ylabel("relative error against the finest 2-D solution")
    ax.set_title(f"speed against accuracy, U_r = {study.case.roller.speed:g} m/s "
                 "(squares: closed form, diamonds: fitted, circles: 1-D, triangles: 2-D)",
                 fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    _label_points(fig, ax, [(r["method"], r["time_s"], max(r["error_mu"], 1e-12))
                            for r in rows])
    return _save(fig, path)


def _label_points(fig, ax, labels) -> None:
    """Name each point (text, x, y) beside it, to its right (to its left near the right
    edge); where that label would cover another label or point (methods of similar time
    and error cluster) it moves up or down in steps, inside the axes, with a thin line to
    its point."""
    from matplotlib.text import Text
    from matplotlib.transforms import Bbox
    fig.canvas.draw()                  # the layout first: the labels then leave it alone
    fig.set_layout_engine("none")
    renderer = fig.canvas.get_renderer()
    edge = ax.get_window_extent(renderer)
    points = ax.transData.transform(np.array([(x, y) for _, x, y in labels], float))
    placed = [Bbox.from_bounds(px - 5, py - 5, 10, 10) for px, py in points]

    def put(text, x, y, dx, dy):
        far = dy != 2
        t = ax.annotate(text, (x, y), fontsize=6, xytext=(dx, dy), textcoords="offset points",
                        ha="left" if dx > 0 else "right", va="center" if far else "baseline",
                        arrowprops=dict(arrowstyle="-", lw=0.4, color="0.5",
                                        shrinkA=0, shrinkB=4) if far else None)
        # the text's own box (an annotation's box takes in its line too)
        t.update_positions(renderer)
        return t, Text.get_window_extent(t, renderer).padded(2)

    for i, (text, x, y) in sorted(enumerate(labels), key=lambda t: (t[1][1], -t[1][2])):
        own = placed[i]
        others = [b for b in placed if b is not own]
        for dy in (2, 12, -12, 22, -22, 32, -32, 42, -42, 52, -52, 62, -62):
            for dx in (6, -6):
                t, box = put(text, x, y, dx, dy)
                inside = edge.x0 <= box.x0 and box.x1 <= edge.x1 and \
                    edge.y0 <= box.y0 and box.y1 <= edge.y1
                if inside and not any(box.overlaps(o) for o in others):
                    break
                t.remove()
            else:
                continue
            break
        else:
            t, box = put(text, x, y, 6, 2)
        placed.append(box)


def stability_chart(study, path) -> Path:
    """One panel per 1-D coupling scheme at level 0: status over speed and wrap angle, with
    the iteration counts."""
    coupling = [r for r in study.rows if r["study"] == "coupling" and r["level"] == 0]
    methods = list(dict.fromkeys(r["method"] for r in coupling))
    speeds = sorted({r["speed"] for r in coupling})
    wraps = sorted({r["wrap_deg"] for r in coupling})
    code = {"converged": 0, "stalled": 1, "diverged": 2}
    cmap = ListedColormap(["#4caf50", "#ffc107", "#e53935"])
    fig, axes = plt.subplots(1, len(methods), figsize=(2.6 * len(methods), 3.2),
                             constrained_layout=True, sharey=True)
    for ax, m in zip(np.atleast_1d(axes), methods):
        Z = np.full((len(wraps), len(speeds)), np.nan)
        for r in coupling:
            if r["method"] == m:
                Z[wraps.index(r["wrap_deg"]), speeds.index(r["speed"])] = code[r["status"]]
                ax.text(speeds.index(r["speed"]), wraps.index(r["wrap_deg"]),
                        str(r["iterations"]), ha="center", va="center", fontsize=6)
        ax.imshow(Z, cmap=cmap, vmin=0, vmax=2, origin="lower", aspect="auto")
        ax.set_xticks(range(len(speeds)), [f"{s:g}" for s in speeds], fontsize=7)
        ax.set_yticks(range(len(wraps)), [f"{w:g}" for w in wraps], fontsize=7)
        ax.set_xlabel("U_r [m/s]", fontsize=8)
        ax.set_title(m, fontsize=8)
    np.atleast_1d(axes)[0].set_ylabel("wrap [deg]")
    fig.suptitle("1-D coupling schemes at mesh level 0: green converged, amber stalled, red "
                 "diverged (numbers: iterations)", fontsize=9)
    return _save(fig, path)


def lambda_table_chart(study, path) -> Path:
    """Eq. 21's central gap error against lambda, one line per web permeability."""
    fig, ax = plt.subplots(figsize=(6.5, 4.2), constrained_layout=True)
    for k, style in zip(dict.fromkeys(r["permeability"] for r in study.rows), ("o-", "s--")):
        sel = [r for r in study.rows if r["permeability"] == k]
        ax.semilogx([r["lambda"] for r in sel], [r["eq21_error_pct"] for r in sel], style,
                    label=f"newsprint (k = {k:g} m^2)" if k else "impermeable web")
    ax.axhline(0.0, color="0.5", lw=0.8)
    ax.set_xlabel("lambda = L / (2 R eps^(1/3))")
    ax.set_ylabel("Eq. 21 central gap error vs 2-D FE [%]")
    ax.set_title(f"Eq. 21 against the 2-D solution, base case at {study.speed:g} m/s",
                 fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path, dpi=120)


def variants_chart(study, path) -> Path:
    """mu against roller speed for each friction option: closed form left, FE model right."""
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2), constrained_layout=True, sharey=True)
    styles = {"exponential": "-", "gaussian": "--"}
    colours = {"paper": "C0", "continuous": "C3"}
    for ax, m in zip(axes, ("closed-form", study.model)):
        for (variant, dist, model), mu in study.mu.items():
            if model == m:
                ax.plot(study.speeds, mu, styles.get(dist, ":"),
                        color=colours.get(variant, "k"), label=f"{variant}, {dist}")
        ax.set_xlabel("roller speed U_r [m/s]")
        ax.set_title(f"base case, {m}", fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("mu [-]")
    return _save(fig, path)
