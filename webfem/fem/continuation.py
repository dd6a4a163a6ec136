"""Continuation: reaching a hard problem through easier ones, each solved from the last.

* :func:`eshel_elrod`: the 1-D model from the Eshel-Elrod problem (impermeable,
  incompressible membrane) to the full one, permeation, compressibility and bending scaled
  by s from 0 to 1;
* :func:`web_width`: the 2-D film from a web 16 times wider (close to the 1-D solution it
  starts from) down to the true width;
* :func:`groove_depth`: the 2-D film on a grooved roller from grooves 1/64 as deep (close to
  the smooth roller) to the true depth.

Each returns ``(u, SolveInfo)``; the info counts every Newton step of the path and says
where it stopped when it fails. The problems are duck-typed (:class:`webfem.fem.film_problem.
FoilBearing2D`, :class:`webfem.models.line.FoilBearing1D`).
"""

from __future__ import annotations

import numpy as np

from ..progress import stage
from .grooves import GroovePattern
from .outcome import SolveInfo

__all__ = ["geometric", "web_width", "groove_depth", "eshel_elrod", "FIRST_TRY"]

#: Newton steps a direct attempt (or the jump to s = 1) gets before the stepped path.
FIRST_TRY = 25


def geometric(problem_at, u, prm, tol, max_iter, failed: SolveInfo, f: float, what: str):
    """Newton along a factor f stepped geometrically (by 4) to 1 from ``f``: each step starts
    from the last converged state on ``problem_at(f)``; a failed step is halved (in log f),
    and the path fails when the step falls below 1 %. ``failed``: the attempt that led
    here (its iterations are counted)."""
    done = failed
    f_prev = None
    while True:
        with stage(f"{what} continuation, {f:.3g} x"):
            v, info = problem_at(f).plain_newton(u, prm, tol, max_iter)
        done = info.after(done)
        if info.converged:
            u, f_prev = v, f
            if f == 1.0:
                return u, done.noted(f"after continuation in {what}")
            f = max(1.0, f / 4.0) if f > 1.0 else min(1.0, 4.0 * f)
        else:
            if f_prev is None or abs(np.log(f / f_prev)) < np.log(1.01):
                done.reason = f"{what} continuation failed at {f:.3g} x the {what}: " \
                              + info.reason
                return v, done
            f = float(np.sqrt(f * f_prev))


def web_width(problem, line_problem, line_state, prm, tol, max_iter, failed: SolveInfo):
    """Newton from a web 16 times wider than ``problem``'s down to its width. The meshes
    differ only by the scaling of Z, so a state carries over as it is (the pressure as a
    function of Z / lambda); the first starts from the 1-D solution."""
    scaled = {}

    def at(f):
        if f not in scaled:
            scaled[f] = problem.variant(Z=problem.Z * f)
        return scaled[f]

    start = at(16.0).start_from_line(line_problem, line_state, prm)
    return geometric(at, start, prm, tol, max_iter, failed, 16.0, "width")


def groove_depth(problem, u0, prm, tol, max_iter, failed: SolveInfo):
    """Newton from grooves 1/64 as deep as ``problem``'s (close to the smooth roller the
    start comes from) to their true depth."""
    g = problem.grooves

    def at(f):
        return problem.variant(grooves=GroovePattern(g.pitch, g.width, g.depth * f))

    return geometric(at, u0, prm, tol, max_iter, failed, 1.0 / 64.0, "groove depth")


def eshel_elrod(problem, prm, tol, max_iter, before: SolveInfo | None = None):
    """Newton along the continuation from the Eshel-Elrod problem, from its cold start:
    permeation K, compressibility d and bending Dn scaled by s from 0 to 1
    (``prm.homotopy(s)``; the impermeable membrane converges from cold).

    From the solution at s = 0 the full problem is tried at once: a far better start than the
    cold one (on a 110-case grid all 18 continued solves took this jump, 7-12 Newton steps
    fewer each, the same mesh and gaps to 1e-12). If the jump fails (after at most
    :data:`FIRST_TRY` steps), the steps are 0.25, then doubled (0.25, 0.75, 1), each failure
    quartering the step, down to 1e-4. ``problem`` offers ``initial_guess(prm)``,
    ``consistent_pressure(u, prm)`` and ``newton(u, prm, tol, max_iter)``; ``before``: the
    iterations already spent, counted in. Returns ``(u, SolveInfo)`` with the parameters
    passed in ``steps``."""
    done = before if before is not None else SolveInfo(steps=[])
    first_try = min(max_iter, FIRST_TRY)
    u = problem.initial_guess(prm.homotopy(0.0))
    s, ds, steps = 0.0, 0.25, []
    first, jump, s_prev = True, False, 0.0
    while True:
        p = prm.homotopy(s)
        with stage(f"Eshel-Elrod continuation, s = {s:.3g}"):
            out = problem.newton(problem.consistent_pressure(u, p), p, tol,
                                 first_try if jump else max_iter)
        done = SolveInfo.of(out, steps).after(done)
        if out.converged:
            u = out.u
            steps.append(s)
            if s >= 1.0:
                done.steps = steps
                return u, done
            ds = min(2.0 * ds, 1.0) if not first else ds
            s_prev = s
            s, jump = (1.0, True) if first else (min(1.0, s + ds), False)
            first = False
        elif jump:
            # the jump from s = 0 failed: the stepped schedule from there
            jump = False
            s = min(1.0, s_prev + ds)
        else:
            done.steps = steps
            if first:
                done.reason = "continuation: Eshel-Elrod start failed: " + out.reason
                return out.u, done
            ds *= 0.25
            if ds < 1e-4:
                done.converged = False
                done.reason = f"continuation stalled at s = {s_prev:.4g}"
                return u, done
            s = min(1.0, s_prev + ds)
