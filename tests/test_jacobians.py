"""Exact Jacobians and convergence orders with every effect of a real line on (issue 12).

The state: a moving, permeable web near landing (base case, U_r = 25 m/s, U_w = 5 m/s), whose
scaled parameters have permeation K, compressibility d, the isothermal sink's ds = d/2 != d,
first-order slip s, bending Dn and asperity contact all non-zero; the converged 1-D solution
perturbed by 1 % random noise, so no term vanishes by equilibrium.
"""

from dataclasses import replace

import numpy as np
import pytest

from webfem import Case
from webfem.fem.mesh import graded_nodes
from webfem.fem.scaling import FoilParameters
from webfem.fem.transfer import width_nodes
from webfem.models.fe1d import FoilBearing1D
from webfem.models.fe2d import FoilBearing2D
from webfem.models.options import FE2DOptions

from orders import GAP_1D, GAP_2D

CASE = Case().updated({"roller.speed": 25.0, "web.speed": 5.0})
PRM = FoilParameters.from_case(CASE)

#: Each effect's part of the residual is F(PRM) - F(PRM with the effect off): checking its
#: derivative apart keeps a small term (slip: s = 0.006) from hiding behind the large ones.
WITHOUT = {"slip": dict(slip=0.0), "isothermal sink": dict(ds=PRM.d),
           "permeation": dict(K=0.0), "compressibility": dict(d=0.0, ds=0.0),
           "bending": dict(Dn=0.0), "contact": dict(contact=0.0)}

#: Relative error of J v against the central difference (step 1e-4 along a direction of the
#: state's own size). Whole residual: measured <= 2e-10 (1-D and 2-D, both orders). Each
#: effect's part: measured <= 4e-7, the truncation error of the stiff contact exp(-H/S) and
#: the round-off of the difference of two assembled Jacobians. A missing or wrong term makes
#: its part's error O(1e-2) to O(1) (the Picard operator, below: 0.04 to 1).
TOL, TOL_PART, ZERO = 1e-8, 1e-5, 1e-10


def test_every_effect_is_on():
    p = PRM
    assert min(p.K, p.d, p.Dn, p.slip, p.contact, p.c) > 0.0
    assert p.ds == pytest.approx(0.5 * p.d, rel=1e-14)
    assert CASE.web_inertia > 0.0


def line_state(order, seed=0):
    # entry/exit zones of 10 units (the models' 40 would put gaps of 800 and conductances
    # H^3 ~ 5e8 at the ends, whose round-off swamps the small parts below)
    pb = FoilBearing1D(graded_nodes(PRM.beta, 10.0, level=0), order=order)
    u, info = pb.solve_newton(pb.initial_guess(PRM), PRM)
    assert info.converged, info.reason
    rng = np.random.default_rng(seed)
    v = u * (1.0 + 1e-2 * rng.standard_normal(u.size))
    v[pb.fixed] = 0.0
    return pb, u, v


def fd_errors(pb, u, blocks, seed=1, t=1e-4, newton=True, prm=PRM):
    """Relative error of J v against the central difference of the residual, for the whole
    residual and for each effect's part, along random directions in each block of DOFs."""
    PRM = prm
    rng = np.random.default_rng(seed)
    variants = {"all": None, **WITHOUT, **({"spans": dict(span=0.0)} if prm.span else {})}
    out = {}
    scale = {}
    for block, idx in blocks.items():
        sel = np.intersect1d(idx, pb.free)
        v = np.zeros_like(u)
        v[sel] = rng.standard_normal(sel.size) * np.maximum(np.abs(u[sel]), 1e-2)
        for name, off in variants.items():
            prms = [PRM] if off is None else [PRM, replace(PRM, **off)]
            Jv = sum(s * (pb.jacobian(u, p, newton) @ v) for s, p in zip((1, -1), prms))
            fd = sum(s * (pb.residual(u + t * v, p) - pb.residual(u - t * v, p))
                     for s, p in zip((1, -1), prms)) / (2 * t)
            if name == "all":
                scale[block] = np.linalg.norm(Jv)
            if np.linalg.norm(Jv) > 0.0:
                # relative to the larger of the two: a term J misses is an error of 1
                norm = max(np.linalg.norm(Jv), np.linalg.norm(fd))
            else:
                # a part that does not depend on this block (bending and contact on P, the
                # sink on W): J's part is exactly 0, the difference must be round-off, below
                # ZERO of the whole residual's J v (measured 1e-13; missing slip: 6e-7)
                norm = scale[block] * ZERO / TOL_PART
            out[block, name] = np.linalg.norm(fd - Jv) / norm
    return out


def assert_small(errors):
    bad = {k: e for k, e in errors.items() if not e < (TOL if k[1] == "all" else TOL_PART)}
    assert not bad, bad


@pytest.mark.parametrize("order", [1, 2], ids=["P1", "P2"])
def test_jacobian_1d(order):
    """FoilBearing1D: P1 (lumped sink) and P2 pressure with the Hermite web."""
    pb, _, v = line_state(order)
    errors = fd_errors(pb, v, {"P": pb.iP, "W": pb.iW_all, "both": np.arange(pb.n_dofs)})
    assert_small(errors)


