"""Would a looser coarse solve do for a continued point? (issue 23, figure 3)

A continued sweep point solves its coarser mesh first (the two-grid start,
:meth:`webfem.models.fe2d._Film._two_grid`), and the mesh error estimate reads the change
between that coarse answer and the fine one. Both are solved to Newton's tolerance (1e-9).
This measures, on the base case's 24-point speed sweep (bench_speed.py's), what stopping the
coarse Newton at a looser residual would do: for each continued point whose coarse mesh was
solved once, the coarse Newton is run again from the same start to residuals 1e-4 .. 1e-8,
and each quantity's coarse error (against the coarse answer at 1e-9, measured as the error
estimate measures, :func:`webfem.models.readout.errors_between`) is printed over the
point's stated error of that quantity, with the Newton steps it took.

Run: ``python benchmarks/coarse_tolerance.py [lo hi n]`` from the repository root (about
15 s).

Measured (2026-11-25): at a residual of 1e-6 the coarse Newton takes one step fewer than
at 1e-9 on 16 of the 23 continued points (two fewer on 2; 18 of the sweep's 179 continued
iterations, all chord steps), and h_min, mu and the contact share move by at most 0.14 % of their
stated errors (3 % at 1e-5, 35 % at 1e-4). But the central gap's stated error is at the
rounding level below 5 m/s (1e-16..1e-13 relative: the two meshes agree there), and the
coarse answer at 1e-6 errs by up to 4e-11: that stated error would grow 10-10,000 times
(still far below ``error_tol``, 1e-3), and with an error of that size beside a difference
this small the stated value no longer measures the difference. A coarse tolerance
justified by the size of the difference must meet the smallest difference, the rounding
level: not adopted. The step it would save is a chord step on the coarse mesh (a residual
and a triangular solve, 1-2 ms of a point's ~150 ms); no factorisation.
"""

import sys
import warnings

import numpy as np

from webfem import load_case, solve_along
from webfem.models import fe2d, readout

TOLERANCES = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8)


def main(lo=0.5, hi=40.0, n=24):
    warnings.simplefilter("ignore")
    base = load_case("cases/base.toml")
    cases = [base.updated({"roller.speed": float(u)}) for u in np.geomspace(lo, hi, n)]
    solved = []
    rounds = fe2d._coarse_rounds

    def recorded(case, prm, options, coarse, u0, what, **kwargs):
        out = rounds(case, prm, options, coarse, u0, what, **kwargs)
        if out is not None and what == "the coarser mesh first":
            solved.append((prm, options, coarse, u0, out))
        return out
    fe2d._coarse_rounds = recorded
    worst = dict.fromkeys(TOLERANCES, 0.0)
    try:
        for case, res in zip(cases, solve_along(cases, "fe2d")):
            if not solved:
                continue                      # the cold first point
            prm, options, first, u0, (coarse, uc, _) = solved.pop()
            solved.clear()
            if coarse is not first:
                print(f"{case.roller.speed:6.3g} m/s: the coarse mesh was refined, left out")
                continue
            answer = readout.read_out(case, coarse, uc, prm)
            stated = {q: res[f"error_{q}"] for q in readout.READ_QUANTITIES}
            line = []
            for tol in TOLERANCES:
                v, info = coarse.plain_newton(u0, prm, tol, options.max_iter,
                                              fe2d.DIRECT_STEPS)
                err = readout.errors_between(case, answer,
                                             readout.read_out(case, coarse, v, prm))
                ratio = {q: err[q] / stated[q] if stated[q] else np.inf for q in err}
                others = max(r for q, r in ratio.items() if q != "h_center")
                worst[tol] = max(worst[tol], others)
                line.append(f"{tol:.0e}: {info.iterations} steps, h_center x{ratio['h_center']:.1e}"
                            f", others x{others:.1e}")
            print(f"{case.roller.speed:6.3g} m/s: " + "; ".join(line))
    finally:
        fe2d._coarse_rounds = rounds
    print("largest coarse error over the stated error, h_min, mu and contact share: "
          + ", ".join(f"{tol:.0e}: {w:.2g}" for tol, w in worst.items()))


if __name__ == "__main__":
    main(*(float(a) for a in sys.argv[1:3]), *(int(a) for a in sys.argv[3:4]))
