"""The web held at the neighbouring rollers (``wrap.span``) instead of at the ends of the FE
models' entry and exit zones (the paper's Eq. 20): webfem.fem.ends and docs/model.md,
"Where the web is held"."""

import numpy as np
import pytest
from scipy.sparse.linalg import splu

import webfem
from webfem import Case
from webfem.errors import InputError
from webfem.fem.picard import lift_correction
from webfem.fem.scaling import FoilParameters

BASE = webfem.load_case(webfem.bundled.find_case("base"))


def solve(model, span, **options):
    case = BASE if span is None else BASE.updated({"wrap.span": span})
    return webfem.solve(case, model=model, **options)


def test_with_a_span_the_answer_no_longer_depends_on_the_zones():
    """Held at the zones' ends, the base case's central gap moves 1.8e-3 (fe2d) when the
    zones double from 40 to 80 units, six times its stated error; held at a 1 m span it
    moves 5e-6 (fe2d) and 9e-5 (fe1d, whose zones' film the longer zone still adds)."""
    for model, tol in (("fe1d", 2e-4), ("fe2d", 2e-5)):
        a, b = (solve(model, 1.0, entry=e) for e in (40.0, 80.0))
        assert b["h_center"] == pytest.approx(a["h_center"], rel=tol)
        assert b["mu"] == pytest.approx(a["mu"], rel=tol)
    held = [solve("fe2d", None, entry=e)["h_center"] for e in (40.0, 80.0)]
    assert abs(held[1] / held[0] - 1.0) > 1e-3


def test_a_longer_span_lifts_the_web_towards_the_far_field_limit():
    """The film lifts the web over the wrap; the shorter the span, the more the spans pull
    it back: held at the zones' ends (66 mm) < a 0.3 m span < a 1 m span (fe2d: 10.242,
    10.271, 10.276 um; free ends 10.279)."""
    h = [solve("fe2d", s)["h_center"] for s in (None, 0.3, 1.0)]
    assert h[0] < h[1] < h[2]
    assert h[2] / h[0] - 1.0 == pytest.approx(0.0034, abs=5e-4)


def test_picard_holds_the_web_through_its_spans_as_newton_does():
    """With the ends unknowns, Picard's frozen operator barely resists a uniform lift of the
    web; without the lift correction (webfem.fem.picard.lift_correction) it took 394
    iterations at 0.3 m (100 held) and diverged at 1 m and 3 m. With it: 44-45 each."""
    held = solve("fe1d", None, method="picard")["iterations"]
    for span in (0.3, 1.0, 3.0):
        newton, picard = solve("fe1d", span), solve("fe1d", span, method="picard")
        assert picard["converged"] and picard["iterations"] <= held
        for key in ("h_center", "h_min", "mu", "contact_share"):
            assert picard[key] == pytest.approx(newton[key], rel=1e-6)


def test_the_lift_correction_removes_the_frozen_operators_overshoot():
    """At the answer (base fe1d, 1 m), a plain Picard sweep multiplies an error along the
    lift mode by 189; the corrected sweep amplifies no error by more than 0.77 (the next
    mode's, which the correction leaves alone)."""
    case = BASE.updated({"wrap.span": 1.0})
    r = webfem.solve(case, model="fe1d", adapt=0, estimate=False)
    problem, u, prm = r.state("problem"), r.state("state"), FoilParameters.from_case(case)
    free = problem.free
    J = problem.jacobian(u, prm).tocsr()[free][:, free]
    A = problem.jacobian(u, prm, newton=False).tocsr()[free][:, free].tocsc()
    solve_A = splu(A).solve
    lift = problem.lift[free]
    plain, corrected = (np.empty((free.size, free.size)) for _ in range(2))
    for i in range(free.size):
        e = np.zeros(free.size)
        e[i] = 1.0
        F = J @ e                              # the residual of an error e, linearised
        step = solve_A(F)
        plain[:, i] = e - step
        corrected[:, i] = e - step + lift_correction(J, solve_A, F, step, lift)
    assert np.max(np.abs(np.linalg.eigvals(plain))) > 100.0
    assert np.max(np.abs(np.linalg.eigvals(corrected))) < 0.8


def test_a_span_inside_the_zones_is_refused_by_name():
    with pytest.raises(InputError, match=r"wrap\.span = 0\.05 m is out of range.*> 0\.06"):
        solve("fe1d", 0.05)
    with pytest.raises(InputError, match=r"wrap\.span"):
        Case().updated({"wrap.span": -1.0})


def test_a_stiff_web_held_at_its_span_does_not_warn():
    board = webfem.load_case(webfem.bundled.find_case("board"))
    warned = webfem.solve(board, model="fe1d")["warnings"]
    assert any("bending length" in w for w in warned)
    spanned = webfem.solve(board.updated({"wrap.span": 1.0}), model="fe1d")
    assert spanned["converged"]
    assert not any("bending length" in w for w in spanned["warnings"])
