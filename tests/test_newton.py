"""The generic Newton solver: chord steps near convergence, the rounding-floor acceptance, and
the grooved case that needed it."""

import numpy as np
import pytest
import scipy.sparse as sp

from webfem.fem import newton as nw


def _problem():
    """A nonlinear 40-unknown system with a known root u = 1 (a diffusion-reaction chain)."""
    n = 40
    L = sp.diags([-1.0, 2.5, -1.0], [-1, 0, 1], shape=(n, n), format="csr")
    b = L @ np.ones(n) + np.ones(n) ** 3

    def F(u):
        return L @ u + u**3 - b

    calls = {"J": 0}

    def J(u):
        calls["J"] += 1
        return (L + sp.diags(3.0 * u**2)).tocsr()

    return F, J, calls, n


@pytest.mark.parametrize("tol, saved, more", [(1e-8, 1, 0), (1e-10, 1, 0), (1e-12, 1, 1)])
def test_chord_steps_save_factorisations_at_the_same_tolerance(tol, saved, more):
    """Residuals 1.1e-3 -> 4.5e-8 -> 0: the chord is tried when the last decrease predicts it
    reaches the tolerance (4.5e-8^2 / 1.1e-3 = 1.8e-12: for 1e-8 and 1e-10) or when that
    decrease was at least :data:`~webfem.fem.newton.CHORD_TRY` times and the chord step
    lowers the residual as many times (for 1e-12: after Newton's 1.1e-3 -> 4.5e-8, chord
    steps to 3.8e-12 and 0: one factorisation fewer for one iteration more)."""
    F, J, calls, n = _problem()
    u0 = np.full(n, 3.0)
    plain = nw.newton(F, J, u0, tol=tol, chord=False)
    j_plain, calls["J"] = calls["J"], 0
    fast = nw.newton(F, J, u0, tol=tol)
    j_fast = calls["J"]
    assert plain.converged and fast.converged
    assert fast.residual <= tol and plain.residual <= tol
    assert np.max(np.abs(fast.u - 1.0)) < 1e-6
    # the last factorisation of the plain solve is replaced by a chord step
    assert j_fast == j_plain - saved
    assert fast.iterations == plain.iterations + more


def test_a_chord_step_that_does_not_pay_is_replaced_by_a_newton_step(monkeypatch):
    """A chord trial that fails (here: forced to a non-finite residual) costs nothing but
    the trial: the iteration takes the Newton step, as without chord steps."""
    F, J, calls, n = _problem()
    plain = nw.newton(F, J, np.full(n, 3.0), tol=1e-10, chord=False)
    j_plain, calls["J"] = calls["J"], 0
    tried = []

    def useless(F, solve, u, r, free):
        tried.append(1)
        return u.copy(), r, np.inf
    monkeypatch.setattr(nw, "_chord_step", useless)
    out = nw.newton(F, J, np.full(n, 3.0), tol=1e-10)
    assert tried and out.converged and out.residual <= 1e-10
    assert calls["J"] == j_plain and np.array_equal(out.u, plain.u)


def _noisy(level, n=50):
    """F with a rounding floor: a root near u = 2 plus a deterministic perturbation of norm
    about 0.58 ``level`` that no step can remove (it changes with every bit of u)."""
    def F(u):
        seed = int(np.frombuffer(np.asarray(u, float).tobytes(), np.uint32).sum()) % 2**32
        noise = np.random.default_rng(seed).uniform(-1.0, 1.0, u.size) / np.sqrt(u.size)
        return (u**3 - 8.0) + level * noise

    def J(u):
        return sp.diags(3.0 * u**2).tocsr()
    return F, J


def test_a_residual_at_its_rounding_floor_is_converged():
    F, J = _noisy(3e-9)
    out = nw.newton(F, J, np.full(50, 1.5), tol=1e-9, step_tol=1e-10)
    assert out.converged, out.reason
    assert "rounding floor" in out.reason and out.residual <= nw.FLOOR_FACTOR * 1e-9
    assert np.max(np.abs(out.u - 2.0)) < 1e-9


def test_a_residual_far_above_the_tolerance_is_never_accepted_as_a_floor():
    F, J = _noisy(1e-6)          # 1000 x the tolerance: not a rounding floor
    out = nw.newton(F, J, np.full(50, 1.5), tol=1e-9, step_tol=1e-10, max_iter=60)
    assert not out.converged
    assert out.residual > nw.FLOOR_FACTOR * 1e-9


