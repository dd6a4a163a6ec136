"""Calibration benchmark: fit mu_cc and C with fe2d to 24 measured rows (issue 14's target).

Run: ``make bench`` or ``python benchmarks/bench_calibration.py``. The 24 rows are made by
fe2d itself at 24 roller speeds of the base case (1 to 40 m/s, log-spaced) with known
constants (mu_cc = 0.25, C = 1.5 x the case's); the fit starts from the case's constants.
Prints the time of the fit (its 24 fe2d gap solves and the least-squares iterations), the
recovered constants against the true ones, and the target (<= 60 s).
"""

import time
import warnings

import numpy as np
from common import target

from webfem import load_case, solve
from webfem.calibrate import calibrate
from webfem.errors import ValidityWarning

TRUE = {"friction.mu_cc": 0.25}


def rows_from_fe2d(case, speeds):
    """Measured rows: fe2d's mu at each speed with the true constants."""
    true = case.updated({**TRUE, "friction.speed_constant":
                         1.5 * case.friction.speed_constant})
    rows = []
    for u in speeds:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            r = solve(true.updated({"roller.speed": float(u)}), model="fe2d")
        rows.append({"roller.speed": float(u), "mu": r["mu"]})
    return rows, true


def main():
    case = load_case("cases/base.toml")
    speeds = np.geomspace(1.0, 40.0, 24)
    t0 = time.perf_counter()
    rows, true = rows_from_fe2d(case, speeds)
    t_rows = time.perf_counter() - t0
    t0 = time.perf_counter()
    fit = calibrate(rows, case, model="fe2d")
    t_fit = time.perf_counter() - t0
    est = fit.estimates
    print(f"calibration with fe2d, 24 rows (made by fe2d in {t_rows:.1f} s): fit {t_fit:.1f} s; "
          f"mu_cc {est['mu_cc']:.4f} (true {true.friction.mu_cc:.4f}), C "
          f"{est['speed_constant']:.4g} (true {true.friction.speed_constant:.4g})")
    print(target("calibration with fe2d on 24 rows", t_fit, 60.0))


if __name__ == "__main__":
    main()
