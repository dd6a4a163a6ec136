"""Manufactured solutions: observed convergence orders of the 2-D Reynolds operator (with the
permeation sink and compressibility) and of the web beam, in L2 and H1 (H2 for the beam)."""

import numpy as np
import pytest
from skfem import (Basis, ElementLineHermite, ElementQuad1, ElementQuad2, Functional,
                   LinearForm, MeshLine, MeshQuad)

from webfem.fem.forms import FILM, SINK, WEB, film_coefficients
from webfem.fem.newton import newton
from webfem.fem.weakform import skfem_forms

from orders import BEAM_HERMITE, REYNOLDS_2D

A, D, K = 0.3, 0.4, 2.0     # gap modulation, compressibility d, sink K


def gap(x):
    return 1.0 + A * np.sin(np.pi * x), A * np.pi * np.cos(np.pi * x)


def exact(x, z):
    s, c = np.sin, np.cos
    P = s(np.pi * x) * s(np.pi * z)
    Px = np.pi * c(np.pi * x) * s(np.pi * z)
    Pz = np.pi * s(np.pi * x) * c(np.pi * z)
    Pxx = -np.pi**2 * P
    return P, Px, Pz, Pxx, Pxx   # Pzz = Pxx for this P


def source(x, z):
    """f = -div((1 + D P) H^3 grad P) + d((1 + D P) H)/dx + K (1 + D P) P."""
    H, Hx = gap(x)
    P, Px, Pz, Pxx, Pzz = exact(x, z)
    rho = 1 + D * P
    div = (D * Px * H**3 * Px + rho * 3 * H**2 * Hx * Px + rho * H**3 * Pxx
           + D * Pz**2 * H**3 + rho * H**3 * Pzz)
    return -div + (D * Px * H + rho * Hx) + K * rho * P


@LinearForm
def load(q, w):
    return w["f"] * q


@Functional
def err_l2(w):
    return (w["P"] - w["E"]) ** 2


@Functional
def err_h1(w):
    return (w["P"].grad[0] - w["Ex"]) ** 2 + (w["P"].grad[1] - w["Ez"]) ** 2


def solve_film(n, element):
    mesh = MeshQuad.init_tensor(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    basis = Basis(mesh, element, intorder=6)
    x, z = (np.asarray(c) for c in basis.global_coordinates())
    H = gap(x)[0]
    prm = {"d": D, "K": K, "floor": 1e-6}
    b = load.assemble(basis, f=source(x, z))

    def parts(p, nt=True):
        P = basis.interpolate(p)
        return P, film_coefficients(H, np.asarray(P), P.grad[0], P.grad[1], prm, nt)

    residual, jacobian = skfem_forms((FILM, SINK), ("p",))   # the declared film forms

    def F(p):
        return residual.assemble(basis, **parts(p)[1]) - b

    def J(p):
        return jacobian.assemble(basis, **parts(p)[1])

    free = basis.complement_dofs(basis.get_dofs())
    out = newton(F, J, np.zeros(basis.N), free, tol=1e-12)
    assert out.converged
    P = basis.interpolate(out.u)
    E, Ex, Ez, _, _ = exact(x, z)
    return (np.sqrt(err_l2.assemble(basis, P=P, E=E)),
            np.sqrt(err_h1.assemble(basis, P=P, Ex=Ex, Ez=Ez)))


@pytest.mark.parametrize("name,element", [("Q1", ElementQuad1), ("Q2", ElementQuad2)])
def test_reynolds_2d_orders(name, element):
    """L2 and H1 orders against tests/orders.py (Q1: 2 and 1, Q2: 3 and 2)."""
    errs = np.array([solve_film(n, element()) for n in (4, 8, 16)])
    orders = np.log2(errs[:-1] / errs[1:])
    l2, h1 = REYNOLDS_2D[name]
    assert orders[-1, 0] == l2.approx(), orders
    assert orders[-1, 1] == h1.approx(), orders


DN = 0.7   # bending stiffness (scaled)


@Functional
def beam_errors(w):
    e = w["W"] - np.sin(np.pi * w.x[0])
    e1 = w["W"].grad[0] - np.pi * np.cos(np.pi * w.x[0])
    e2 = w["W"].hess[0, 0] + np.pi**2 * np.sin(np.pi * w.x[0])
    return np.stack([e**2, e1**2, e2**2])[w["k"]]


def solve_beam(n):
    """-W'' + Dn W'''' = f on (0, 1), W = 0 and W'' = 0 (natural) at the ends."""
    mesh = MeshLine(np.linspace(0, 1, n + 1)).with_boundaries(
        {"left": lambda x: x[0] == 0, "right": lambda x: x[0] == 1})
    basis = Basis(mesh, ElementLineHermite(), intorder=8)   # a new Hermite element per mesh
    x = np.asarray(basis.global_coordinates()[0])
    f = (np.pi**2 + DN * np.pi**4) * np.sin(np.pi * x)
    zero = np.zeros_like(x)
    residual, jacobian = skfem_forms((WEB,), ("w",))          # the declared web forms

    def coef(w):
        W = basis.interpolate(w)
        return {"dW": W.grad[0], "bend": DN * W.hess[0, 0], "load": f, "k_c": zero, "Dn": DN}

    free = basis.complement_dofs(basis.get_dofs({"left", "right"}).all("u"))
    out = newton(lambda w: residual.assemble(basis, **coef(w)),
                 lambda w: jacobian.assemble(basis, **coef(w)), np.zeros(basis.N), free,
                 tol=1e-12)
    W = basis.interpolate(out.u)
    return [np.sqrt(beam_errors.assemble(basis, W=W, k=k)) for k in range(3)]


def test_beam_orders():
    """Cubic Hermite: L2 order 4, H1 seminorm 3, H2 seminorm 2 (tests/orders.py)."""
    errs = np.array([solve_beam(n) for n in (4, 8, 16)])
    orders = np.log2(errs[:-1] / errs[1:])[-1]
    for observed, pin in zip(orders, BEAM_HERMITE, strict=True):
        assert observed == pin.approx(), orders
