"""Continued 2-D starts (:mod:`webfem.models.continued`): a sweep point started from the
previous point's state on its moved mesh answers what a cold solve answers, within the two
answers' stated mesh errors, in fewer Newton steps; a continued start that fails falls back
to the cold start; a restart that does not fit (other options, a grooved roller) starts
cold."""

import dataclasses

import numpy as np
import pytest
from conftest import BASE, GROOVED

import webfem
from webfem.models import continued
from webfem.models.readout import READ_QUANTITIES, error_scale

#: Rounding of a read-out quantity, relative: where the web rests on its asperities the
#: central gap is set by the contact law alone and two meshes' estimates of it are 1e-15
#: (the change between them is rounding); two answers on different meshes then differ by
#: rounding too, a few times 1e-15.
ROUNDING = 1e-12


def agree(case, a, b):
    """Quantities of ``a`` and ``b`` whose difference exceeds their stated errors summed."""
    out = []
    for q in READ_QUANTITIES:
        bound = sum(r[f"error_{q}"] * error_scale(case, q, r[q]) for r in (a, b))
        bound += ROUNDING * error_scale(case, q, b[q])
        if not abs(a[q] - b[q]) <= bound:
            out.append((q, a[q], b[q], bound))
    return out


#: Two stretches of the base case's realistic log-spaced speed sweep (0.5-40 m/s, 24
#: points, a step of 1.21x): the web resting on its asperities, and taking off.
PATHS = [np.geomspace(1.07, 1.57, 3), np.geomspace(15.4, 22.6, 3)]


@pytest.mark.parametrize("speeds", PATHS, ids=["resting", "taking-off"])
def test_continued_sweep_equals_cold_solves_within_stated_errors(speeds):
    cases = [BASE.updated({"roller.speed": float(u)}) for u in speeds]
    along = list(webfem.solve_along(cases, "fe2d"))
    for i, (case, a) in enumerate(zip(cases, along)):
        cold = webfem.solve(case, "fe2d")
        assert a["converged"] and cold["converged"]
        assert "line_start" in cold.diagnostics.solver      # the 1-D start a cold solve made
        assert agree(case, a, cold) == [], case.roller.speed
        if i == 0:
            assert "continued" not in a.diagnostics.solver
            continue
        # a continued start: no 1-D solve, the previous mesh (moved) or the one its gap asks
        # for, a secant from the third point on while the mesh stayed
        note = a.diagnostics.solver["continued"]
        assert note.startswith("continued") and "line_start" not in a.diagnostics.solver
        assert a["iterations"] < cold["iterations"], (case.roller.speed, a["iterations"],
                                                      cold["iterations"])


def test_a_continued_start_that_fails_falls_back_cold():
    """A restart whose state Newton cannot solve from (five times the solved state: the
    coupled steps fail; from three times it the film's streamline diffusion now lets Newton
    converge, to the cold answer within its stated errors, or end on an inadmissible field): the answer is the cold solve's,
    and its reason says the cold start followed the continued one. A state that is not finite is not started from at all."""
    before = webfem.solve(BASE.updated({"roller.speed": 18.0}), "fe2d")
    cold = webfem.solve(BASE, "fe2d")
    for u, why in ((5.0 * before.restart.u, "cold start after the continued start"),
                   (np.full_like(before.restart.u, np.nan), None)):
        r = webfem.solve(BASE, "fe2d",
                         initial=dataclasses.replace(before.restart, u=u, prior=None))
        assert r["converged"]
        if why:
            assert why in r.summary.solver_message
        else:
            assert "continued" not in r.diagnostics.solver
        # the failed continued start falls back to the cold start itself; a state that is
        # not finite still leaves the restart's 1-D state (finite) to start the 1-D solve
        # from, so that answer agrees with the cold one to Newton's tolerance, not bitwise
        rel = 1e-12 if why else 1e-9
        for q in READ_QUANTITIES:
            assert r[q] == pytest.approx(cold[q], rel=rel, abs=1e-15), q