def _stiff(scale, n=50):
    """u^3 = 8 with every row scaled by ``scale``: a true rounding floor eps |J| |u| of about
    eps 12 scale sqrt(n) (a stiff web's bending rows), and noise at about a tenth of it."""
    F0, J0 = _noisy(np.finfo(float).eps * 12.0 * scale * 0.1, n)
    return (lambda u: scale * (u**3 - 8.0) + (F0(u) - (u**3 - 8.0)),
            lambda u: (scale * J0(u)).tocsr())


def test_a_floor_above_the_default_tolerance_is_converged_and_says_so():
    """Board's bending (Dn in the hundreds) put the residual's rounding floor, eps |J| |u|,
    at 4e-7, far above the absolute tolerance 1e-9: the iterate no longer moved and was
    called a failure. At the default tolerance it is converged, and the reason names both
    figures; a stricter tolerance asked for is still taken strictly."""
    F, J = _stiff(1e8)
    u0 = np.full(50, 1.5)
    out = nw.newton(F, J, u0, tol=1e-9, step_tol=1e-10, max_iter=60)
    floor = nw.rounding_floor(J(out.u), out.u, np.arange(50))
    assert floor > 1e3 * 1e-9
    assert out.converged and "below what double precision resolves" in out.reason
    assert 1e-9 < out.residual <= nw.FLOOR_FACTOR * floor
    assert np.max(np.abs(out.u - 2.0)) < 1e-12
    strict = nw.newton(F, J, u0, tol=1e-12, step_tol=1e-10, max_iter=60)
    assert not strict.converged and "stalls" in strict.reason


def test_fast_grooved_design_at_high_speed_converges():
    """1.27 mm pitch, 95 % land, 0.25 mm deep, 51.8 m/s: the traction-loss search of the
    groove map stopped here with 'line search failed ... residual 1.243e-09' (corrections
    ~3e-15) on the solver without chord steps and the rounding-floor acceptance."""
    from webfem import load_case
    from webfem.groove_sizing import _grooved
    from webfem.models import fe2d

    case = _grooved(load_case("cases/base.toml"), 1.27e-3, 0.95, 0.25e-3)
    r = fe2d.solve(case.updated({"roller.speed": 51.8}))
    assert r["converged"] and r["h_min"] > 0.0


def test_a_kept_ordering_gives_the_same_solution_to_the_bit():
    """The orderings are kept by the pattern's bytes (:data:`webfem.fem.newton.ORDERINGS`):
    a new matrix object of the same pattern reuses one, and its solution equals, to the
    bit, that of an ordering computed anew."""
    F, J, calls, n = _problem()
    A = J(np.linspace(0.5, 2.0, n))
    b = np.linspace(-1.0, 1.0, n)
    free = np.arange(1, n - 1)
    nw.ORDERINGS.clear()
    fresh = nw.PatternSolver(scaled=True).solve(A, free, b[free])
    assert len(nw.ORDERINGS) == 1
    again = nw.PatternSolver(scaled=True).solve(A.copy(), free, b[free])   # kept
    assert len(nw.ORDERINGS) == 1
    assert np.array_equal(fresh, again)
    nw.ORDERINGS.clear()
    assert np.array_equal(nw.PatternSolver(scaled=True).solve(A.copy(), free, b[free]), fresh)


def test_chord_steps_do_not_spend_the_newton_budget():
    """max_iter bounds the Newton steps (the factorisations); chord steps come on top: six
    Newton steps and two chord steps converge within max_iter = 7 (a budget that counted
    the chord steps would have stopped one short)."""
    F, J, calls, n = _problem()
    fast = nw.newton(F, J, np.full(n, 3.0), tol=1e-12, max_iter=7)
    assert fast.converged and fast.iterations == 8 and calls["J"] == 6


def test_a_jacobian_with_nan_entries_ends_the_solve_without_factorising_it(capfd):
    """A non-finite Jacobian at a finite residual (a stiff web's extreme iterate) is a failed
    step, said so; factorised it failed as singular after SuperLU's BLAS calls printed
    "illegal value" lines to stderr."""
    def F(u):
        return u - 1.0

    def J(u):
        return sp.csr_matrix(np.array([[np.nan, 0.0], [0.0, 1.0]]))

    out = nw.newton(F, J, np.zeros(2), tol=1e-12, max_iter=5)
    assert not out.converged and out.reason == "Jacobian not finite"
    assert "illegal" not in capfd.readouterr().err


