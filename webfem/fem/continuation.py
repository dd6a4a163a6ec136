"""Continuation: reaching a hard problem through easier ones, each solved from the last.

* :func:`eshel_elrod`: the 1-D model from the Eshel-Elrod problem (impermeable,
  incompressible membrane) to the full one, permeation, compressibility and bending scaled
  by s from 0 to 1;
* :func:`web_width`: the 2-D film from a web 16 times wider (close to the 1-D solution it
  starts from) down to the true width;
* :func:`groove_depth`: the 2-D film on a grooved roller from the smooth roller (depth 0, on
  the same mesh; itself by :func:`web_width` where it must) through grooves a quarter of the
  film deep to the true depth;
* :func:`film_strength`: the 1-D model from the web resting on its asperities alone (the
  Couette flux switched off, so no film pressure) to the full film: the resting branch of
  stiff webs, which :func:`eshel_elrod`'s flying branch does not reach past its fold.

Each returns ``(u, SolveInfo)``; the info counts every Newton step of the path and says
where it stopped when it fails. The problems are duck-typed (:class:`webfem.fem.film_problem.
FoilBearing2D`, :class:`webfem.models.line.FoilBearing1D`).
"""

from __future__ import annotations

import copy
import dataclasses
import hashlib

import numpy as np

from ..progress import stage
from .grooves import GroovePattern
from .outcome import SolveInfo

__all__ = ["geometric", "web_width", "groove_depth", "eshel_elrod", "film_strength",
           "arclength", "tangent_step", "FIRST_TRY", "FIRST_DEPTH", "STEP_ITER"]

#: Newton steps a direct attempt (or the jump to s = 1) gets before the stepped path.
FIRST_TRY = 25

#: The smallest first factor :func:`geometric` tries from below (a path from f = 0).
FIRST_MIN = 1e-4


#: A path from below ends at once when its next step by 4 would reach this factor: the last
#: step is then at most 4 / LAST_STEP (5.3) instead of a step of 4 and one of up to 1.33
#: (the groove depth's 0.236 -> 0.943 -> 1 on the groove map's narrow designs: one
#: Newton solve of 6-12 steps less).
LAST_STEP = 0.75


def geometric(problem_at, u, prm, tol, max_iter, failed: SolveInfo, f: float, what: str):
    """Newton along a factor f stepped geometrically (by 4) to 1 from ``f``: each step starts
    from the last converged state on ``problem_at(f)``; a failed step is halved (in log f),
    and the path fails when the step falls below 1 %. A path from below (``f`` < 1, the
    start being the problem at f = 0) whose first step fails tries f / 4, down to
    :data:`FIRST_MIN`. ``failed``: the attempt that led
    here (its iterations are counted).

    Each step starts from the last state, not from a secant predictor through the last two:
    on grooved narrow webs the predicted starts converged to a branch with the web through
    the roller at the wrap's entry (2 of 10 hard points of benchmarks/groove_scan.py) and
    took 1.0-2.0 times the iterations."""
    done = failed
    last = None                 # the factor of the last converged step
    while True:
        with stage(f"{what} continuation, {f:.3g} x"):
            v, info = problem_at(f).plain_newton(u, prm, tol, max_iter)
        done = info.after(done)
        if info.converged:
            u, last = v, f
            if f == 1.0:
                return u, done.noted(f"after continuation in {what}")
            f = max(1.0, f / 4.0) if f > 1.0 else (1.0 if 4.0 * f >= LAST_STEP else 4.0 * f)
        else:
            if last is None and f < 1.0 and f / 4.0 >= FIRST_MIN:
                # the first step from the problem at f = 0 (e.g. the smooth film) failed: a
                # smaller one (a stiff board's 1/64 of the groove depth failed, 1/256 went)
                f /= 4.0
                continue
            if last is None or abs(np.log(f / last)) < np.log(1.01):
                done.reason = f"{what} continuation failed at {f:.3g} x the {what}: " \
                              + info.reason
                return v, done
            f = float(np.sqrt(f * last))


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


#: Newton steps a step of the depth continuation gets before it is halved.
STEP_ITER = 20

#: The depth continuation's first step: grooves this deep relative to the smooth film's
#: thinnest gap (or the roughness, where that is larger), and at most 1/64 of the depth.
FIRST_DEPTH = 0.25


