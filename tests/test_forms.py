"""Each weak form declared once (webfem.fem.forms), both assemblies generated from it: the
vectorised one (webfem.fem.weakform.FastForm) against scikit-fem's forms (and, for the blocks
that cross from the 2-D film to the 1-D web, the transfer matrices).

Residual and Jacobian of the 1-D (P1 and P2 pressure, Hermite web) and 2-D (Q1 and Q2 film,
Hermite web; smooth, grooved full width and grooved periodic cell) systems at a state that
is not a solution, with contact, compressibility, permeation (with the sink's own
compressibility), slip and bending all non-zero, exact Newton and Picard's
frozen-coefficient operator, every declared block and term on.
"""

import numpy as np
import pytest

from webfem.fem import fast, forms
from webfem.fem.mesh import graded_nodes
from webfem.fem.scaling import FoilParameters
from webfem.fem.transfer import width_nodes
from webfem.fem.weakform import coefficient
from webfem.models.fe1d import FoilBearing1D
from webfem.models.fe2d import FoilBearing2D

PRM = FoilParameters(beta=12.0, K=0.08, d=0.4, ds=0.2, slip=0.07, Dn=0.03, c=0.6, S=0.12,
                     contact=1.0, floor=0.02, H_c=0.3)
TOL = 1e-12




def _relative(a, b):
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def _line_state(p):
    rng = np.random.default_rng(1)
    u = p.initial_guess(PRM)
    u[p.iP] += 0.3 * np.sin(p.basis.doflocs[0][p.iP])
    u[p.iW] *= 1.0 + 0.2 * rng.random(p.iW.size)
    u[p.fixed] = 0.0
    return u


@pytest.fixture(scope="module", params=[1, 2])
def line(request):
    p = FoilBearing1D(graded_nodes(PRM.beta, 6.0, level=0), order=request.param)
    return p, _line_state(p)


def test_line_residual(line):
    p, u = line
    fast_F, ref_F = p.residual(u, PRM), p.system.reference_residual(u, PRM)
    assert np.max(np.abs(ref_F)) > 1e-3            # the state is not a solution
    assert _relative(fast_F, ref_F) < TOL


@pytest.mark.parametrize("newton", [True, False])
def test_line_jacobian(line, newton):
    p, u = line
    A = p.jacobian(u, PRM, newton).toarray()
    B = p.system.reference_jacobian(u, PRM, newton).toarray()
    assert _relative(A, B) < TOL


def test_line_terms_are_on():
    """Each effect changes the residual: a test of the fast path against the forms with one
    of them silently dropped by both would pass otherwise."""
    p = FoilBearing1D(graded_nodes(PRM.beta, 6.0, level=0), order=1)
    u = _line_state(p)
    base = p.residual(u, PRM)
    for name in ("K", "d", "ds", "slip", "Dn", "c"):
        off = p.residual(u, FoilParameters(**{**PRM.__dict__, name: 0.0}))
        assert np.max(np.abs(off - base)) > 1e-6, name


@pytest.fixture(scope="module", params=[1, 2])
def film(request):
    X = graded_nodes(PRM.beta, 6.0, level=0)
    p1 = FoilBearing1D(X)
    u1 = _line_state(p1)
    p = FoilBearing2D(X, width_nodes(3.0), order=request.param)
    u = p.start_from_line(p1, u1, PRM)
    loc = p.fbasis.doflocs
    u[:p.nP] *= 1.0 + 0.3 * np.cos(loc[0]) * np.sin(loc[1])
    u[p.fixed] = 0.0
    return p, u


def test_film_residual(film):
    p, u = film
    fast_F, ref_F = p.residual(u, PRM), p.system.reference_residual(u, PRM)
    assert np.max(np.abs(ref_F)) > 1e-3
    assert _relative(fast_F[:p.nP], ref_F[:p.nP]) < TOL
    assert _relative(fast_F[p.nP:], ref_F[p.nP:]) < TOL


