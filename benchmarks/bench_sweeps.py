"""Sweep throughput: the 24-point fe2d speed sweep and traction-loss search (issue 14's
targets; each serial and on 2 processes), then the 1-D FE model serial (with continuation),
local processes, Dask.

Run: ``python benchmarks/bench_sweeps.py [N_POINTS]`` (default 40 speeds of the base case).
For each way it prints the wall time, solves per second and the ratio to serial, and where
the time goes: the summed solve time of the points (``solve``: more than serial means cold
starts at chunk heads cost iterations), the summed Newton iterations, and the rest of the
wall time (``overhead``: starting workers, sending cases and results, writing the CSV).
On a 2-core machine the parallel runs can at best double the serial rate.
"""

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from webfem import Case
from webfem.sweepspec import Sweep
from webfem.sweeps import run

WAYS = (("serial", {}),
        ("2 processes, chunk 4", {"workers": 2, "chunk": 4}),
        ("2 processes, chunk 10 (default)", {"workers": 2}),
        ("Dask LocalCluster, 2 workers", {"workers": 2, "dask": "local"}))


def fe2d_targets(runs: int = 3):
    """24-point fe2d speed sweep of the base case with continuation (median of ``runs``) and
    ``webfem traction-loss cases/base.toml --mu-min 0.1 --model fe2d`` (one run, the CLI in
    a fresh process, imports included)."""
    import statistics
    import subprocess

    from common import target

    from webfem.api import sweep
    from webfem.sweepspec import load_sweep

    spec = load_sweep("cases/base.toml").respaced(24)
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        out = list(sweep(spec, "fe2d"))
        times.append(time.perf_counter() - t0)
    ok = sum(r["converged"] for _, _, r in out)
    its = sum(r["iterations"] for _, _, r in out)
    t = statistics.median(times)
    print(f"fe2d speed sweep, 24 points {spec.values[0]:g}..{spec.values[-1]:g} m/s: {t:.2f} s "
          f"(median of {runs}), {ok}/24 converged, {its} iterations")
    print(target("24-point fe2d sweep", t, 4.0))
    # the same sweep as `webfem sweep cases/base.toml --model fe2d --num 24 --workers 2` runs
    # it: two processes, each chunk with continuation (process start-up included)
    times2 = []
    for _ in range(runs):
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            rows = run(spec, "fe2d", Path(tmp) / "s.csv", workers=2)
            times2.append(time.perf_counter() - t0)
    t2 = statistics.median(times2)
    print(f"  the same sweep on 2 processes: {t2:.2f} s (median of {runs}; {t / t2:.2f}x "
          f"serial), {sum(bool(r['converged']) for r in rows)}/24 converged")
    print(target("24-point fe2d sweep, 2 processes", t2, 4.0))
    for extra in (["--workers", "1"], ["--workers", "2"]):   # serial, and the 2-core default
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "webfem", "traction-loss", "cases/base.toml",
                        "--mu-min", "0.1", "--model", "fe2d"] + extra, check=True,
                       capture_output=True)
        t = time.perf_counter() - t0
        cmd = " ".join(["traction-loss --model fe2d"] + extra)
        print(f"webfem traction-loss cases/base.toml --mu-min 0.1 --model fe2d "
              f"{' '.join(extra)}: {t:.2f} s (one run)")
        print(target(cmd, t, 5.0))


def main(n: int = 40):
    spec = Sweep("roller.speed", tuple(np.linspace(30.0, 44.0, n).tolist()), (("base", Case()),))
    serial_rate = None
    with tempfile.TemporaryDirectory() as tmp:
        for name, kw in WAYS:
            t0 = time.perf_counter()
            rows = run(spec, "fe1d", Path(tmp) / name.replace(" ", "_") / "s.csv", **kw)
            dt = time.perf_counter() - t0
            assert len(rows) == n
            rate = n / dt
            serial_rate = serial_rate or rate
            solve = sum(r["solve_time_s"] or 0.0 for r in rows)
            iterations = sum(r["iterations"] or 0 for r in rows)
            print(f"{name:30s} {dt:6.2f} s: {rate:6.1f} solves/s, {rate / serial_rate:.2f}x "
                  f"serial; solve {solve:5.2f} s, {iterations} iterations, outside the solves "
                  f"{dt - solve / kw.get('workers', 1):5.2f} s", flush=True)


if __name__ == "__main__":
    fe2d_targets()
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 40)