def groove_depth(problem, u0, prm, tol, max_iter, failed: SolveInfo):
    """Newton from the smooth roller (grooves of depth 0 on ``problem``'s mesh) to the true
    groove depth, in steps of 4 (:func:`geometric`) from grooves :data:`FIRST_DEPTH` times
    the smooth film's thinnest gap deep.

    The smooth film is solved first, from ``u0``, and where that fails on a web with edges,
    by :func:`web_width` from the 1-D state the problem started from (``problem.line_start``):
    a narrow web (lambda ~ 1) fails a direct start even without grooves, and the grooves'
    continuation then failed at its first step (5 of the 33 webs of 5-20 mm in
    benchmarks/groove_scan.py). The first depth follows the film: a groove a few times
    deeper than the film it opens under changes the film at once (a 499 um groove's 1/64,
    7.8 um, under a 1.2 um film failed; a quarter of the film converged, each later step
    in 4-9 Newton steps).

    The path is a pure function of the problem, ``u0``, ``prm``, ``tol`` and ``max_iter``:
    it is kept (:data:`DEPTH_PATHS`) and a second call with the same ones returns it again
    (copies; ``failed`` counted in as it would have been). Why: the driver's safe start,
    the check of a resting answer, runs it from the same start as the direct start's
    fallback did (envelope #171, a board's groove cell: the same 6 steps twice)."""
    key = _depth_key(problem, u0, prm, tol, max_iter)
    kept = DEPTH_PATHS.get(key)
    if kept is None:
        kept = _groove_depth_path(problem, u0, prm, tol, max_iter)
        while len(DEPTH_PATHS) >= DEPTH_PATHS_KEPT:
            DEPTH_PATHS.pop(next(iter(DEPTH_PATHS)))
        DEPTH_PATHS[key] = (kept[0].copy(), copy.deepcopy(kept[1]))
    u, info = kept
    # the path computed after no failed attempt: ``failed`` joins it as it would have
    return u.copy(), copy.deepcopy(info).after(failed)


#: The depth continuations of the solve under way (:func:`groove_depth`), by their inputs;
#: the model clears them when a solve starts and ends (:func:`forget_depth_paths`), so what
#: a solve reports never depends on an earlier one.
DEPTH_PATHS: dict = {}
#: At most this many are kept (a cell's and its safe start's are one).
DEPTH_PATHS_KEPT = 2


def forget_depth_paths() -> None:
    """Drop the kept depth continuations (:data:`DEPTH_PATHS`)."""
    DEPTH_PATHS.clear()


def _depth_key(problem, u0, prm, tol, max_iter) -> bytes:
    """What a depth continuation depends on: the problem's nodes and configuration, the
    start, the 1-D state its width continuation would start from, the parameters and
    Newton's tolerance and limit."""
    h = hashlib.blake2b(digest_size=32)
    arrays = [problem.X, problem.Z, u0]
    line = getattr(problem, "line_start", None)
    if line is not None:
        arrays += [line[0].X, line[1]]
    for a in arrays:
        a = np.ascontiguousarray(a, dtype=float)
        h.update(repr(a.shape).encode())
        h.update(a.tobytes())
    h.update(repr((problem.config, line is not None, prm, float(tol), int(max_iter))).encode())
    return h.digest()


def _groove_depth_path(problem, u0, prm, tol, max_iter):
    """:func:`groove_depth`'s work, after no failed attempt."""
    failed = SolveInfo()
    g = problem.grooves

    def at(f):
        return problem.variant(grooves=GroovePattern(g.pitch, g.width, g.depth * f))

    flat = at(0.0)
    with stage("groove depth continuation, the smooth film"):
        u, info = flat.plain_newton(u0, prm, tol, max_iter)
    info = info.after(failed)
    if not info.converged and problem.web_edges and problem.line_start is not None:
        u, info = web_width(flat, *problem.line_start, prm, tol, max_iter, info)
    if not info.converged:
        info.reason = ("groove depth continuation failed: the smooth film (depth 0) did not "
                       "converge: " + info.reason)
        return u, info
    film = max(float(np.min(flat.gap(u, prm, flat.X))), float(prm.S))
    first = min(1.0 / 64.0, FIRST_DEPTH * film / g.depth) if g.depth > 0.0 else 1.0
    # a step that has not converged in STEP_ITER Newton steps is halved: converged steps
    # took 3-18 on the grooved webs of benchmarks/groove_scan.py, failed ones the whole
    # budget (40) before they were halved
    return geometric(at, u, prm, tol, min(max_iter, STEP_ITER), info, first, "groove depth")


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


