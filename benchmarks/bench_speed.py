"""Speed on real cases (issue 23's six figures, each beside its target, met or not).

Run: ``make bench`` or ``python benchmarks/bench_speed.py [--no-map]`` from the repository
root (about 4 minutes with the groove map, which alone took 2.7 minutes before issue 23;
``--no-map`` leaves it out and says so). It first prints the machine's speed on a fixed
piece of work (:func:`common.machine_reference`): the machines these targets are judged on
differ (the same code's cold base case took 0.090-0.106 s on one and 0.137 s on another),
and the figures of two runs compare only beside their references. Figures, on the base case
with its default physics:

1. a cold ``webfem.solve(cases/base.toml, model="fe2d")`` (median of 3; the 1-D model's
   problem cache cleared before each, imports and first-use set-up excluded by a warm-up);
2. the 24-point log-spaced speed sweep 0.5-40 m/s through :func:`webfem.solve_along`
   (one run; its points are also checked against cold solves elsewhere: tests/
   test_continued.py), beside it the process's CPU time (on a shared machine the wall
   time varied 1.5-2x between runs, the CPU time about 10 %), the iterations and the
   sparse factorisations (both deterministic);
3. the median Newton iterations of that sweep's continued points (points 2-24), as each
   result reports them: the solve's steps plus those of its mesh error estimate (a solve on
   the mesh with cells twice as long; a continued point solves that mesh first, its
   two-grid start, and the estimate reuses it), chord steps included; beside it the sparse
   factorisations they took (a Newton step is one, a chord step none);
4. ``webfem traction-loss base --mu-min 0.1 --model fe2d`` (the CLI in a fresh process,
   imports included; its scan stops at the first speed below mu_min and runs on 2
   processes where the machine has 2 cores, the default: they pay only where both are
   idle); beside it the same with ``--workers 1``
   (serial; not the target's figure);
5. one grooved design, a cold ``webfem.solve(cases/base_grooved.toml, model="fe2d")``
   (median of 3, after a warm-up);
6. the 32-design groove map ``webfem grooves base --mu-min 0.2`` (the CLI in a fresh
   process; its designs in 2 worker processes on a machine with 2 cores or more).
"""

import contextlib
import os
import statistics
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np
from common import machine_reference, median_time, target

import webfem
from webfem import load_case, solve_along
from webfem.fem import newton
from webfem.models import fe1d


def _cold(case):
    fe1d.LINE.problems.clear()
    return webfem.solve(case, "fe2d")


@contextlib.contextmanager
def _counting(counts, sizes=None):
    """Count the sparse factorisations (:meth:`webfem.fem.newton.PatternSolver.factor`)
    into ``counts[-1]`` while in the block, and their matrices' sizes into ``sizes[-1]``."""
    factor = newton.PatternSolver.factor

    def counted(self, A, free):
        counts[-1] += 1
        if sizes is not None:
            sizes[-1].append(A.shape[0])
        return factor(self, A, free)
    newton.PatternSolver.factor = counted
    try:
        yield
    finally:
        newton.PatternSolver.factor = factor


def _cli(args):
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "webfem", *args], check=True, capture_output=True)
    return time.perf_counter() - t0


def _cores() -> str:
    """What the command's default scan runs on here (webfem.cli.traction_loss)."""
    from webfem.cli.common import local_workers
    from webfem.cli.traction_loss import DEFAULT_WORKERS

    n = local_workers(None, DEFAULT_WORKERS)
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return f"its scan on {n} process{'es' if n > 1 else ''} at load {load:.2g}"


def main(groove_map: bool = True):
    warnings.simplefilter("ignore")
    print(f"0. machine reference (benchmarks/common.py machine_reference: a 10,000-unknown "
          f"sparse LU and element contractions, one thread, shortest of 9): "
          f"{machine_reference():.1f} ms; load {os.getloadavg()[0]:.2g}")
    base = load_case("cases/base.toml")
    grooved = load_case("cases/base_grooved.toml")
    _cold(base)                                          # imports, first-use caches
    t, r = median_time(lambda: _cold(base), 3)
    print(f"1. fe2d cold base case: {t:.3f} s (median of 3), {r['iterations']} iterations, "
          f"{r['n_dofs']:,} unknowns")
    print(target("fe2d cold base case", t, 0.10))

    cases = [base.updated({"roller.speed": float(u)}) for u in np.geomspace(0.5, 40.0, 24)]
    factors, sizes, out = [0], [[]], []
    with _counting(factors, sizes):
        t0, c0 = time.perf_counter(), time.process_time()
        for res in solve_along(cases, "fe2d"):
            out.append(res)
            factors.append(0)
            sizes.append([])
        t, cpu = time.perf_counter() - t0, time.process_time() - c0
    its = [res["iterations"] for res in out]
    ok = sum(res["converged"] for res in out)
    print(f"2. 24-point speed sweep 0.5-40 m/s (log-spaced), solve_along: {t:.2f} s "
          f"({cpu:.2f} s CPU), {ok}/24 converged, {sum(its)} iterations, "
          f"{sum(factors)} factorisations")
    print(target("24-point speed sweep", t, 2.0))
    med = statistics.median(its[1:])
    print(f"3. Newton iterations per continued point (solve + mesh error estimate): median "
          f"{med:g}, range {min(its[1:])}-{max(its[1:])}; cold first point {its[0]}")
    print(target("median iterations per continued point", med, 3, ""))
    fac = factors[1:-1]
    fine = [sum(n == res["n_dofs"] for n in s) for s, res in zip(sizes[1:-1], out[1:])]
    print(f"   factorisations per continued point (the rest are chord steps, a residual and "
          f"a triangular solve each): median {statistics.median(fac):g}, range "
          f"{min(fac)}-{max(fac)}; of them on the answer's mesh (the rest on coarser ones): "
          f"median {statistics.median(fine):g}, range {min(fine)}-{max(fine)}")

    args = ["traction-loss", "base", "--mu-min", "0.1", "--model", "fe2d"]
    where = _cores()
    t = _cli(args)
    serial = _cli(args + ["--workers", "1"])
    print(f"4. webfem traction-loss base --mu-min 0.1 --model fe2d: {t:.2f} s (one run, a "
          f"fresh process; {where}); serial (--workers 1) {serial:.2f} s")
    print(target("traction-loss base, fe2d", t, 3.0))

    webfem.solve(grooved, "fe2d")
    t, r = median_time(lambda: _cold(grooved), 3)
    print(f"5. one grooved design (cases/base_grooved.toml), cold: {t:.2f} s (median of 3), "
          f"{r['iterations']} iterations, {r['n_dofs']:,} unknowns")
    print(target("one grooved design", t, 0.5))

    if not groove_map:
        print("6. the groove map: not run (--no-map); target 30 s")
        return
    with tempfile.TemporaryDirectory() as out:    # a fresh map (the map resumes its CSV)
        t = _cli(["grooves", "base", "--mu-min", "0.2", "--out", out])
    print(f"6. webfem grooves base --mu-min 0.2 (32 designs): {t:.1f} s (one run, a fresh "
          "process)")
    print(target("32-design groove map", t, 30.0))


if __name__ == "__main__":
    main(groove_map="--no-map" not in sys.argv[1:])