@pytest.mark.parametrize("newton", [True, False])
def test_film_jacobian(film, newton):
    p, u = film
    A = p.jacobian(u, PRM, newton).toarray()
    B = p.system.reference_jacobian(u, PRM, newton).toarray()
    assert _relative(A, B) < TOL


def test_every_declared_block_and_term_is_assembled_and_matters():
    """Each term and block of every declaration contributes on the systems above: dropping
    it from the generated assembly changes the result (so the comparisons above cover every
    one of them)."""
    from webfem.fem.weakform import FastForm, Part, WeakForm

    X = graded_nodes(PRM.beta, 6.0, level=0)
    p1 = FoilBearing1D(X, order=2)
    u1 = _line_state(p1)
    p2 = FoilBearing2D(X, width_nodes(3.0), order=2)
    u2 = p2.start_from_line(p1, u1, PRM)
    seen = set()
    for p, u in ((p1, u1), (p2, u2)):
        sys_ = p.system
        values = sys_.values(u, PRM)
        full_F, full_J = sys_.fast.residual(values), sys_.fast.jacobian(values).toarray()
        for k, part in enumerate(sys_.fast.parts):
            for form in part.forms:
                for item in form.terms + form.blocks:
                    if item.op == "dz" and "dz" not in part.spaces[item.field].ops:
                        continue
                    kept = WeakForm(form.name, form.fields,
                                    tuple(t for t in form.terms if t is not item),
                                    tuple(b for b in form.blocks if b is not item))
                    parts = [Part(tuple(kept if f is form else f for f in q.forms), q.spaces,
                                  q.dx) if i == k else q
                             for i, q in enumerate(sys_.fast.parts)]
                    other = FastForm(parts, sys_.fast.n)
                    changed = (np.max(np.abs(other.residual(values) - full_F)) > 0
                               if item in form.terms else
                               np.max(np.abs(other.jacobian(values).toarray() - full_J)) > 0)
                    assert changed, (form.name, item)
                    seen.add((form.name, item))
    declared = {(f.name, i) for f in (forms.FILM, forms.SINK, forms.WEB, forms.COUPLING)
                for i in f.terms + f.blocks}
    assert declared <= seen, declared - seen


def test_pattern_is_shared():
    """Every Jacobian of a mesh has the same index arrays (the solver caches on them)."""
    p = FoilBearing1D(graded_nodes(PRM.beta, 6.0, level=0), order=2)
    u = _line_state(p)
    A, B = p.jacobian(u, PRM), p.jacobian(2.0 * u, PRM)
    assert A.indices is B.indices and A.indptr is B.indptr
    assert A.has_canonical_format


@pytest.mark.parametrize("n, top", [(0, 5), (1, 5), (1000, 7), (200_000, 10**9), (50, 2**60)])
def test_unique_inverse_is_numpys(n, top):
    """The Pattern's unique by a stable sort returns np.unique's keys and inverse exactly."""
    keys = np.random.default_rng(n).integers(0, top, n, dtype=np.int64)
    got, inv = fast._unique_inverse(keys)
    want, want_inv = np.unique(keys, return_inverse=True)
    assert np.array_equal(got, want) and np.array_equal(inv, want_inv.ravel())
    assert np.array_equal(got[inv], keys)



@pytest.fixture(scope="module", params=["full", "cell"])
def grooved(request):
    """A grooved roller (gap H_web + Delta(Z), contact on the lands): the full width with
    its edge lands, or the periodic cell."""
    from webfem.fem.grooves import GroovePattern, groove_nodes

    X = graded_nodes(PRM.beta, 6.0, level=0)
    p1 = FoilBearing1D(X)
    u1 = _line_state(p1)
    g = GroovePattern(pitch=1.0, width=0.3, depth=0.7)
    cell = request.param == "cell"
    p = FoilBearing2D(X, groove_nodes(g, 0.0, 0.5 if cell else 3.0), grooves=g,
                      web_edges=not cell)
    u = p.start_from_line(p1, u1, PRM)
    loc = p.fbasis.doflocs
    u[:p.nP] *= 1.0 + 0.3 * np.cos(loc[0]) * np.sin(3.0 * loc[1] + 0.2)
    u[p.fixed] = 0.0
    return p, u