def test_a_restart_that_does_not_fit_starts_cold():
    """Other options (another level) or a grooved roller: no continued start."""
    r = webfem.solve(BASE.updated({"roller.speed": 18.0}), "fe2d")
    opts = webfem.models.registry.make_options("fe2d", None, level=1)
    assert continued.continued_state(BASE, opts, r.restart) is None
    same = webfem.models.registry.make_options("fe2d", None)
    assert continued.continued_state(BASE, same, r.restart) is not None
    assert continued.continued_state(GROOVED, same, r.restart) is None


def test_secant_only_on_a_one_parameter_path():
    c = [BASE.updated({"roller.speed": u}) for u in (10.0, 12.0, 14.4)]
    assert continued.secant_factor(*c) == pytest.approx(1.0)
    # two inputs change: no secant
    assert continued.secant_factor(c[0], c[1], c[2].updated({"web.tension": 90.0})) is None
    # a jump of more than MAX_SECANT steps: no secant
    far = BASE.updated({"roller.speed": 12.0 * 1.2 ** 3})
    assert continued.secant_factor(c[0], c[1], far) is None


def test_moved_nodes_keep_the_wrap_edges_and_the_entry_length():
    X = np.array([-9.0, -6.0, -5.0, -1.0, 0.0, 2.0, 5.0, 8.0])
    Y = continued.moved_nodes(X, 10.0, 14.0)
    assert Y[[2, 6]].tolist() == [-7.0, 7.0]                  # the wrap edges
    assert Y[0] - Y[2] == pytest.approx(X[0] - X[2])          # the entry zone's length
    assert Y[-1] - Y[-2] == pytest.approx(X[-1] - X[-2])
    assert np.all(np.diff(Y) > 0)


def test_two_grid_start_solves_the_coarser_mesh_first():
    """A continued point whose restart keeps its coarse state (``restart.coarse``, the
    estimate's coarser mesh) solves that mesh first and starts the fine Newton from it: on
    the same mesh, the answer is the one started without it (the coarse state dropped) to
    Newton's tolerance, with the same stated errors, and within its stated errors of the
    cold solve. Every solve to the tolerance (``algebraic_share = 0``): with balanced
    stopping the two answers differ by their algebraic errors, tests/test_algebraic.py."""
    cases = [BASE.updated({"roller.speed": u}) for u in (15.4, 18.6)]
    first = webfem.solve(cases[0], "fe2d", algebraic_share=0.0)
    assert first.restart.coarse is not None
    Xc, Zc, uc = first.restart.coarse
    assert uc.size < first.restart.u.size and Xc.size < first.restart.X.size
    two = webfem.solve(cases[1], "fe2d", initial=first, algebraic_share=0.0)
    plain = webfem.solve(cases[1], "fe2d", algebraic_share=0.0,
                         initial=dataclasses.replace(first.restart, coarse=None))
    assert "coarser mesh solved first" in two.diagnostics.solver["continued"]
    assert "coarser mesh" not in plain.diagnostics.solver["continued"]
    assert two["n_dofs"] == plain["n_dofs"]
    for q in READ_QUANTITIES:
        assert two[q] == pytest.approx(plain[q], rel=1e-7, abs=1e-15), q
        assert two[f"error_{q}"] == pytest.approx(plain[f"error_{q}"], rel=1e-5, abs=1e-12)
    cold = webfem.solve(cases[1], "fe2d")
    assert agree(cases[1], two, cold) == []


def test_quadratic_predictor_on_a_path_of_four_points():
    """From the fourth point of a path on one mesh the start is the quadratic through the
    three states before it (in log speed), and the answer still agrees with the cold
    solve within the stated errors."""
    cases = [BASE.updated({"roller.speed": float(u)}) for u in np.geomspace(4.07, 7.20, 4)]
    along = list(webfem.solve_along(cases, "fe2d"))
    assert all(a["converged"] for a in along)
    assert "quadratic predictor" in along[3].diagnostics.solver["continued"]
    cold = webfem.solve(cases[3], "fe2d")
    assert agree(cases[3], along[3], cold) == []
    w = continued.extrapolation_weights(cases[:3], cases[3])
    assert w.sum() == pytest.approx(1.0) and w.tolist() == pytest.approx([1.0, -3.0, 3.0])


