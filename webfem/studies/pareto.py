"""Speed against accuracy: every method's time per solve against its error.

Methods: the closed form; the 1-D FE model at several mesh levels (Newton, and Picard at the
default mesh); the 2-D FE model at several levels and both element orders (Newton, and
Picard at the default mesh). Time: median of ``repeats`` warm solves. Error: relative to the
finest 2-D solution (Q2, two levels above the default), in the central gap, the minimum gap
and the wrap-averaged mu. The chart (log-log, time against the mu error) marks the Pareto
front: the methods no other method beats in both time and error.

Writes ``pareto.csv``, ``pareto.png`` and ``pareto.md``.
"""

from __future__ import annotations

import csv
import statistics
import time
from pathlib import Path

from .. import Case, solve

QUANTITIES = ("h_center", "h_min", "mu")


def methods(quick: bool = False):
    lv1 = (0, 1) if quick else (0, 1, 2)
    out = [("closed form", "closed-form", {})]
    out += [(f"fe1d P2 level {lv}", "fe1d", {"level": lv}) for lv in lv1]
    out += [("fe1d P1 level 0", "fe1d", {"order": 1}),
            ("fe1d Picard", "fe1d", {"method": "picard"})]
    out += [("fe2d Q2 level 0", "fe2d", {}), ("fe2d Q1 level 0", "fe2d", {"order": 1}),
            ("fe2d Q1 level 1", "fe2d", {"order": 1, "level": 1})]
    if not quick:
        out += [("fe2d Q2 level 1", "fe2d", {"level": 1}),
                ("fe2d Picard", "fe2d", {"method": "picard"})]
    return out


def pareto_front(points):
    """Indices of the points no other point beats in both coordinates (lower is better)."""
    front = []
    for i, (t, e) in enumerate(points):
        if not any((t2 <= t and e2 <= e) and (t2 < t or e2 < e)
                   for j, (t2, e2) in enumerate(points) if j != i):
            front.append(i)
    return front


def run(case: Case, out, quick: bool = False, repeats: int = 3, progress=print) -> dict:
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    ref = solve(case, model="fe2d", level=1 if quick else 2)
    if progress:
        progress(f"reference fe2d Q2 level {1 if quick else 2}: {ref['n_dofs']} unknowns")
    rows = []
    for name, model, opts in methods(quick):
        times, r = [], None
        for _ in range(repeats):
            t0 = time.perf_counter()
            r = solve(case, model=model, **opts)
            times.append(time.perf_counter() - t0)
        row = {"method": name, "model": model, "time_s": statistics.median(times),
               "iterations": r["iterations"], "n_dofs": r["n_dofs"]}
        for q in QUANTITIES:
            row[f"error_{q}"] = abs(r[q] / ref[q] - 1.0)
        rows.append(row)
        if progress:
            progress(f"{name}: {row['time_s'] * 1e3:.1f} ms, mu error {row['error_mu']:.2e}")
    front = pareto_front([(r["time_s"], max(r["error_mu"], 1e-16)) for r in rows])
    for i, r in enumerate(rows):
        r["pareto_mu"] = i in front
    with (out / "pareto.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    chart(rows, out / "pareto.png", case)
    lines = [f"Reference: fe2d Q2 level {1 if quick else 2} ({ref['n_dofs']} unknowns); "
             f"case U_r = {case.roller.speed:g} m/s, lambda = {case.lam:.3g}, "
             f"beta = {case.beta:.3g}. Time: median of {repeats} solves.", "",
             "| method | time [ms] | iterations | error h_center | error h_min | error mu | "
             "Pareto (mu) |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['method']} | {r['time_s'] * 1e3:.2f} | {r['iterations']} | "
                     f"{r['error_h_center']:.1e} | {r['error_h_min']:.1e} | "
                     f"{r['error_mu']:.1e} | {'yes' if r['pareto_mu'] else ''} |")
    text = "\n".join(lines) + "\n"
    (out / "pareto.md").write_text(text)
    return {"rows": rows, "reference": ref, "report": text}


def chart(rows, path, case):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5.5), constrained_layout=True)
    markers = {"closed-form": "s", "fe1d": "o", "fe2d": "^"}
    for q, colour in (("mu", "C0"), ("h_center", "C1"), ("h_min", "C2")):
        for r in rows:
            ax.loglog(r["time_s"], max(r[f"error_{q}"], 1e-12), markers[r["model"]],
                      color=colour, ms=7 if q == "mu" else 4,
                      mfc=colour if (q == "mu" and r["pareto_mu"]) else "none")
        ax.plot([], [], "o", color=colour, label=f"error in {q}")
    front = sorted((r for r in rows if r["pareto_mu"]), key=lambda r: r["time_s"])
    ax.loglog([r["time_s"] for r in front], [max(r["error_mu"], 1e-12) for r in front], "-",
              color="C0", lw=1, label="Pareto front (mu), filled")
    for r in rows:
        ax.annotate(r["method"], (r["time_s"], max(r["error_mu"], 1e-12)), fontsize=6,
                    xytext=(4, 2), textcoords="offset points")
    ax.set_xlabel("time per solve [s] (median)")
    ax.set_ylabel("relative error against the finest 2-D solution")
    ax.set_title(f"speed against accuracy, U_r = {case.roller.speed:g} m/s "
                 "(squares: closed form, circles: 1-D, triangles: 2-D)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)
