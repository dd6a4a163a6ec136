"""The traction-loss search's solves: the scan of roller speeds (the web at the case's ratio
U_w/U_r, :func:`webfem.line_speed.at_speed`) and the root find after it.

:func:`scan` walks the speeds upwards with continuation and stops at the first crossing (a
speed where mu is below the threshold after having reached it): the speeds above cannot
move it. An FE scan walks the speeds in two runs, the lowest :data:`LOW_SHARE` and the
rest, the second from a cold start, on one process or two: so its answer is the same to the
bit whatever the machine's cores. On two, this process walks the low run while a worker
walks the other, stops at a crossing of its own and refines it right away (:func:`refine`)
while the low run is still being walked: where it is the scan's first crossing, the root
find is done when the scan is.
"""

from __future__ import annotations

import contextlib
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass

from threadpoolctl import threadpool_limits

from .api import solve_along
from .case import Case
from .errors import ConvergenceError, NoAdmissibleSolution
from .line_speed import at_speed
from .models.options import Options

__all__ = ["scan", "refine", "crossing", "Refused", "LOW_SHARE"]

#: Models that answer a point in about a millisecond or less: a worker process would cost
#: more than it saves, so their scans stay in this process whatever ``workers`` says.
_AT_ONCE = ("closed-form", "fitted")

#: Share of a two-process scan's speeds walked by the calling process: the low ones, which
#: cost more per point (the web rests on its asperities; 0.12-0.37 s against 0.04-0.26 s
#: above 5 m/s for fe2d on the base case), while the worker pays a cold start and the root
#: find. The base case's fe2d search (24 speeds, crossing at 23.4 m/s): with 0.375 this
#: process walks 9 speeds in 1.67 s CPU, the worker 9 and the root find in 1.83 s; with
#: 0.42, 10 in 1.85 s against 8 and the root find in 1.84 s.
LOW_SHARE = 0.375


@dataclass(frozen=True)
class Refused:
    """A scanned speed at which the case is not one the model holds
    (:class:`~webfem.errors.NoAdmissibleSolution`: the closed form's contact gap above R/100
    as the moving web's T_eff falls, say): the scan ends at the speed before it, its answer
    the speeds solved so far. ``speed`` [m/s] the roller's, ``reason`` the model's words."""

    speed: float
    reason: str

    def error(self, model: str, where: str = "the scan's first speed") -> NoAdmissibleSolution:
        """The error where nothing can be answered: no speed below was solved (``where``
        says which speed it was: the scan's first, or one inside the root find's bracket)."""
        return NoAdmissibleSolution(f"traction-loss search: the {model} model has no answer "
                                    f"at U_r = {self.speed:.4g} m/s, {where}: {self.reason}")


def crossing(mu, mu_min: float) -> int | None:
    """Index of the first value below ``mu_min`` after one at or above it (NaN is neither),
    or None."""
    reached = False
    for i, m in enumerate(mu):
        if m >= mu_min:
            reached = True
        elif reached and m < mu_min:
            return i
    return None


def scan(case: Case, speeds, model: str, opts: Options, workers: int = 1,
         stop: float | None = None, xtol: float = 1e-3):
    """Results at ``speeds`` in order with continuation, the number of solves made, a
    worker's refinement of the first crossing (None: refine it with :func:`refine`), and
    where the scan ended early: a :class:`Refused` speed, or None.

    A speed the model refuses (:class:`~webfem.errors.NoAdmissibleSolution`) before any
    crossing ends the scan there: the results are the speeds below it (the speeds above
    are not walked: a scan with a hole could miss the crossing), and the :class:`Refused`
    says why; refused at the first speed, it is an error. A solve that does not converge
    before any crossing ends the walk too, its ConvergenceError (naming the speed) in place
    of the :class:`Refused`: the caller raises it, saying what the speeds below found.

    ``stop``: end the walk at the first crossing of ``stop`` (:func:`crossing`); the
    results then end there. An FE model's speeds are walked in two runs
    (:func:`_in_runs`), the second from a cold start, on a worker process where
    ``workers`` > 1 (more than 2 are not used): the same results either way; the worker's
    refinement, if any, is ``((a, b), speed, cache)`` as :func:`refine`'s between the scan
    speeds ``a`` and ``b``, to ``xtol``.
    """
    if len(speeds) > 2 and model not in _AT_ONCE:
        return _in_runs(case, speeds, model, opts, workers > 1, stop, xtol)
    out, err = _walk(case, speeds, model, opts, stop=stop)
    return _ended(out, len(out), err, model)


def refine(case: Case, model: str, opts: Options, a: float, b: float, at_a, at_b,
           mu_min: float, xtol: float):
    """Brent's method for the speed where mu crosses ``mu_min`` between the solved speeds
    ``a < b`` (results ``at_a`` and ``at_b``), to ``xtol`` relative to ``a``: the speed and
    every result by speed (the two given first; the others are the solves made)."""
    # imported here: on two processes the worker that refines pays for it (0.05 s), not
    # the command's start
    from scipy.optimize import brentq

    # the bracket's ends are the scan's own answers: Brent's first two evaluations read
    # them (solving them again cost 0.6 s of the base case's 6-9 s fe2d search)
    cache = {a: at_a, b: at_b}

    def f(u):
        if u not in cache:
            # each evaluation starts from the nearest speed solved so far
            nearest = cache[min(cache, key=lambda v: abs(v - u))]
            out, err = _walk(case, [u], model, opts, initial=nearest)
            if err is not None:
                raise (err.error(model, f"inside the bracket {a:.4g}..{b:.4g} m/s of the "
                                        "crossing") if isinstance(err, Refused) else err)
            cache[u] = out[0]
        return cache[u]["mu"] - mu_min

    return float(brentq(f, a, b, xtol=xtol * a, rtol=1e-10)), cache