def tangent_step(problem, u, before, after) -> np.ndarray:
    """``u``, solved for the parameters ``before``, moved along the path's tangent to
    ``after``: u - J(u)^-1 (F(u; after) - F(u; before)), the Euler step for a residual affine
    in the path's parameter, taken whole (no line search). ``u`` where it is not finite."""
    J = problem.jacobian(u, before)
    change = (problem.residual(u, after) - problem.residual(u, before))[problem.free]
    v = np.array(u, copy=True)
    v[problem.free] -= problem.solver.factor(J, problem.free)(change)
    return v if np.all(np.isfinite(v)) else u


def film_strength(problem, prm, tol, max_iter, before: SolveInfo | None = None):
    """Newton along the film's strength a (the factor of the Couette flux,
    ``prm.film_strength(a)``) from 0 to 1, starting from the web resting on its asperities.

    At a = 0 the film carries nothing (P = 0 solves it), so the web rests on contact and
    bending alone: the web's rows are solved by Newton from the web wrapped at the contact
    gap ``prm.H_c`` (:meth:`initial_guess` with ``H0 = H_c``, the pressure zero). Then the
    full problem is tried at a = 1 at once and, if that fails (after at most
    :data:`FIRST_TRY` steps), in steps of 0.25, doubled after each success and quartered
    after each failure, down to 1e-4. Why: for a stiff web (board, Dn in the hundreds or
    more) the flying film's branch ends at a fold in Dn (Dn ~ 950 for 1 mm board on the base
    roller, on mesh levels 0 and 2 alike), where :func:`eshel_elrod`'s path stalls, and Newton
    from a resting guess with the film at full strength fails its line search.
    Needs asperity contact (``prm.contact``): without it nothing holds the web at a = 0.
    With the web held through spans (``problem.spans``), each step starts on the path's
    tangent (:func:`tangent_step`) and, where the steps stall, the jump to a = 1 is tried
    from the last state: a stiff web's spans have nearly singular Jacobians, and a start
    this close to the last state has its residual near the rounding floor, where Newton's
    corrections are noise (a 1 mm board held through 1 m spans stalled at a = 0.38 on its
    refined meshes). The held ends keep the path as it was.
    Returns ``(u, SolveInfo)`` with the strengths passed in ``steps``."""
    done = before if before is not None else SolveInfo(steps=[])
    if not prm.contact:
        done = SolveInfo(**{**done.__dict__, "converged": False,
                            "reason": "film strength continuation: needs asperity contact"})
        return problem.initial_guess(prm), done
    off = prm.film_strength(0.0)
    u = problem.initial_guess(prm, H0=prm.H_c)
    u[problem.iP] = 0.0
    with stage("film strength continuation, the web on its asperities"):
        out = problem.newton(u, off, tol, max_iter, rows=problem.free_W)
    done = SolveInfo.of(out, [0.0]).after(done)
    if not out.converged:
        done.reason = "film strength continuation: the web on its asperities alone did " \
                      "not converge: " + out.reason
        return out.u, done
    u, steps = out.u, [0.0]
    a_prev, da, jump = 0.0, 0.25, True
    spans, rejumped = bool(getattr(problem, "spans", False)), False
    while True:
        a = 1.0 if jump else min(1.0, a_prev + da)
        # with spans, each step starts on the path's tangent: from the last state itself
        # the steps of a 1 mm board (base roller, span 1 m) failed their line search from
        # a = 0.38 on (the corrections at the rounding floor are large, see
        # FoilBearing1D.newton); the held ends keep their path as it was
        start = u if jump or not spans else \
            tangent_step(problem, u, prm.film_strength(a_prev), prm.film_strength(a))
        with stage(f"film strength continuation, a = {a:.3g}"):
            out = problem.newton(start, prm.film_strength(a), tol,
                                 min(max_iter, FIRST_TRY) if jump else max_iter)
        if out.converged and problem.vacuum(out.u, prm):
            # a step that ends with the absolute film pressure <= 0 has left the physical
            # path (a sub-vacuum branch of the discrete problem): a shorter step instead
            out = dataclasses.replace(out, converged=False,
                                      reason="the absolute film pressure fell to <= 0")
        # counted after the vacuum test: a path that ends on a rejected step has not
        # converged (before, the rejected step's ``converged`` was kept, and a 0.5 mm board
        # on a 30 mm roller returned its state at a = 0.83 as the answer at a = 1)
        done = SolveInfo.of(out, steps).after(done)
        if out.converged:
            u, a_prev = out.u, a
            steps.append(a)
            if a >= 1.0:
                done.steps = steps
                return u, done.noted("after continuation in the film's strength from the "
                                     "web resting on its asperities")
            da = min(2.0 * da, 1.0)
        elif not jump:      # a failed jump goes on with the first step, da = 0.25
            da *= 0.25
            if da < 1e-4 and spans and not rejumped:
                # with spans, the jump to a = 1 from where the steps stalled: the 1 mm
                # board's steps on its first refined mesh stalled at a = 0.894 (starts
                # this close put the residual near its rounding floor, where the
                # corrections are noise), the jump from there converged in 6 Newton steps
                rejumped = jump = True
                continue
            if da < 1e-4:
                return _past_folds(problem, prm, u, a_prev, tol, max_iter, steps, done,
                                   f"film strength continuation stalled at a = {a_prev:.4g}")
        elif rejumped:
            return _past_folds(problem, prm, u, a_prev, tol, max_iter, steps, done,
                               f"film strength continuation stalled at a = {a_prev:.4g}, and "
                               "the jump to a = 1 from there failed")
        jump = False


