"""Damped Newton with a backtracking line search, generic over a residual and its Jacobian.

A solver never reads files and knows nothing of the physics: it receives callables.

Examples
--------
>>> import numpy as np, scipy.sparse as sp
>>> F = lambda u: u**3 - 8.0
>>> J = lambda u: sp.diags(3 * u**2)
>>> out = newton(F, J, np.array([1.0]), tol=1e-12)
>>> out.converged, round(float(out.u[0]), 10)
(True, 2.0)
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..progress import report

__all__ = ["NewtonResult", "newton", "norm2", "solve_linear", "factorised", "PatternSolver",
           "SOLVER"]


def norm2(r) -> float:
    """||r||_2 by numpy's pairwise sum: the same bits whatever the number of BLAS threads
    (BLAS's nrm2 splits a long vector among its threads, so a solve's residual, and the
    tolerance test on it, changed in the last bit between a process and its workers)."""
    r = np.asarray(r, float)
    return float(np.sqrt(np.add.reduce(r * r)))


def solve_linear(A, b) -> np.ndarray:
    """Sparse direct solve (SuperLU) with the minimum-degree ordering on A^T + A: for the
    nearly symmetric FE patterns here it fills in 4-6x less than the default COLAMD and is
    4x faster at 4e5 unknowns (measured; see benchmarks/bench_fe2d.py). Diagonal pivots are
    preferred (threshold 0.01, as :class:`PatternSolver`): partial pivoting's row exchanges
    undo the ordering on the coupled film + web systems (100x the time on a grooved cell)."""
    return factorised(A)(b)


#: SuperLU's panel size (columns factorised together; SuperLU's default is larger). On the
#: base case's fe2d Jacobians (ordered as :class:`PatternSolver` orders them, CPU time, median
#: of 7): 3,004 unknowns 2.9 -> 2.2 ms, 10,634 15.5 -> 9.8 ms, 21,298 39.4 -> 30.0 ms, and
#: at level 2 (101,372 unknowns) 336 -> 269 ms; the same fill (the ordering is not
#: touched), the solutions the same to rounding (4e-11 relative where the matrix's own
#: conditioning allows no better).
PANEL_SIZE = 2


class PatternSolver:
    """Repeated solves with matrices of one fixed sparsity pattern, restricted to ``free``.

    The FE models return Jacobians whose index arrays are the same objects from call to call
    (:class:`webfem.fem.fast.Pattern`). For such a pattern, the restriction to the free
    unknowns and the fill-reducing ordering (minimum degree on A^T + A, as
    :func:`solve_linear`, applied symmetrically) are computed once; every solve, the first
    included, gathers the data array into the ordered matrix and factorises it with SuperLU
    in that order, preferring diagonal pivots (threshold 0.01, SuperLU's symmetric mode):
    less fill and about a quarter less time per factorisation on the 2-D film
    (benchmarks/bench_fe2d.py).

    The ordering depends on the pattern alone and every factorisation of a pattern takes the
    same path, so a solve's numbers do not depend on what was solved before it in the
    process (a plan kept from an earlier solve changes the time, never the answer).

    ``scaled``: factorise S A S with S = |diag A|^(-1/2) (1 where the diagonal is 0) and
    solve through it. Where the web rests on its asperities the 2-D film + web Jacobian
    mixes contact stiffnesses of 1e10 with film entries of 1e-5 (scaled units): a third of
    the film's diagonal pivots then fall below 0.01 of their column, SuperLU exchanges rows
    and the fill-reducing ordering is lost (a grooved cell of 7,315 unknowns filled 14.4 M
    entries in 2.1 s; scaled, 0.17 M in 4 ms). The scaled system has a unit diagonal, the
    same pattern and ordering, and the same solution to rounding.
    """

    def __init__(self, size: int = 6, scaled: bool = False, plans: dict | None = None):
        self.size = size
        self.scaled = bool(scaled)
        # (id(indices), id(indptr), free bytes) -> plan; ``plans``: a dict kept elsewhere
        # (a :class:`webfem.fem.fast.Pattern`'s, shared by the problems of one mesh
        # topology: a continued point's new problem finds the previous point's plan)
        self._plans: dict = {} if plans is None else plans

    @staticmethod
    def _factor(B, spec):
        return spla.splu(B, permc_spec=spec, diag_pivot_thresh=0.01, panel_size=PANEL_SIZE,
                         options=dict(SymmetricMode=True))

    @staticmethod
    def _plan(A, free):
        """The gather map and the ordering of (pattern, free), with the ordered matrix's
        entries per column and diagonal places (the scaled solve's). The minimum-degree
        ordering is SuperLU's, read from an incomplete factorisation that drops every entry
        (the column ordering is computed from the pattern before any value is used; it is
        the complete factorisation's ordering at a fraction of its cost). Read instead from
        the first complete factorisation (splu's own MMD_AT_PLUS_A), the ordering is the
        same but the factors are not: solutions 2e-14 to 3e-11 apart (relative) on the base
        case's 12 patterns, so a pattern's first solve would not be its later ones'."""
        probe = sp.csr_matrix((np.arange(1.0, A.nnz + 1.0), A.indices, A.indptr), shape=A.shape)
        red = probe[free][:, free].tocsc()
        red.sort_indices()
        inv = _ordering(red)
        B = red[inv][:, inv].tocsc()
        B.sort_indices()
        idx = np.int32 if A.nnz < 2**31 else np.int64
        # the entries per column and the place of each diagonal entry (-1: none), for the
        # scaled factorisation: the pattern's, so found here once rather than per solve
        # (of the size of the matrix's side: an entry's column, as large as its data, is
        # not held)
        counts = np.diff(B.indptr)
        cols = np.repeat(np.arange(B.shape[1], dtype=idx), counts)
        diag = np.full(B.shape[1], -1, dtype=idx)
        on = np.flatnonzero(B.indices == cols)
        diag[cols[on]] = on
        # the ordered matrix's structure only (its values are gathered at each solve)
        return (A.indices, A.indptr, (B.indices, B.indptr, B.shape),
                (B.data - 1).astype(idx), inv, counts, diag)

    def solve(self, A, free, b) -> np.ndarray:
        """Solve A[free][:, free] x = b."""
        return self.factor(A, free)(b)

    def factor(self, A, free) -> Callable[[np.ndarray], np.ndarray]:
        """A factorisation of A[free][:, free], as a function solving it for a right-hand
        side (:func:`newton` keeps the last one for its chord steps)."""
        A = A if isinstance(A, sp.csr_matrix) else sp.csr_matrix(A)
        free = np.asarray(free)
        key = (id(A.indices), id(A.indptr), free.tobytes())
        plan = self._plans.get(key)
        if plan is None or plan[0] is not A.indices or plan[1] is not A.indptr:
            while len(self._plans) >= self.size:
                self._plans.pop(next(iter(self._plans)))
            plan = self._plans[key] = self._plan(A, free)   # keeps the ids unique
        _, _, (indices, indptr, shape), gather, inv, counts, diag = plan
        B = sp.csc_matrix((A.data[gather], indices, indptr), shape=shape, copy=False)
        B.has_canonical_format = True      # as the plan left it: sorted, no duplicates
        if not self.scaled:
            lu = self._factor(B, "NATURAL")

            def solve(b):
                x = np.empty_like(b)
                x[inv] = lu.solve(b[inv])
                return x
            return solve
        # B.diagonal() (canonical: one entry or none per column), from the plan's places
        d = np.abs(np.where(diag >= 0, B.data[diag], 0.0))
        s = np.where(d > 0.0, 1.0 / np.sqrt(np.where(d > 0.0, d, 1.0)), 1.0)
        # each entry's column's s by repeating s along the columns: s[column] to the bit,
        # without an array of the entries' columns (as large as the matrix's data: 80 MB
        # at 3.9e5 unknowns, at the process's peak)
        B.data *= s[B.indices] * np.repeat(s, counts)
        lu = self._factor(B, "NATURAL")

        def solve_scaled(b):
            x = np.empty_like(b)
            x[inv] = s * lu.solve(s * b[inv])
            return x
        return solve_scaled


#: The orderings of the patterns factorised last, by the pattern's bytes (at most
#: :data:`ORDERINGS_KEPT`): a continued sweep point's mesh is the previous point's moved, or
#: its coarser mesh the previous one's moved, so the same pattern in a new problem. An
#: ordering is a function of the pattern alone (:meth:`PatternSolver._plan`): one kept gives
#: the same factorisation, to the bit, as one computed again (a pure cache: no answer
#: depends on what was solved before).
ORDERINGS: dict = {}
ORDERINGS_KEPT = 8


def _ordering(red) -> np.ndarray:
    """The inverse minimum-degree permutation of the (free) pattern ``red`` (CSC, indices
    sorted), kept in :data:`ORDERINGS`."""
    key = hashlib.blake2b(np.ascontiguousarray(red.indptr).tobytes()
                          + np.ascontiguousarray(red.indices).tobytes(),
                          digest_size=32).digest() + repr(red.shape).encode()
    inv = ORDERINGS.get(key)
    if inv is None:
        structure = sp.csc_matrix((np.ones(red.nnz), red.indices, red.indptr),
                                  shape=red.shape)
        structure = structure + sp.identity(red.shape[0], format="csc") * red.shape[0]
        perm = spla.spilu(structure.tocsc(), permc_spec="MMD_AT_PLUS_A", drop_tol=np.inf,
                          fill_factor=1.0, diag_pivot_thresh=0.01,
                          options=dict(SymmetricMode=True)).perm_c
        inv = np.argsort(perm)
        inv.setflags(write=False)
        if len(ORDERINGS) >= ORDERINGS_KEPT:
            ORDERINGS.pop(next(iter(ORDERINGS)))
        ORDERINGS[key] = inv
    return inv


def factorised(A) -> Callable[[np.ndarray], np.ndarray]:
    """:func:`solve_linear`'s factorisation of A, as a solving function (for several
    right-hand sides: Picard's lift correction)."""
    return PatternSolver._factor(sp.csc_matrix(A), "MMD_AT_PLUS_A").solve


#: The solver :func:`newton` uses when it is given none (the FE problems own one each).
SOLVER = PatternSolver()


@dataclass
class NewtonResult:
    """Outcome of :func:`newton`: the iterate and how it was reached."""

    u: np.ndarray
    converged: bool
    iterations: int
    residual: float                      # ||F(u)||_2 over the free unknowns at the end
    history: list[float] = field(default_factory=list)   # ||F|| per iteration
    reason: str = ""
    #: what ``accept`` returned for an iterate accepted by it (its algebraic error bounds),
    #: else None
    algebraic: object = None


#: A residual at most this many times the tolerance is accepted when the Newton correction is
#: below the step tolerance and the full step along it does not lower the residual: the
#: iterate is then at the rounding floor of the residual's assembly (seen at high speed on
#: grooved rollers, where the scaled terms are large: 1.0-1.2e-9 against a tolerance of 1e-9,
#: corrections ~3e-15).
FLOOR_FACTOR = 10.0


#: A tolerance below this (webfem's default, 1e-9) is a caller asking for more than the
#: default: it is taken strictly, and a residual that cannot reach it for rounding fails.
STRICT_BELOW = 1e-9


def rounding_floor(Jm, u, free) -> float:
    """The smallest residual double precision resolves at ``u``: eps || |J| |u| ||_2 over the
    free rows, the normwise backward error's scale (every term of the residual's assembly
    rounds at about eps times its size, and |J| |u| is their size). A stiff web's bending
    (Dn in the hundreds: 0.5 mm board on a 30 mm roller) puts it above an absolute tolerance
    of 1e-9 (4e-7 there, against 3e-11 on the base case).

    Computed on the whole matrix with |u| set to 0 off the free unknowns: each free row's
    sum meets the same non-zero terms in the same order, and the others add +0 (|J| and |u|
    are >= 0), so the same bits as on the reduced matrix, whose three copies of the
    Jacobian (row and column selection, absolute value) held ~350 MB beside Newton's
    factorisation at 3.9e5 unknowns. A matrix with duplicate or non-finite entries (inf x 0
    is no zero) takes the reduced matrix."""
    J = sp.csr_matrix(Jm)
    A = abs(J)
    if not (J.has_canonical_format and np.all(np.isfinite(A.data))):
        A = abs(J[free][:, free])
        return float(np.finfo(float).eps * norm2(A @ np.abs(u[free])))
    x = np.zeros(J.shape[1])
    x[free] = np.abs(u[free])
    return float(np.finfo(float).eps * norm2((A @ x)[free]))

#: The largest Newton correction (max-norm, relative to 1 + ||u||_inf) of an iterate accepted
#: at its rounding floor when no step along the correction lowers the residual. A stiff
#: web's bending (Dn in the thousands: board) puts the floor of the residual's assembly at
#: 1e-6-1e-3, and the correction computed from a residual at that floor is the floor's noise
#: amplified by J^-1: 1e-10-1e-6 relative on stiff boards (envelope #57: 21 such iterates,
#: median 5e-9, largest 6e-7), four orders below the mesh errors webfem states (~1e-2), and
#: no iterate is resolved more finely in double precision. Below :data:`STRICT_BELOW` no
#: such iterate is accepted.
FLOOR_STEP = 1e-6

#: A chord step is kept when it reaches the tolerance or lowers the residual this many times.
CHORD_GAIN = 10.0

#: A chord step is also tried when the last step lowered the residual this many times (on
#: the base case's 24-point speed sweep: 142 factorisations become 111, the median per
#: continued point 5 -> 4, 3 below 3 m/s; a chord step counts as an iteration, so the
#: median iterations grow 5 -> 8).
CHORD_TRY = 100.0  # and such a chord step is kept only at this gain too

#: ``accept`` is asked about an iterate only when the simplified Newton correction there is
#: at most this times the step that led to it (max-norms): the contraction of Newton's (or
#: the chord iteration's) local convergence, under which the distance to the discrete
#: solution is at most the correction / (1 - theta) (Deuflhard's error-oriented test).
ACCEPT_CONTRACTION = 0.1


def newton(F: Callable[[np.ndarray], np.ndarray], J: Callable[[np.ndarray], sp.spmatrix],
           u0: np.ndarray, free: np.ndarray | None = None, tol: float = 1e-10,
           step_tol: float = 1e-10, max_iter: int = 50, min_damping: float = 1e-4,
           monitor: Callable[[int, float], None] | None = None,
           rtol: float = 0.0, chord: bool = True,
           solver: PatternSolver | None = None, noise: bool = False,
           accept: Callable[[np.ndarray, np.ndarray, float], object] | None = None
           ) -> NewtonResult:
    """Solve F(u) = 0 for the ``free`` entries of u (others keep u0's values).

    Converged when ||F||_2 <= max(tol, rtol ||F(u0)||_2), or when the full Newton step's
    max-norm is <= step_tol (scaled by 1 + ||u||_inf) and ||F|| <= :data:`FLOOR_FACTOR`
    times the larger of tol and the residual's rounding floor (:func:`rounding_floor`, eps
    || |J| |u| ||: no step can lower a residual there, and the Newton correction, the
    iterate's own error, is below step_tol). The reason then says which: a residual above
    tol is named with its floor. A tol below :data:`STRICT_BELOW` (the default) is taken
    strictly: only the FLOOR_FACTOR tol test. A residual that stalls above both is a failure whose reason
    names it. The step is halved until ||F|| decreases (Armijo-like, no sufficient-decrease
    constant) down to ``min_damping``; below that the solve is declared failed ("line search
    failed"), never silently accepted, unless the residual is within FLOOR_FACTOR of its
    rounding floor and the correction is below :data:`FLOOR_STEP` (then the correction is
    the floor's noise; the reason says so with its size).

    ``chord``: when the last step's decrease predicts that one more step with the last
    factorisation reaches the tolerance (||F_k||^2 / ||F_k-1|| <= tol: Newton's quadratic
    regime), or when that decrease was at least :data:`CHORD_TRY` times (the Jacobian then
    moves little over the next step), that chord step is tried first. It costs a residual
    and a triangular solve instead of an assembly and a factorisation, and is kept only if
    it reaches the tolerance or lowers ||F|| :data:`CHORD_GAIN` times (in Newton's quadratic
    regime) or :data:`CHORD_TRY` times (otherwise: a chord step accepted at a gain of 10
    away from it led a 1-D continuation onto another branch); otherwise the iteration takes the Newton step
    from the same point. After a chord step that was kept, the next chord step is tried
    when that one lowered ||F|| :data:`CHORD_GAIN` times, and kept at that gain too: the
    chord iteration converges linearly, at a rate that the kept step has shown. Why: on the
    base case's cold fe2d solve (10,777 unknowns) the fine mesh's chord steps lowered the
    residual 150, 70, 70 and 60 times from 1.3e-2; at 100 times required the second was
    refused and a Newton step taken (an assembly and a factorisation, 20-25 ms, where the
    four chord steps cost 3.5 ms each). The converged state meets the same tolerance either
    way. A chord step counts as an iteration but not against ``max_iter`` (the Newton steps'
    budget).

    ``solver``: the :class:`PatternSolver` whose plans the factorisations reuse (a discrete
    problem keeps its own; default: :data:`SOLVER`).

    ``noise``: where no step lowers a residual within FLOOR_FACTOR of its rounding floor,
    the iterate is also accepted when the correction is no larger than
    :data:`NOISE_FACTOR` times the corrections of random residuals of the same norm
    (:func:`noise_correction`): the correction is then the floor's noise amplified by
    J^-1, however large J^-1 makes it (a problem with a soft mode: a stiff web held
    through long spans, :mod:`webfem.fem.ends`).

    ``accept(u, du, theta)``: balanced stopping. After a full step (Newton's or a kept chord
    step) with the residual still above the tolerance, the simplified Newton correction
    ``du = -J_k^-1 F(u)`` (the last factorisation: one triangular solve, reused as the next
    chord step's) estimates the iterate's algebraic error; where it is at most
    :data:`ACCEPT_CONTRACTION` times the step just taken, ``accept`` is called (``du`` on
    every unknown, 0 off ``free``; ``theta`` that ratio) and an answer other than None
    ends the solve, converged, with the iterate ``u`` (not ``u + du``) and that answer in
    :attr:`NewtonResult.algebraic`: the caller's bound of the iterate's error in what it
    reads, which it must state (:func:`webfem.models.algebraic.acceptor`). A chord step
    that lowers the residual but too little to be kept is asked about too before the
    Newton step replaces it: accepted, it saves that step's Jacobian and factorisation (on
    the base case's 24-point speed sweep 78 -> 71 factorisations of the continued points).
    """
    u = np.array(u0, dtype=float, copy=True)
    free = np.arange(u.size) if free is None else np.asarray(free)
    r = F(u)[free]
    norm = norm2(r)
    history = [norm]
    if np.isfinite(norm):
        tol = max(tol, rtol * norm)
    report("newton", 0, norm, tol)
    last = None                       # the last factorisation, for chord steps
    pending = None                    # (residual, its correction by ``last``): accept's
    it = chords = 0
    chained = False                   # the last step was a chord step, kept
    while it - chords < max_iter:         # chord steps do not spend the Newton budget
        it += 1
        if not np.isfinite(norm):
            return NewtonResult(u, False, it - 1, norm, history, "residual not finite")
        if norm <= tol:
            return NewtonResult(u, True, it - 1, norm, history, "residual below tolerance")
        near = last is not None and norm * norm <= tol * history[-2]
        # after a kept chord step the next one is tried and kept at CHORD_GAIN: the first
        # chord step already showed the factorisation good here (see the docstring)
        easy = near or chained
        if chord and last is not None and (near or norm * CHORD_TRY <= history[-2]
                                           or (chained and norm * CHORD_GAIN
                                               <= history[-2])):
            # the correction accept's test made from this residual, not solved again
            solve = last if pending is None or pending[0] is not r else \
                (lambda b, d=pending[1]: -d)
            trial, r_trial, n_trial = _chord_step(F, solve, u, r, free)
            if n_trial <= tol or n_trial * (CHORD_GAIN if easy else CHORD_TRY) <= norm:
                step = float(np.max(np.abs(trial[free] - u[free])))
                u, r, norm = trial, r_trial, n_trial
                history.append(norm)
                report("newton", it, norm, tol)
                if monitor:
                    monitor(it, norm)
                chords += 1
                chained = True
                if accept is not None and norm > tol:
                    done, pending = _balanced(accept, last, u, r, free, step, it, norm,
                                              history)
                    if done is not None:
                        return done
                continue
            if accept is not None and n_trial < norm:
                # a chord step that lowers the residual too little to go on with may still
                # end at an iterate whose algebraic error is negligible: that saves the
                # Jacobian and the factorisation of the Newton step (the history then
                # ends on it)
                done, _ = _balanced(accept, last, trial, r_trial, free,
                                    float(np.max(np.abs(trial[free] - u[free]))), it,
                                    n_trial, history + [n_trial])
                if done is not None:
                    report("newton", it, n_trial, tol)
                    if monitor:
                        monitor(it, n_trial)
                    return done
        chained = False
        # the last factorisation and Jacobian let go before the new ones are built: held
        # through them, they set the peak (a 390,819-unknown grooved strip: 3.4 GB)
        last = Jm = None
        try:
            Jm = J(u)
            if not np.all(np.isfinite(getattr(Jm, "data", Jm))):
                # factorised, it fails as singular after SuperLU's BLAS calls print "illegal
                # value" lines to stderr (a stiff web's extreme iterates: 1 mm newsprint)
                return NewtonResult(u, False, it - 1, norm, history, "Jacobian not finite")
            last = (solver or SOLVER).factor(Jm, free)
            du = last(-r)
        except RuntimeError as err:  # singular factor
            return NewtonResult(u, False, it - 1, norm, history, f"linear solve failed: {err}")
        if not np.all(np.isfinite(du)):
            return NewtonResult(u, False, it - 1, norm, history, "Newton step not finite")
        tiny = np.max(np.abs(du)) <= step_tol * (1.0 + np.max(np.abs(u[free])))
        floor = (rounding_floor(Jm, u, free) if tiny and norm > tol and tol >= STRICT_BELOW
                 else 0.0)
        at_floor = tiny and norm <= FLOOR_FACTOR * max(tol, floor)
        alpha = 1.0
        while True:
            trial = u.copy()
            trial[free] += alpha * du
            with np.errstate(all="ignore"):   # a wild trial is rejected below, not reported
                r_trial = F(trial)[free]
                n_trial = norm2(r_trial)
            if np.isfinite(n_trial) and (n_trial < norm or n_trial <= tol):
                break
            if at_floor:
                return NewtonResult(u, True, it - 1, norm, history,
                                    _at_floor(norm, tol, floor))
            alpha *= 0.5
            small = alpha < min_damping and not tiny and tol >= STRICT_BELOW and \
                np.max(np.abs(du)) <= FLOOR_STEP * (1.0 + np.max(np.abs(u[free])))
            if (small or noise) and alpha < min_damping and not tiny and tol >= STRICT_BELOW:
                # no step along the correction lowers a residual at its rounding floor: the
                # correction is rounding noise amplified by J^-1, below FLOOR_STEP or (noise)
                # as large as that of a random residual of its size
                floor = rounding_floor(Jm, u, free)
                if norm <= FLOOR_FACTOR * floor:
                    if small:
                        return NewtonResult(u, True, it - 1, norm, history,
                                            _at_floor(norm, tol, floor)
                                            + _noise_step(du, u, free))
                    if np.max(np.abs(du)) <= NOISE_FACTOR * noise_correction(last, norm,
                                                                             len(free)):
                        return NewtonResult(u, True, it - 1, norm, history,
                                            _at_floor(norm, tol, floor)
                                            + _noise_step(du, u, free)
                                            + " (as large as a random residual's of that size)")
            if alpha < min_damping:
                return NewtonResult(u, False, it, norm, history,
                                    _stalls(norm, tol, floor) if tiny
                                    else "line search failed")
        u, r, norm = trial, r_trial, n_trial
        history.append(norm)
        report("newton", it, norm, tol)
        if monitor:
            monitor(it, norm)
        if accept is not None and alpha == 1.0 and norm > tol and not tiny:
            done, pending = _balanced(accept, last, u, r, free, np.max(np.abs(du)), it, norm,
                                      history)
            if done is not None:
                return done
        if alpha == 1.0 and tiny:
            if norm <= FLOOR_FACTOR * tol:
                return NewtonResult(u, True, it, norm, history, "step below tolerance")
            floor = rounding_floor(J(u), u, free) if tol >= STRICT_BELOW else 0.0
            if norm <= FLOOR_FACTOR * floor:
                return NewtonResult(u, True, it, norm, history, _at_floor(norm, tol, floor))
            # the iterate no longer moves but the residual stays above the tolerance and
            # the rounding floor: never an answer
            return NewtonResult(u, False, it, norm, history, _stalls(norm, tol, floor))
    return NewtonResult(u, norm <= tol, it, norm, history, "iteration limit")


#: How many times the largest correction of :data:`NOISE_SAMPLES` random residuals a
#: correction may be and still count as noise (``newton(noise=True)``).
NOISE_FACTOR = 2.0
NOISE_SAMPLES = 4


def noise_correction(solve, norm: float, n: int) -> float:
    """The largest max-norm correction ``solve`` (a factorised Jacobian) gives for
    :data:`NOISE_SAMPLES` random residuals of 2-norm ``norm`` (Gaussian directions of a
    fixed seed: the same answer every run): what rounding noise of that size moves the
    iterate by."""
    z = np.random.default_rng(0).standard_normal((NOISE_SAMPLES, n))
    return max(float(np.max(np.abs(solve(norm * v / norm2(v))))) for v in z)


def _stalls(norm, tol, floor) -> str:
    """Why a residual that no longer moves is no answer. A tolerance below
    :data:`STRICT_BELOW` is taken strictly: the rounding floor is then not computed (0), and
    the reason says so rather than state a floor of 0."""
    if tol < STRICT_BELOW or floor <= 0.0:
        return (f"the residual stalls at {norm:.3g}, above the tolerance {tol:.3g} (a "
                f"tolerance below {STRICT_BELOW:g} is taken strictly: a residual at its "
                f"rounding floor is not accepted, and the floor is not computed; a tolerance "
                f">= {STRICT_BELOW:g} accepts one within {FLOOR_FACTOR:g} x that floor)")
    return (f"the residual stalls at {norm:.3g}, above the tolerance {tol:.3g} and "
            f"{FLOOR_FACTOR:g} x its rounding floor {floor:.3g}")


def _at_floor(norm, tol, floor) -> str:
    if norm <= FLOOR_FACTOR * tol:
        return "step below tolerance, the residual at its rounding floor"
    return (f"step below tolerance, the residual {norm:.3g} at its rounding floor {floor:.3g} "
            f"(eps |J| |u|): the tolerance {tol:.3g} is below what double precision resolves "
            "here")


def _noise_step(du, u, free) -> str:
    rel = float(np.max(np.abs(du)) / (1.0 + np.max(np.abs(u[free]))))
    return f"; no step lowers it, the Newton correction {rel:.2g} (relative) is its noise"


def _balanced(accept, solve, u, r, free, step, it, norm, history):
    """``newton``'s balanced stop at ``u`` (residual ``r``, reached by a step of max-norm
    ``step``): ``(NewtonResult or None, (r, correction))``, the correction kept for the
    next chord step from ``u``."""
    with np.errstate(all="ignore"):
        dfree = -solve(r)
    pending = (r, dfree)
    if not np.all(np.isfinite(dfree)) or not step > 0.0:
        return None, pending
    theta = float(np.max(np.abs(dfree)) / step)
    if theta > ACCEPT_CONTRACTION:
        return None, pending
    du = np.zeros_like(u)
    du[free] = dfree
    bound = accept(u, du, theta)
    if bound is None:
        return None, pending
    return NewtonResult(u, True, it, norm, history, "algebraic error negligible against "
                        "the mesh error target (balanced stopping)", algebraic=bound), pending


def _chord_step(F, solve, u, r, free):
    """u plus the step of an earlier factorisation ``solve``; the trial, its residual and
    norm (inf when not finite)."""
    trial = u.copy()
    with np.errstate(all="ignore"):
        trial[free] -= solve(r)
        r_trial = F(trial)[free]
        n_trial = norm2(r_trial)
    return trial, r_trial, (n_trial if np.isfinite(n_trial) else np.inf)