@pytest.mark.parametrize("newton", [True, False])
def test_grooved_film(grooved, newton):
    p, u = grooved
    prm = FoilParameters(**{**PRM.__dict__, "land": 0.7})
    assert np.any(p.groove_q > 0) and np.any(p.groove_q == 0)
    fast_F, ref_F = p.residual(u, prm), p.system.reference_residual(u, prm)
    assert _relative(fast_F, ref_F) < TOL
    A = p.jacobian(u, prm, newton).toarray()
    B = p.system.reference_jacobian(u, prm, newton).toarray()
    assert _relative(A, B) < TOL
    # the grooves and the land fraction are in both
    smooth = FoilBearing2D(p.X, p.Z, web_edges=p.web_edges)
    assert _relative(smooth.residual(u, prm), fast_F) > 1e-6
    assert _relative(p.residual(u, PRM), fast_F) > 1e-6


def test_film_fields_are_scikit_fems(film):
    """The 2-D problem's gap and width-averaged pressure at points (web probes kept per point
    set, the average kept for the last state) are the web's Hermite functions at the points
    (:class:`~webfem.fem.hermite.LineProbes`, a fresh one: the same bits) of scikit-fem's
    interpolate's average, and scikit-fem's probes within their own error (1e-8 relative:
    its global monomials), for a second state too; the kept values cannot be changed from
    outside."""
    import scipy.sparse.linalg as spla
    from skfem import BilinearForm

    from webfem.fem import forms
    from webfem.fem.hermite import LineProbes

    p, u = film
    X = np.concatenate([p.X, 0.5 * (p.X[1:] + p.X[:-1])])
    probes = p.wbasis.probes(X[None, :])
    mass = spla.splu(BilinearForm(lambda a, b, w: a * b).assemble(p.wbasis).tocsc())
    for v in (u, np.where(np.arange(u.size) < p.nP, 0.5 * u, u)):
        w = v[p.nP:]
        gap = p.gap(v, PRM, X)
        assert np.array_equal(gap, LineProbes(p.wbasis)(X, w) + forms.departure(X, PRM.beta))
        np.testing.assert_allclose(gap, probes @ w + forms.departure(X, PRM.beta), rtol=0.0,
                                   atol=1e-7 * np.max(np.abs(w)))
        Pq = np.asarray(p.fbasis.interpolate(v[:p.nP])).ravel()
        avg = mass.solve(p.T["M"].T @ (p.T["dx"] * Pq) / p.width)
        got = p.pressure(v, X)
        assert np.array_equal(got, LineProbes(p.wbasis)(X, avg))
        np.testing.assert_allclose(got, probes @ avg, rtol=0.0, atol=1e-7 * np.max(np.abs(avg)))
        p.width_average(v)[:] = 0.0
        assert np.array_equal(p.pressure(v, X), got)


@pytest.mark.parametrize("stacked", [False, True])
def test_contraction_is_bilinear(stacked):
    """The contraction with the test side laid out once per mesh is BasisData.bilinear's
    einsum (the same batched product: equal to rounding, in practice bit for bit)."""
    p = FoilBearing1D(graded_nodes(PRM.beta, 6.0, level=0), order=2)
    b = p.system.b
    q, gq, v = b.phi_c[0], b.grad_c[0][:, 0], b.phi_c[1]
    rng = np.random.default_rng(5)
    test = np.stack([gq, q]) if stacked else v
    trial = rng.standard_normal((2,) + q.shape if stacked else v.shape)
    got = fast.contract_layout(fast.test_layout(test), trial)
    np.testing.assert_allclose(got, fast.BasisData.bilinear(test, trial), rtol=1e-14,
                               atol=1e-14 * np.max(np.abs(got)))