#: Pseudo-arclength continuation (:func:`arclength`): at most this many steps along the
#: path, each corrected by at most :data:`ARC_ITER` bordered Newton steps.
ARC_STEPS = 200
ARC_ITER = 15
#: Its first step moves the film strength by about this much (then it follows the path);
#: a step is at most ARC_MAX_DS long (the unknowns' 2-norm and a together; scaled units).
ARC_FIRST = 0.01
ARC_MAX_DS = 2.0
#: A step is taken only where the tangent turns by less than arccos(ARC_COS) over it.
ARC_COS = 0.9
#: The film strength's difference step of dF/da (the residual is not affine in a: the
#: streamline diffusion reads the Couette speed); its rounding error, the residual's
#: rounding floor over this step, stays below the path's own.
ARC_DA = 1e-3


def _past_folds(problem, prm, u, a_prev, tol, max_iter, steps, done, stalled):
    """Where :func:`film_strength`'s steps stall, the path from the last state by
    pseudo-arclength continuation (:func:`arclength`), which follows it around its folds;
    the failure as it was where that fails too."""
    v, info = arclength(problem, prm, u, a_prev, tol, max_iter)
    done = info.after(done)
    done.steps = steps + list(info.steps)
    if info.converged:
        return v, done.noted(f"{stalled}; past the path's folds by arclength continuation "
                             "in the film's strength, from the web resting on its asperities")
    done.converged = False
    done.reason = f"{stalled}; {info.reason}"
    return u, done


