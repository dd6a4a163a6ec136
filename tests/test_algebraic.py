"""Balanced stopping (webfem/models/algebraic.py, newton's ``accept``): a continued point's
Newton stops where its algebraic error is negligible, and the bound it carries holds."""

import numpy as np
import pytest
import scipy.sparse as sp
from conftest import BASE

import webfem
from webfem.fem.film_problem import FoilBearing2D
from webfem.fem.newton import ACCEPT_CONTRACTION, newton
from webfem.fem.scaling import FoilParameters
from webfem.models import fe1d
from webfem.models.options import FE2DOptions
from webfem.models.readout import READ_QUANTITIES, errors_between, read_out

F = lambda u: u**3 - 8.0                       # noqa: E731
J = lambda u: sp.diags(3 * u**2)               # noqa: E731


def test_newton_stops_where_accept_says_and_keeps_its_answer():
    seen = []

    def accept(u, du, theta):
        seen.append(theta)
        assert theta <= ACCEPT_CONTRACTION
        # the correction bounds the iterate's error: accepted once it is below 1e-6
        return {"x": 2.0 * abs(du[0])} if abs(du[0]) < 1e-6 else None

    out = newton(F, J, np.array([1.0]), tol=1e-14, accept=accept)
    strict = newton(F, J, np.array([1.0]), tol=1e-14)
    assert out.converged and out.algebraic is not None and seen
    assert "balanced" in out.reason and out.residual > 1e-14
    assert out.iterations < strict.iterations
    assert abs(out.u[0] - 2.0) <= out.algebraic["x"]
    # an accept that never answers leaves the solve as it was
    never = newton(F, J, np.array([1.0]), tol=1e-14, accept=lambda u, du, t: None)
    assert never.iterations == strict.iterations and never.algebraic is None
    assert never.u[0] == strict.u[0]


def _true_errors(case, X, Z, u):
    """``u`` on X x Z against the discrete solution there (solved on to tol), relative as
    the stated errors."""
    o = FE2DOptions()
    prm = FoilParameters.from_case(case, o.compressible, o.contact, o.floor)
    p = FoilBearing2D(X, Z, order=o.order, spans=fe1d.spans(case, X))
    out = p.newton(u, prm, o.tol, o.max_iter)
    assert out.converged
    return errors_between(case, read_out(case, p, out.u, prm), read_out(case, p, u, prm))


@pytest.fixture(scope="module")
def sweeps():
    cases = [BASE.updated({"roller.speed": float(u)}) for u in np.geomspace(7.2, 10.5, 3)]
    balanced = list(webfem.solve_along(cases, "fe2d"))
    strict = list(webfem.solve_along(cases, "fe2d", algebraic_share=0.0))
    return cases, balanced, strict


def test_each_bound_holds_and_is_stated(sweeps):
    """Each continued answer stopped early carries per-quantity bounds of its own and of its
    coarser mesh's algebraic error; solved on to tol on their meshes, both states move by
    less than those bounds, which the stated errors include."""
    cases, balanced, strict = sweeps
    stopped = 0
    for case, b in zip(cases[1:], balanced[1:]):
        bound = b.diagnostics.solver["algebraic"]
        added = b.diagnostics.solver["algebraic_stated"]
        if bound is None:
            continue
        stopped += 1
        st = b.restart
        true = _true_errors(case, st.X, st.Z, st.u)
        coarse = _true_errors(case, *st.coarse)
        for q in READ_QUANTITIES:
            assert true[q] <= bound[q], q
            assert coarse[q] <= added[q] - 2.0 * bound[q], q
            assert b[f"error_{q}"] >= added[q]
            assert added[q] <= 3.0 * FE2DOptions().algebraic_share * FE2DOptions().error_tol
        assert "balanced" in b.summary.solver_message
    assert stopped == 2


def test_answers_move_within_their_bounds_and_take_fewer_iterations(sweeps):
    """Against the same sweep solved to tol, on the same meshes, each answer moves by less
    than its bound plus the strict answer's rounding, and the continued points take fewer
    Newton iterations."""
    cases, balanced, strict = sweeps
    for case, b, s in zip(cases, balanced, strict):
        assert b["n_dofs"] == s["n_dofs"]
        bound = b.diagnostics.solver["algebraic"] or dict.fromkeys(READ_QUANTITIES, 0.0)
        moved = errors_between(case, read_out(case, *_readable(b), prm=_prm(case)),
                               read_out(case, *_readable(s), prm=_prm(case)))
        for q in READ_QUANTITIES:
            assert moved[q] <= bound[q] + 1e-12, q
    assert sum(r["iterations"] for r in balanced[1:]) < sum(r["iterations"]
                                                             for r in strict[1:])


def _prm(case):
    o = FE2DOptions()
    return FoilParameters.from_case(case, o.compressible, o.contact, o.floor)


def _readable(result):
    st = result.restart
    return FoilBearing2D(st.X, st.Z, order=2, spans=fe1d.spans(result.case, st.X)), st.u


def test_a_tol_the_user_sets_is_met_strictly():
    cases = [BASE.updated({"roller.speed": u}) for u in (8.71, 10.5)]
    for r in webfem.solve_along(cases, "fe2d", tol=5e-10):
        assert r.diagnostics.solver["algebraic"] is None
        assert r["residual"] <= 5e-10
        assert "balanced" not in r.summary.solver_message


def test_solved_problems_are_freed_without_the_cyclic_collector():
    """The acceptor a problem keeps refers back to it weakly: with a strong reference each
    solved problem was a cycle, alive until the cyclic collector ran (17 after an 8-point
    sweep; GB at 1e5 unknowns)."""
    import gc

    import numpy as np

    from webfem import load_case, solve_along
    from webfem.fem.film_problem import FoilBearing2D

    base = load_case("cases/base.toml")
    cases = [base.updated({"roller.speed": float(u)}) for u in np.geomspace(5.0, 20.0, 4)]
    gc.collect()
    gc.disable()
    try:
        out = list(solve_along(cases, "fe2d"))
        assert any("balanced stopping" in (r.summary.solver_message or "") for r in out)
        del out
        alive = [o for o in gc.get_objects() if isinstance(o, FoilBearing2D)]
    finally:
        gc.enable()
    assert alive == []
