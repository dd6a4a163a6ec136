"""2-D film + 1-D web: wide-web limit, symmetry, load balance, convergence order, VTU output."""

import json

import meshio
import numpy as np
import pytest

from webfem.cli import main
from webfem.fem.mesh import graded_nodes
from webfem.fem.scaling import FoilParameters
from webfem.fem.transfer import width_nodes
from webfem.io.vtu import FILM_FIELDS, WEB_FIELDS, write_result
from webfem.models import fe1d, fe2d
from webfem.models.refine import minimum
from webfem.models.fe1d import FoilBearing1D
from webfem.models.fe2d import FoilBearing2D
from webfem.models.options import FE2DOptions

from conftest import BASE, FLYING as FAST
from orders import GAP_2D

EE = FoilParameters(beta=30.0, K=0.0, d=0.0, Dn=0.0, c=0.0, S=1.0, contact=0.0, floor=1e-3)


def line_solution(X, prm=EE):
    p1 = FoilBearing1D(X)
    u1, info = p1.solve_newton(p1.initial_guess(prm), prm)
    assert info.converged
    return p1, u1


def film_solution(X, lam, p1, u1, prm=EE, level=0, order=2, half=True):
    pb = FoilBearing2D(X, width_nodes(lam, level=level, half=half), order=order)
    u, info = pb.solve_newton(pb.start_from_line(p1, u1, prm), prm, FE2DOptions())
    assert info.converged, info.reason
    return pb, u


def test_wide_web_limit_is_the_1d_model():
    """Edge leakage lowers the central gap by about 1.48/lambda (and the minimum by about
    1.87/lambda); extrapolated to lambda -> infinity the 2-D gaps are the 1-D ones within
    0.1 % (Eshel-Elrod setting, beta = 30)."""
    X = graded_nodes(30.0, 40.0)
    p1, u1 = line_solution(X)
    H1 = float(p1.gap(u1, EE, np.array([0.0]))[0])
    M1 = minimum(p1, u1, EE)[0]
    lams = np.array([50.0, 100.0, 200.0, 400.0])
    H, M = [], []
    for lam in lams:
        pb, u = film_solution(X, lam, p1, u1)
        H.append(float(pb.gap(u, EE, np.array([0.0]))[0]))
        M.append(minimum(pb, u, EE)[0])
    H, M = np.array(H), np.array(M)
    scaled = (1 - H / H1) * lams                      # ~ constant: a 1/lambda law
    assert np.all(np.abs(scaled / scaled[-1] - 1) < 0.06), scaled
    A = np.vstack([np.ones_like(lams), 1 / lams, 1 / lams**2]).T
    H_inf = np.linalg.lstsq(A, H, rcond=None)[0][0]
    M_inf = np.linalg.lstsq(A, M, rcond=None)[0][0]
    assert H_inf == pytest.approx(H1, rel=1e-3)
    assert M_inf == pytest.approx(M1, rel=1e-3)


def central_gaps(order, levels=range(3)):
    H = []
    for lev in levels:
        X = graded_nodes(30.0, 20.0, level=lev)
        p1, u1 = line_solution(X)
        pb, u = film_solution(X, 10.0, p1, u1, level=lev, order=order)
        H.append(float(pb.gap(u, EE, np.array([0.0]))[0]))
    d = np.abs(np.diff(H))
    return np.log2(d[0] / d[1])


@pytest.mark.parametrize("order", [1, pytest.param(2, marks=pytest.mark.slow)])
def test_convergence_order(order):
    """Central gap under refinement of both directions (levels 0-2) against tests/orders.py:
    Q1 order 2, Q2 order 4 (slow test)."""
    assert central_gaps(order) == GAP_2D[order].approx()




@pytest.fixture(scope="module")
def fast_result():
    return fe2d.solve(FAST)


def test_half_and_full_width_agree(fast_result):
    full = fe2d.solve(FAST, symmetry=False)
    for key in ("h_center", "h_min", "h_outlet", "mu"):
        assert full[key] == pytest.approx(fast_result[key], rel=1e-3)


def test_width_averaged_pressure_carries_the_wrap(fast_result):
    """In the uniform part of the wrap the width-averaged film pressure plus contact equals
    T/R within 0.5 % (the web is straight there: no membrane term)."""
    f = fast_result.fields
    c = FAST
    mid = np.abs(f["x"]) < 0.25 * c.roller.radius * c.B
    load = (f["p_rel"][mid] + f["p_contact"][mid]) / c.p_bar
    assert np.all(np.abs(load - 1.0) < 5e-3), load


def test_edge_leakage_lowers_gap_below_1d(fast_result):
    one = fe1d.solve(FAST)
    assert fast_result["h_center"] < one["h_center"]
    assert fast_result["h_min"] < one["h_min"]
    assert fast_result["converged"] and fast_result["n_dofs"] > one["n_dofs"]


@pytest.mark.parametrize("changes", [{"web.width": 0.020},            # lambda = 4.8 < 7
                                     {"wrap.angle_deg": 10.0}])       # beta = 4.6 < 6
