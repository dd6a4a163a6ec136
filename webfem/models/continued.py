"""A continued 2-D start: the previous point's solved state on the previous point's final
mesh, moved to this point's scaled geometry, with a secant predictor along the path.

A cold fe2d solve spends most of its time finding its mesh (a 1-D start, a 2-D solve on the
start mesh, the refinement where the film is thin) and its state (Newton from the 1-D
solution). Along a path of nearby cases (a sweep) the previous point has both: its final
mesh, moved with the scaled geometry (:func:`moved_nodes`), and its state, extrapolated
along the path from the states before it on that mesh (solved there, or carried over to it
where the mesh changed: :func:`predicted`), start this point's Newton. When the previous
point kept its solution on its coarser mesh (``State.coarse``, the error estimate's), the
2-D model solves this point's coarser mesh first and starts the fine Newton from it (a
two-grid start: :meth:`webfem.models.fe2d._Film._two_grid`). Nothing here decides the answer: the driver still refines where the film
is thin, the mesh error estimate still confirms (or refines) the mesh, and a start that
fails or ends inadmissible is retried cold (:func:`webfem.models.driver.solve_fe`).

Examples
--------
>>> moved_nodes(np.array([-7.0, -5.0, 0.0, 5.0, 7.0]), 10.0, 8.0).tolist()
[-6.0, -4.0, 0.0, 4.0, 6.0]
"""

from __future__ import annotations

import math

import numpy as np

from ..case import Case
from ..fem.outcome import SolveInfo
from ..result import State
from .refine import FLAT_GAP, adapted_nodes

__all__ = ["moved_nodes", "secant_factor", "extrapolation_weights", "mesh_key",
           "continued_state", "predicted", "similar", "near", "refused_again", "planned_nodes",
           "start_info",
           "MAX_SECANT", "MESH_SLACK"]

#: The secant extrapolates at most this many previous steps ahead (a sweep's next step is
#: one; a jump of many steps is a poor linear prediction, and the previous state is the
#: safer start then).
MAX_SECANT = 2.0

#: A moved mesh is reused while its nodes along each direction number at most this factor
#: more (or fewer) than the cold mesh of the case: along a sweep from 0.5 to 40 m/s the
#: cold meshes shrink from 21,793 to 5,963 unknowns, and a mesh carried along unchanged
#: costs up to 4 times per iteration what the cold one does.
MESH_SLACK = 1.2


def moved_nodes(X: np.ndarray, beta0: float, beta1: float) -> np.ndarray:
    """The nodes ``X`` of a wrap of scaled length ``beta0`` moved to one of ``beta1``: the
    wrap |X| <= beta0/2 scaled by beta1/beta0, the entry and exit zones shifted with their
    wrap edge (their scaled length is the case's ``entry``, whatever beta). The wrap edges
    stay nodes, the grading towards them and the cells' order are kept."""
    X = np.asarray(X, float)
    e0, e1 = 0.5 * beta0, 0.5 * beta1
    inside = np.abs(X) <= e0 * (1.0 + 1e-12)
    out = np.where(inside, X * (beta1 / beta0), X + np.sign(X) * (e1 - e0))
    out[np.isclose(X, e0, rtol=1e-12, atol=1e-12)] = e1
    out[np.isclose(X, -e0, rtol=1e-12, atol=1e-12)] = -e1
    return out


def _numbers(case: Case) -> dict[str, float]:
    """The case's numeric inputs by dotted key (``roller.speed``)."""
    out = {}
    for section, values in case.to_dict().items():
        for key, value in (values or {}).items():
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                out[f"{section}.{key}"] = float(value)
    return out


def _path(cases) -> list[float] | None:
    """The values along ``cases`` of the one numeric input that changes along them (in its
    logarithm when all are > 0: a log-spaced sweep's steps are then equal), or None when
    they are not on a one-parameter path stepping forward each time by at most
    :data:`MAX_SECANT` times the step before."""
    numbers = [_numbers(c) for c in cases]
    if any(n.keys() != numbers[0].keys() for n in numbers):
        return None
    changed = {k for k in numbers[0] if any(n[k] != numbers[0][k] for n in numbers)}
    if len(changed) != 1:
        return None
    key = changed.pop()
    s = [n[key] for n in numbers]
    if all(v > 0.0 for v in s):
        s = [math.log(v) for v in s]
    for i in range(1, len(s) - 1):
        if s[i] == s[i - 1] or not 0.0 < (s[i + 1] - s[i]) / (s[i] - s[i - 1]) <= MAX_SECANT:
            return None
    return s


