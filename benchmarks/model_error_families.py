"""The cheaper models' stated errors against fe2d's answers on families of cases: how often
and how far the true error exceeds the stated one (webfem.models.model_error's basis).

    python benchmarks/model_error_families.py board     # closed form, 36 board points
    python benchmarks/model_error_families.py low       # fe1d, 24 base points at 0.3-2 m/s
    python benchmarks/model_error_families.py fitted    # fitted, 25 base points at 10-30 m/s

``board``: the bundled board on rollers of R 0.03-0.2 m, 0.1-1 m wide, at 5, 15 and 30 m/s
(points without a closed-form answer are skipped). ``low``: the base case at 0.3-2 m/s,
tensions 50-130 N/m, 35 and 100 mm wide. ``fitted``: the base case at 10-30 m/s, tensions
0.6-1.6x its 80 N/m. The true error is measured as the answer's stated errors are
(:func:`webfem.models.readout.error_scale`), less the reference's own stated error; the
ratio true/stated above 1 means the stated error falls short. A few minutes on 2 cores.
"""

from __future__ import annotations

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
    "low": ("fe1d", [Case().updated({"roller.speed": U, "web.tension": T, "web.width": W})
                     for U in (0.3, 0.5, 1.0, 2.0) for T in (50.0, 80.0, 130.0)
                     for W in (0.035, 0.1)]),
    "fitted": ("fitted", [Case().updated({"roller.speed": U, "web.tension": 80.0 * f})
                          for U in (10.0, 15.0, 20.0, 25.0, 30.0)
                          for f in (0.6, 0.8, 1.0, 1.3, 1.6)]),
}


def label(case: Case) -> str:
    return (f"R {case.roller.radius:g} m, L {case.web.width:g} m, U_r {case.roller.speed:g} "
            f"m/s, T {case.web.tension:g} N/m")


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
        print(f"  {q}: worst {max(r):.2f}, above 1 on {sum(x > 1 for x in r)}, "
              f"above 2 on {sum(x > 2 for x in r)}")
    print(f"wall {time.perf_counter() - t:.0f} s, CPU {time.process_time() - c:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
