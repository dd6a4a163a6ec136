"""2-D FE benchmark: base-case solve time and accuracy, the Newton floor, one large Newton step.

Run: ``make bench`` or ``python benchmarks/bench_fe2d.py [MAX_LEVEL]`` (default 2; each level
quadruples the unknowns of the scaling table; level 3 has about 2e5 unknowns and takes a
minute, level 4 several GB).

Prints (issue 14's targets beside each figure, met or not)
1. cases/base.toml with the default mesh: cold solve time (median of 3, caches cleared),
   continued sweep point (from the solution at 19.5 m/s, median of 3), Newton iterations,
   unknowns, central and minimum gap errors against the Richardson extrapolation of levels
   0-2, and the ratio of the solve time to one assembly + one factorisation (the floor).
2. assembly with the decorated forms against the vectorised assembly, and the factorisation
   with a fresh ordering against the reused one, on the same Jacobian.
3. one Newton step (assembly + factorisation) against the number of unknowns on the
   Eshel-Elrod problem, peak memory; then one step at about 2e5 unknowns in its own
   process (issue 14's target: <= 3 s, <= 2 GB).
"""

import resource
import sys

from common import floor, median_time, richardson, target

from webfem import load_case
from webfem.fem.newton import solve_linear
from webfem.fem.scaling import FoilParameters
from webfem.models import fe1d, fe2d


def cold(case, **opts):
    fe1d.LINE.problems.clear()
    return fe2d.solve(case, **opts)


def base_case():
    case = load_case("cases/base.toml")
    t_cold, r = median_time(lambda: cold(case), 3)
    before = fe2d.solve(case.updated({"roller.speed": case.roller.speed - 0.5}))
    t_cont, rc = median_time(lambda: fe2d.solve(case, initial=before), 3)
    levels = [r] + [fe2d.solve(case, level=lv) for lv in (1, 2)]
    err = {k: abs(r[k] / richardson(*[x[k] for x in levels]) - 1) for k in ("h_center", "h_min")}
    prm = FoilParameters.from_case(case)
    problem, u = r.state("problem"), r.state("state")
    t_asm, t_fact = floor(problem, u, prm)
    print(f"fe2d base case, default mesh: {r['n_dofs']} unknowns, {r['iterations']} iterations "
          f"(1-D start included), cold {t_cold:.3f} s, continued {t_cont:.3f} s "
          f"({rc['iterations']} iterations)")
    print(f"  error against levels 0-2 extrapolated: h_center {err['h_center']:.1e}, "
          f"h_min {err['h_min']:.1e}")
    print(f"  one assembly {t_asm * 1e3:.1f} ms + one factorisation {t_fact * 1e3:.1f} ms; "
          f"cold solve / floor = {t_cold / (t_asm + t_fact):.0f}")
    print(target("cold solve", t_cold, 0.10))
    print(target("continued sweep point", t_cont, 0.03))
    print(target("h_center error", err["h_center"], 1e-4, ""))
    print(target("h_min error", err["h_min"], 1e-3, ""))
    return problem, u, prm


def assembly_and_solver(problem, u, prm):
    t_fast, J = median_time(lambda: problem.jacobian(u, prm))
    t_forms, _ = median_time(lambda: problem.system.reference_jacobian(u, prm), 3)
    r_fast, F = median_time(lambda: problem.residual(u, prm))
    r_forms, _ = median_time(lambda: problem.system.reference_residual(u, prm), 3)
    free = problem.free
    t_fresh, _ = median_time(lambda: solve_linear(J.tocsr()[free][:, free], -F[free]))
    _, t_reuse = floor(problem, u, prm)
    print(f"  Jacobian: forms {t_forms * 1e3:.1f} ms, vectorised {t_fast * 1e3:.1f} ms "
          f"({t_forms / t_fast:.1f}x); residual: forms {r_forms * 1e3:.1f} ms, vectorised "
          f"{r_fast * 1e3:.1f} ms")
    print(f"  factorisation + solve: fresh ordering {t_fresh * 1e3:.1f} ms, reused ordering "
          f"{t_reuse * 1e3:.1f} ms")


def _eshel_elrod(lx, lz):
    """The Eshel-Elrod problem on X level ``lx`` x Z level ``lz``: (problem, state, prm)."""
    from webfem.fem.mesh import graded_nodes
    from webfem.fem.transfer import width_nodes
    from webfem.models.fe1d import FoilBearing1D
    from webfem.models.fe2d import FoilBearing2D

    prm = FoilParameters(beta=30.0, K=0.0, d=0.0, Dn=0.0, c=0.0, S=1.0, contact=0.0,
                         floor=1e-3)
    X = graded_nodes(30.0, 40.0, level=lx)
    p1 = FoilBearing1D(X)
    u1, _ = p1.solve_newton(p1.initial_guess(prm), prm)
    pb = FoilBearing2D(X, width_nodes(10.6, level=lz))
    u = pb.start_from_line(p1, u1, prm)
    pb.jacobian(u, prm)                 # the pattern, built once per mesh
    return pb, u, prm


def scaling(max_level):
    print(f"{'level':>5} {'unknowns':>9} {'assembly':>9} {'factor':>8} {'step':>8} {'peak MB':>8}")
    for lev in range(max_level + 1):
        pb, u, prm = _eshel_elrod(lev, lev)
        ta, tf = floor(pb, u, prm, runs=3)
        mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        print(f"{lev:5d} {pb.n_dofs:9d} {ta:8.3f}s {tf:7.3f}s {ta + tf:7.3f}s {mb:8.0f}",
              flush=True)


def step_2e5():
    """One Newton step (assembly + factorisation + solve) at about 2e5 unknowns (X level 3,
    Z level 2), in a fresh process so that its peak memory is its own."""
    import subprocess
    out = subprocess.run([sys.executable, __file__, "--step-2e5"], capture_output=True,
                         text=True, check=True).stdout.split()
    n, t, mb = int(out[0]), float(out[1]), float(out[2])
    print(f"one Newton step at {n} unknowns: {t:.2f} s (assembly + factorisation with the "
          f"ordering reused, as from a solve's second step), peak memory {mb:.0f} MB (its own "
          "process, imports included)")
    print(target(f"one Newton step at {n} unknowns", t, 3.0))
    print(target("peak memory", mb, 2048, "MB"))


if __name__ == "__main__":
    if sys.argv[1:] == ["--step-2e5"]:
        pb, u, prm = _eshel_elrod(3, 2)
        ta, tf = floor(pb, u, prm, runs=3)
        print(pb.n_dofs, ta + tf, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
        sys.exit(0)
    problem, u, prm = base_case()
    assembly_and_solver(problem, u, prm)
    scaling(int(sys.argv[1]) if len(sys.argv) > 1 else 2)
    step_2e5()
