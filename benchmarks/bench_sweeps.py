"""Sweep throughput of the 1-D FE model: serial (with continuation), local processes, Dask.

Run: ``python benchmarks/bench_sweeps.py [N_POINTS]`` (default 40 speeds of the base case).
Prints solves per second for each way and the ratio to serial. On a 2-core machine the
parallel runs can at best double the serial rate, less the start-up of the workers.
"""

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from webfem import Case
from webfem.case import Sweep
from webfem.sweeps import run


def main(n: int = 40):
    spec = Sweep("roller.speed", tuple(np.linspace(10.0, 40.0, n).tolist()), (("base", Case()),))
    rates = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, kw in (("serial", {}), ("2 processes", {"workers": 2}),
                         ("Dask LocalCluster (2 workers)", {"workers": 2, "dask": "local"})):
            t0 = time.perf_counter()
            rows = run(spec, "fe1d", Path(tmp) / name.replace(" ", "_") / "s.csv", **kw)
            dt = time.perf_counter() - t0
            assert len(rows) == n and all(r["converged"] for r in rows)
            rates[name] = n / dt
            print(f"{name:32s} {n} solves in {dt:6.2f} s: {n / dt:6.1f} solves/s, "
                  f"{rates[name] / rates['serial']:.2f}x serial", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 40)
