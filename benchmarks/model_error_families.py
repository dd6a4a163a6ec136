"""The cheaper models' stated errors against fe2d's answers on families of cases: how often
and how far the true error exceeds the stated one (webfem.models.model_error's basis).

    python benchmarks/model_error_families.py board     # closed form, 36 board points
    python benchmarks/model_error_families.py board-check   # closed form, 42 other board points
    python benchmarks/model_error_families.py board-small   # closed form, 12 board points
    python benchmarks/model_error_families.py bundled   # closed form, 90 points of 10 cases
    python benchmarks/model_error_families.py low       # fe1d, 24 base points at 0.3-2 m/s
    python benchmarks/model_error_families.py fitted    # fitted, 25 base points at 10-30 m/s

``board``: the bundled board on rollers of R 0.03-0.2 m, 0.1-1 m wide, at 5, 15 and 30 m/s
(points without a closed-form answer are skipped). ``board-check``: the board on other
rollers (R 0.02-0.3 m), widths (0.2, 0.6 m), speeds (10, 20, 25 m/s), wraps (45, 180 deg)
and tensions (400, 1500 N/m), none of them a ``board`` point. ``board-small``: the board on rollers of 25-60 mm at
12-22 m/s (and 700, 1300 N/m), where its film runs out of air in the wrap, none of them a
``board`` or ``board-check`` point. ``bundled``: every bundled
case but the board and the grooved ones at 0.5, 1 and 1.5x its speeds and 0.7, 1 and 1.4x
its tension. ``low``: the base case at 0.3-2 m/s,
tensions 50-130 N/m, 35 and 100 mm wide. ``fitted``: the base case at 10-30 m/s, tensions
0.6-1.6x its 80 N/m. The true error is measured as the answer's stated errors are
(:func:`webfem.models.readout.error_scale`), less the reference's own stated error; the
ratio true/stated above 1 means the stated error falls short. A few minutes on 2 cores.
"""

from __future__ import annotations

import math
import statistics
import sys
import time
import warnings

import webfem
from webfem import Case
from webfem.bundled import as_case
from webfem.errors import ConvergenceError, NoAdmissibleSolution
from webfem.models.readout import READ_QUANTITIES, error_scale

FAMILIES = {
    "board": ("closed-form", [as_case("board").updated(
        {"roller.radius": R, "web.width": W, "roller.speed": U, "web.speed": U})
        for R in (0.03, 0.05, 0.1, 0.2) for W in (0.1, 0.3, 1.0) for U in (5.0, 15.0, 30.0)]),
    "board-check": ("closed-form", [as_case("board").updated(u) for u in (
        [{"roller.radius": R, "web.width": W, "roller.speed": U, "web.speed": U}
         for R in (0.02, 0.04, 0.07, 0.15, 0.3) for W in (0.2, 0.6) for U in (10.0, 20.0, 25.0)]
        + [{"roller.radius": R, "roller.speed": U, "web.speed": U, "wrap.angle_deg": a}
           for R in (0.05, 0.2) for U in (15.0, 30.0) for a in (45.0, 180.0)]
        + [{"roller.radius": R, "roller.speed": U, "web.speed": U, "web.tension": T}
           for R in (0.05, 0.2) for U in (15.0, 30.0) for T in (400.0, 1500.0)])]),
    "board-small": ("closed-form", [as_case("board").updated(u) for u in (
        [{"roller.radius": R, "web.width": 0.4, "roller.speed": U, "web.speed": U}
         for R in (0.025, 0.035, 0.045) for U in (12.0, 18.0, 22.0)]
        + [{"roller.radius": 0.03, "roller.speed": 18.0, "web.speed": 18.0, "web.tension": T}
           for T in (700.0, 1300.0)]
        + [{"roller.radius": 0.06, "roller.speed": 18.0, "web.speed": 18.0}])]),
    "bundled": ("closed-form", [
        c.updated({"roller.speed": c.roller.speed * f, "web.speed": c.web.speed * f,
                   "web.tension": c.web.tension * g})
        for c in map(as_case, ("base", "driven_roller", "fig10_wrap", "fig11_tension",
                               "fig12_width", "fig13_radius", "foil_roller", "idler",
                               "pet_idler", "press_idler"))
        for f in (0.5, 1.0, 1.5) for g in (0.7, 1.0, 1.4)]),
    "low": ("fe1d", [Case().updated({"roller.speed": U, "web.tension": T, "web.width": W})
                     for U in (0.3, 0.5, 1.0, 2.0) for T in (50.0, 80.0, 130.0)
                     for W in (0.035, 0.1)]),
    "fitted": ("fitted", [Case().updated({"roller.speed": U, "web.tension": 80.0 * f})
                          for U in (10.0, 15.0, 20.0, 25.0, 30.0)
                          for f in (0.6, 0.8, 1.0, 1.3, 1.6)]),
}


def label(case: Case) -> str:
    return (f"R {case.roller.radius:g} m, L {case.web.width:g} m, U_r {case.roller.speed:g} "
            f"m/s, T {case.web.tension:g} N/m, B {math.degrees(case.B):.4g} deg")


def ratios(model: str, cases) -> tuple[list[tuple[Case, dict]], list[str]]:
    """Per case with an answer from both models: {quantity: (true, stated)}; and why the
    other cases have none."""
    out, skipped = [], []
    for case in cases:
        try:
            r = webfem.solve(case, model=model)
            ref = webfem.solve(case, model="fe2d")
        except (ConvergenceError, NoAdmissibleSolution) as e:
            skipped.append(f"{label(case)}: {str(e)[:100]}")
            continue
        out.append((case, {q: (max(abs(r[q] - ref[q]) / error_scale(case, q, r[q])
                                   - ref[f"error_{q}"], 0.0), r[f"error_{q}"])
                           for q in READ_QUANTITIES}))
    return out, skipped


def main(argv: list[str]) -> int:
    name = argv[0] if argv else "board"
    model, cases = FAMILIES[name]
    warnings.simplefilter("ignore")
    t, c = time.perf_counter(), time.process_time()
    rows, skipped = ratios(model, cases)
    for why in skipped:
        print("no answer:", why)
    for case, e in rows:
        print(f"{label(case)}: " + ", ".join(
                  f"{q} {t_:.3g}/{s:.3g}" for q, (t_, s) in e.items()))
    print(f"{model} on {len(rows)} points of '{name}' (true/stated):")
    for q in READ_QUANTITIES:
        r = [t_ / s if s > 0 else (float("inf") if t_ > 0 else 0.0)
             for _, e in rows for t_, s in (e[q],)]
        loose = [s / t_ for _, e in rows for t_, s in (e[q],) if t_ > 0]
        median = f"{statistics.median(loose):.3g}" if loose else "-"
        print(f"  {q}: worst {max(r):.2f}, above 1 on {sum(x > 1 for x in r)}, "
              f"above 2 on {sum(x > 2 for x in r)}; median stated/true {median} "
              f"(on {len(loose)} with a true error)")
    print(f"wall {time.perf_counter() - t:.0f} s, CPU {time.process_time() - c:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
