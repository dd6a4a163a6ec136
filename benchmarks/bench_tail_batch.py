"""CPU time of a stiff closed-form idler batch (``webfem.solve_many``), where most points
carry the exponential heights' tail warning (webfem.physics.contact.tail_warning).

Run: ``python benchmarks/bench_tail_batch.py [N]`` (default 3000 points: the bundled idler
with E_b = 2e7 Pa, 60 line speeds 1-20 m/s x N/60 tensions 40-200 N/m). Prints the best of
3 runs' CPU and wall time, how many points the tail warns, and the load average: the warning's
Gaussian h_c is solved once per batch (``tail_gaussian_gaps``), not once per point.
"""

import os
import sys
import time

import numpy as np

import webfem
from webfem.api import as_case


def main(n: int = 3000, runs: int = 3) -> None:
    base = as_case("idler").updated({"web.modulus_thickness": 2e7})
    cases = [base.updated({"roller.speed": u, "web.speed": u, "web.tension": T})
             for T in np.linspace(40.0, 200.0, max(n // 60, 1)).tolist()
             for u in np.linspace(1.0, 20.0, 60).tolist()]
    webfem.solve_many(cases[:50], model="closed-form")        # imports and caches
    cpu, wall = [], []
    for _ in range(runs):
        c0, w0 = time.process_time(), time.perf_counter()
        results = webfem.solve_many(cases, model="closed-form")
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - w0)
    warned = sum(any(w.startswith("the asperities carry") for w in r.summary.warnings)
                 for r in results)
    print(f"stiff closed-form idler batch: {len(cases)} points, CPU {min(cpu):.3f} s, wall "
          f"{min(wall):.3f} s (best of {runs}), tail warned at {warned}, load average "
          f"{os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3000)
