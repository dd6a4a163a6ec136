"""The film's streamline diffusion (webfem.fem.forms.streamline_diffusion): it vanishes to high
order where the cell Peclet number is small (ordinary films unchanged, the order kept), it is
full upwinding where the number is large (a web resting deep on its asperities), both
assemblies carry it (fast and scikit-fem), its Jacobian is exact, and the 1 mm board on the
base roller, whose film is a seal with cell Peclet numbers up to 1e15, answers."""

import numpy as np
import pytest
from skfem import Basis, ElementLineP2, Functional, LinearForm, MeshLine

from webfem.fem import forms
from webfem.fem.mesh import graded_nodes
from webfem.fem.newton import newton
from webfem.fem.scaling import FoilParameters
from webfem.fem.systems import _LastState, cell_lengths
from webfem.fem.transfer import width_nodes
from webfem.fem.weakform import skfem_forms
from webfem.models.fe1d import FoilBearing1D
from webfem.models.fe2d import FoilBearing2D

#: every effect on, with the air flowing through the roughness (a resting web has a flow
#: gap E[(H - z)+] > 0 however deep it rests)
PRM = FoilParameters(beta=12.0, K=0.08, d=0.4, ds=0.2, slip=0.07, Dn=0.03, c=0.6, S=0.12,
                     contact=1.0, floor=0.02, H_c=0.3, flow=1)
ARGS = PRM.as_form_args()


def test_switch():
    """psi(t) = t^16 / (1 + t^16): 1e-16 at t = 0.1, 1/2 at 1, 1 at 1e15 (no overflow), and
    its logarithmic derivative m psi (1 - psi) against a difference quotient."""
    t = np.array([0.1, 0.5, 1.0, 3.0, 1e15, 0.0, -1.0])
    psi, dpsi = forms.upwind_switch(t)
    assert psi[0] < 1e-15 and psi[2] == 0.5 and psi[4] == 1.0
    assert psi[5] == 1.0 and psi[6] == 1.0     # no conductance: fully upwinded
    h = 1e-4    # psi = 1 - 2e-8 at t = 3: a shorter step loses the difference to rounding
    fd = t[:4] * (forms.upwind_switch(t[:4] * (1 + h))[0]
                  - forms.upwind_switch(t[:4] * (1 - h))[0]) / (2 * h * t[:4])
    np.testing.assert_allclose(dpsi[:4], fd, rtol=1e-5)


def _coefficients(H, hx):
    P = 0.3 + 0.1 * H
    PX = 0.7 * np.ones_like(H)
    return (forms.film_coefficients(H, P, PX, 0.0, ARGS, True, hx),
            forms.film_coefficients(H, P, PX, 0.0, ARGS, True, None))


def test_vanishes_where_peclet_is_small():
    """At the largest cell Peclet number of the bundled flying cases (0.6) every coefficient
    is the Galerkin one to rounding; at 5, the largest of the bundled board (resting 0.6
    sigma deep), to 1e-10 (nu / D = Pe psi(Pe / 30) = 2e-12, its derivative in P 16 times
    that)."""
    H = np.linspace(0.3, 3.0, 50)
    Hf = forms.flow_gap(H, ARGS)[0]
    D = (1 + PRM.d * (0.3 + 0.1 * H)) * Hf**3 + PRM.slip * Hf**2
    for pe, bound in ((0.6, 1e-15), (5.0, 1e-10)):
        hx = pe * 2.0 * D / (PRM.d * Hf)          # the cells where Pe is exactly pe
        on, off = _coefficients(H, hx)
        for key in off:
            a, b = np.broadcast_arrays(on[key], off[key])
            assert np.max(np.abs(a - b)) <= bound * np.max(np.abs(b)), key


def test_full_upwinding_where_peclet_is_large():
    """Deep on the asperities (H = -2, 17 S: Pe ~ 1e6 on a cell of 0.1) the X conductance is
    the physical one plus b h / 2, b = d H_f: the effective Peclet number is 1."""
    H = np.array([-2.0, -1.5])
    hx = np.full(2, 0.1)
    on, off = _coefficients(H, hx)
    Hf = forms.flow_gap(H, ARGS)[0]
    assert np.all(PRM.d * Hf * hx / (2 * off["jD"]) > 1e5)
    np.testing.assert_allclose(on["jDX"] - on["jD"], 0.5 * PRM.d * Hf * hx, rtol=1e-12)
    assert np.all(on["jD"] == off["jD"])         # nothing across the width