def _walk(case: Case, speeds, model: str, opts: Options, initial=None,
          stop: float | None = None):
    """:func:`scan`'s serial walk: ``(results, None)``, or the results before a solve that
    raised and why: a :class:`Refused` speed, a ConvergenceError naming its speed or another
    error; returned, so a worker sends it back with the results before it."""
    # the line moves: the web keeps the case's ratio to the roller (webfem.line_speed)
    cases = [at_speed(case, float(u)) for u in speeds]
    out: list = []
    try:
        for res in solve_along(cases, model, opts, keep_failures=False, initial=initial):
            out.append(res)
            if stop is not None and crossing([r["mu"] for r in out], stop) is not None:
                break
    except NoAdmissibleSolution as err:
        # the case at this speed is not one the model holds: the scan's answer ends below it
        return out, Refused(float(speeds[len(out)]), " ".join(str(err).split()))
    except ConvergenceError as err:
        u = float(speeds[len(out)])
        return out, ConvergenceError(f"traction-loss search: the {model} solve at U_r = "
                                     f"{u:.4g} m/s did not converge ({err})", err.result,
                                     err.history)
    except Exception as err:   # noqa: BLE001 - the caller raises it where the scan needs it
        return out, err
    return out, None


def _run(case: Case, speeds, model: str, opts: Options, stop, xtol: float):
    """The high run of :func:`_in_runs` in a worker: :func:`_walk`, then :func:`refine` at a
    crossing of its own. Returns the slim results, the error, the refinement (None where
    there is no crossing or a solve of the root find failed: the caller's, should it need
    it) and the root find's solves."""
    out, err = _walk(case, speeds, model, opts, stop=stop)
    k = None if stop is None or err is not None else crossing([r["mu"] for r in out], stop)
    refined, made = None, 0
    if k is not None:
        a, b = float(speeds[k - 1]), float(speeds[k])
        try:
            speed, cache = refine(case, model, opts, a, b, out[k - 1], out[k], stop, xtol)
        except Exception:   # noqa: BLE001 - the caller refines again if it needs this one
            pass
        else:
            made = len(cache) - 2
            refined = ((a, b), speed, {u: r.slim() for u, r in cache.items()})
    return [r.slim() for r in out], err, refined, made


def _in_runs(case: Case, speeds, model: str, opts: Options, parallel: bool,
             stop: float | None, xtol: float):
    """:func:`scan` in two runs of consecutive speeds, each with continuation and each
    stopping at a crossing of its own: the lowest :data:`LOW_SHARE` of the speeds, then the
    rest from a cold start (a cold solve ends where a continued one does, on a mesh of its
    own). ``parallel``: a worker process walks the second run (and refines its crossing)
    while this one walks the first; else this process walks both, the second only where the
    first has no crossing. The results are the same either way (the worker's refinement
    is the root find this process would make), so the answer does not depend on the
    machine's cores. A run ends early only at a crossing of its own, so the scan's first
    crossing comes before any gap; the count of solves includes those made past it. A
    worker that dies is replaced by the same walk here."""
    first = max(1, round(LOW_SHARE * len(speeds)))
    high = speeds[first:]
    pool = future = None
    if parallel:
        from .sweeps.workers import Processes
        pool = Processes(1)
        future = pool.pool.submit(_run, case, high, model, opts, stop, xtol)
    try:
        # one BLAS thread here too where a worker runs beside this process
        with threadpool_limits(limits=1) if parallel else contextlib.nullcontext():
            low, err = _walk(case, speeds[:first], model, opts, stop=stop)
        done = err is not None or (stop is not None and
                                   crossing([r["mu"] for r in low], stop) is not None)
        got = None      # the high run: (results, error, refinement, the root find's solves)
        if future is not None:
            if done:
                pool.stop()     # the low run ends the scan: the worker's run is not needed
            else:
                try:
                    got = future.result()
                except BrokenProcessPool:
                    pass        # the worker died (killed, out of memory): walk it here
        if got is None and not done:
            # kept whole: the root find continues from the solved states, as the worker's
            got = (*_walk(case, high, model, opts, stop=stop), None, 0)
    except BaseException:
        if pool is not None:
            pool.stop()
        raise
    finally:
        if pool is not None:
            pool.close()
    out, why, refined, solved = low, err, None, len(low)
    if got is not None:
        res, failed, refined, made = got
        out, why, solved = low + res, failed, solved + len(res) + made
    j = None if stop is None else crossing([r["mu"] for r in out], stop)
    if j is not None:
        bracket = (float(speeds[j - 1]), float(speeds[j]))
        kept = refined if refined and refined[0] == bracket else None
        return out[:j + 1], solved, kept, None
    return _ended(out, solved, why, model)


def _ended(out, solved: int, why, model: str):
    """:func:`scan`'s answer without a crossing to refine, the walk ended at ``why`` (None:
    it reached its last speed): a refused speed or a solve that did not converge after
    solved ones ends the scan there (the caller says what the speeds below found, and
    raises the latter); a first speed refused, or any other error, is raised."""
    if why is None or (isinstance(why, (Refused, ConvergenceError)) and out):
        return out, solved, None, why
    raise why.error(model) if isinstance(why, Refused) else why
