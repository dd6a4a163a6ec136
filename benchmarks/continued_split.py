"""Where a continued sweep's time goes (issue 23): the base case's 24-point speed sweep
(0.5-40 m/s, log-spaced, :func:`webfem.solve_along` with fe2d, bench_speed.py's figure 2),
its continued points (2-24) timed by what they do.

Run: ``python benchmarks/continued_split.py`` from the repository root (about 10 s). Each
category's time is exclusive: a timed function called inside another counts for itself
only (a factorisation inside a Newton solve is a factorisation, not the solve). The
categories: the sparse factorisations and their fill-reducing orderings, the triangular
solves (Newton's and the chord steps'), the residual and Jacobian assemblies, building a
mesh's problem (mesh, bases, the web at the film's points) and its system (forms, sparsity
pattern), carrying states between meshes, the web evaluated at points (gaps for readout,
refinement, admissibility), the readout and the result; ``other`` is the rest (Newton's own
loop, the continuation's logic). On a shared machine the times vary 1.5-3 times between
runs; the counts do not.
"""

import collections
import functools
import sys
import time
import warnings

import numpy as np

import webfem
from webfem import load_case, solve_along
from webfem.fem import film_problem, hermite, newton, systems, transfer
from webfem.models import admissible, continued, outcome, readout

TIMES: dict = collections.defaultdict(float)
CALLS: collections.Counter = collections.Counter()
_STACK: list = []


def _enter(name):
    t = time.perf_counter()
    if _STACK:
        TIMES[_STACK[-1][0]] += t - _STACK[-1][1]
    _STACK.append([name, t])
    CALLS[name] += 1


def _leave():
    t = time.perf_counter()
    name, t0 = _STACK.pop()
    TIMES[name] += t - t0
    if _STACK:
        _STACK[-1][1] = t


def _timed(f, name):
    @functools.wraps(f)
    def g(*args, **kwargs):
        _enter(name)
        try:
            return f(*args, **kwargs)
        finally:
            _leave()
    return g


def _patch(owner, attr, name):
    """``owner.attr`` timed as ``name``, also where a webfem module imported it by name."""
    f = getattr(owner, attr)
    g = _timed(f, name)
    for module in list(sys.modules.values()):
        if getattr(module, "__name__", "").startswith("webfem") and module is not owner \
                and getattr(module, attr, None) is f:
            setattr(module, attr, g)
    if isinstance(vars(owner).get(attr), staticmethod):
        g = staticmethod(g)
    setattr(owner, attr, g)


def _timed_factor(factor):
    """SuperLU's factorisation timed, and its triangular solves apart."""
    def timed(B, spec):
        _enter("factorisation")
        try:
            lu = factor(B, spec)
        finally:
            _leave()

        class Solves:
            def solve(self, b):
                _enter("triangular solves")
                try:
                    return lu.solve(b)
                finally:
                    _leave()
        return Solves()
    return staticmethod(timed)


def main():
    warnings.simplefilter("ignore")
    base = load_case("cases/base.toml")
    webfem.solve(base, "fe2d")                 # imports and first-use caches
    newton.PatternSolver._factor = _timed_factor(newton.PatternSolver._factor)
    for owner, attr, name in (
            (newton.PatternSolver, "_plan", "fill-reducing ordering"),
            (systems.FilmSystem, "residual", "residual assembly"),
            (systems.FilmSystem, "jacobian", "Jacobian assembly"),
            (film_problem.FoilBearing2D, "__init__", "problem (mesh, bases)"),
            (transfer, "quadrature_matrices", "problem (mesh, bases)"),
            (systems.FilmSystem, "__init__", "system (forms, pattern)"),
            (film_problem.FoilBearing2D, "transfer", "state carried to another mesh"),
            (hermite.LineProbes, "__call__", "web at points (gaps)"),
            (continued, "planned_nodes", "meshes planned"),
            (readout, "read_out", "readout"),
            (admissible, "admissibility", "admissibility"),
            (outcome, "build_result", "result"),
            (webfem.api, "solve", "other")):
        _patch(owner, attr, name)
    cases = [base.updated({"roller.speed": float(u)}) for u in np.geomspace(0.5, 40.0, 24)]
    results, t0 = [], 0.0
    for i, res in enumerate(solve_along(cases, "fe2d")):
        results.append(res)
        if i == 0:                 # the cold first point left out
            TIMES.clear()
            CALLS.clear()
            t0, c0 = time.perf_counter(), time.process_time()
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    its = sum(r["iterations"] for r in results[1:])
    print(f"continued points 2-24: {wall:.2f} s ({cpu:.2f} s CPU), {its} iterations")
    for name, t in sorted(TIMES.items(), key=lambda kv: -kv[1]):
        print(f"  {name:32s} {t:6.3f} s {100 * t / wall:5.1f} %  ({CALLS[name]} calls)")


if __name__ == "__main__":
    main()
