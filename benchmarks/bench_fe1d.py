"""1-D FE benchmark: time per solve, error against the converged mesh, the Newton floor.

Run: ``make bench`` or ``python benchmarks/bench_fe1d.py``. For the base case at 40 m/s (no
contact: the web floats) and 20 m/s (the web lands; adaptive refinement rounds) and the
paper's physics at 20 m/s it prints: the default solve's time (median of 5, mesh and basis
cached as in a sweep) and a cold one (caches cleared, median of 3), iterations, unknowns, the
relative errors of the central and minimum gaps against a level-3 refinement (level 4 at 20 m/s is on a knife edge: a 1e-14 change of the residual decides whether its continuation converges), and the ratio
of the solve time to one assembly + one factorisation. Issue 14's targets: <= 10 ms without
contact, <= 30 ms with the web landing.
"""

from common import floor, median_time, target

from webfem import Case
from webfem.fem.scaling import FoilParameters
from webfem.models import fe1d

CASES = (("40 m/s, no contact", Case().updated({"roller.speed": 40.0}), 0.010),
         ("20 m/s, web lands", Case().updated({"roller.speed": 20.0}), 0.030),
         ("20 m/s, paper physics", Case().updated({"model.physics": "paper"}), None))


def cold(case):
    fe1d.LINE.problems.clear()
    return fe1d.solve(case)


def main():
    print(f"{'case':>22} {'dofs':>5} {'it':>3} {'warm':>8} {'cold':>8} {'err h_c':>8} "
          f"{'err h_min':>9} {'floor':>7} {'ratio':>6}")
    for name, case, limit in CASES:
        t_cold, _ = median_time(lambda: cold(case), 3)
        t, r = median_time(lambda: fe1d.solve(case), 5)
        fine = fe1d.solve(case, level=3)
        e_c = abs(r["h_center"] / fine["h_center"] - 1)
        e_m = abs(r["h_min"] / fine["h_min"] - 1)
        ta, tf = floor(r.state("problem"), r.state("state"), FoilParameters.from_case(case))
        print(f"{name:>22} {r['n_dofs']:5d} {r['iterations']:3d} {t * 1e3:6.1f}ms "
              f"{t_cold * 1e3:6.1f}ms {e_c:8.1e} {e_m:9.1e} {(ta + tf) * 1e3:5.2f}ms "
              f"{t / (ta + tf):6.0f}", flush=True)
        if limit is not None:
            print(target(f"fe1d {name} (warm)", t * 1e3, limit * 1e3, "ms"))


if __name__ == "__main__":
    main()
