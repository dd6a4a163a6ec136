"""Balanced stopping: Newton ends where its algebraic error is negligible against the mesh
error the answer states.

A continued sweep point, and a cold start on a smooth roller (whose mesh is decided up front),
solves two meshes, the coarser one (the mesh error estimate's partner and the fine mesh's
start) and the answer's, each to a residual of ``tol`` (1e-9, scaled) by default: several
chord steps past the iterate whose error in every quantity a user reads is already far below
the error the answer states. :func:`acceptor` gives
:func:`webfem.fem.newton.newton` the test that stops there: at an iterate ``u`` in Newton's
local convergence (the simplified correction ``du`` at most
:data:`webfem.fem.newton.ACCEPT_CONTRACTION` times the step that led there), the change
``du`` makes to h_center, h_min, mu and the contact share (:func:`~webfem.models.readout.
errors_between`, the estimate's own measure), times :data:`SAFETY`, bounds the iterate's
algebraic error in them (plus :data:`FLOOR`); the iterate is accepted where that bound is at
most ``share`` x ``error_tol``. The iterate is read in full (:func:`~webfem.models.readout.
read_out`: the answer's read-out, kept if accepted), ``u + du`` on the iterate's wrap
quadrature (:func:`~webfem.models.readout.read_moved`, about two thirds of the price: no
search for its jump crossings, no new tables of the basis functions; the crossings' moves
bounded and added to mu's change), in full only where a quadrature point's gap crosses a
jump. The bounds are added to the stated errors (:func:`stated`): the answer's twice (its
error, and its share of the estimate's change), the coarser mesh's once.

Where it applies is decided in :func:`enabled` alone: Newton with the mesh error estimate
on, ``tol`` left at its default (a ``tol`` the user sets is met strictly) and
``algebraic_share`` > 0.
"""

from __future__ import annotations

import weakref
from typing import Callable

import numpy as np

from .readout import READ_QUANTITIES, error_scale, errors_between, read_moved, read_out

__all__ = ["SAFETY", "acceptor", "enabled", "stated"]

#: The bound is this many times the change the simplified correction makes: the distance to
#: the discrete solution is at most the correction / (1 - theta) <= 1.11 x it at the
#: contraction accepted (0.1), and a quantity's change is linear in it to that order; the
#: rest is margin for the readout's own non-linearity (its regime cuts and minimum).
SAFETY = 2.0

#: Added to every bound (relative, as the stated errors): the readout's own resolution. A
#: quantity the correction leaves unchanged to the bit still differs from the discrete
#: solution's by rounding (h_center at 1.3 m/s: 1.7e-16 where the change was 0), and mu's
#: quadrature cuts move with the iterate (at 0.89 m/s mu's true error was 0.83 of twice the
#: change, 3.4e-11). Far below any mesh error webfem states (1e-8 and up on the sweep).
FLOOR = 1e-9

#: The readouts are called only where the correction's largest change of the web's node
#: values (against sigma) and of the film pressure (against its largest value) is at most
#: this times the limit: a cheap pre-test (the iterate's read-out and its corrected
#: state's cost about nine chord steps: 3.5 + 2.2 ms at 11,117 unknowns against a
#: residual's 0.67 ms and a triangular solve's 0.63 ms). It only skips the test: an
#: iterate it turns away takes the next step. On the 24-point
#: speed sweep, every iterate asked about with its readouts printed (before this gate):
#: the accepted corrections measured up to 1.6e-4 (bound 9.7e-7, at 40 m/s on 1,765
#: unknowns), those the readouts turned away from 2.7e-6 up (bound above 1e-6).
GATE = 30.0


def enabled(options) -> bool:
    """Whether ``options`` ask for balanced stopping (see the module text)."""
    default_tol = type(options).__dataclass_fields__["tol"].default
    share = getattr(options, "algebraic_share", 0.0)
    return (share > 0.0 and options.method == "newton" and options.estimate
            and options.tol == default_tol)


def acceptor(case, prm, problem, options) -> Callable | None:
    """``newton``'s ``accept`` for ``problem`` under ``options`` (None where
    :func:`enabled` says no): the bounds per quantity of :data:`READ_QUANTITIES`, or None
    while one exceeds ``algebraic_share`` x ``error_tol``."""
    if not enabled(options):
        return None
    limit = options.algebraic_share * options.error_tol
    n_p, sigma = problem.nP, case.sigma / case.h_scale
    # the problem keeps this function: a strong reference back would make each solved
    # problem a cycle, freed only by the cyclic collector (18 problems of 110k unknowns
    # alive after 8 sweep points)
    owner = weakref.ref(problem)

    def accept(u, du, theta):
        problem = owner()
        if problem is None:
            return None
        p_max = np.max(np.abs(u[:n_p])) if n_p else 0.0
        moves = max(np.max(np.abs(du[problem.iWv])) / sigma,
                    np.max(np.abs(du[:n_p])) / p_max if p_max > 0.0 else 0.0)
        if not moves <= GATE * limit:
            return None
        here = read_out(case, problem, u, prm)     # kept: the answer's, if accepted
        cheap = read_moved(case, problem, u, du, prm, here)
        if cheap is None:       # a quadrature point crosses a jump: read in full
            change = errors_between(case, here, read_out(case, problem, u + du, prm,
                                                         keep=False))
        else:
            change = errors_between(case, here, cheap[0])
            change["mu"] += cheap[1] / error_scale(case, "mu", here.mu)
        bound = {q: SAFETY * v + FLOOR for q, v in change.items()}
        if not all(np.isfinite(v) and v <= limit for v in bound.values()):
            return None
        return bound
    return accept


def stated(errors: dict, answer: dict | None, coarse: dict | None) -> dict:
    """The mesh error estimate's ``errors`` with the algebraic bounds of the answer (twice)
    and of the coarser mesh's state (once) added (None: solved to ``tol``, nothing added).
    Why twice: the answer's true error is at most its discrete solution's plus its own
    algebraic one, and the estimate's change between the meshes is off by both states'."""
    out = dict(errors)
    for q in READ_QUANTITIES:
        if out.get(q) is None:
            continue
        out[q] = out[q] + 2.0 * (answer or {}).get(q, 0.0) + (coarse or {}).get(q, 0.0)
    return out
