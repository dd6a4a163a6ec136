"""What a continued point shares with the previous one's set-up (issue 23): the sparsity
pattern and factorisation plan of a mesh with the same cells and DOFs (a moved mesh), and a
problem's last read-out. Each is a pure cache: the numbers are those computed afresh, to the
bit."""

import numpy as np

from webfem.fem import fast, newton
from webfem.fem.film_problem import FoilBearing2D
from webfem.fem.scaling import FoilParameters
from webfem.models import continued
from webfem.models.readout import read_out
from webfem.models.options import FE2DOptions

from conftest import BASE


def _problems():
    X = np.concatenate([np.linspace(-9.0, -5.0, 5), np.linspace(-4.0, 4.0, 9),
                        np.linspace(5.0, 9.0, 5)])
    Z = np.linspace(0.0, 3.0, 4)
    moved = continued.moved_nodes(X, 10.0, 8.0)
    return FoilBearing2D(X, Z), FoilBearing2D(moved, Z * 0.9)


def _prm(case):
    o = FE2DOptions()
    return FoilParameters.from_case(case, o.compressible, o.contact, o.floor)


def test_moved_mesh_shares_pattern_and_plan():
    """A moved mesh's Jacobian has the previous mesh's index arrays (one pattern) and its
    factorisation the same plan; the solution equals one with every cache emptied."""
    fast.PATTERNS.clear()
    a, b = _problems()
    pa, pb = a.system.pattern, b.system.pattern
    assert pa is pb
    u = np.linspace(0.1, 1.0, b.n_dofs)
    u[b.fixed] = 0.0
    prm = _prm(BASE)
    J = b.jacobian(u, prm)
    rhs = np.linspace(-1.0, 1.0, b.free.size)
    kept = b.solver.solve(J, b.free, rhs)
    assert len(pb.plans) == 1
    again = a.solver.solve(a.jacobian(u, prm), a.free, rhs)   # the same plan, a's values
    assert len(pb.plans) == 1
    fast.PATTERNS.clear()
    newton.ORDERINGS.clear()
    _, fresh = _problems()
    Jf = fresh.jacobian(u, prm)
    assert Jf.indices is not J.indices
    assert np.array_equal(Jf.toarray(), J.toarray())
    assert np.array_equal(fresh.solver.solve(Jf, fresh.free, rhs), kept)
    assert np.all(np.isfinite(again))


def test_read_out_kept_for_the_same_state():
    """The same (case, problem, state, parameters) reads the kept answer; another state a new
    one, equal to a read-out on a problem that kept nothing."""
    prm = _prm(BASE)
    e = 0.5 * prm.beta
    X = np.concatenate([[-e - 5.0], np.linspace(-e, e, 21), [e + 5.0]])
    p = FoilBearing2D(X, np.linspace(0.0, BASE.lam, 4))
    u = np.zeros(p.n_dofs)
    u[p.iWv] = 2.0
    first = read_out(BASE, p, u, prm)
    assert read_out(BASE, p, u.copy(), prm) is first
    v = u.copy()
    v[p.iWv] = 2.5
    other = read_out(BASE, p, v, prm)
    assert other is not first
    q = FoilBearing2D(X, np.linspace(0.0, BASE.lam, 4))
    fresh = read_out(BASE, q, v, prm)
    assert fresh.h_center == other.h_center and fresh.mu == other.mu
    assert np.array_equal(fresh.h, other.h)
    # a trial state read with keep=False (balanced stopping's corrected state, read in
    # full) leaves the kept read-out as it was
    trial = read_out(BASE, p, u, prm, keep=False)
    assert trial is not other and trial.mu == first.mu
    assert read_out(BASE, p, v.copy(), prm) is other
