"""model="fitted" (issue 24): its groups and domain, its refusals, the CI-sized campaign, the
shipped fit's stated errors on fresh points and the drift guard against the current fe2d."""

import json

import math

import numpy as np
import pytest

import webfem
from webfem import Case
from webfem.cli import main
from webfem.models import fit_groups as fg
from webfem.models import fitted
from webfem.models.readout import READ_QUANTITIES, error_scale
from webfem.studies import fit_campaign as fc
from webfem.studies import time_limit

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")


def test_campaign_cases_have_the_design_groups():
    G = fc.design(64)
    lo, hi = fg.box()
    x = fg.coordinates(G)
    kb = fg.GROUPS.index("Kb")
    assert np.all(x[:, kb] >= lo[kb] - 1e-12)        # Kb = 0 sits at the bottom
    assert (G[:, kb] == 0.0).any() and (G[:, kb] > 0.0).any()
    for row in G[:16]:
        g = dict(zip(fg.GROUPS, row))
        back = fg.groups_of(fc.case_of_groups(g))
        for k in fg.GROUPS:
            assert back[k] == pytest.approx(g[k], rel=1e-9, abs=1e-12), k


def test_the_quadrature_averages_exactly():
    assert fg.WEIGHTS.sum() == pytest.approx(1.0)
    # Clenshaw-Curtis integrates polynomials of degree n - 1 exactly: mean of s^2 = 1/12
    assert np.sum(fg.WEIGHTS * fg.NODES**2) == pytest.approx(1.0 / 12.0, rel=1e-12)


@pytest.mark.parametrize("values, name", [
    ({"web.width": 0.002}, "lam = "),
    ({"roller.groove_pitch": 2e-3, "roller.groove_width": 0.5e-3,
      "roller.groove_depth": 0.1e-3}, "grooved roller"),
    ({"model.physics": "paper"}, "model.physics = 'paper'"),
    ({"wrap.ends": "held"}, "wrap.ends = 'held': the fit's errors were measured with the web "
                            "held through 1 m spans"),
    ({"wrap.span": 0.5}, "wrap.span = 0.5 m"),
])
def test_outside_the_domain_it_refuses_naming_the_group(values, name):
    case = Case().updated(values)
    with pytest.raises(fitted.OutsideDomain, match=name) as err:
        webfem.solve(case, model="fitted")
    if name == "lam = ":   # the value and the range
        assert "1.2 <= lam <= 4000" in str(err.value)


def test_auto_passes_over_it_outside_its_domain():
    r = webfem.solve(Case().updated({"web.width": 0.002}), model="auto", tol=0.5)
    assert r["model_used"] != "fitted"
    assert "fitted: lam = " in r["why"] and "outside" in r["why"]


