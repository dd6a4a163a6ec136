"""Sweep throughput of the 1-D FE model: serial (with continuation), local processes, Dask.

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
from webfem.case import Sweep
from webfem.sweeps import run

WAYS = (("serial", {}),
        ("2 processes, chunk 4", {"workers": 2, "chunk": 4}),
        ("2 processes, chunk 10 (default)", {"workers": 2}),
        ("Dask LocalCluster, 2 workers", {"workers": 2, "dask": "local"}))


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
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 40)