def test_a_near_step_keeps_the_previous_mesh():
    """A step of at most continued.NEAR_STEP (a root finder's) from a point whose error
    estimate refined the mesh its gap asked for starts on that point's mesh (planned again,
    its estimate refined it again), and the mark stays with the mesh; the answer agrees
    with the cold solve within the stated errors. A sweep's step is not near. Here at
    30 m/s with a target of 5e-4, which the mesh its cold start decides up front misses
    along x (at fe2d's default target the base case's meshes decided up front meet it from
    1 to 40 m/s)."""
    a, b = (BASE.updated({"roller.speed": u}) for u in (30.0, 28.6))
    assert continued.near(a, b) and not continued.near(a, a.updated({"roller.speed": 36.0}))
    first = webfem.solve(a, "fe2d", error_tol=5e-4)
    assert first.restart.refined
    r = webfem.solve(b, "fe2d", initial=first, error_tol=5e-4)
    assert r["converged"] and "carried over" not in r.diagnostics.solver["continued"]
    assert r["n_dofs"] == first["n_dofs"] and r.restart.refined
    cold = webfem.solve(b, "fe2d", error_tol=5e-4)
    assert agree(b, r, cold) == []
    assert r["iterations"] < cold["iterations"]


def test_a_refined_mesh_is_kept_where_the_planned_one_was_refused():
    """A sweep's step (not near) from a point whose error estimate refused the mesh its
    predicted gap asked for, to a point whose gap asks for about that mesh again
    (:func:`continued.refused_again`): the refined mesh is kept, not planned again and
    refined again by the estimate. On the benchmark sweep's 15.4-27.3 m/s the estimate
    refines the mesh planned at 22.6 m/s; at 27.3 m/s the planned mesh, refused and refined
    again, took 15 Newton steps where the kept one takes 8. The answer agrees with the cold
    solve within the stated errors. The path starts cold at 18.7 m/s: from 15.4 m/s the
    mesh it keeps (its long cells where the web lies flat kept too, :data:`webfem.models.
    fe2d.FLAT_KEPT`) is one the estimate accepts at 22.6 m/s."""
    cases = [BASE.updated({"roller.speed": float(u)})
             for u in np.geomspace(0.5, 40.0, 24)[19:22]]
    along = list(webfem.solve_along(cases, "fe2d"))
    refined, last = along[1], along[2]
    assert all(a["converged"] for a in along) and refined.restart.refined
    assert not continued.near(cases[1], cases[2])
    assert "carried over" not in last.diagnostics.solver["continued"]
    assert last["n_dofs"] == refined["n_dofs"] and last.restart.refined
    cold = webfem.solve(cases[2], "fe2d")
    assert agree(cases[2], last, cold) == []
    assert last["iterations"] < 12


def test_long_cells_where_the_web_lay_flat_stay_along_a_sweep():
    """Along the base case's sweep from 3.4 to 10.5 m/s (7 of its 24 points) the web lifts
    from its asperities from the entry on: cells the first (cold) point left long where the
    web lay flat leave the cold rule's flat set (a gap change of 0.01 sigma) as the front
    passes. A continued point judges them flat up to :data:`webfem.models.fe2d.FLAT_KEPT`
    times that: every point keeps the first point's mesh (with the cold bound each point
    after it refined its coarser mesh where its gap asked, 8-10 Newton steps against 6-8),
    and each answer agrees with its cold solve within the stated errors."""
    from webfem.models import fe2d

    cases = [BASE.updated({"roller.speed": float(u)})
             for u in np.geomspace(0.5, 40.0, 24)[10:17]]
    along = list(webfem.solve_along(cases, "fe2d"))
    assert fe2d.FLAT_KEPT > 1.0 and all(a["converged"] for a in along)
    for case, a in zip(cases[1:], along[1:]):
        assert a["n_dofs"] == along[0]["n_dofs"]
        assert "refined" not in a.diagnostics.solver["continued"]
        assert agree(case, a, webfem.solve(case, "fe2d")) == []


