"""Shared helpers of the benchmarks: medians of repeated runs, the Newton floor, targets.

The machines are shared and noisy: every time printed is the median of several runs.
"""

import statistics
import time

import numpy as np


def median_time(f, runs: int = 5):
    """(median wall time in s, last return value) of ``runs`` calls of f()."""
    times, out = [], None
    for _ in range(runs):
        t0 = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def floor(problem, u, prm, runs: int = 5) -> tuple[float, float]:
    """(one residual + Jacobian assembly, one factorisation and solve) at the state u, in s,
    as Newton does them (the vectorised assembly, the pattern-reusing solver)."""
    from webfem.fem.newton import SOLVER

    t_asm, (F, J) = median_time(lambda: (problem.residual(u, prm), problem.jacobian(u, prm)),
                                runs)
    free = problem.free
    SOLVER.solve(J, free, -F[free])            # the pattern is seen twice: its plan is made
    SOLVER.solve(J, free, -F[free])
    t_fact, _ = median_time(lambda: SOLVER.solve(J, free, -F[free]), runs)
    return t_asm, t_fact


def target(name: str, value: float, limit: float, unit: str = "s") -> str:
    """One line: the figure, its target and whether it is met."""
    ok = value <= limit
    return f"  target {name}: {value:.3g} {unit} <= {limit:g} {unit} -> {'met' if ok else 'NOT met'}"


def richardson(h0: float, h1: float, h2: float) -> float:
    """Extrapolated value from three levels (each halving the cells), with the observed order;
    the finest value when the differences do not shrink."""
    d1, d2 = abs(h1 - h0), abs(h2 - h1)
    if d2 == 0.0 or d1 <= d2:
        return h2
    p = np.log2(d1 / d2)
    return h2 + (h2 - h1) / (2.0**p - 1.0)