def test_line_coefficients_kept_for_the_last_state_only():
    """The coefficients kept between a residual and a Jacobian at the same state are used
    only for that state: a changed state (even changed in place) or parameters recompute."""
    X = graded_nodes(PRM.beta, 6.0, level=0)
    p, fresh = FoilBearing1D(X, order=2), FoilBearing1D(X, order=2)
    u = _line_state(p)
    p.residual(u, PRM)
    np.testing.assert_array_equal(p.jacobian(u, PRM).toarray(), fresh.jacobian(u, PRM).toarray())
    u[p.iW] *= 1.1                       # in place: the same array object, a new state
    np.testing.assert_array_equal(p.residual(u, PRM), fresh.residual(u, PRM))
    other = PRM.homotopy(0.5)
    np.testing.assert_array_equal(p.jacobian(u, other).toarray(),
                                  fresh.jacobian(u, other).toarray())


def test_a_released_problem_assembles_and_solves_as_before(grooved):
    """:meth:`FoilBearing2D.release` drops the assembly and the factorisation plans (a mesh
    kept for its nodes while a finer one is solved) and keeps the web's mass factorisation
    (the web's size; the result reads the released answer's pressure); used again, the
    problem builds them anew: the same residual, Jacobian, solve and width average, to the
    bit."""
    p, u = grooved
    prm = FoilParameters(**{**PRM.__dict__, "land": 0.7})
    J0, R0, A0 = p.jacobian(u, prm), p.residual(u, prm), p.width_average(u)
    x0 = p.solver.solve(J0, p.free, R0[p.free])
    p.release()
    assert p._system is None and p._solver is None and p._mass is not None
    J1, R1 = p.jacobian(u, prm), p.residual(u, prm)
    assert np.array_equal(R0, R1) and (J0 != J1).nnz == 0
    assert np.array_equal(x0, p.solver.solve(J1, p.free, R1[p.free]))
    assert np.array_equal(A0, p.width_average(u))


def test_film_basis_data_is_held_once_with_the_same_bits(film):
    """The 2-D film's basis data held once (the values a broadcast of the reference
    element's, scikit-fem's gradients views of BasisData's, the p-w test layout a view of
    the p-p one, the trial sides summed into the product's operand) gives every block, the
    residual and the interpolated state bit for bit as the contiguous copies and the
    per-operator stacks do (the assembly before these were shared)."""
    p, u = film
    system = p.system
    f, ff = system.f, system.fast
    assert f.phi_c[0].strides[1] == 0                          # one element's values
    for i in range(p.fbasis.Nbfun):
        assert np.shares_memory(p.fbasis.basis[i][0].grad, f.grad_c[0])
    film_layouts = ff._layouts[0]
    assert np.shares_memory(film_layouts["p", "w"][1], film_layouts["p", "p"][1])
    # interpolation and the residual's contraction over a broadcast and a contiguous copy
    phi = np.ascontiguousarray(f.phi_c[0])
    coef = u[f.dofs]
    assert np.array_equal(np.einsum("ie,ieq->eq", coef, f.phi_c[0]),
                          np.einsum("ie,ieq->eq", coef, phi))
    values = system.values(u, PRM)
    c = values[0]["sink"] * f.dx
    assert np.array_equal(np.einsum("ieq,eq->ie", f.phi_c[0], c),
                          np.einsum("ieq,eq->ie", phi, c))
    # every block as the per-operator assembly computes it: stacked trial sides, layouts
    # built afresh from contiguous copies, fast.contract_layout
    got = ff.blocks(values)
    k = 0
    for part, groups, vals in zip(ff.parts, ff._groups, values):
        for (fi, fj), group in groups.items():
            ops = list(dict.fromkeys(b.op for b in group))
            trial = dict.fromkeys(ops)
            total = None
            for b in group:
                cb = coefficient(vals, b.coef)
                if np.ndim(cb) == 0:
                    piece = float(cb) * fast.contract_layout(
                        fast.test_layout(np.ascontiguousarray(part.spaces[fi].ops[b.op])),
                        part.spaces[fj].ops[b.trial_op] * part.dx)
                    total = piece if total is None else total + piece
                    continue
                term = np.ascontiguousarray(part.spaces[fj].ops[b.trial_op]) * (cb * part.dx)
                trial[b.op] = term if trial[b.op] is None else trial[b.op] + term
            used = [o for o in ops if trial[o] is not None]
            if used:
                lay = fast.test_layout(np.stack([np.ascontiguousarray(part.spaces[fi].ops[o])
                                                 for o in used]))
                piece = fast.contract_layout(lay, np.stack([trial[o] for o in used]))
                total = piece if total is None else total + piece
            assert np.array_equal(got[k], total), (fi, fj)
            k += 1
    assert k == len(got)