def _resting_line(order=2):
    """A 1-D state with the web resting 2.5 units (21 S) deep in the middle of the wrap: the
    cell Peclet number spans 1e-3 to 1e12, the switch fully off, in between and fully on."""
    p = FoilBearing1D(graded_nodes(PRM.beta, 6.0, level=0), order=order)
    u = p.initial_guess(PRM)
    x = p.basis.doflocs[0]
    xn = x[p.iW]
    target = 0.6 - 3.1 * np.exp(-(xn / 3.0) ** 2)
    u[p.iW] = target - forms.departure(xn, PRM.beta)
    u[p.iWx] = 3.1 * 2 * xn / 9.0 * np.exp(-(xn / 3.0) ** 2) - np.sign(xn) * np.maximum(
        np.abs(xn) - 0.5 * PRM.beta, 0.0)
    u[p.iP] = 0.5 * np.cos(0.2 * x[p.iP]) * forms.in_wrap(x[p.iP], PRM.beta) + 0.1 * np.sin(
        x[p.iP])
    u[p.fixed] = 0.0
    return p, u


def _peclet(p, u):
    b = p.system.b
    P, dP = b.interpolate(u, 0)
    W = b.interpolate(u, 1)[0]
    H = W + forms.departure(b.x, PRM.beta)
    Hf = forms.flow_gap(H, ARGS)[0]
    D = (1 + PRM.d * P) * Hf**3 + PRM.slip * Hf**2
    return PRM.d * Hf * p.system.hx / (2 * D)


def test_resting_state_spans_the_switch():
    p, u = _resting_line()
    Pe = _peclet(p, u)
    assert Pe.min() < 1e-2 and Pe.max() > 1e10
    assert np.any((Pe > 0.5 * forms.UPWIND_PE) & (Pe < 2.0 * forms.UPWIND_PE))


@pytest.mark.parametrize("order", [1, 2])
def test_line_assemblies_agree_with_upwinding(order):
    """The fast assembly and scikit-fem's forms, both from the declarations, agree to 1e-12
    where the streamline diffusion is on (tests/test_forms.py checks it where it is off)."""
    p, u = _resting_line(order)
    rel = lambda a, b: float(np.max(np.abs(a - b)) / np.max(np.abs(b)))  # noqa: E731
    assert rel(p.residual(u, PRM), p.system.reference_residual(u, PRM)) < 1e-12
    for nt in (True, False):
        assert rel(p.jacobian(u, PRM, nt).toarray(),
                   p.system.reference_jacobian(u, PRM, nt).toarray()) < 1e-12


def test_film_assemblies_agree_with_upwinding():
    p1, u1 = _resting_line()
    p = FoilBearing2D(p1.X, width_nodes(3.0), order=2)
    u = p.start_from_line(p1, u1, PRM)
    rel = lambda a, b: float(np.max(np.abs(a - b)) / np.max(np.abs(b)))  # noqa: E731
    vals = p.system.values(u, PRM)[0]
    assert np.max((vals["jDX"] - vals["jD"]) / vals["jD"]) > 1e6     # on somewhere
    assert rel(p.residual(u, PRM), p.system.reference_residual(u, PRM)) < 1e-12
    assert rel(p.jacobian(u, PRM).toarray(), p.system.reference_jacobian(u, PRM).toarray()) \
        < 1e-12


def _part(p, u, v, t):
    """J v and the central difference of F along v, for the streamline diffusion's part of
    the residual alone (F with it minus F without)."""
    def both(fn):
        on = fn()
        hx, p.system.hx = p.system.hx, None
        p.system._last = _LastState()
        try:
            off = fn()
        finally:
            p.system.hx = hx
            p.system._last = _LastState()
        return on - off
    Jv = both(lambda: p.jacobian(u, PRM) @ v)
    fd = both(lambda: (p.residual(u + t * v, PRM) - p.residual(u - t * v, PRM)) / (2 * t))
    return Jv, fd