def secant_factor(c0: Case, c1: Case, c2: Case) -> float | None:
    """(s2 - s1) / (s1 - s0) of the one input that changes along c0, c1, c2 (in its
    logarithm when its values are > 0: a log-spaced sweep's steps are then equal), or None
    when the three cases are not on a one-parameter path stepping forward by at most
    :data:`MAX_SECANT` previous steps.

    >>> from webfem import Case
    >>> cs = [Case().updated({"roller.speed": u}) for u in (10.0, 20.0, 40.0)]
    >>> round(secant_factor(*cs), 12)
    1.0
    >>> secant_factor(cs[2], cs[1], cs[0]) is not None   # a path walked downwards
    True
    >>> secant_factor(cs[0], cs[1], cs[1].updated({"web.tension": 90.0})) is None
    True
    """
    s = _path([c0, c1, c2])
    return None if s is None else (s[2] - s[1]) / (s[1] - s[0])


def extrapolation_weights(cases, case: Case) -> np.ndarray | None:
    """The weights of the states of ``cases`` (oldest first) whose sum is the polynomial
    through them along the path (:func:`_path`) evaluated at ``case``: with two states the
    secant, with three the quadratic. None when they are not on one path.

    >>> from webfem import Case
    >>> cs = [Case().updated({"roller.speed": u}) for u in (10.0, 20.0, 40.0, 80.0)]
    >>> extrapolation_weights(cs[:3], cs[3]).round(12).tolist()
    [1.0, -3.0, 3.0]
    >>> extrapolation_weights(cs[1:3], cs[3]).round(12).tolist()
    [-1.0, 2.0]
    """
    s = _path([*cases, case])
    if s is None:
        return None
    x, nodes = s[-1], s[:-1]
    return np.array([math.prod((x - nodes[m]) / (nodes[j] - nodes[m])
                               for m in range(len(nodes)) if m != j)
                     for j in range(len(nodes))])


def mesh_key(options) -> dict:
    """What a restart must share with this solve to start from its mesh: every option (a
    sweep solves all its points with one options object; a restart made with other options,
    another level or element order, starts cold)."""
    return options.to_dict()


def continued_state(case: Case, options, restart: State | None):
    """``(X, Z)``: the restart's final mesh moved to this case's beta and lambda, or None
    when the restart cannot start this solve (another model or options, a grooved roller,
    a user mesh). The state on it is :func:`predicted`'s."""
    if (restart is None or restart.model != "fe2d" or restart.Z is None or case.grooved
            or restart.case.grooved or options.mesh is not None or options.nodes is not None
            or restart.key != mesh_key(options)):
        return None
    old = restart.case
    return moved_nodes(restart.X, old.beta, case.beta), restart.Z * (case.lam / old.lam)


def predicted(problem, case: Case, restart: State) -> tuple[np.ndarray, str]:
    """The start of ``case`` on ``problem`` (the restart's mesh moved,
    :func:`continued_state`): the restart's state, extrapolated along the path when the
    restart keeps the states before it on the same mesh (``restart.prior``, ``restart.
    prior2``): by a secant through two, a quadratic through three (in the logarithm of a
    positive parameter, :func:`extrapolation_weights`), and a note saying which.

    The quadratic, measured on the coarse meshes of the base case's 24-point speed sweep
    (0.5-40 m/s, 7 points with three states on one mesh): its largest error 0.15-15 % of
    the state where the secant's was 1.3-24 % (at the exit's pressure peak), Newton from it
    3-5 steps where from the secant 4-5; on the whole sweep 204 iterations and 103
    factorisations where the secant alone took 207 and 111 (the median per point 8 both).

    The state is carried in scaled values. Carrying it in physical ones (a resting web keeps
    its physical gap as the scales change) was measured on the base case's 24-point speed
    sweep: 4-5 times smaller first residuals where the web rests, but not one Newton step
    fewer, and 2-3 times the steps where it flies."""
    u0, note = restart.u.copy(), "continued from the previous point's state and mesh"
    chain = [(restart.case, restart.u)]
    for before in (restart.prior, restart.prior2):
        if before is None or before[1].shape != u0.shape:
            break
        chain.insert(0, before)
    while len(chain) > 1:
        w = extrapolation_weights([c for c, _ in chain], case)
        if w is not None:
            u0 = sum(wj * uj for wj, (_, uj) in zip(w, chain))
            note = ("continued by a secant predictor" if len(chain) == 2 else
                    "continued by a quadratic predictor") + " on the previous point's mesh"
            break
        chain.pop(0)
    u0[problem.fixed] = 0.0
    return u0, note


