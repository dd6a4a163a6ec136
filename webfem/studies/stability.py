"""Stability map: where each method converges, diverges or stalls.

1. Coupling schemes on the 1-D model over roller speed x wrap angle x mesh level: Newton with
   and without its continuation fallback; Picard with fixed relaxation (omega 1, 0.5, 0.2; no
   acceleration, no safeguard), Picard with Anderson acceleration and its safeguard (the
   default), and the staggered Picard (film, then web).
2. The low-speed contact regime with and without asperity contact in the web equilibrium.
3. The 2-D model (Newton) over speed x web width.
4. The closed form's stated range (beta > 6, lambda > 7) over speed x width x wrap.

Each point: ``converged``, ``diverged`` or ``stalled``, with iterations and final residual.
Writes ``stability.csv``, ``stability.png`` and ``stability.md``.
"""

from __future__ import annotations

import csv
import time
import warnings
from pathlib import Path

import numpy as np

from .. import Case, solve
from ..errors import ConvergenceError, ValidityWarning

SCHEMES = (("Newton", {"method": "newton"}),
           ("Newton, no continuation", {"method": "newton", "continuation": False}),
           ("Picard omega 1", {"method": "picard", "omega": 1.0, "aitken": False,
                               "anderson": 0, "backtrack": 0}),
           ("Picard omega 0.5", {"method": "picard", "omega": 0.5, "aitken": False,
                                 "anderson": 0, "backtrack": 0}),
           ("Picard omega 0.2", {"method": "picard", "omega": 0.2, "aitken": False,
                                 "anderson": 0, "backtrack": 0}),
           ("Picard Anderson (default)", {"method": "picard"}),
           ("Picard staggered", {"method": "picard-staggered", "omega": 0.5}))
STATUS = ("converged", "stalled", "diverged")


def classify(result) -> str:
    if result["converged"]:
        return "converged"
    msg = str(result.get("solver_message", "")).lower()
    if any(w in msg for w in ("diverg", "not finite", "linear solve failed", "map failed")):
        return "diverged"
    return "stalled"


def attempt(case: Case, model: str, opts: dict) -> dict:
    t0 = time.perf_counter()
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", ValidityWarning)   # the map crosses ranges on purpose
        warnings.simplefilter("ignore", RuntimeWarning)    # diverging iterates overflow
        try:
            r = solve(case, model=model, **opts)
        except ConvergenceError as err:
            r = err.result
        except (FloatingPointError, ValueError, RuntimeError, np.linalg.LinAlgError) as err:
            return {"status": "diverged", "iterations": -1, "residual": float("nan"),
                    "message": f"{type(err).__name__}: {err}",
                    "time_s": time.perf_counter() - t0}
    return {"status": classify(r), "iterations": r["iterations"], "residual": r["residual"],
            "message": r.get("solver_message", ""), "time_s": time.perf_counter() - t0,
            "h_min": r["h_min"]}


def run(case: Case, out, quick: bool = False, progress=print) -> dict:
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    speeds = (2.0, 20.0, 40.0) if quick else (0.5, 2.0, 5.0, 10.0, 20.0, 30.0, 40.0)
    wraps = (60.0,) if quick else (20.0, 60.0, 120.0)
    levels = (0,) if quick else (0, 1, 2)
    picard_iter = 60 if quick else 300
    rows = []
    for name, opts in SCHEMES:
        for level in levels:
            for wrap in wraps:
                for u in speeds:
                    c = case.updated({"roller.speed": u, "wrap.angle_deg": wrap})
                    o = dict(opts, level=level, picard_max_iter=picard_iter, adapt=0)
                    rows.append({"study": "coupling", "method": name, "model": "fe1d",
                                 "speed": u, "wrap_deg": wrap, "width": case.web.width,
                                 "level": level, **attempt(c, "fe1d", o)})
        if progress:
            progress(f"{name}: done")
    for contact in (True, False):
        for u in speeds:
            c = case.updated({"roller.speed": u})
            rows.append({"study": "contact", "method": f"Newton, contact {'on' if contact else 'off'}",
                         "model": "fe1d", "speed": u, "wrap_deg": case.wrap.angle_deg,
                         "width": case.web.width, "level": 0,
                         **attempt(c, "fe1d", {"contact": contact})})
    widths = (0.02, 0.1) if quick else (0.01, 0.02, 0.035, 0.1, 0.3)
    for width in widths:
        for u in speeds[::2] if not quick else speeds:
            c = case.updated({"roller.speed": u, "web.width": width})
            rows.append({"study": "2-D", "method": "fe2d Newton", "model": "fe2d", "speed": u,
                         "wrap_deg": case.wrap.angle_deg, "width": width, "level": 0,
                         **attempt(c, "fe2d", {})})
    if progress:
        progress("contact and 2-D: done")
    for width in widths:
        for wrap in (10.0, 20.0, 60.0, 120.0):
            for u in speeds:
                c = case.updated({"roller.speed": u, "web.width": width, "wrap.angle_deg": wrap})
                r = solve(c, model="closed-form")
                rows.append({"study": "closed form", "method": "Eq. 21", "model": "closed-form",
                             "speed": u, "wrap_deg": wrap, "width": width, "level": 0,
                             "status": "converged" if r["eq21_valid"] else "outside range",
                             "iterations": 0, "residual": 0.0,
                             "message": f"beta = {r['beta']:.3g}, lambda = {r['lambda']:.3g}",
                             "time_s": r["solve_time_s"], "h_min": r["h_min"]})
    keys = sorted({k for r in rows for k in r}, key=lambda k: list(rows[0]).index(k)
                  if k in rows[0] else 99)
    with (out / "stability.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    chart(rows, out / "stability.png")
    text = report(rows)
    (out / "stability.md").write_text(text)
    return {"rows": rows, "report": text}


def chart(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    coupling = [r for r in rows if r["study"] == "coupling" and r["level"] == 0]
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
    fig.savefig(path, dpi=110)
    plt.close(fig)


def report(rows) -> str:
    lines = ["| study | method | points | converged | stalled | diverged | other |",
             "|---|---|---|---|---|---|---|"]
    for (study, method) in dict.fromkeys((r["study"], r["method"]) for r in rows):
        sel = [r for r in rows if r["study"] == study and r["method"] == method]
        n = {s: sum(r["status"] == s for r in sel) for s in STATUS}
        other = len(sel) - sum(n.values())
        lines.append(f"| {study} | {method} | {len(sel)} | {n['converged']} | {n['stalled']} | "
                     f"{n['diverged']} | {other} |")
    return "\n".join(lines) + "\n"