def test_a_well_predicted_point_takes_one_fine_factorisation(monkeypatch):
    """The fine start of a two-grid start carries what the coarser mesh does not of the
    prediction (a full-approximation start, :func:`webfem.models.fe2d._fine_start`): where
    the quadratic predictor is good (the web resting at 0.6-1.1 m/s, four points of the
    benchmark's sweep) the fine Newton takes one factorisation and chord steps from it
    (three steps, two factorisations with the previous point's fine-minus-coarse
    difference alone; the chord steps chain at a gain of 10, :func:`webfem.fem.newton.
    newton`). Iteration counts do not depend on the machine's load. The answer agrees with
    the cold solve."""
    from webfem import progress
    from webfem.fem import newton

    cases = [BASE.updated({"roller.speed": float(u)})
             for u in np.geomspace(0.5, 40.0, 24)[1:5]]
    seen = []
    factor = newton.PatternSolver.factor

    def counted(self, A, free):
        seen.append(("factor", progress._STAGE.get()))
        return factor(self, A, free)

    monkeypatch.setattr(newton.PatternSolver, "factor", counted)
    with progress.reporting(seen.append):
        along = list(webfem.solve_along(cases, "fe2d"))
    monkeypatch.undo()
    last = along[-1]
    assert "quadratic predictor" in last.diagnostics.solver["continued"]
    fine = f"fe2d newton, {last['n_dofs']:,} unknowns"
    # the last point's fine Newton (the last call on the fine mesh: from its start,
    # iteration 0, on): its steps and its factorisations
    def stage(s):
        return s.stage if isinstance(s, progress.Step) else s[1]

    on_fine = [s for s in seen if stage(s) and stage(s)[-1] == fine]
    first = max(i for i, s in enumerate(on_fine)
                if isinstance(s, progress.Step) and s.iteration == 0)
    call = on_fine[first:]
    assert sum(isinstance(s, progress.Step) for s in call) - 1 <= 3
    assert sum(not isinstance(s, progress.Step) for s in call) == 1
    cold = webfem.solve(cases[-1], "fe2d")
    assert agree(cases[-1], last, cold) == []


def test_a_kept_mesh_that_misses_the_predicted_state_is_bisected_up_front(monkeypatch):
    """Along the benchmark sweep's 10.5-22.6 m/s (5 of its 24 points) the mesh planned at
    12.8 m/s is kept to 22.6 m/s, where the exit's pressure dip has moved off its cells:
    the cells of the coarser mesh that miss the predicted state by more than
    :data:`webfem.models.fe2d.MISFIT_KEPT` times the cold rule's bound are bisected (as a
    cold start's, :func:`webfem.models.fe2d._misfit_kept`) before the solve, so the error
    estimate accepts the mesh: no second fine solve. Without the rule (the bound never
    met) the estimate refuses the kept mesh and solves one with every cell bisected along
    x. Both answers agree with the cold solve within the stated errors."""
    from webfem.models import fe2d

    cases = [BASE.updated({"roller.speed": float(u)})
             for u in np.geomspace(0.5, 40.0, 24)[16:21]]
    along = list(webfem.solve_along(cases, "fe2d"))
    last = along[-1]
    assert all(a["converged"] for a in along)
    assert "refined where" in last.diagnostics.solver["continued"]
    assert not last.restart.refined and last["n_dofs"] < 1.5 * along[-2]["n_dofs"]
    monkeypatch.setattr(fe2d, "MISFIT_KEPT", np.inf)
    plain = list(webfem.solve_along(cases, "fe2d"))[-1]
    assert plain.restart.refined and plain["n_dofs"] > 1.9 * along[-2]["n_dofs"]
    assert last["iterations"] < plain["iterations"]
    cold = webfem.solve(cases[-1], "fe2d")
    assert agree(cases[-1], last, cold) == [] and agree(cases[-1], plain, cold) == []
