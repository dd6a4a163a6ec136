"""Convergence study: mesh refinement of the FE models and Eq. 21 against the converged 2-D gap.

1. For the case: uniform refinement (every cell bisected per level, the adaptive refinement
   off so the sequence is nested) of the 1-D model (P1, P2 pressure) and the 2-D model
   (Q1, Q2): central gap, minimum gap and mu per level, the observed order from the last three
   levels and the Richardson-extrapolated value with its error estimate.
2. Eq. 21's central gap against the 2-D solution over a grid of lambda and beta (web width
   and wrap angle varied at the case's speed), inside and outside Eq. 21's stated range.

Writes ``convergence_refinement.csv``, ``convergence_eq21.csv``, ``convergence.png`` and
``convergence.md`` into the output folder.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from .. import Case, solve

QUANTITIES = ("h_center", "h_min", "mu")
SEQUENCES = (("fe1d", 1), ("fe1d", 2), ("fe2d", 1), ("fe2d", 2))


def richardson(values):
    """Observed order from the last three values of a refinement-by-2 sequence, the
    extrapolated value and the error estimate of the finest value (NaN when not monotone)."""
    v = np.asarray(values, float)
    d1, d2 = v[-2] - v[-3], v[-1] - v[-2]
    if d1 == 0 or d2 == 0 or d1 * d2 < 0:
        return math.nan, float(v[-1]), abs(d2)
    p = math.log2(abs(d1 / d2))
    ext = v[-1] + d2 / (2**p - 1)
    return p, float(ext), abs(ext - v[-1])


def refinement(case: Case, levels=(0, 1, 2, 3), levels2d=(0, 1, 2), progress=print) -> list:
    rows = []
    for model, order in SEQUENCES:
        seq = levels if model == "fe1d" else levels2d
        res = [solve(case, model=model, level=lv, order=order, adapt=0) for lv in seq]
        for lv, r in zip(seq, res):
            rows.append({"model": model, "order": order, "level": lv, "n_dofs": r["n_dofs"],
                         "time_s": r["solve_time_s"],
                         **{q: r[q] for q in QUANTITIES}})
        if progress:
            progress(f"{model} order {order}: levels {list(seq)} done")
    return rows


def summarise(rows) -> list:
    out = []
    for model, order in SEQUENCES:
        sel = [r for r in rows if r["model"] == model and r["order"] == order]
        for q in QUANTITIES:
            p, ext, err = richardson([r[q] for r in sel])
            out.append({"model": model, "order": order, "quantity": q, "observed_order": p,
                        "richardson": ext, "error_estimate": err,
                        "relative_error_finest": err / abs(ext) if ext else math.nan,
                        "relative_error_coarsest": abs(sel[0][q] - ext) / abs(ext)})
    return out


def eq21_grid(case: Case, lambdas=(3.0, 5.0, 7.0, 10.0, 20.0, 50.0),
              betas=(3.0, 6.0, 10.0, 20.0, 40.0), progress=print) -> list:
    rows = []
    cube = case.eps ** (1 / 3)
    for beta in betas:
        angle = math.degrees(beta * cube)
        if not 0 < angle < 360:
            continue
        for lam in lambdas:
            c = case.updated({"wrap.angle_deg": angle,
                              "web.width": lam * 2 * case.roller.radius * cube})
            cf = solve(c, model="closed-form")
            fe = solve(c, model="fe2d")
            rows.append({"lambda": lam, "beta": beta, "eq21_valid": cf["eq21_valid"],
                         "h_center_fe2d": fe["h_center"], "h_center_eq21": cf["h_center"],
                         "gap_error_pct": 100 * (cf["h_center"] / fe["h_center"] - 1),
                         "mu_fe2d": fe["mu"], "mu_eq21": cf["mu"],
                         "mu_error_pct": 100 * (cf["mu"] / fe["mu"] - 1)})
        if progress:
            progress(f"beta = {beta:g}: {len(lambdas)} widths done")
    return rows


def _write(rows, path):
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def chart(rows, grid, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(16, 4.4), constrained_layout=True)
    ax = axes[0]
    for model, order in SEQUENCES:
        sel = [r for r in rows if r["model"] == model and r["order"] == order]
        p, ext, _ = richardson([r["h_center"] for r in sel])
        err = [abs(r["h_center"] / ext - 1) for r in sel[:-1]]
        ax.loglog([r["n_dofs"] for r in sel[:-1]], np.maximum(err, 1e-16), "o-",
                  label=f"{model} {'P' if model == 'fe1d' else 'Q'}{order} (order {p:.2f})")
    ax.set_xlabel("unknowns")
    ax.set_ylabel("|h_center / Richardson - 1|")
    ax.set_title("mesh refinement", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
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
    fig.savefig(path, dpi=110)
    plt.close(fig)


def report(summary, grid, case) -> str:
    lines = [f"Case: U_r = {case.roller.speed:g} m/s, lambda = {case.lam:.3g}, "
             f"beta = {case.beta:.3g}. Uniform refinement (adaptivity off).", "",
             "| model | element | quantity | observed order | Richardson value | "
             "error of finest | error of coarsest |", "|---|---|---|---|---|---|---|"]
    for s in summary:
        el = ("P" if s["model"] == "fe1d" else "Q") + str(s["order"])
        lines.append(f"| {s['model']} | {el} | {s['quantity']} | {s['observed_order']:.2f} | "
                     f"{s['richardson']:.6g} | {s['relative_error_finest']:.1e} | "
                     f"{s['relative_error_coarsest']:.1e} |")
    inside = [g for g in grid if g["eq21_valid"]]
    outside = [g for g in grid if not g["eq21_valid"]]
    fmt = lambda rows, k: (f"{min(r[k] for r in rows):+.0f} % to {max(r[k] for r in rows):+.0f} %"  # noqa: E731
                           if rows else "no points")
    lines += ["", f"Eq. 21 against the 2-D central gap: inside its range {fmt(inside, 'gap_error_pct')}"
              f", outside {fmt(outside, 'gap_error_pct')}; its wrap-averaged mu: inside "
              f"{fmt(inside, 'mu_error_pct')}, outside {fmt(outside, 'mu_error_pct')}."]
    return "\n".join(lines) + "\n"


def run(case: Case, out, quick: bool = False, progress=print) -> dict:
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    if quick:
        rows = refinement(case, (0, 1, 2), (0, 1, 2), progress)
        grid = eq21_grid(case, (5.0, 10.0), (6.0, 20.0), progress)
    else:
        rows = refinement(case, progress=progress)
        grid = eq21_grid(case, progress=progress)
    summary = summarise(rows)
    _write(rows, out / "convergence_refinement.csv")
    _write(grid, out / "convergence_eq21.csv")
    chart(rows, grid, out / "convergence.png")
    text = report(summary, grid, case)
    (out / "convergence.md").write_text(text)
    return {"refinement": rows, "summary": summary, "eq21": grid, "report": text}
