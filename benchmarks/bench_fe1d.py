"""1-D FE benchmark: time per solve, Newton against Picard, error against the converged mesh.

Run: ``make bench`` or ``python benchmarks/bench_fe1d.py``. Prints, for the base case at a few
speeds: the default solve's time (median of 5 warm runs, the mesh and basis cached as in a
sweep, plus one cold run that builds them), its iterations, the relative error of the central
and minimum gaps against a level-4 refinement of the same graded mesh, and Newton and Picard
(Aitken) times and iteration counts at the same residual tolerance. Targets (issue 3):
default solve within 0.1 % of the converged central gap in under 50 ms; Newton >= 5x faster
than Picard.
"""

import statistics
import time

from webfem import Case
from webfem.models import fe1d


def timed(case, repeats=5, **opts):
    runs = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        r = fe1d.solve(case, raise_on_failure=False, **opts)
        runs.append(time.perf_counter() - t0)
    return r, statistics.median(runs)


def main():
    print(f"{'U_r':>5} {'cells':>5} {'dofs':>5} {'it':>3} {'t_solve':>9} {'t_cold':>8} "
          f"{'err h_c':>9} {'err h_min':>9} | {'Newton':>14} {'Picard':>16} {'ratio':>6}")
    for speed in (5.0, 20.0, 40.0):
        case = Case().updated({"roller.speed": speed})
        fe1d._CACHE.clear()
        t0 = time.perf_counter()
        fe1d.solve(case)
        cold = time.perf_counter() - t0
        r, t = timed(case)
        fine = fe1d.solve(case, level=4)
        e_c = abs(r["h_center"] / fine["h_center"] - 1)
        e_m = abs(r["h_min"] / fine["h_min"] - 1)
        p, tp = timed(case, repeats=3, method="picard")
        pit = p["iterations"] if p["converged"] else f"fail({p['iterations']})"
        print(f"{speed:5.1f} {r['n_cells']:5d} {r['n_dofs']:5d} {r['iterations']:3d} "
              f"{t * 1e3:7.1f}ms {cold * 1e3:6.0f}ms {e_c:9.1e} {e_m:9.1e} | "
              f"{r['iterations']:3d} it {t * 1e3:6.1f}ms {str(pit):>5} it {tp * 1e3:7.1f}ms "
              f"{tp / t:5.1f}x")


if __name__ == "__main__":
    main()