def _soft(scale=1e8, soft=1e-12, n=50):
    """:func:`_stiff` with the first unknown a soft mode (row 0: ``soft`` scale (u0 - 2)):
    the floor's noise in its row moves it by noise / (soft scale), about 1e-3, far above
    :data:`FLOOR_STEP` (a stiff web held through long spans: webfem/fem/ends.py)."""
    F, J = _stiff(scale, n)

    def Fs(u):
        r = F(u)
        r[0] += scale * (soft * (u[0] - 2.0) - (u[0]**3 - 8.0))
        return r

    def Js(u):
        A = J(u).tolil()
        A[0, 0] = scale * soft
        return A.tocsr()
    return Fs, Js


def test_a_correction_that_is_the_floors_noise_is_converged_where_asked():
    """A soft mode amplifies the rounding floor's noise into corrections no step along
    which lowers the residual: with ``noise`` the iterate is converged (its correction as
    large as random residuals' of its size), without it the line search fails."""
    F, J = _soft()
    u0 = np.full(50, 1.5)
    strict = nw.newton(F, J, u0, tol=1e-9, step_tol=1e-10, max_iter=60)
    assert not strict.converged
    out = nw.newton(F, J, u0, tol=1e-9, step_tol=1e-10, max_iter=60, noise=True)
    assert out.converged and "random residual" in out.reason
    floor = nw.rounding_floor(J(out.u), out.u, np.arange(50))
    assert out.residual <= nw.FLOOR_FACTOR * floor
    assert np.max(np.abs(out.u[1:] - 2.0)) < 1e-12
    assert 1e-6 < abs(out.u[0] - 2.0) < 1e-1       # the soft mode: as precise as it gets


def test_noise_accepts_no_residual_above_its_floor():
    F, J = _noisy(1e-6)          # 1000 x the tolerance: not a rounding floor
    out = nw.newton(F, J, np.full(50, 1.5), tol=1e-9, step_tol=1e-10, max_iter=60,
                    noise=True)
    assert not out.converged


def test_scaled_solve_is_the_diagonally_scaled_factorisation_to_the_bit():
    """The scaled factorisation's scale is |diag|^(-1/2) of the ordered matrix (1 where the
    diagonal is 0 or not stored), read from the plan's diagonal places: the same solution,
    bit for bit, as scaling by ``B.diagonal()`` and factorising that matrix."""
    rng = np.random.default_rng(5)
    n = 30
    M = sp.random(n, n, density=0.2, random_state=rng, format="coo")
    keep = M.row != M.col
    rows = np.concatenate([M.row[keep], np.arange(n)])
    cols = np.concatenate([M.col[keep], np.arange(n)])
    diag = rng.uniform(1.0, 1e6, n)
    diag[7] = 0.0                                       # a stored zero on the diagonal
    vals = np.concatenate([M.data[keep], diag])
    stored = rows != 3                                  # row 3: no diagonal entry at all
    stored |= rows != cols
    A = sp.csr_matrix((vals[stored], (rows[stored], cols[stored])), shape=(n, n))
    assert A[3, 3] == 0.0 and A.has_canonical_format
    free = np.arange(1, n - 1)
    b = rng.standard_normal(free.size)
    got = nw.PatternSolver(scaled=True).solve(A, free, b)
    plan = nw.PatternSolver._plan(A, free)
    (indices, indptr, shape), gather, inv = plan[2], plan[3], plan[4]
    B = sp.csc_matrix((A.data[gather], indices, indptr), shape=shape)
    d = np.abs(B.diagonal())
    s = np.where(d > 0.0, 1.0 / np.sqrt(np.where(d > 0.0, d, 1.0)), 1.0)
    cols = np.repeat(np.arange(n - 2), np.diff(B.indptr))
    B.data *= s[B.indices] * s[cols]
    lu = nw.PatternSolver._factor(B, "NATURAL")
    want = np.empty_like(b)
    want[inv] = s * lu.solve(s * b[inv])
    assert np.any(d == 0.0)
    assert np.array_equal(got, want)
    np.testing.assert_allclose(A[free][:, free] @ got, b, rtol=0, atol=1e-9)
