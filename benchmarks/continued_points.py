"""Where a continued sweep point's Newton iterations go (issue 23, item 1).

Run: ``python benchmarks/continued_points.py [lo hi n]`` from the repository root (the
base case's log-spaced speed sweep, default 0.5-40 m/s in 24 points: bench_speed.py's; about
10 s). For each point it prints the iterations the result reports and, per Newton solve,
the stage it ran in (the coarse mesh first, the fine solve, a refinement round, the error
estimate's solves), its steps and sparse factorisations (a step without one is a chord step)
and, with ``-v``, its residual history. For each continued point also how far its starts are
from its answer (relative 2-norm of the DOF vector, where they are on the answer's mesh):
the predictor's (:func:`webfem.models.continued.predicted`: the previous state, a secant or a
quadratic in log speed), the previous state's, and the fine Newton's start (the two-grid
start). Iteration and factorisation counts do not depend on the machine's load.
"""

import statistics
import sys
import warnings

import numpy as np

from webfem import load_case, solve_along
from webfem.fem import newton
from webfem.models import continued, fe2d
from webfem.progress import reporting


def _relative(start, state):
    """|start - answer| / |answer| where ``start`` is on the answer's mesh, else None."""
    u, X0, Z0 = start
    if X0.shape != state.X.shape or Z0.shape != state.Z.shape or u.shape != state.u.shape \
            or not (np.allclose(X0, state.X) and np.allclose(Z0, state.Z)):
        return None
    return float(np.linalg.norm(u - state.u) / np.linalg.norm(state.u))


def main(lo=0.5, hi=40.0, n=24, verbose=False):
    warnings.simplefilter("ignore")
    base = load_case("cases/base.toml")
    cases = [base.updated({"roller.speed": float(u)}) for u in np.geomspace(lo, hi, n)]
    events, starts = [], {}
    predicted, start, factor = continued.predicted, fe2d.FILM.start, \
        newton.PatternSolver.factor

    def predicted_(problem, case, restart):
        u0, note = predicted(problem, case, restart)
        starts["predictor"] = (u0.copy(), problem.X.copy(), problem.Z.copy())
        starts["previous"] = (restart.u.copy(), problem.X.copy(), problem.Z.copy())
        return u0, note

    def start_(case, prm, options, restart, informed=True):
        out = start(case, prm, options, restart, informed)
        if restart is not None and "fine start" not in starts:
            p = out.problem
            starts["fine start"] = (out.u0.copy(), p.X.copy(), p.Z.copy())
        return out

    def factor_(self, A, free):
        events.append("F")
        return factor(self, A, free)

    continued.predicted, fe2d.FILM.start, newton.PatternSolver.factor = \
        predicted_, start_, factor_
    its, facts = [], []
    try:
        with reporting(events.append):
            for i, res in enumerate(solve_along(cases, "fe2d")):
                calls = []
                for e in events:
                    if e == "F":
                        if calls:
                            calls[-1][2] += 1
                    elif e.iteration == 0:
                        calls.append([e.stage[-1] if e.stage else "", [e.residual], 0])
                    else:
                        calls[-1][1].append(e.residual)
                events.clear()
                errors = {k: _relative(v, res.restart) for k, v in starts.items()}
                starts.clear()
                its.append(res["iterations"])
                facts.append(sum(c[2] for c in calls))
                told = ", ".join(f"{k} {v:.1e}" if v is not None else f"{k} on another mesh"
                                 for k, v in errors.items())
                print(f"{i:2d} {cases[i].roller.speed:6.3g} m/s: {res['iterations']:2d} "
                      f"iterations, {facts[-1]} factorisations, {res['n_dofs']:,} unknowns"
                      + (f"; start errors: {told}" if told else ""))
                for name, history, nf in calls:
                    line = f"     {len(history) - 1:2d} steps, {nf} factorisations: {name}"
                    if verbose:
                        line += "  " + " ".join(f"{r:.1e}" for r in history)
                    print(line)
    finally:
        continued.predicted, newton.PatternSolver.factor = predicted, factor
        del fe2d.FILM.start
    print(f"continued points: iterations median {statistics.median(its[1:]):g} (range "
          f"{min(its[1:])}-{max(its[1:])}, {sum(its[1:])} in all), factorisations median "
          f"{statistics.median(facts[1:]):g} ({sum(facts[1:])} in all); the cold first "
          f"point {its[0]} iterations, {facts[0]} factorisations")


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "-v"]
    main(*(float(a) for a in args[:2]), *(int(a) for a in args[2:3]),
         verbose="-v" in sys.argv[1:])
