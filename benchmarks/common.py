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


def machine_reference(runs: int = 9) -> float:
    """The shortest time in ms (the least disturbed by other work on a shared machine) of a fixed piece of the work webfem's solves do, on this
    machine: the sparse LU factorisation (SuperLU, minimum-degree ordering) of a 2-D
    nine-point Laplacian on a 100 x 100 grid (10,000 unknowns, about the base case's mesh)
    and a batch of element-style contractions (``numpy.einsum``), in one thread. The same
    code's timings on two machines scale roughly as their references do; printed beside
    every speed benchmark, so figures from different machines can be compared."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    from threadpoolctl import threadpool_limits

    n = 100
    one = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n))
    eye = sp.identity(n)
    A = (sp.kron(one, eye) + sp.kron(eye, one) + 0.25 * sp.kron(one, one)
         + 1e-3 * sp.identity(n * n)).tocsc()
    rng = np.random.default_rng(0)
    B, C = rng.standard_normal((2000, 9, 9)), rng.standard_normal((2000, 9, 16))

    def work():
        spla.splu(A, permc_spec="MMD_AT_PLUS_A")
        np.einsum("eij,ejq->eiq", B, C)
    with threadpool_limits(1):
        work()
        times = []
        for _ in range(runs):
            t0 = time.perf_counter()
            work()
            times.append(time.perf_counter() - t0)
    return 1e3 * min(times)