def arclength(problem, prm, u, a, tol, max_iter):
    """The film-strength path from ``u`` (solved at strength ``a``) to a = 1 by
    pseudo-arclength continuation: the path (u(s), a(s)) parametrised by its length, each
    step predicted along the tangent and corrected by Newton on the residual bordered with
    the arclength condition, so a fold in a (where the natural steps of
    :func:`film_strength` stall: the path turns back and no state lies ahead at a larger
    a) is passed. Once a step passes a = 1 the state interpolated to a = 1 is solved by
    :meth:`problem.newton` at the full problem, whose acceptance decides the answer.

    Why: a stiff board resting on a small roller (0.5 mm on a 30 mm roller at 15 m/s,
    Dn 274) puts small folds on the path near a = 0.84, where the film's inlet peak jumps
    from node to node of the under-resolved inlet layer: the natural steps stalled at a =
    0.84, 0.83 and 0.89 on mesh levels 0-2, and the path continued past them to an
    admissible answer at a = 1 (the absolute film pressure 0.12 p_a at its lowest).

    Corrector steps are halved until the bordered residual falls; a corrector converges at
    ``tol`` or within :data:`~webfem.fem.newton.FLOOR_FACTOR` of the residual's rounding
    floor (a stiff web's floor is far above ``tol``); a step that ends with the absolute
    film pressure <= 0 (:meth:`vacuum`) or whose corrector fails is halved. Returns ``(u,
    SolveInfo)``, ``steps`` the strengths passed."""
    from .newton import FLOOR_FACTOR, norm2, rounding_floor
    free = problem.free
    n_free = free.size
    iterations, history, passed = 0, [], []

    def residual(x):
        w = np.array(u, copy=True)
        w[free] = x[:n_free]
        return w, problem.residual(w, prm.film_strength(x[-1]))[free]

    def dF_da(w, s):
        return (problem.residual(w, prm.film_strength(s + ARC_DA))[free]
                - problem.residual(w, prm.film_strength(s - ARC_DA))[free]) / (2.0 * ARC_DA)

    def tangent(w, s, before=None):
        solve = problem.solver.factor(problem.jacobian(w, prm.film_strength(s)), free)
        z = solve(-dF_da(w, s))
        t = np.concatenate([z, [1.0]])
        t /= np.linalg.norm(t)
        # along the path's direction so far (a increasing at the start)
        return -t if before is not None and float(t @ before) < 0.0 else t

    def failed(reason):
        return u, SolveInfo(converged=False, iterations=iterations, residual=history[-1]
                            if history else float("inf"), history=history,
                            reason=f"arclength continuation {reason}", steps=passed)

    x = np.concatenate([u[free], [a]])
    t = tangent(u, a)
    # a first step of ARC_FIRST in a, or of ARC_FIRST in the path's length at a fold
    ds = ARC_FIRST / max(abs(t[-1]), ARC_FIRST / ARC_MAX_DS)
    for _ in range(ARC_STEPS):
        if ds < 1e-9 * (1.0 + np.linalg.norm(x)):
            return failed(f"stalled at a = {x[-1]:.4g}")
        y = x + ds * t
        ok = False
        with stage(f"arclength continuation, a = {y[-1]:.4g}"):
            for _k in range(ARC_ITER):
                w, r = residual(y)
                g = float(t @ (y - x)) - ds
                norm = float(np.hypot(norm2(r), g))
                iterations += 1
                history.append(norm)
                J = problem.jacobian(w, prm.film_strength(y[-1]))
                if not np.all(np.isfinite(r)):
                    break
                if norm2(r) <= max(tol, FLOOR_FACTOR * rounding_floor(J, w, free)) \
                        and abs(g) <= 1e-9 * (1.0 + abs(ds)):
                    ok = not problem.vacuum(w, prm)
                    break
                solve = problem.solver.factor(J, free)
                z1, z2 = solve(-r), solve(-dF_da(w, y[-1]))
                step_a = -(g + float(t[:-1] @ z1)) / (t[-1] + float(t[:-1] @ z2))
                dy = np.concatenate([z1 + step_a * z2, [step_a]])
                lam = 1.0
                while lam >= 1e-4:
                    trial = y + lam * dy
                    with np.errstate(all="ignore"):
                        _, rt = residual(trial)
                        nt = float(np.hypot(norm2(rt), float(t @ (trial - x)) - ds))
                    if np.isfinite(nt) and nt < norm:
                        break
                    lam *= 0.5
                if lam < 1e-4:
                    break
                y = trial
        if not ok:
            ds *= 0.5
            continue
        t_new = tangent(w, y[-1], t)
        if float(t_new @ t) < ARC_COS and ds > ARC_FIRST * 1e-3:
            # the path turned by more than ~25 degrees over the step: too long to be sure
            # it stayed on the same branch (at a sharp fold a long step lands on the path's
            # way back and follows it down to a = 0)
            ds *= 0.5
            continue
        if y[-1] >= 1.0:
            # the state at a = 1 interpolated between the last two on the path, then the
            # full problem solved from it
            f = (1.0 - x[-1]) / (y[-1] - x[-1])
            start = np.array(u, copy=True)
            start[free] = x[:n_free] + f * (y[:n_free] - x[:n_free])
            out = problem.newton(start, prm, tol, max_iter)
            iterations += out.iterations
            history += list(out.history)
            if out.converged and not problem.vacuum(out.u, prm):
                passed.append(1.0)
                return out.u, SolveInfo(converged=True, iterations=iterations,
                                        residual=out.residual, history=history,
                                        reason=out.reason, steps=passed)
            ds *= 0.5
            continue
        if y[-1] <= 0.0:
            return failed("turned back to a = 0")
        passed.append(float(y[-1]))
        x, t, u = y, t_new, w
        if _k <= 3:
            ds = min(1.5 * ds, ARC_MAX_DS)
    return failed(f"took {ARC_STEPS} steps without reaching a = 1 (at a = {x[-1]:.4g})")
