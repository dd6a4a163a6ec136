"""2-D FE benchmark: base-case solve time and accuracy, peak memory, and scaling to ~1e6 unknowns.

Run: ``make bench`` or ``python benchmarks/bench_fe2d.py [MAX_LEVEL]`` (default 4: about
1.5e6 unknowns; each level quadruples the unknowns; level 4 takes minutes and several GB).

Prints
1. the base case (cases/base.toml, 20 m/s): solve time (median of 3, each in a fresh process
   so the peak memory is that of one solve), central gap against the Richardson extrapolation
   of levels 0-2, and peak resident memory. Targets (issue 7): within 0.5 % in under 2 s,
   under 1 GB.
2. time of one Newton step (Jacobian + residual assembly and the sparse direct solve) against
   the number of unknowns on the Eshel-Elrod problem (lambda = 10.6, beta = 30), with the
   fitted exponent t ~ N^a.
"""

import json
import statistics
import subprocess
import sys
import time

import numpy as np

ONE_SOLVE = r"""
import json, resource, time
from webfem import load_case
from webfem.models import fe2d
case = load_case("cases/base.toml")
t0 = time.perf_counter()
r = fe2d.solve(case, level={level})
dt = time.perf_counter() - t0
print(json.dumps(dict(t=dt, h=r["h_center"], n=r["n_dofs"], it=r["iterations"],
                      rss_mb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)))
"""


def one_solve(level):
    out = subprocess.run([sys.executable, "-c", ONE_SOLVE.format(level=level)],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def base_case():
    runs = [one_solve(0) for _ in range(3)]
    r0 = runs[0]
    h = [r0["h"]] + [one_solve(lv)["h"] for lv in (1, 2)]
    d = np.abs(np.diff(h))
    order = np.log2(d[0] / d[1])
    rich = h[2] + (h[2] - h[1]) / (2**order - 1)
    t = statistics.median(r["t"] for r in runs)
    err = abs(r0["h"] / rich - 1)
    print(f"base case fe2d level 0: {r0['n']} unknowns, {r0['it']} iterations (1-D start "
          f"included), solve {t:.2f} s (median of 3), peak memory {r0['rss_mb']:.0f} MB")
    print(f"  h_center {r0['h'] * 1e6:.4f} um; levels 0-2 {[round(v * 1e6, 4) for v in h]} um, "
          f"observed order {order:.2f}, Richardson {rich * 1e6:.4f} um, error {err:.1e}")
    print(f"  targets: error < 5e-3 -> {'met' if err < 5e-3 else 'NOT met'}, time < 2 s -> "
          f"{'met' if t < 2 else 'NOT met'} (ratio {t / 2:.2f}), memory < 1024 MB -> "
          f"{'met' if r0['rss_mb'] < 1024 else 'NOT met'}")


def scaling(max_level):
    from webfem.fem.mesh import graded_nodes
    from webfem.fem.newton import solve_linear
    from webfem.fem.transfer import width_nodes
    from webfem.models.fe1d import FoilBearing1D, FoilParameters
    from webfem.models.fe2d import FoilBearing2D

    prm = FoilParameters(beta=30.0, K=0.0, d=0.0, Dn=0.0, c=0.0, S=1.0, contact=0.0,
                         floor=1e-3)
    ns, ts = [], []
    print(f"{'level':>5} {'unknowns':>9} {'assembly':>9} {'solve':>8} {'step':>8}")
    for lev in range(max_level + 1):
        X = graded_nodes(30.0, 40.0, level=lev)
        p1 = FoilBearing1D(X)
        u1, _ = p1.solve_newton(p1.initial_guess(prm), prm)
        pb = FoilBearing2D(X, width_nodes(10.6, level=lev))
        u = pb.start_from_line(p1, u1, prm)
        t0 = time.perf_counter()
        J = pb.jacobian(u, prm)[pb.free][:, pb.free]
        F = pb.residual(u, prm)[pb.free]
        ta = time.perf_counter() - t0
        t0 = time.perf_counter()
        solve_linear(J, -F)
        tsol = time.perf_counter() - t0
        ns.append(pb.n_dofs)
        ts.append(ta + tsol)
        print(f"{lev:5d} {pb.n_dofs:9d} {ta:8.2f}s {tsol:7.2f}s {ta + tsol:7.2f}s", flush=True)
    if len(ns) >= 3:
        a = np.polyfit(np.log(ns[1:]), np.log(ts[1:]), 1)[0]
        print(f"Newton step time ~ N^{a:.2f} over N = {ns[1]} .. {ns[-1]}")


if __name__ == "__main__":
    base_case()
    scaling(int(sys.argv[1]) if len(sys.argv) > 1 else 4)