#: A step along the path this short (in the logarithm of a positive parameter: 10 %) keeps
#: the previous point's mesh where its error estimate refined it (``State.refined``),
#: whatever the mesh the predicted gap asks for: that mesh was too coarse a step away. A
#: traction-loss search's root finding steps 0.06-6 % from the nearest solved speed, near
#: 23 m/s on the base case where the estimate bisects the mesh the gap asks for; planned
#: again, each evaluation had its estimate bisect it again (14-20 Newton steps each). Only
#: a refined mesh: kept on every short step, any mesh would drift from what the case asks
#: for along a finely stepped sweep (the 1.2x of :data:`MESH_SLACK` bounds that).
NEAR_STEP = 0.1


def near(c0: Case, c1: Case) -> bool:
    """Whether ``c1`` is a step of at most :data:`NEAR_STEP` from ``c0`` along one input
    (:func:`_path`).

    >>> from webfem import Case
    >>> near(Case().updated({"roller.speed": 23.54}), Case().updated({"roller.speed": 23.41}))
    True
    >>> near(Case().updated({"roller.speed": 20.0}), Case().updated({"roller.speed": 24.0}))
    False
    """
    s = _path([c0, c1])
    return s is not None and abs(s[1] - s[0]) <= NEAR_STEP


def refused_again(restart: State, planned: np.ndarray) -> bool:
    """Whether the mesh this case's predicted gap asks for (``planned``, its nodes along x)
    is about the one the restart's error estimate refused: the restart's mesh was refined
    by its estimate (``restart.refined``) and its coarser mesh (``restart.coarse``, the
    refused one, moved along while the refined mesh is kept) has within
    :data:`MESH_SLACK` as many nodes along x. Such a mesh is likely to be refused again, a
    step away however long: :meth:`webfem.models.fe2d._Film._continued` keeps the refined
    mesh then, as on a :func:`near` step. Why: on the base case's 24-point speed sweep
    (0.5-40 m/s) the estimate refused the mesh planned at 22.6 m/s (9,097 unknowns,
    h_min 1.02e-3 against 1e-3) and bisected it along x; planned again at 27.3 m/s (8,521)
    it was refused and bisected again: 15 Newton steps and 8 factorisations there, where
    on the refined mesh kept the point took 8 and 5 (the answers at most 6e-8 apart,
    relative; stated errors 2e-5 to 1.6e-4)."""
    return (restart.refined and restart.coarse is not None
            and similar(np.size(restart.coarse[0]), np.size(planned)))


def similar(n_moved: int, n_cold: int) -> bool:
    """Whether a moved mesh's node count along one direction is within
    :data:`MESH_SLACK` of the cold mesh's (either way)."""
    return n_cold / MESH_SLACK <= n_moved <= n_cold * MESH_SLACK


class _Gap:
    """What :func:`webfem.models.refine.adapted_nodes` reads of a problem: its nodes and
    its gap, here a predicted gap on nodes not yet solved on."""

    def __init__(self, X, gap):
        self.X, self._gap = X, gap

    def gap(self, u, prm, X):
        return self._gap(np.clip(X, self.X[0], self.X[-1]))


def planned_nodes(X, prm, options, gap, coarser: int = 1, flat: float = 1.0,
                  flat_gap: float = FLAT_GAP) -> np.ndarray:
    """The nodes along x a cold solve would refine its graded start mesh ``X``
    (:func:`webfem.fem.mesh.graded_nodes`) to for the gap ``gap(X)`` (a predicted one):
    bisected by the adaptive rule (:func:`webfem.models.refine.adapted_nodes`), up to
    ``options.adapt`` rounds, as the 1-D start of a cold solve does with its own gap.
    ``coarser``: the rule's cell lengths (``adapt_ratio``, ``min_cell``) times this (2: a
    mesh whose every cell bisected meets the rule). ``flat``: the rule's factor where the web
    lies flat and ``flat_gap`` the gap's change that says so (:func:`webfem.models.refine.
    adapted_nodes`)."""
    for _ in range(options.adapt):
        finer = adapted_nodes(_Gap(X, gap), None, prm, coarser * options.adapt_ratio,
                              coarser * options.min_cell, flat=flat, flat_gap=flat_gap)
        if finer is None:
            break
        X = finer
    return X


def start_info() -> SolveInfo:
    """The work a continued start spent before its Newton: none."""
    return SolveInfo(converged=True, iterations=0)
