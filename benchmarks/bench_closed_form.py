"""Throughput of the vectorised closed-form model (operating points per second).

Run: ``make bench`` or ``python benchmarks/bench_closed_form.py [N]``. Prints times and
points per second; the target is >= 1e6 points/s on a 2-core machine. The wrap average of
mu uses the exact integral over the linear Eq. 21 gap (no quadrature).
"""

import sys
import time

import numpy as np

from webfem.models.closed import evaluate


def main(n: int = 1_000_000, repeats: int = 5) -> None:
    rng = np.random.default_rng(1)
    args = dict(R=rng.uniform(0.035, 0.1, n), U_r=rng.uniform(0.5, 40.0, n), U_w=0.0,
                L=rng.uniform(0.02, 0.5, n), T=rng.uniform(40.0, 120.0, n),
                B=np.radians(rng.uniform(20.0, 180.0, n)), k=5e-15, t=70e-6, eta=1.81e-5,
                E_b=175e3, sigma=4e-6, mu_cc=0.3, C=0.4)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = evaluate(**args)
        times.append(time.perf_counter() - t0)
    assert np.isfinite(out["mu"]).all()
    best, median = min(times), float(np.median(times))
    print(f"closed form: {n} operating points, best {best:.3f} s, median {median:.3f} s")
    print(f"throughput: {n / median:.3e} points/s (median), {n / best:.3e} points/s (best); "
          f"target 1e6/s -> ratio {n / median / 1e6:.2f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000)