def test_outside_eq21_range(changes):
    case = FAST.updated(changes)
    r = fe2d.solve(case)
    assert r["converged"] and not r["eq21_valid"]
    assert 0.0 < r["h_min"] <= r["h_center"]


def test_vtu_round_trip(fast_result, tmp_path):
    paths = write_result(fast_result, tmp_path, "base")
    assert [p.name for p in paths] == ["base_web.vtu", "base_film.vtu"]
    web = meshio.read(paths[0])
    film = meshio.read(paths[1])
    for name in WEB_FIELDS:
        assert name in web.point_data
    for name in FILM_FIELDS:
        assert name in film.point_data
    assert np.allclose(web.point_data["h [m]"], fast_result.fields["h"])
    # the half-width film is written mirrored to the full width: the solved half comes first
    n = len(fast_result.film["points"])
    assert film.points.shape[0] > n
    assert np.allclose(film.point_data["p [Pa]"][:n], fast_result.film["p"])
    pv = pytest.importorskip("pyvista")
    grid = pv.read(paths[1])
    assert grid.n_points == film.points.shape[0] and "p-p_a [Pa]" in grid.point_data


def test_cli_fe2d_json_vtu_and_pictures(tmp_path, capsys):
    assert main(["solve", "cases/base.toml", "--model", "fe2d", "--json", "--set",
                 "roller.speed=40", "--vtu", str(tmp_path), "--plot"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["model"] == "fe2d" and data["converged"]
    for name in ("base_fe2d_web.vtu", "base_fe2d_film.vtu", "base_fe2d_film.png"):
        assert (tmp_path / name).stat().st_size > 1000


def test_sweep_writes_pvd(tmp_path):
    case = tmp_path / "s.toml"
    case.write_text('[sweep]\nparameter = "roller.speed"\nvalues = [38.0, 40.0]\n')
    assert main(["sweep", str(case), "--model", "fe2d", "--out", str(tmp_path), "--vtu",
                 str(tmp_path / "vtu"), "--quiet"]) == 0
    pvd = (tmp_path / "vtu" / "s_fe2d_s01_base_film.pvd").read_text()   # series 1, "base"
    assert pvd.count("<DataSet") == 2 and 'timestep="40.0"' in pvd


def test_picard_matches_newton_2d(fast_result):
    p = fe2d.solve(FAST, method="picard")
    assert p["converged"] and p["method"] == "picard"
    for key in ("h_center", "h_min"):
        assert p[key] == pytest.approx(fast_result[key], rel=1e-6)
    assert p["iterations"] > fast_result["iterations"]


def test_a_kept_result_holds_little_memory():
    """A process that keeps its results (a traction-loss search, a sweep) grew by about
    600 MB per result at 1.4e5 unknowns (11.6 GB in one worker of the figures' traction-loss
    chart): each held its 2-D problem's bases, assembly maps and factorisation plans. A
    result now keeps the recipe of its problem (built again by ``state("problem")``): the
    base case's result at 21 m/s holds 0.9 MB (18,457 unknowns) where it held 37 MB. Measured
    as what freeing it returns: the process also grows by the bounded caches of sparsity
    patterns (fast.pattern_of), which a new mesh size fills."""
    import gc
    import tracemalloc

    case = BASE
    fe2d.solve(case)                       # caches and imports warm
    gc.collect()
    tracemalloc.start()
    try:
        r = fe2d.solve(case.updated({"roller.speed": 21.0}))
        gc.collect()
        with_it = tracemalloc.get_traced_memory()[0]
        n_dofs = r["n_dofs"]
        del r                              # what the result alone held (not the caches)
        gc.collect()
        held = with_it - tracemalloc.get_traced_memory()[0]
    finally:
        tracemalloc.stop()
    assert held < 10 * 2**20, f"{held / 2**20:.1f} MB"
    r = fe2d.solve(case.updated({"roller.speed": 21.0}))
    assert r["n_dofs"] == n_dofs
    problem = r.state("problem")
    assert problem.n_dofs == r["n_dofs"]
    assert np.allclose(problem.gap(r.state("state"), FoilParameters.from_case(case.updated(
        {"roller.speed": 21.0})), np.array([0.0])) * r.case.h_scale, r["h_center"], rtol=1e-9)


def test_film_friction_is_the_local_friction_at_every_vertex(fast_result):
    """The film's friction and regime (computed once per X line of vertices) equal
    friction_for at each vertex's own gap, bit for bit."""
    from webfem.physics.friction import friction_for

    r = fast_result
    film = r.film
    assert np.unique(film.points[:, 0]).size < film.points.shape[0]   # lines of vertices
    gap = film.h          # smooth roller: the film gap is the web's
    loc = friction_for(r.case, gap, resting=True)
    for key in ("chi_c", "mu"):
        assert np.array_equal(getattr(film, key), loc[key])
    assert np.array_equal(film.regime, loc["regime"].astype(float))