@pytest.mark.parametrize("block", ["P", "W"])
def test_jacobian_of_the_upwinding(block):
    """dF/du of the streamline diffusion's part against central differences, along random
    directions in the pressure and in the web, at the resting state (the switch on, off and
    in between): relative error <= 1e-6 (measured ~1e-9; a missing derivative is O(1))."""
    p, u = _resting_line()
    rng = np.random.default_rng(3)
    idx = np.intersect1d(p.iP if block == "P" else p.iW_all, p.free)
    v = np.zeros_like(u)
    v[idx] = rng.standard_normal(idx.size) * np.maximum(np.abs(u[idx]), 1e-2)
    Jv, fd = _part(p, u, v, 1e-6)
    rows = p.free
    assert np.linalg.norm(Jv[rows]) > 1e-6
    assert np.linalg.norm((fd - Jv)[rows]) <= 1e-6 * np.linalg.norm(Jv[rows])


# -- the order with the streamline diffusion on at the coarse cells ---------------------------
D_MMS, K_MMS, G = 0.4, 2.0, 0.041    # compressibility, sink, gap: Pe ~ 30 on 4 cells


def _gap(x):
    return G * (1 + 0.3 * np.sin(np.pi * x)), G * 0.3 * np.pi * np.cos(np.pi * x)


def _source(x):
    """f = -(rho H^3 P')' + (rho H)' + K rho P for P = sin(pi x), rho = 1 + d P."""
    H, Hx = _gap(x)
    P, Px, Pxx = np.sin(np.pi * x), np.pi * np.cos(np.pi * x), -np.pi**2 * np.sin(np.pi * x)
    rho = 1 + D_MMS * P
    div = D_MMS * Px**2 * H**3 + rho * 3 * H**2 * Hx * Px + rho * H**3 * Pxx
    return -div + D_MMS * Px * H + rho * Hx + K_MMS * rho * P


@LinearForm
def _load(q, w):
    return w["f"] * q


@Functional
def _errors(w):
    return np.stack([(w["P"] - np.sin(np.pi * w.x[0])) ** 2,
                     (w["P"].grad[0] - np.pi * np.cos(np.pi * w.x[0])) ** 2])[w["k"]]


def _solve_mms(n):
    basis = Basis(MeshLine(np.linspace(0, 1, n + 1)), ElementLineP2(), intorder=6)
    x = np.asarray(basis.global_coordinates()[0])
    H, hx = _gap(x)[0], cell_lengths(basis)
    prm = {"d": D_MMS, "K": K_MMS, "floor": 1e-6}
    b = _load.assemble(basis, f=_source(x))
    residual, jacobian = skfem_forms((forms.FILM, forms.SINK), ("p",))

    def coef(p):
        P = basis.interpolate(p)
        return forms.film_coefficients(H, np.asarray(P), P.grad[0], 0.0, prm, True, hx)

    free = basis.complement_dofs(basis.get_dofs())
    out = newton(lambda p: residual.assemble(basis, **coef(p)) - b,
                 lambda p: jacobian.assemble(basis, **coef(p)), np.zeros(basis.N), free,
                 tol=1e-12)
    assert out.converged
    P = basis.interpolate(out.u)
    Pe = D_MMS * H * hx / (2 * (1 + D_MMS * np.asarray(P)) * H**3)
    return [np.sqrt(_errors.assemble(basis, P=P, k=k)) for k in (0, 1)], Pe.max()


def test_order_is_kept():
    """P2: L2 order 3 and H1 order 2 between 16 and 32 cells, with the streamline diffusion
    on at 4 cells (Pe ~ UPWIND_PE) and vanishing as the cells shrink."""
    runs = [_solve_mms(n) for n in (4, 8, 16, 32)]
    assert runs[0][1] > 0.8 * forms.UPWIND_PE
    errs = np.array([r[0] for r in runs])
    orders = np.log2(errs[:-1] / errs[1:])
    assert orders[-1, 0] == pytest.approx(3.0, abs=0.15), orders
    assert orders[-1, 1] == pytest.approx(2.0, abs=0.15), orders
