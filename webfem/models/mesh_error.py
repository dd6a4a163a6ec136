"""The mesh error of an FE answer, estimated from the solution itself, and the refinement it
asks for.

The answer's mesh is compared with the mesh that has every other node (cells twice as long,
the same grading; the nodes on the wrap edges and on every land/groove edge kept). The
change of each quantity a user reads (:data:`~webfem.models.readout.READ_QUANTITIES`)
between the two is its stated error. For a scheme converging at order p, Richardson's
estimate of the error on the finer mesh is that change over 2^p - 1, so for any order
p >= 1 the change bounds it (Q2 converges at order 4 in the central gap: the statement is
then about 15 times the true error there; where the exit constriction or a landing web is
not yet resolved, the convergence is slower and the margin smaller). tests/test_mesh_error.py
checks the statement against mesh-converged solutions on smooth and grooved cases.

While an estimate exceeds ``options.error_tol``, the cells of the answer's mesh are
bisected and the case solved again from the answer (the old answer's mesh is then the
coarser one), up to :data:`MAX_DOFS` unknowns: along x or across the width, whichever
direction's error is the larger (each estimated apart, :func:`_by_direction`, on a grooved
film; on a smooth roller from one more solve, on the mesh coarser across only, made only
once the estimate exceeds the target, :func:`_across_only`). Where that finer mesh gives no
admissible answer, the one with the cells along x quartered instead is tried once; where
neither does, the result says that its estimate is unconfirmed.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..case import Case
from ..fem.scaling import FoilParameters
from ..progress import stage
from ..fem.outcome import SolveInfo
from .admissible import admissibility
from .algebraic import stated
from .readout import READ_QUANTITIES, errors_between, read_out

__all__ = ["MeshError", "estimate_mesh_error", "coarser_nodes", "bisected_nodes", "kept_nodes",
           "summary_keys", "MAX_DOFS", "LOCAL_BUDGET"]

#: The refinement the estimate asks for stops before a mesh of more unknowns than this (a
#: Newton step at 2e5 unknowns takes about a second and 1.2 GB on these machines).
MAX_DOFS = 2.5e5

#: A grooved film's round along x bisects only the cells that held most of the change that
#: asked for it (:func:`_local_x_nodes`); the other cells keep their error, at most their
#: share of that change, which is added to the stated x error. Those additions take at most
#: this share of ``error_tol`` in all (each round at most half of what is left), so they
#: never keep the estimate from meeting it. Why: envelope #147 (a 3.1 cm PET web) changed
#: by up to 59 % of the local gap at its exit constriction and by less than 1 % of that over
#: three quarters of its 271 x cells; its two uniform rounds solved 123,691 and 247,267
#: unknowns.
LOCAL_BUDGET = 0.25

#: A local round bisects every cell once it would bisect more than this share of them.
LOCAL_MOST = 0.6


@dataclass
class MeshError:
    """The estimate: per quantity (None: no estimate could be made), how it was obtained,
    the notes a result should carry, and the Newton iterations it took."""

    errors: dict[str, float | None] = field(default_factory=lambda: dict.fromkeys(
        READ_QUANTITIES))
    basis: str = ""
    notes: list[str] = field(default_factory=list)
    iterations: int = 0
    rounds: int = 0
    #: False when the refinement the estimate asked for gave no answer (the errors are
    #: then the change from the coarser mesh alone, unconfirmed)
    confirmed: bool = True
    #: how the answer's mesh was refined when not by bisecting every cell (None: it was)
    refined: str | None = None
    #: ``(problem, state)`` solved on the answer's coarser mesh (the estimate's; None on a
    #: grooved film, estimated by direction, or when it did not converge)
    coarse: tuple | None = None
    #: the algebraic error bounds added to ``errors`` (:func:`webfem.models.algebraic.
    #: stated`), per quantity; None: every state solved to the tolerance
    algebraic: dict | None = None


def coarser_nodes(nodes: np.ndarray, keep=()) -> np.ndarray:
    """Every other node of ``nodes`` (sorted), the ends and the nodes nearest to ``keep``
    (the wrap edges, the land/groove edges) kept. None when fewer than 3 nodes would be left.

    >>> coarser_nodes(np.arange(7.0), keep=[3.0]).tolist()
    [0.0, 2.0, 3.0, 4.0, 6.0]
    """
    X = np.asarray(nodes, float)
    take = np.zeros(X.size, dtype=bool)
    take[::2] = True
    take[[0, -1]] = True
    for k in keep:
        take[int(np.argmin(np.abs(X - k)))] = True
    return X[take] if take.sum() >= 3 and take.sum() < X.size else None


def bisected_nodes(nodes: np.ndarray) -> np.ndarray:
    """Every cell of ``nodes`` halved."""
    X = np.asarray(nodes, float)
    return np.sort(np.concatenate([X, 0.5 * (X[1:] + X[:-1])]))


def kept_nodes(problem, prm: FoilParameters):
    """Nodes that the coarser mesh must keep: the wrap edges in X, the land/groove edges in
    Z (the steps of the wrap pressure and of the gap lie on element edges)."""
    e = 0.5 * prm.beta
    keep_z = ()
    Z = getattr(problem, "Z", None)
    grooves = getattr(problem, "grooves", None)
    if Z is not None and grooves is not None:
        keep_z = grooves.edges(float(Z[0]), float(Z[-1]))
    return (-e, e), keep_z


def _newton_options(options):
    return options.replace(method="newton") if options.method != "newton" else options


def estimate_mesh_error(disc, case: Case, problem, u, prm: FoilParameters, options,
                        iterate, solved=None, estimate_if=None, algebraic=None) -> tuple:
    """The estimate for the solved state ``u`` of ``problem``, refining while it exceeds
    ``options.error_tol``. ``iterate(problem, u0, prm, options) -> (u, info)`` solves on a
    mesh. Returns ``(problem, u, info_or_None, MeshError)``: the answer's problem and state
    (finer than the input when the estimate asked for refinement; ``info`` is then that
    solve's, else None).

    On a grooved film the two directions are estimated apart (:func:`_by_direction`) and
    only the one whose error is the larger is bisected in a round.

    ``solved``: ``(problem, state)`` already solved on some mesh (a cold 2-D start's solve on
    the coarser mesh first); when it is this answer's coarser mesh, the coarse solve starts
    from that state instead of from the answer carried over (the same discrete solution, to
    Newton's tolerance, in fewer steps: none when it is still converged). Where that
    problem's last solve stopped on its algebraic error bounds (``problem.bounds``: a
    continued point's coarser mesh, :mod:`webfem.models.algebraic`), the state is taken as
    solved, and its bounds, with the answer's ``algebraic`` ones, are added to the stated
    errors (:func:`webfem.models.algebraic.stated`).

    ``estimate_if(problem, u, prm) -> bool``: whether the answer on a refined mesh is still the
    one its caller returns (None: always); the refinement stops once it is not (a groove
    cell whose refined answer asks for the edge strip after all: a resting board's cell went
    on to 0.19 M unknowns, 50 s, before the strip that replaced it)."""
    out = MeshError()
    here = read_out(case, problem, u, prm)
    release(problem)       # solved: only its nodes and state are read from here on
    keep_x, keep_z = kept_nodes(problem, prm)
    Z = getattr(problem, "Z", None)
    Xc = coarser_nodes(problem.X, keep_x)
    Zc = coarser_nodes(Z, keep_z) if Z is not None else None
    if Z is not None and Zc is None:
        Zc = Z           # too few cells across to coarsen: the estimate is then along x only
    split = getattr(problem, "grooves", None) is not None and Xc is not None
    parts = None
    # a grooved film's rounds along x bisect where the last x change was
    # (:func:`_local_x_nodes`): the state on the mesh coarser along x that change came
    # from, the change, and the x error the cells left unbisected keep (added to the
    # stated one)
    source = None
    left_error = dict.fromkeys(out.errors, 0.0)
    coarse_bounds = None        # the coarser state's algebraic error bounds, where stopped
    if split:
        parts, source = _by_direction(disc, case, problem, u, prm, options, here, out, Xc, Zc)
    elif Xc is not None:
        with stage(f"{disc.name} error estimate on the coarser mesh"):
            bounds = None
            if _same_mesh(solved, Xc, Zc):
                coarse, uc = solved[0], solved[1].copy()
                bounds = getattr(coarse, "bounds", None)
            else:
                coarse, uc = disc.remeshed(problem, u, prm, Xc, Zc, options)
            if bounds is not None:
                # stopped where its algebraic error is negligible: not solved on
                info = SolveInfo(converged=True, iterations=0, algebraic=bounds)
            else:
                uc, info = coarse.solve_newton(uc, prm, _newton_options(options))
        out.iterations += info.iterations
        if info.converged:
            out.coarse = (coarse, uc)
            coarse_bounds = info.algebraic
            out.errors = errors_between(case, here, read_out(case, coarse, uc, prm))
            if algebraic is not None or coarse_bounds is not None:
                out.errors = stated(out.errors, algebraic, coarse_bounds)
                out.algebraic = stated(dict.fromkeys(out.errors, 0.0), algebraic,
                                       coarse_bounds)
            out.basis = (f"change from the mesh with cells twice as long ({coarse.n_dofs:,} "
                         f"against {problem.n_dofs:,} unknowns)")
    user_mesh = options.mesh is not None or options.nodes is not None
    across_coarse = None
    if (parts is None and out.coarse is not None and not user_mesh and Zc is not Z
            and _exceeds(out.errors, options.error_tol)):
        parts, across_coarse = _across_only(disc, case, problem, u, prm, options, here, out,
                                            Zc)
    last_info = None
    while _exceeds(out.errors, options.error_tol) and not user_mesh:
        # the direction to bisect: the one whose error is the larger when they were
        # estimated apart (a grooved film; a smooth one past the target), else both
        along_x = parts is None or _larger(parts[0], parts[1])
        across = Z is not None and (parts is None or not along_x)
        growth = (2 if along_x else 1) * (2 if across else 1)
        Xf = bisected_nodes(problem.X) if along_x else problem.X
        local = None
        if along_x and not across and source is not None:
            # the share of the change the cells left may hold: half the room left in the
            # budget, for the quantity it is tightest for
            allowed = min((0.5 * (LOCAL_BUDGET * options.error_tol - left_error[q]) / v
                           for q, v in source[2].items() if v > 0.0), default=0.0)
            local = _local_x_nodes(case, problem, u, source[0], source[1], prm, allowed)
        if local is not None:
            Xf = local[0]
            growth = Xf.size / problem.X.size
        if problem.n_dofs * growth > MAX_DOFS:
            out.notes.append(_cap_note(out, problem.n_dofs * growth, options.error_tol))
            break
        Zf = bisected_nodes(Z) if across else Z
        fine, uf, info, why = _solved_on(disc, case, problem, u, prm, options, iterate, out,
                                         Xf, Zf)
        if why and local is not None and problem.n_dofs * 2 <= MAX_DOFS:
            # no answer on the locally bisected mesh: every cell bisected, as without it
            local, growth, Xf = None, 2, bisected_nodes(problem.X)
            fine, uf, info, why = _solved_on(disc, case, problem, u, prm, options, iterate,
                                             out, Xf, Zf)
        quartered = False
        if why and along_x and local is None and problem.n_dofs * growth * 2 <= MAX_DOFS:
            # the finer mesh along x from the same answer: 1 mm board resting on the base
            # roller does not converge with its 160 cells along x halved (nor do fe1d's 160
            # and 640 of that grading) but does with them quartered (issue 22)
            quarter, uq, info_q, why_q = _solved_on(disc, case, problem, u, prm, options,
                                                    iterate, out, bisected_nodes(Xf), Zf)
            if quarter is not None and not why_q:
                n_halved = fine.n_dofs
                fine, uf, info, why, quartered = quarter, uq, info_q, None, True
        if why:
            _unconfirmed(out, fine.n_dofs, why, options.error_tol)
            break
        finer = read_out(case, fine, uf, prm)
        change = errors_between(case, finer, here)
        if parts is None:
            out.errors = change
            out.basis = (f"change from the mesh with cells "
                         f"{'four times as long along x' if quartered else 'twice as long'} "
                         f"({problem.n_dofs:,} against {fine.n_dofs:,} unknowns)")
        else:
            # the bisected direction's error is the change it made (along x, plus what the
            # cells a local round left keep); the other's stays
            if along_x and local is not None:
                left_error = {q: left_error[q] + local[1] * source[2][q] for q in left_error}
            elif along_x:
                # every cell bisected: the change bounds them all again
                left_error = dict.fromkeys(left_error, 0.0)
            x_error = {q: change[q] + left_error[q] for q in change} if along_x else None
            parts = (x_error, parts[1]) if along_x else (parts[0], change)
            out.errors = _summed(*parts)
            if local is not None:
                out.basis = (f"changes from the meshes with cells twice as long along x and "
                             f"across the width, summed (the last bisection along x, of the "
                             f"{local[2]:,} of {problem.X.size - 1:,} cells where "
                             f"{100 * (1 - local[1]):.3g} % of the change along x was, "
                             f"{problem.n_dofs:,} against {fine.n_dofs:,} unknowns; the "
                             "other cells' share of the changes along x added)")
            elif quartered:
                out.basis = (f"changes from the mesh with cells four times as long along x "
                             f"({problem.n_dofs:,} against {fine.n_dofs:,} unknowns) and from "
                             f"the one with cells twice as long across the width, summed")
            else:
                out.basis = (f"changes from the meshes with cells twice as long along x and "
                             f"across the width, summed (the last bisection "
                             f"{'along x' if along_x else 'across'}: {problem.n_dofs:,} "
                             f"against {fine.n_dofs:,} unknowns)")
        # the restart's coarser state is that of cells twice as long (None: not solved)
        if quartered:
            out.refined = "its cells along x quartered instead of halved"
            out.notes.append(_quartered_note(out, problem.n_dofs, n_halved, fine.n_dofs,
                                             options.error_tol))
            out.coarse = None
        elif parts is None:
            out.coarse = (problem, u)
        else:
            # the x-bisected mesh's coarser mesh (every other node both ways) is the one
            # solved coarser across; after any other bisection none is kept
            out.coarse = (across_coarse if across_coarse is not None and along_x
                          and not across and out.rounds == 0 else None)
        if local is not None:
            out.refined = "the cells along x that held most of the change along x bisected"
        # the next local round along x bisects where this round's change was (a round
        # across the width, or a quartered one, leaves none to read: every cell then)
        source = ((problem, u, change) if parts is not None and along_x and not across
                  and not quartered else None)
        problem, u, here, Z, last_info = fine, uf, finer, getattr(fine, "Z", None), info
        out.rounds += 1
        if estimate_if is not None and not estimate_if(problem, u, prm):
            out.notes.append("the mesh error estimate was not refined further: on this mesh "
                             "the answer is no longer the one returned")
            break
        if quartered:
            # not refined further: the next halving is of the kind that failed, and on 1 mm
            # board it is 0.24 M unknowns, stopped after 2 min at 7 GB without an answer
            break
    if out.rounds and out.algebraic is not None and out.errors["h_center"] is not None:
        # a refined answer's changes are from the states stopped early: their bounds kept
        out.errors = stated(out.errors, algebraic, coarse_bounds)
    if out.errors["h_center"] is None:
        out.basis = "none: no coarser mesh solved"
        if not any(n.startswith("no mesh error estimate") for n in out.notes):
            out.notes.append("no mesh error estimate: the mesh with cells twice as long did "
                             "not converge")
    elif user_mesh and _exceeds(out.errors, options.error_tol):
        out.notes.append(_user_note(out, options.error_tol))
    if out.algebraic is not None and out.errors["h_center"] is not None:
        out.basis += (f"; Newton stopped where its algebraic error was negligible, its "
                      f"bounds added (at most {max(out.algebraic.values()):.2g})")
    return problem, u, last_info, out


def _solved_on(disc, case, problem, u, prm, options, iterate, out: MeshError, X, Z):
    """``(fine, state, info, why)``: the answer carried over to the nodes X x Z and solved
    there, ``why`` the reason it is not an answer (None: admissible). ``fine`` is None (not
    tried) beyond :data:`MAX_DOFS` unknowns."""
    fine, uf = disc.remeshed(problem, u, prm, X, Z, options)
    if fine.n_dofs > MAX_DOFS:
        return None, None, None, "beyond the cap"
    release(problem)          # kept for its nodes and state while the finer one is solved
    with stage(f"{disc.name} error estimate asks for a finer mesh, {fine.n_dofs:,} "
               "unknowns"):
        if options.method == "newton" and getattr(fine, "grooves", None) is not None:
            # a grooved film's finer mesh from the answer carried over, without the
            # continuation from the smooth roller: a finer mesh that Newton does not reach
            # from the answer does not confirm it (the quartered mesh, or an unconfirmed
            # estimate, follows; :meth:`FoilBearing2D.solve_near`)
            uf, info = fine.solve_near(uf, prm, options)
        else:
            uf, info = iterate(fine, uf, prm, options)
    out.iterations += info.iterations
    why = "did not converge" if not info.converged else admissibility(case, fine, uf, prm)
    return fine, uf, info, why


def release(problem) -> None:
    """Drop what ``problem`` builds on first use (a 2-D film's assembly and factorisation
    plans, :meth:`webfem.fem.film_problem.FoilBearing2D.release`), where it can: a mesh
    kept for its nodes and state while another is solved (#147 of the envelope: the peak
    resident memory 2.75 -> 2.37 GB, the same answer)."""
    drop = getattr(problem, "release", None)
    if drop is not None:
        drop()


def _same_mesh(solved, X, Z) -> bool:
    """Whether ``solved`` (``(problem, state)`` or None) is on the nodes X x Z."""
    if solved is None:
        return False
    p = solved[0]
    Zp = getattr(p, "Z", None)
    return (np.array_equal(p.X, X) and (Z is None) == (Zp is None)
            and (Z is None or np.array_equal(Zp, Z)))


def _by_direction(disc, case, problem, u, prm, options, here, out: MeshError, Xc, Zc):
    """The estimate of a grooved film by direction: the change from the mesh with cells
    twice as long along x (the same nodes across) and from the one with cells twice as
    wide (the same x nodes), each a bound of that direction's error; the stated error is
    their sum. Why: the film over a landing web needs its x cells halved where its width
    nodes are long since fine enough (a 36 um PET film on 1 mm deep grooves: h_min 1.1 %
    off along x, 1e-5 across), and bisecting both directions quadruples the unknowns where
    halving x doubles them. Returns the two changes (None: that coarse mesh did not
    converge; the width's is 0 where it has too few cells to coarsen) and ``(problem, state,
    change)`` of the mesh coarser along x (None where it did not converge), from which a
    round along x reads where to bisect (:func:`_local_x_nodes`)."""
    found, along = [], None
    for name, X, Z in (("along x", Xc, problem.Z), ("across the width", problem.X, Zc)):
        if Z is problem.Z and X is problem.X:
            found.append(dict.fromkeys(out.errors, 0.0))
            continue
        with stage(f"{disc.name} error estimate on the mesh coarser {name}"):
            coarse, uc = disc.remeshed(problem, u, prm, X, Z, options)
            uc, info = coarse.solve_newton(uc, prm, _newton_options(options))
        out.iterations += info.iterations
        found.append(errors_between(case, here, read_out(case, coarse, uc, prm))
                     if info.converged else dict.fromkeys(out.errors))
        release(coarse)
        if info.converged and name == "along x" and Z is problem.Z:
            along = (coarse, uc, found[-1])
    out.errors = _summed(*found)
    if out.errors["h_center"] is not None:
        out.basis = (f"changes from the meshes with cells twice as long along x and across "
                     f"the width, summed ({problem.n_dofs:,} unknowns)")
    return tuple(found), along


def _across_only(disc, case, problem, u, prm, options, here, out: MeshError, Zc):
    """On a smooth roller whose estimate (the change from the mesh coarser both ways)
    exceeds ``error_tol``: the change from the mesh coarser across the width only (the same
    x nodes), so that a round bisects only the direction whose error is the larger, as on a
    grooved film. Returns ``(parts, across)``: the two directions' errors, the x one being
    the change from the mesh coarser both ways (a bound of it; only the direction's choice
    and, until x is bisected, the sum read it), and ``(problem, state)`` of that solve;
    ``(None, None)`` when it did not converge (every cell is bisected then). Why: at
    22.6 m/s on the base case's speed sweep the estimate was 1.02e-3 (h_min) on 9,385
    unknowns, all but 2e-5 of it along x; bisecting every cell both ways solved 35,927."""
    with stage(f"{disc.name} error estimate on the mesh coarser across the width"):
        coarse, uc = disc.remeshed(problem, u, prm, problem.X, Zc, options)
        uc, info = coarse.solve_newton(uc, prm, _newton_options(options))
    out.iterations += info.iterations
    if not info.converged:
        return None, None
    ez = errors_between(case, here, read_out(case, coarse, uc, prm))
    if any(v is None for v in ez.values()):
        return None, None
    return (dict(out.errors), ez), (coarse, uc)


def _local_x_nodes(case: Case, problem, u, coarse, uc, prm: FoilParameters,
                   allowed: float):
    """The x nodes of a round along x that bisects only where the change along x was: the
    fewest cells of ``problem`` (the largest shares first) that leave at most the share
    ``allowed`` of it to the others, from the answer ``u`` against ``uc`` solved on
    ``coarse``, its mesh coarser along x (the same nodes across). A cell's share is its
    length times the largest change, at its ends and quarter points, of the gap relative
    to the larger of the gap and the roughness sigma (as :func:`~webfem.models.readout.
    error_scale`) plus that of the width-averaged film pressure relative to the wrap
    pressure. Returns ``(nodes, left, bisected)``: ``left`` the share of the cells not
    bisected (the caller adds that share of the change to the stated x error: those cells
    keep the error they had) and how many cells are bisected; or None (every cell
    bisected: ``allowed`` is 0, more than :data:`LOCAL_MOST` of the cells would be
    bisected, or the change cannot be read).

    Why the share is added: the change from the mesh coarser along x bounds the answer's x
    error cell by cell as a whole; a round that bisects some cells measures only what those
    cells still err, the others keep theirs (at most their share of the change)."""
    X = np.asarray(problem.X, float)
    t = np.linspace(0.0, 1.0, 5)
    pts = (X[:-1, None] + np.diff(X)[:, None] * t).ravel()
    with np.errstate(all="ignore"):
        H = problem.gap(u, prm, pts)
        dH = np.abs(H - coarse.gap(uc, prm, pts)) / np.maximum(np.abs(H),
                                                              case.sigma / case.h_scale)
        dP = np.abs(problem.pressure(u, pts) - coarse.pressure(uc, pts))
        w = np.diff(X) * (dH + dP).reshape(-1, t.size).max(axis=1)
    total = float(np.sum(w))
    if not (np.all(np.isfinite(w)) and total > 0.0) or not allowed > 0.0:
        return None
    order = np.argsort(-w, kind="stable")
    k = int(np.searchsorted(np.cumsum(w[order]), (1.0 - allowed) * total)) + 1
    mark = np.zeros(w.size, dtype=bool)
    mark[order[:k]] = True
    if mark.sum() > LOCAL_MOST * mark.size:
        return None
    left = max(float(np.sum(w[~mark]) / total), 0.0)
    mids = 0.5 * (X[:-1] + X[1:])[mark]
    return np.sort(np.concatenate([X, mids])), left, int(mark.sum())


def _summed(ex: dict, ez: dict) -> dict:
    return {q: None if ex[q] is None or ez[q] is None else ex[q] + ez[q] for q in ex}


def _larger(ex: dict, ez: dict) -> bool:
    """True when the x direction's error is the larger (or not known)."""
    wx = max((v for v in ex.values() if v is not None), default=np.inf)
    wz = max((v for v in ez.values() if v is not None), default=0.0)
    return any(v is None for v in ex.values()) or wx >= wz


def _exceeds(errors, tol) -> bool:
    return any(v is None or v > tol for v in errors.values())


def _worst(errors) -> str:
    name = max(errors, key=lambda k: errors[k] if errors[k] is not None else np.inf)
    # None: no change could be measured for it (no coarser answer either)
    return f"{name} {'unknown' if errors[name] is None else format(errors[name], '.2g')}"


def _unconfirmed(out: MeshError, n: int, why: str, tol: float) -> None:
    """The finer meshes the estimate asked for gave no answer (``why``: the halved one's
    reason): the estimate stays the change from the coarser mesh, and the result says that
    it is unconfirmed. Why: a change above ``tol`` says the answer's mesh is not yet fine,
    and only a solve on a finer mesh shows whether it is in the range where the change
    bounds the error. On 1 mm board resting on the base roller it was not: 0.9 % (h_min)
    and 1.5 % (mu) from 80 to 160 cells along x, 4.4 % and 7.3 % from 160 to 640
    (docs/model.md)."""
    out.confirmed = False
    if out.basis:
        out.basis += (f"; unconfirmed: the mesh with every cell halved ({n:,} unknowns) "
                      "gave no answer, so the change may understate the error")
    if out.errors["h_center"] is None:
        # no change was measured either: there is no estimate to call unconfirmed
        out.notes.append(
            f"no mesh error estimate: the mesh with cells twice as long gave no answer, and "
            f"the mesh with every cell halved ({n:,} unknowns) gave no admissible answer "
            f"from this one ({why}); no error is stated, and no second mesh confirms this "
            "answer")
        return
    out.notes.append(
        f"mesh error estimate {_worst(out.errors)} exceeds error_tol = {tol:g} and could not "
        f"be confirmed: the mesh with every cell halved ({n:,} unknowns) gave no admissible "
        f"answer from this one ({why}). The stated errors are the change from the mesh "
        "with cells twice as long alone; on a mesh that does not yet resolve the film that "
        "change can be several times smaller than the error (no bound is stated)")


def _quartered_note(out: MeshError, n: int, n_halved: int, n_quartered: int,
                    tol: float) -> str:
    over = (f"; they exceed error_tol = {tol:g} ({_worst(out.errors)}), and the mesh is not "
            "refined further" if _exceeds(out.errors, tol) else "")
    return (f"the mesh with every cell halved ({n_halved:,} unknowns) gave no admissible answer "
            f"from the one of {n:,} unknowns; with that mesh's cells along x quartered "
            "instead of halved "
            f"({n_quartered:,} unknowns) it did, and that is the answer: its stated errors "
            f"are the change from the mesh of {n:,} unknowns (cells four times as long along "
            f"x){over}")


def _cap_note(out: MeshError, n: float, tol: float) -> str:
    return (f"mesh error estimate {_worst(out.errors)} exceeds the target error_tol = "
            f"{tol:g}; the finer mesh it asks for ({n:,.0f} unknowns) is beyond webfem's cap of "
            f"{MAX_DOFS:,.0f}: the estimates state this answer's error")


def _user_note(out: MeshError, tol: float) -> str:
    return (f"user mesh: its error estimate {_worst(out.errors)} exceeds error_tol = {tol:g} "
            "(a user mesh is not refined): refine the mesh or use webfem's graded one")


def summary_keys(out: MeshError) -> dict:
    """The summary keys of an estimate: ``error_<quantity>`` and ``error_basis``."""
    return {**{f"error_{k}": v for k, v in out.errors.items()}, "error_basis": out.basis}