@pytest.mark.parametrize("order", [1, 2], ids=["Q1", "Q2"])
def test_jacobian_2d(order):
    """FoilBearing2D (half width, level-0 mesh) at the perturbed 1-D state spread across the
    width."""
    p1, u1, _ = line_state(2)
    pb = FoilBearing2D(p1.X, width_nodes(CASE.lam, level=0, half=True), order=order)
    u = pb.start_from_line(p1, u1, PRM)
    rng = np.random.default_rng(2)
    u = u * (1.0 + 1e-2 * rng.standard_normal(u.size))
    u[pb.fixed] = 0.0
    errors = fd_errors(pb, u, {"P": np.arange(pb.nP), "W": np.arange(pb.nP, pb.n_dofs),
                               "both": np.arange(pb.n_dofs)})
    assert_small(errors)


#: The web held through spans beyond the domain (wrap.span): 30 units from each wrap edge,
#: 20 beyond the test's zones of 10.
PRM_SPAN = replace(PRM, span=30.0)


def test_jacobian_with_the_spans_springs():
    """The spans' springs on the end deflections (:mod:`webfem.fem.ends`), 1-D (P2) and
    2-D (Q2), the end deflections free: their part (the residual less that of the web held
    at the domain's ends) is differentiated exactly too."""
    p0, _, _ = line_state(2)
    pb = FoilBearing1D(p0.X, order=2, spans=True)
    u, info = pb.solve_newton(pb.initial_guess(PRM_SPAN), PRM_SPAN)
    assert info.converged, info.reason
    assert np.all(np.abs(u[pb.iW_ends]) > 0.0)        # the ends move: free, on springs
    v = u * (1.0 + 1e-2 * np.random.default_rng(3).standard_normal(u.size))
    v[pb.fixed] = 0.0
    assert_small(fd_errors(pb, v, {"W": pb.iW_all, "both": np.arange(pb.n_dofs)},
                           prm=PRM_SPAN))
    p2 = FoilBearing2D(pb.X, width_nodes(CASE.lam, level=0, half=True), order=2, spans=True)
    w = p2.start_from_line(pb, u, PRM_SPAN)
    w = w * (1.0 + 1e-2 * np.random.default_rng(4).standard_normal(w.size))
    w[p2.fixed] = 0.0
    assert_small(fd_errors(p2, w, {"W": np.arange(p2.nP, p2.n_dofs),
                                   "both": np.arange(p2.n_dofs)}, prm=PRM_SPAN))


@pytest.mark.parametrize("order", sorted(GAP_1D), ids=lambda o: f"P{o}")
def test_convergence_order_with_every_effect(order):
    """Central gap under uniform refinement of the graded mesh (levels 0-3, no adaptive
    refinement) with every effect on, against the Eshel-Elrod pins of tests/orders.py (P1 2,
    P2 4): the effects add smooth lower-order terms, not new singularities. Measured on a
    flying moving web (U_r = 30, U_w = 10 m/s): P1 1.99, 2.00; P2 3.90, 4.01."""
    case = Case().updated({"roller.speed": 30.0, "web.speed": 10.0})
    prm = FoilParameters.from_case(case)
    assert min(prm.K, prm.d, prm.Dn, prm.slip, prm.contact) > 0 and prm.ds != prm.d
    H = []
    for level in range(4):
        pb = FoilBearing1D(graded_nodes(prm.beta, 40.0, level=level), order=order)
        u, info = pb.solve_newton(pb.initial_guess(prm), prm)
        assert info.converged, info.reason
        H.append(float(pb.gap(u, prm, np.array([0.0]))[0]))
    d = np.abs(np.diff(H))
    orders = np.log2(d[:-1] / d[1:])
    assert orders[-1] == GAP_1D[order].approx(), orders



def test_convergence_order_2d_with_every_effect():
    """Central gap of the 2-D film (Q1, half width, lambda = 8.2) + web under refinement of
    both directions (levels 0-2, entry 20) with every effect on, against the Eshel-Elrod pin
    of tests/orders.py (Q1: 2). Measured 1.99 (about 2 s)."""
    case = Case().updated({"roller.speed": 30.0, "web.speed": 10.0})
    prm = FoilParameters.from_case(case)
    H = []
    for level in range(3):
        X = graded_nodes(prm.beta, 20.0, level=level)
        line = FoilBearing1D(X)
        u1, info = line.solve_newton(line.initial_guess(prm), prm)
        assert info.converged, info.reason
        pb = FoilBearing2D(X, width_nodes(case.lam, level=level, half=True), order=1)
        u, info = pb.solve_newton(pb.start_from_line(line, u1, prm), prm, FE2DOptions())
        assert info.converged, info.reason
        H.append(float(pb.gap(u, prm, np.array([0.0]))[0]))
    d = np.abs(np.diff(H))
    assert np.log2(d[0] / d[1]) == GAP_2D[1].approx(), H


def test_the_check_sees_a_wrong_jacobian():
    """Picard's operator (film coefficients frozen: no derivative of 1 + d P, nor of the
    conductance in H) fails the check in the compressibility and slip parts."""
    pb, _, v = line_state(2)
    errors = fd_errors(pb, v, {"P": pb.iP, "W": pb.iW_all}, newton=False)
    for part in [("P", "compressibility"), ("P", "isothermal sink"), ("W", "slip"),
                 ("W", "compressibility")]:
        assert errors[part] > 1e-2, (part, errors)