def test_the_cli_answers_and_refuses_without_a_traceback(capsys):
    assert main(["solve", "base", "--model", "fitted", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    fe2d = webfem.solve(Case(), model="fe2d", estimate=False)
    assert set(data) - {"units"} == set(fe2d.summary.to_dict())
    assert data["model"] == "fitted" and data["converged"]
    assert all(data[f"error_{q}"] > 0.0 for q in READ_QUANTITIES)
    assert main(["solve", "base", "--model", "fitted", "--set", "web.width=0.002"]) == 2
    err = capsys.readouterr().err
    assert "lam = " in err and "Traceback" not in err


def test_ci_sized_campaign_builds_a_fit_that_answers(tmp_path, capsys):
    store = tmp_path / "camp"
    assert main(["fit", "build", "--points", "6", "--store", str(store), "--timeout", "30",
                 "--json", "--quiet"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["train"] + report["holdout"] + report["failed"] == 6
    assert report["holdout"] >= 1
    out = store / "fitted_coefficients.npz"
    r = webfem.solve(Case(), model="fitted", coefficients=str(out))
    assert r["model"] == "fitted" and np.isfinite(r["mu"])
    # a handful of hold-out points states nothing (their percentiles are luck: user38 saw
    # h_min stated 0.46 where its error was 2.5)
    assert not report["errors_stated"]
    assert all(np.isnan(r[f"error_{q}"]) for q in READ_QUANTITIES)
    assert any("the fit states no errors" in w for w in r["warnings"])
    # resumable: a second run solves nothing new and keeps the rows
    assert main(["fit", "build", "--points", "6", "--store", str(store), "--json",
                 "--quiet"]) == 0
    again = json.loads(capsys.readouterr().out)
    assert again["train"] == report["train"] and again["holdout"] == report["holdout"]
    # more points extend the campaign: the six rows are kept as they were, one is solved
    before = (store / "campaign.csv").read_text().splitlines()
    assert main(["fit", "build", "--points", "7", "--store", str(store), "--timeout", "30",
                 "--json", "--quiet"]) == 0
    grown = json.loads(capsys.readouterr().out)
    assert grown["train"] + grown["holdout"] + grown["failed"] == 7
    assert not grown["holdout_rechecked"]
    # so few training points are all kept as centres: the compressed fit is the full one
    assert grown["centres"] == [grown["train"]] * 3
    assert grown["full_fit_percentiles_50_90_95_max"] == grown["percentiles_50_90_95_max"]
    # --recheck: the hold-out point (design point 4) solved again with today's physics into
    # holdout.csv, whose rows then state the errors; here the physics is the same, so the
    # answers and the stated table are too
    assert main(["fit", "build", "--points", "7", "--store", str(store), "--timeout", "30",
                 "--recheck", "--fit-only", "--json", "--quiet"]) == 0
    rechecked = json.loads(capsys.readouterr().out)
    assert rechecked["holdout_rechecked"] and rechecked["holdout"] == grown["holdout"]
    assert rechecked["stated"] == grown["stated"]
    from webfem.sweeps.table import read_table, typed
    rows = typed(read_table(store / "holdout.csv").rows)
    assert [r["n"] for r in rows] == [4]
    assert (store / "campaign.csv").read_text().splitlines()[:7] == before
    # --extra-holdout: points of another design (EXTRA_SEED), every one held out, join the
    # hold-out rows in stating the errors
    assert main(["fit", "build", "--points", "7", "--store", str(store), "--timeout", "30",
                 "--extra-holdout", "2", "--fit-only", "--json", "--quiet"]) == 0
    extra = json.loads(capsys.readouterr().out)
    rows = typed(read_table(store / "extra_holdout.csv").rows)
    assert [r["n"] for r in rows] == [0, 1] and all(r["holdout"] == 1 for r in rows)
    assert [r["g_beta"] for r in rows] == pytest.approx(
        fc.design(2, seed=fc.EXTRA_SEED)[:, fg.GROUPS.index("beta")], rel=1e-12)
    answered = sum(bool(r["converged"]) for r in rows)
    assert extra["holdout_extra"] == answered >= 1
    assert extra["holdout"] == rechecked["holdout"] + answered
    # the fit does not depend on the order of the rows (an interrupted parallel run leaves
    # them in the order they finished): the rows reversed refit to the same arrays
    lines = (store / "campaign.csv").read_text().splitlines(keepends=True)
    (store / "campaign.csv").write_text("".join(lines[:1] + lines[:0:-1]))
    again = store / "again.npz"
    assert main(["fit", "build", "--store", str(store), "--fit-only", "--out", str(again),
                 "--json", "--quiet"]) == 0
    capsys.readouterr()
    with np.load(store / "fitted_coefficients.npz") as a, np.load(again) as b:
        assert set(a.files) == set(b.files)
        for key in set(a.files) - {"info"}:          # info: the date
            assert np.array_equal(a[key], b[key]), key


def _without_seconds(rows):
    return [{k: v for k, v in r.items() if k != "seconds"} for r in rows]


def test_campaign_in_processes_and_on_dask_gives_the_serial_rows(tmp_path):
    """--workers and --dask solve each design point as a serial campaign does (the same
    rows, bit for bit, in design order), each point under its own time limit in its worker
    (a Dask worker solves in a thread, which SIGALRM does not reach), failures kept unless
    retried."""
    serial = fc.run(tmp_path / "s" / "campaign.csv", 2, timeout=30.0)
    assert all(r["converged"] for r in serial)
    engines = [{"workers": 2}]
    try:
        import distributed  # noqa: F401
        engines.append({"workers": 2, "dask": "local"})
    except ImportError:
        pass
    for k, engine in enumerate(engines):
        csv = tmp_path / f"p{k}" / "campaign.csv"
        timed_out = fc.run(csv, 2, timeout=0.01, **engine)
        assert [r["n"] for r in timed_out] == [0.0, 1.0]
        assert all(not r["converged"] and r["message"] == "TimeoutError: no answer within "
                   "0.01 s" for r in timed_out), (engine, timed_out)
        assert fc.run(csv, 2, timeout=30.0, **engine) == timed_out   # failures kept
        retried = fc.run(csv, 2, timeout=30.0, retry_failed=True, **engine)
        assert _without_seconds(retried) == _without_seconds(serial), engine


def _swallowing_spin(seconds):
    """Under a limit of ``seconds``: spin, swallow the first TimeoutError as code catching
    every error would, spin again; what the limit raised and said, and the time taken."""
    import time

    t0 = time.perf_counter()
    try:
        with time_limit.time_limit(seconds) as limit:
            try:
                while True:
                    pass
            except Exception:   # noqa: BLE001 - swallowed, as some library code does
                pass
            while True:
                pass
    except TimeoutError as err:
        return limit.expired, str(err), time.perf_counter() - t0


@pytest.mark.parametrize("in_thread", [False, True])
def test_time_limit_strikes_again_and_leaves_the_thread_clean(in_thread):
    """The campaign's per-point limit in the main thread (SIGALRM: serial and local
    workers) and in another (a Dask worker's): raised again after a swallowed one, and
    nothing raised after a block that ended in time."""
    import threading
    import time

    out = []

    def spin():
        out.append(_swallowing_spin(0.1))
        with time_limit.time_limit(0.1):       # ends in time: nothing raised later
            pass
        time.sleep(0.3)
        out.append("clean")

    if in_thread:
        thread = threading.Thread(target=spin)
        thread.start()
        thread.join(10)
    else:
        spin()
    (expired, message, seconds), clean = out
    assert expired and message == "no answer within 0.1 s" and clean == "clean"
    assert time_limit._AGAIN_S + 0.1 <= seconds < time_limit._AGAIN_S + 2.0


def test_campaign_options_refused_before_anything_runs(tmp_path, capsys):
    store = tmp_path / "c"
    assert main(["fit", "build", "--points", "3", "--store", str(store), "--dask", "foo",
                 "--quiet"]) == 2
    assert "dask = 'foo' is not valid" in capsys.readouterr().err
    assert not (store / "campaign.csv").exists()
    assert main(["fit", "build", "--store", str(store), "--fit-only", "--workers", "2"]) == 2
    assert "--fit-only solves nothing" in capsys.readouterr().err


def test_drift_the_current_fe2d_reproduces_the_hold_out_answers():
    """The stated errors were measured against these fe2d answers: if the physics or the
    solver changes them, the fit must be rebuilt (`webfem fit build`)."""
    fit = np.load(fitted.COEFFICIENTS)
    # the six hold-out points fe2d solved fastest in the campaign
    pick = np.argsort(fit["holdout_seconds"])[:6]
    G, V = fit["holdout_groups"][pick], fit["holdout_values"][pick]
    checked = 0
    for g, v in zip(G, V):
        case = fc.case_of_groups(dict(zip(fg.GROUPS, g)))
        r = webfem.solve(case, model="fe2d", **fc.FE2D_OPTIONS)
        for q, ref in zip(fitted.QUANTITIES, v):
            assert abs(r[q] - ref) / error_scale(case, q, ref) <= 1e-6, (q, r[q], ref)
        checked += 1
    assert checked >= 4


@pytest.mark.slow
def test_stated_errors_bound_the_true_error_on_fresh_points():
    """Points of another design (never solved in the campaign): the true error is within
    the stated one (the hold-out's 95th percentile of the point's region) for at least 80 %
    of the point-quantity pairs, and within twice it for 90 %."""
    G = fc.design(24, seed=2024)
    pairs = within = within2 = 0
    for i, row in enumerate(G[::3]):
        g = dict(zip(fg.GROUPS, row))
        case = fc.case_of_groups(g)
        ref = fc.solve_point(i, g, timeout=30.0, options=fc.FE2D_OPTIONS)
        if not ref["converged"]:
            continue
        r = webfem.solve(case, model="fitted")
        for q in READ_QUANTITIES:
            true = abs(r[q] - ref[q]) / error_scale(case, q, ref[q])
            pairs += 1
            within += true <= r[f"error_{q}"]
            within2 += true <= 2.0 * r[f"error_{q}"]
    assert pairs >= 16
    assert within >= 0.8 * pairs and within2 >= 0.9 * pairs


# -- the vectorised evaluation (solve_many) --------------------------------------------------

#: Cases inside the domain that exercise every branch of the read-out: sliding and not (an
#: idler), a moving web (inertia), an idler load, permeable webs and an impermeable one, a
#: resting web.
VARIED = [Case(), Case().updated({"roller.speed": 10.0, "web.speed": 10.0}),
          Case().updated({"web.permeability": 1e-14, "roller.speed": 40.0}),
          Case().updated({"web.permeability": 0.0, "roller.speed": 30.0}),
          Case().updated({"web.speed": 15.0, "roller.drag_torque": 0.02}),
          Case().updated({"web.tension": 30.0, "roller.speed": 5.0}),
          Case().updated({"roller.speed": 8.0, "web.speed": 8.0, "web.acceleration": 2.0,
                          "roller.inertia": 1e-3, "wrap.angle_deg": 120.0})]


def _close(a, b, scale=None):
    if isinstance(b, float) and not isinstance(b, bool):
        return a == pytest.approx(b, rel=1e-12, abs=1e-12 * (scale or abs(b)))
    return a == b


def test_solve_many_answers_as_solve_does_case_by_case():
    many = webfem.solve_many(VARIED, model="fitted")
    assert len(many) == len(VARIED)
    for case, m in zip(VARIED, many):
        one = webfem.solve(case, model="fitted")
        a, b = m.summary.to_dict(), one.summary.to_dict()
        assert set(a) == set(b)
        for k in a:
            if k != "solve_time_s":
                assert _close(a[k], b[k]), (k, a[k], b[k])
        assert set(m.fields.keys()) == set(one.fields.keys())
        for k in one.fields.keys():
            ref = np.asarray(one.fields[k], float)
            np.testing.assert_allclose(m.fields[k], ref, rtol=1e-12,
                                       atol=1e-12 * np.abs(ref).max())
    assert webfem.solve_many([], model="fitted") == []


def test_solve_many_keeps_the_case_outside_the_domain():
    """The case outside is kept in its place, not answered, saying why; the others keep
    their answers (webfem.solve_many keeps every point, whatever the model)."""
    inside, outside = Case(), Case().updated({"web.width": 0.002})
    many = webfem.solve_many([inside, outside, inside], model="fitted")
    assert [r["converged"] for r in many] == [True, False, True]
    assert many[1]["solver_message"].startswith("no fitted answer: lam = ")
    assert many[1]["warnings"] == (many[1]["solver_message"],)
    assert math.isnan(many[1]["mu"]) and many[1].to_dict()["h_min"] is None
    assert many[0]["mu"] == many[2]["mu"]
    assert math.isclose(many[0]["mu"], webfem.solve(inside, model="fitted")["mu"], rel_tol=1e-12)
    with pytest.raises(fitted.OutsideDomain, match="no fitted answer: lam = "):
        webfem.solve(outside, model="fitted")


def test_vectorised_groups_and_traction_equal_the_per_case_ones():
    from webfem.physics.effects import traction_summaries, traction_summary
    G = fg.groups_of_columns(fg.case_columns(VARIED))
    for case, row in zip(VARIED, G):
        g = fg.groups_of(case)
        np.testing.assert_allclose(row, [g[k] for k in fg.GROUPS], rtol=1e-13, atol=0)
    mu, share = np.linspace(-1e-3, 0.3, len(VARIED)), np.linspace(0.0, 1.0, len(VARIED))
    for case, m, s, many in zip(VARIED, mu, share, traction_summaries(VARIED, mu, share)):
        one = traction_summary(case, float(m), float(s))
        assert set(one) == set(many)
        for k in one:
            assert (many[k] is None) == (one[k] is None), k
            if one[k] is not None:
                assert many[k] == pytest.approx(one[k], rel=1e-13, abs=1e-300), k


def test_the_read_out_is_the_physics_functions_on_the_profile():
    """The array read-out against the physics functions called on each Case (as the FE
    models' read-out does)."""
    from webfem.physics.contact import contact_pressure
    from webfem.physics.friction import friction_for
    pr = fitted.predict(fg.groups_of_columns(fg.case_columns(VARIED)))
    for i, case in enumerate(VARIED):
        H, P = pr["H"][i], pr["P"][i]
        v = fitted.read_profile(case, H, P, pr["H_min"][i], pr["s_min"][i])
        h = H * case.h_scale
        p = np.maximum(case.air.ambient_pressure + P * case.p_bar,
                       0.1 * case.air.ambient_pressure)
        dpdx = np.gradient(P, fg.NODES * case.beta) * case.p_bar / case.x_scale
        loc = friction_for(case, h, resting=True, p=p, dpdx=dpdx)
        scale = np.abs(loc["mu"]).max()
        assert v["mu"] == pytest.approx(np.sum(fg.WEIGHTS * loc["mu"]), rel=1e-12,
                                        abs=1e-12 * scale)
        for k in ("mu", "mu_f", "chi_c"):
            np.testing.assert_allclose(v["loc"][k], loc[k], rtol=1e-12,
                                       atol=1e-12 * np.abs(loc[k]).max())
        w = case.web
        Pc = contact_pressure(h, w.modulus_thickness, case.sigma, w.thickness) / case.p_bar
        share = np.clip(np.sum(fg.WEIGHTS * Pc) / np.sum(fg.WEIGHTS * (P + Pc)), 0.0, 1.0)
        assert v["contact_share"] == pytest.approx(share, rel=1e-12, abs=1e-15)
        assert v["h_center"] == h[len(h) // 2]


def test_the_blocked_shear_quadrature_is_the_same_sum():
    from webfem.physics import roughness
    h = np.random.default_rng(1).uniform(-2e-5, 5e-5, (200, 33))
    # (the Gaussian heights': the exponential's shear is in closed form, without blocks)
    whole = roughness._shear_factor(*np.broadcast_arrays(h, 4e-6, 1.3e-7), "gaussian")
    assert h.size > roughness._BLOCK
    assert np.array_equal(roughness.shear_factor(h, 4e-6, 1.3e-7, "gaussian"), whole)


def test_the_blocked_kernel_is_the_generic_formula():
    from webfem.models.fit_kernel import Kernel, matern52
    rng = np.random.default_rng(3)
    c, x = rng.uniform(size=(40, 3)), rng.uniform(size=(700, 3))
    k = Kernel(centres=c, scales=np.array([0.3, 0.7, 1.1]), trend=rng.normal(size=(4, 5)),
               weights=rng.normal(size=(40, 5)), y_mean=rng.normal(size=5),
               y_std=rng.uniform(0.5, 2.0, 5))
    generic = ((np.hstack([np.ones((len(x), 1)), x]) @ k.trend
                + matern52(x, c, k.scales) @ k.weights) * k.y_std + k.y_mean)
    np.testing.assert_allclose(k(x), generic, rtol=1e-12, atol=1e-12)       # many points
    np.testing.assert_allclose(k(x[:5]), generic[:5], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(k(c), (np.hstack([np.ones((40, 1)), c]) @ k.trend
                                      + matern52(c, c, k.scales) @ k.weights) * k.y_std
                               + k.y_mean, rtol=1e-9, atol=1e-9)   # at the centres (r = 0)


def test_the_stacked_kernels_are_each_kernel_side_by_side():
    from webfem.models.fit_kernel import Kernel, Stack
    rng = np.random.default_rng(4)
    kernels = [Kernel(centres=rng.uniform(size=(m, 3)), scales=rng.uniform(0.2, 2.0, 3),
                      trend=rng.normal(size=(4, k)), weights=rng.normal(size=(m, k)),
                      y_mean=rng.normal(size=k), y_std=rng.uniform(0.5, 2.0, k))
               for m, k in ((40, 5), (25, 2), (60, 1))]
    x = rng.uniform(size=(700, 3))
    each = np.column_stack([k(x) for k in kernels])
    stack = Stack(kernels)
    assert stack.n_outputs == 8
    np.testing.assert_allclose(stack(x), each, rtol=1e-12, atol=1e-12)   # many points
    np.testing.assert_allclose(stack(x[:3]), each[:3], rtol=1e-12, atol=1e-12)
    # the radial function and the weight products in float32 (as the fitted model runs
    # them): float32's rounding (6e-8) times the weights' sum, and each point's answer still
    # independent of the batch and of its place in it (every block the same shape)
    fast = Stack(kernels, radial=np.float32)
    bound = 1e-6 * sum(np.abs(k.weights * k.y_std).sum(axis=0).max() for k in kernels)
    np.testing.assert_allclose(fast(x), each, rtol=0, atol=bound)
    assert np.abs(fast(x) - each).max() > 1e-12            # float32 it is
    for i in (0, 1, 33, 699):
        np.testing.assert_allclose(fast(x[i:i + 1])[0], fast(x)[i], rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(fast(x[30:40]), fast(x)[30:40], rtol=1e-13, atol=1e-13)
    # at a centre (r = 0, where the distances' rounding may fall below 0) the clamped square
    # gives the kernel's value, not a NaN
    c = kernels[1].centres
    np.testing.assert_allclose(fast(c), np.column_stack([k(c) for k in kernels]), rtol=0,
                               atol=bound)


def test_a_root_of_a_square_below_zero_is_taken_again_clamped():
    """The float32 Matern stack takes the squared distances' root unclamped: where rounding
    leaves a square below 0 (a point at a centre) the root is NaN, and evaluate takes that
    point again with |.|, to the bits a clamped evaluation gives; the others are untouched."""
    from webfem.models.fit_kernel import CHUNK
    stack = fitted.coefficients()["stack"]
    centres = np.vstack([k.centres for k in stack.kernels])
    with np.errstate(invalid="ignore"):
        raw = stack._evaluate(centres, CHUNK, False)
    bad = np.isnan(raw).any(axis=1)
    assert 0 < bad.sum() < len(centres)          # the path is taken, not everywhere
    out = stack(centres)
    assert np.isfinite(out).all()
    assert np.array_equal(out, stack.evaluate(centres, clamp=True))
    assert np.array_equal(out[~bad], raw[~bad])
    # each point its own: a centre alone gives its row's bits
    i = int(np.flatnonzero(bad)[0])
    assert np.array_equal(stack(centres[i:i + 1])[0], out[i])


def test_the_compressed_fit_is_the_gp_mean_with_every_centre_and_spreads_them():
    from webfem.models.fit_kernel import matern52
    from webfem.studies import fit_build as fb
    rng = np.random.default_rng(5)
    x = rng.uniform(size=(60, 2))
    y = np.column_stack([np.sin(3 * x[:, 0]) * x[:, 1], np.cos(2 * x[:, 1])])
    scales, nugget = np.array([0.4, 0.6]), 1e-3
    gp = np.linalg.solve(matern52(x, x, scales) + nugget * np.eye(60), y)
    np.testing.assert_allclose(fb.sor_weights(x, y, scales, nugget, np.arange(60)), gp,
                               rtol=1e-6, atol=1e-6 * np.abs(gp).max())
    # on a line the pivoted Cholesky takes the ends first, then fills in between
    line = np.linspace(0.0, 1.0, 41)[:, None]
    idx = fb.select_centres(line, np.array([0.2]), 5)
    assert len(set(idx.tolist())) == 5
    assert set(idx[:2].tolist()) == {0, 40}
    assert np.diff(np.sort(line[idx, 0])).min() > 0.15
    # fewer centres, fitted to every point: close to the full fit on a smooth function
    k = fb.fit_kernel(x, y, trend=False, hyper=(scales, nugget), centres=25)
    full = fb.fit_kernel(x, y, trend=False, hyper=(scales, nugget))
    xt = rng.uniform(0.1, 0.9, size=(200, 2))
    assert len(k.centres) == 25
    assert np.abs(k(xt) - full(xt)).max() < 0.05 * np.abs(full(xt)).max()


def test_the_shipped_fit_is_the_compressed_build():
    """The shipped coefficients come from `webfem fit build` with its compression (the
    stated errors are this fit's own hold-out errors)."""
    from webfem.studies import fit_build as fb
    fit = fitted.coefficients()
    assert [len(k.centres) for k in (fit["kernel"], *fit["scalars"])] == list(fb.CENTRES)
    assert fit["stack"] is not None
    # the stated table is this fit's: its hold-out answers, judged through it, give it back
    npz = np.load(fitted.COEFFICIENTS)
    rows = [{**{f"g_{g}": v for g, v in zip(fg.GROUPS, G)}, **dict(zip(fitted.QUANTITIES, V))}
            for G, V in zip(npz["holdout_groups"], npz["holdout_values"])]
    table = fb.region_errors(fb.holdout_errors(rows, fit))
    assert np.allclose(table, fit["errors"], rtol=1e-9, atol=0.0)


def test_restate_measures_the_table_again_and_keeps_the_rest(tmp_path):
    """fit_build.restate: a file whose table is wrong gets the shipped fit's own table back
    (its hold-out rows through today's evaluation), every other array as it was."""
    from webfem.studies import fit_build as fb
    npz = np.load(fitted.COEFFICIENTS)
    arrays = {k: npz[k] for k in npz.files}
    path = tmp_path / "wrong.npz"
    np.savez_compressed(path, **{**arrays, "region_errors": np.zeros_like(
        arrays["region_errors"])})
    table = fb.restate(path, tmp_path / "restated.npz")
    out = np.load(tmp_path / "restated.npz")
    assert set(out.files) == set(arrays)
    for k, a in arrays.items():
        if k != "region_errors":
            assert np.array_equal(out[k], a), k
    np.testing.assert_allclose(out["region_errors"], arrays["region_errors"], rtol=1e-12)
    np.testing.assert_array_equal(table, out["region_errors"])
    assert not np.load(path)["region_errors"].any()        # the input file untouched


def test_the_gaps_and_share_fitted_on_their_own_are_the_answers():
    """The shipped fit answers h_center, h_min and the contact share from their own kernels
    (docs/fit.md), h_min capped by the profile's smallest node; the profile still gives the
    fields."""
    fit = fitted.coefficients()
    assert set(fit["scalar_names"]) == {"h_center", "h_min", "contact_share"}
    pr = fitted.predict(fg.groups_of_columns(fg.case_columns(VARIED)))
    assert np.all(pr["H_min"] <= pr["H"].min(axis=1))
    assert np.all((pr["share"] >= 0.0) & (pr["share"] <= 1.0))
    for i, case in enumerate(VARIED):
        r = webfem.solve(case, model="fitted")
        assert r["h_center"] == pytest.approx(pr["H_center"][i] * case.h_scale, rel=1e-12)
        assert r["h_min"] == pytest.approx(pr["H_min"][i] * case.h_scale, rel=1e-12)
        assert r["contact_share"] == pytest.approx(pr["share"][i], rel=1e-12, abs=1e-15)
        np.testing.assert_allclose(r.fields.h, pr["H"][i] * case.h_scale, rtol=1e-12)


def test_a_fit_with_another_kernel_does_not_reuse_the_shipped_stack():
    """A fit dict whose kernel was swapped (as a build's candidates are) is evaluated with
    that kernel, not with the one-pass stack cached for the shipped kernels."""
    import dataclasses
    fit = fitted.coefficients()
    k = fit["kernel"]
    doubled = dataclasses.replace(k, y_std=2.0 * k.y_std)
    G = fg.groups_of_columns(fg.case_columns(VARIED))
    shipped = fitted.predict(G, fit)
    other = fitted.predict(G, {**fit, "kernel": doubled})
    assert not np.allclose(other["H"], shipped["H"])
    direct = fitted.predict(G, {**fit, "kernel": doubled, "stack": None})
    assert np.array_equal(other["H"], direct["H"])


def test_centres_stop_where_the_points_are_spanned():
    """Five distinct points, each four times: asking for 20 centres gives the five, not a
    division by a vanished remaining variance."""
    from webfem.studies import fit_build as fb
    x = np.repeat(np.random.default_rng(1).random((5, 3)), 4, axis=0)
    idx = fb.select_centres(x, np.ones(3), 20)
    assert len(idx) == 5 and len({tuple(x[i]) for i in idx}) == 5


def _without_local(tmp_path):
    """The shipped file without its per-point statement (a file from before it)."""
    from webfem.models import fit_stated
    npz = np.load(fitted.COEFFICIENTS)
    path = tmp_path / "cells.npz"
    np.savez_compressed(path, **{k: npz[k] for k in npz.files if k not in fit_stated.KEYS})
    return str(path)


def test_a_file_without_the_per_point_statement_states_its_table(tmp_path):
    """The stated table has a row per (gap region, Dn band): a stiff web's stated errors
    are its band's, not the flexible webs' it shared a row with before (a flying stiff web's
    h_min 95th percentile is several times a flexible one's on the hold-out set), and the
    basis names the cell. A file without the ``local_*`` arrays (before them) states it."""
    path = _without_local(tmp_path)
    fit = fitted.coefficients(path)
    assert fit["local"] is None
    assert fit["errors"].shape == (9, len(fitted.QUANTITIES))
    flying = fit["errors"][6:9]
    assert flying[2, 1] > 2.0 * flying[0, 1]
    stiff = Case().updated({"web.bending_stiffness": 0.5, "roller.speed": 30.0})
    g = fg.groups_of(stiff)
    assert g["Dn"] > 100.0 and fg.outside(stiff) is None
    r = webfem.solve(stiff, model="fitted", coefficients=path)
    region = int(fitted.predict(fg.group_array(g))["region"][0])
    assert region % 3 == 2
    assert r["error_h_min"] == fit["errors"][region, 1]
    assert "95th percentile of the hold-out errors against fe2d in its region" in \
        r["error_basis"]
    assert "stiff web (bending group Dn > 100)" in r["error_basis"]
    # the same answers; only the statement differs
    shipped = webfem.solve(stiff, model="fitted")
    assert shipped["h_min"] == r["h_min"] and shipped["error_h_min"] != r["error_h_min"]


def test_the_stated_error_is_its_nearest_hold_out_points_mean_error_scaled():
    """Each answer states, per quantity, factor x (mean error of its K nearest hold-out
    points + floor), nearness in its metric (fit_stated): checked against a brute-force
    search by full sort, for a flexible and a stiff web."""
    from webfem.models import fit_stated as fs
    fit = fitted.coefficients()
    loc = fit["local"]
    assert loc is not None and int(loc["local_k"]) == fs.K
    for case in (Case(), Case().updated({"web.bending_stiffness": 0.5,
                                         "roller.speed": 30.0})):
        G = fg.group_array(fg.groups_of(case))
        pr = fitted.predict(G)
        x = (fg.coordinates(G) - fit["lo"]) / (fit["hi"] - fit["lo"])
        c = np.r_[x[0], np.log10(max(pr["H_min"][0] / G[0, fg.GROUPS.index("S")], 0.1)),
                  np.arcsin(np.sqrt(pr["share"][0]))]
        r = webfem.solve(case, model="fitted")
        for j, q in enumerate(fitted.QUANTITIES):
            s = loc["local_scales"][loc["local_metric"][j]]
            d = (((loc["local_x"] - c) / s) ** 2).sum(axis=1)
            near = np.argsort(d)[:fs.K]
            want = loc["local_factor"][j] * (loc["local_errors"][near, j].mean()
                                             + loc["local_floor"][j])
            assert r[f"error_{q}"] == pytest.approx(want, rel=1e-12), q
        assert "hold-out points nearest it" in r["error_basis"]


def test_the_per_point_statement_holds_for_95_percent_of_the_hold_out_left_out():
    """The factor is the 95th percentile of error / spread with each hold-out point left
    out of its own neighbours: so left out, the statement holds for 95 % of them in every
    quantity, and the shipped arrays are this fit's own (its hold-out errors measured
    again through today's evaluation give them back)."""
    from webfem.models import fit_stated as fs
    from webfem.studies import fit_build as fb
    fit = fitted.coefficients()
    loc = fit["local"]
    E = loc["local_errors"]
    held = E <= fs.spread(loc["local_x"], loc, exclude_self=True) * loc["local_factor"]
    assert np.all(np.abs(held.mean(axis=0) - 0.95) <= 1.0 / len(E))
    npz = np.load(fitted.COEFFICIENTS)
    rows = [{**{f"g_{g}": v for g, v in zip(fg.GROUPS, G)}, **dict(zip(fitted.QUANTITIES, V))}
            for G, V in zip(npz["holdout_groups"], npz["holdout_values"])]
    again = fb.local_arrays(npz["holdout_groups"], fb.holdout_errors(rows, fit), fit)
    for k in fs.KEYS:
        np.testing.assert_allclose(again[k], loc[k], rtol=1e-9, atol=1e-12)


def test_many_points_are_answered_alone_whatever_the_threads_and_the_batch():
    """predict shares blocks of points among threads: each point's answer is its own, the
    same on one thread or two, in a batch of any size and alone (to rounding)."""
    G = fc.design(2 * fitted.BLOCK + 37, seed=11)
    one = fitted.predict(G, n_threads=1)
    two = fitted.predict(G, n_threads=2)
    for k, a in one.items():
        if a is not None:
            assert np.array_equal(a, two[k]), k
    # a batch that cuts the blocks elsewhere, and points alone
    part = fitted.predict(G[fitted.BLOCK - 5:], n_threads=2)
    alone = [fitted.predict(G[i:i + 1]) for i in (0, fitted.BLOCK, len(G) - 1)]
    for k in ("H", "P", "H_min", "s_min", "H_center", "share"):
        np.testing.assert_allclose(part[k], one[k][fitted.BLOCK - 5:], rtol=1e-12, atol=1e-14)
        for i, a in zip((0, fitted.BLOCK, len(G) - 1), alone):
            np.testing.assert_allclose(a[k][0], one[k][i], rtol=1e-12, atol=1e-14)
    assert np.array_equal(part["region"], one["region"][fitted.BLOCK - 5:])


def test_the_baseline_factors_are_the_baseline_in_sigmas():
    """predict reads the gap as F e^Y + K from fit_groups.baseline_factors, fewer passes
    for the same baseline: F = S (E + FLOOR), K = H_c - FLOOR S, and E at the centre node
    and of the smallest gap, E from baseline_sigmas (to rounding: sums that cancel where
    the web lands are grouped otherwise)."""
    G = fc.design(2048, seed=13)
    E, E_min = fg.baseline_sigmas(G)
    F, K, E_center, E_low = fg.baseline_factors(G)
    S = G[:, fg.GROUPS.index("S")]
    H_c = S * np.log(G[:, fg.GROUPS.index("c")])
    np.testing.assert_allclose(F, S[:, None] * (E + fg.FLOOR_SIGMAS), rtol=1e-12, atol=0)
    np.testing.assert_allclose(K, H_c - fg.FLOOR_SIGMAS * S, rtol=1e-15, atol=0)
    np.testing.assert_allclose(E_center, E[:, len(fg.NODES) // 2], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(E_low, E_min, rtol=1e-12, atol=1e-12)
    assert (E.min() < 1e-3) and (E.max() > 1e3)          # resting and flying both checked


def test_the_read_out_is_the_fit_variables_inverse():
    """predict's gap is the fit's variable over the baseline, inverted: H = fit_to_gap(Y +
    gap_to_fit(baseline)) (the algebra predict shortcuts), and softplus is logaddexp."""
    z = np.concatenate([np.linspace(-800, 800, 4001), [0.0, 1e-300, -1e-300]])
    np.testing.assert_allclose(fg.softplus(z), np.logaddexp(0.0, z), rtol=1e-15, atol=0)
    fit = fitted.coefficients()
    G = fc.design(300, seed=12)
    pr = fitted.predict(G, fit)
    x = (fg.coordinates(G) - fit["lo"]) / (fit["hi"] - fit["lo"])
    Y = fit["stack"](x)
    n = len(fg.NODES)
    S = G[:, fg.GROUPS.index("S")][:, None]
    H_c = S * np.log(G[:, fg.GROUPS.index("c")])[:, None]
    base, base_min = fg.baseline(G)
    H = fg.fit_to_gap(Y[:, :n] + fg.gap_to_fit(base, S, H_c), S, H_c)
    np.testing.assert_allclose(pr["H"], H, rtol=1e-12, atol=1e-12 * np.abs(H).max())
    centre = fg.asinh_to_gap(Y[:, 2 * n + 2] + fg.gap_to_asinh(base[:, n // 2], S[:, 0],
                                                                  H_c[:, 0]), S[:, 0], H_c[:, 0])
    np.testing.assert_allclose(pr["H_center"], centre, rtol=1e-12,
                               atol=1e-12 * np.abs(centre).max())
    # the contact share is fitted in its arcsine transform: predict's share is sin^2 of its
    # column (clipped to [0, pi/2])
    assert fit["share_variable"] == fitted.SHARE_VARIABLE
    np.testing.assert_allclose(pr["share"], np.sin(np.clip(Y[:, -1], 0, np.pi / 2)) ** 2,
                               rtol=1e-12, atol=1e-15)
    s = np.array([-0.1, 0.0, 1e-4, 0.2, 0.5, 0.9, 1.0, 1.2])
    np.testing.assert_allclose(fg.fit_to_share(fg.share_to_fit(s)), np.clip(s, 0, 1),
                               rtol=1e-12, atol=1e-16)


@pytest.mark.parametrize("kind", ["gaussian", "cauchy"])
def test_other_kernels_stack_and_fit_as_the_generic_formula(kind):
    """The build's other radial functions: fitted by the same machinery, and the one-pass
    stack evaluates them as their formula does."""
    from webfem.models.fit_kernel import KINDS, Stack
    from webfem.studies import fit_build as fb
    rng = np.random.default_rng(6)
    x = rng.uniform(size=(80, 3))
    y = np.column_stack([np.sin(3 * x[:, 0]) * x[:, 1], np.cos(2 * x[:, 2])])
    k = fb.fit_kernel(x, y, trend=False, restarts=0, centres=40, kind=kind)
    s = fb.fit_kernel(x, y[:, :1], trend=False, restarts=0, kind=kind)
    assert k.kind == s.kind == kind and len(k.centres) == 40
    xt = rng.uniform(size=(300, 3))
    generic = np.column_stack([
        KINDS[kind](xt, q.centres, q.scales) @ q.weights * q.y_std + q.y_mean for q in (k, s)])
    np.testing.assert_allclose(k(xt), generic[:, :2], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(Stack([k, s])(xt), generic, rtol=1e-10, atol=1e-10)
    fast = Stack([k, s], radial=np.float32)(xt)
    bound = 1e-6 * sum(np.abs(q.weights * q.y_std).sum(axis=0).max() for q in (k, s))
    np.testing.assert_allclose(fast, generic, rtol=0, atol=bound)
    # a smooth function, interpolated: the fit means something
    truth = np.column_stack([np.sin(3 * xt[:, 0]) * xt[:, 1], np.cos(2 * xt[:, 2])])
    assert np.abs(k(xt) - truth).max() < 0.1
    with pytest.raises(ValueError, match="one kind"):
        Stack([k, fb.fit_kernel(x, y, trend=False, restarts=0)])


@pytest.mark.parametrize("bad", [0, -1, 2.5, True])
def test_predict_refuses_a_bad_thread_count_naming_it(bad):
    with pytest.raises(ValueError, match="n_threads"):
        fitted.predict(fc.design(3, seed=1), n_threads=bad)


@pytest.mark.parametrize("name, speed", [("idler", 12.4), ("press_idler", 20.7)])
def test_where_nothing_slides_the_stated_mu_error_bounds_the_true_one(name, speed):
    """mu = mu_cc x contact share on an idler: the cell's mu error (measured on the
    campaign's sliding webs) stated 0.2 here against a true 2.4; the share's error carried
    through bounds it, and the answer says so."""
    case = webfem.load_case(f"cases/{name}.toml").updated(
        {"roller.speed": speed, "web.speed": speed})
    fit, fe = webfem.solve(case, "fitted"), webfem.solve(case, "fe2d")
    true = abs(fit["mu"] - fe["mu"]) / error_scale(case, "mu", fe["mu"])
    assert true > 1.0                       # the fit is far off here: the test can fail
    assert fit["error_mu"] >= true
    assert fit["error_mu"] == pytest.approx(fitted.onset_error(
        fit["mu"], case.friction.mu_cc, fit["error_contact_share"]))
    assert "contact share's stated error carried through" in fit.summary.error_basis


def test_a_sliding_web_keeps_its_cells_mu_error():
    fit = webfem.solve("base", "fitted")
    assert fit.summary.U_slide > 0.0
    assert "carried through" not in fit.summary.error_basis
    assert fit["error_mu"] < 1.0


def test_the_per_point_statement_holds_on_hold_out_points_it_was_not_set_on():
    """The factor holds 95 % of the points it was set on by construction; on points it was
    not set on it must hold nearly as often. The hold-out's two designs (the campaign's own
    321 points and the 314 of another seed) state each other's errors: at least 90 % held in
    every quantity, both ways (fiterr38 measured 92.5-97.5 %; the table per region it
    replaced held mu on 79-82 % of them)."""
    from webfem.models import fit_stated as fs
    loc = fitted.coefficients()["local"]
    X, E = loc["local_x"], loc["local_errors"]
    halves = (np.arange(len(E)) < 321, np.arange(len(E)) >= 321)
    for fit_on, check_on in (halves, halves[::-1]):
        half = fs.calibrate(X[fit_on], E[fit_on], loc["local_scales"], loc["local_metric"],
                            k=int(loc["local_k"]))
        held = (E[check_on] <= fs.stated(X[check_on], half)).mean(axis=0)
        assert np.all(held >= 0.90), held