def test_rounding_floor_on_the_whole_jacobian_is_the_reduced_ones(film):
    """newton.rounding_floor sums |J| |u| over the whole film + web Jacobian with |u| zero
    off the free unknowns: the same bits as on the reduced matrix (also with a state whose
    fixed entries are not zero; a matrix not in canonical form takes the reduced path)."""
    import scipy.sparse as sp

    from webfem.fem import newton as nw

    p, u = film
    J = p.jacobian(u, PRM)
    v = u.copy()
    v[p.fixed] = 7.0
    for w in (u, v):
        A = abs(J[p.free][:, p.free])
        want = float(np.finfo(float).eps * nw.norm2(A @ np.abs(w[p.free])))
        assert nw.rounding_floor(J, w, p.free) == want > 0.0
    dup = sp.csr_matrix((np.append(J.data, 1.0), np.append(J.indices, J.indices[0]),
                         np.append(J.indptr[:-1], J.nnz + 1)), shape=J.shape)
    assert not dup.has_canonical_format
    assert np.isfinite(nw.rounding_floor(dup, u, p.free))


@pytest.mark.parametrize("newton", [True, False])
def test_leading_blocks_in_one_product_are_the_block_by_block_bits(film, newton):
    """The film's leading blocks (each test operator's first, with that operator on the
    trial side too) filled in one product (FastForm._lead_terms) give the element matrices
    of the block-by-block fill, bit for bit."""
    p, u = film
    fast_form = p.system.fast
    values = p.system.values(u, PRM, newton)
    assert any(leads for leads in fast_form._leads[0].values())      # the path is taken
    with_leads = fast_form.blocks(values)
    kept = fast_form._leads
    fast_form._leads = [{} for _ in kept]
    try:
        one_by_one = fast_form.blocks(values)
    finally:
        fast_form._leads = kept
    assert len(with_leads) == len(one_by_one)
    for a, b in zip(with_leads, one_by_one):
        np.testing.assert_array_equal(a, b)


def test_residual_coefficients_first_then_the_jacobians_are_the_same_bits(film):
    """A residual's coefficients computed alone, then the Jacobian's from their parts (Newton's
    and Picard's at one state), are film_coefficients' all at once, bit for bit; a residual
    after a Jacobian at the same state is the one before it."""
    p, u = film
    fresh = FoilBearing2D(p.X, p.Z, order=p.order)
    F = p.residual(u, PRM)
    for newton in (True, False):
        J = p.system.fast.jacobian(p.system.values(u, PRM, newton)).toarray()
        full = fresh.system._film_values(*_film_state(fresh, u), PRM, newton)
        np.testing.assert_array_equal(J, fresh.system.fast.jacobian(
            [full, fresh.system.values(u, PRM, newton)[1]]).toarray())
    np.testing.assert_array_equal(F, p.residual(u, PRM))
    np.testing.assert_array_equal(F, fresh.residual(u, PRM))


def _film_state(p, u):
    P, gP = p.system.f.interpolate(u[:p.nP])
    return P, gP[0], gP[1], u[p.nP:]
