"""The fitted model's figures (issue 24): coverage of the envelope benchmark's smooth points,
evaluation speed, and its errors against fe2d on fresh points of another design.

    python benchmarks/bench_fitted.py coverage [--points 2000]
    python benchmarks/bench_fitted.py speed [--coefficients FILE.npz]
    python benchmarks/bench_fitted.py fresh [--points 40] [--seed 2024]
    python benchmarks/bench_fitted.py maps [--out docs/fit_errors.png]
    python benchmarks/bench_fitted.py methods [--store out/fit/campaign.csv]
    python benchmarks/bench_fitted.py kernels [--store benchmarks/fit_campaign/campaign.csv]
    python benchmarks/bench_fitted.py bundled [--points 3] [--seed 5]

``methods`` compares fitting methods inside the training set (three quarters fit, the
fourth checks; the hold-out rows are not touched), as docs/fit.md reports.

``kernels`` builds the fit from a campaign with each radial function the one-pass stack
evaluates (the shipped Matern-5/2, a Gaussian, a rational-quadratic), as ``webfem fit
build --fit-only`` does, and gives each one's hold-out errors, a paired bootstrap of its
change against the first's, and predict's speed, alternated.

``bundled`` checks the stated errors against fe2d on the bundled cases at random speeds and
tensions, as idlers (nothing slides: mu's stated error is the contact share's carried
through, ``fitted.onset_error``) and sliding (``--points`` per case and kind, about 2
minutes for 3).

``coverage`` counts the envelope's smooth points that are physically possible (T_eff > 0 and
a thin film; ``envelope_sample.IMPOSSIBLE``) and the share of them inside the domain.
``fresh`` solves points of a Sobol design with another seed (never in the campaign) with
fe2d and reports the error distribution and how often the stated error holds.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))


def coverage(points: int) -> None:
    import envelope_sample as es
    from webfem.models import fit_groups as fg
    possible = inside = 0
    why: dict[str, int] = {}
    for case in es.smooth_possible(points):
        possible += 1
        text = fg.outside(case)
        if text is None:
            inside += 1
        else:
            key = text.split(" = ")[0]
            why[key] = why.get(key, 0) + 1
    print(f"envelope points 0-{points - 1}: {possible} smooth and possible, {inside} inside "
          f"the fitted domain ({inside / possible:.1%}); outside by group: {why}")


def speed(coefficients: str | None = None) -> None:
    """The speed targets of issue 24, each figure beside its target (best of three runs by
    wall time, with that run's CPU time, summed over the threads: the machine's load counts,
    so the load average is printed before and after); ``coefficients``: another fit's
    file."""
    import os
    import webfem
    from webfem import Case
    from webfem.models import fit_groups as fg
    from webfem.models import fitted
    fit = fitted.coefficients(coefficients)
    case = Case()
    webfem.solve(case, model="fitted", coefficients=coefficients)
    load = os.getloadavg()[0]

    def best(f, repeat=3):
        times = []
        for _ in range(repeat):
            t0, c0 = time.perf_counter(), time.process_time()
            f()
            times.append((time.perf_counter() - t0, time.process_time() - c0))
        return min(times)
    n = 200
    one, one_cpu = (t / n for t in best(
        lambda: [webfem.solve(case, model="fitted", coefficients=coefficients)
                 for _ in range(n)]))
    cases = [case.updated({"roller.speed": float(u)}) for u in np.linspace(15, 40, 10_000)]
    many, many_cpu = best(lambda: webfem.solve_many(cases, model="fitted",
                                                    coefficients=coefficients))
    G = np.repeat(fg.group_array(fg.groups_of(case)), 100_000, axis=0)
    G *= np.exp(np.random.default_rng(0).uniform(-0.1, 0.1, G.shape))
    raw, raw_cpu = best(lambda: fitted.predict(G, fit))
    raw1, raw1_cpu = best(lambda: fitted.predict(G, fit, n_threads=1))
    x = (fg.coordinates(G) - fit["lo"]) / (fit["hi"] - fit["lo"])
    kernels = [fit["kernel"], *fit["scalars"]]
    if fit.get("stack") is not None:      # the kernels in one pass, as predict runs them
        b = getattr(fitted, "BLOCK", len(G))
        kernel, kernel_cpu = best(
            lambda: [fit["stack"](x[i:i + b]) for i in range(0, len(x), b)])
    else:
        kernel, kernel_cpu = best(lambda: [k(x) for k in kernels])
    m = len(G)
    print(f"load average {load:.1f} -> {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores; "
          "fit: " + ", ".join(f"{len(k.centres)} centres x {k.weights.shape[1]} outputs"
                              for k in kernels))
    print("                                           wall                 CPU")
    print(f"one webfem.solve(model='fitted'):       {one * 1e3:8.3f} ms        "
          f"{one_cpu * 1e3:8.3f} ms    (target <= 1 ms)")
    print(f"webfem.solve_many of 10,000 (results):  {many:8.3f} s         "
          f"{many_cpu:8.3f} s     (target <= 1 s)")
    print(f"fitted.predict (raw profile, 100,000):  {m / raw:8.3g} points/s  "
          f"{raw_cpu / m * 1e6:8.2f} us/point (target >= 1e6 points/s; "
          f"{min(fitted.threads(), -(-m // fitted.BLOCK))} threads)")
    print(f"  on one thread:                        {m / raw1:8.3g} points/s  "
          f"{raw1_cpu / m * 1e6:8.2f} us/point")
    print(f"  of which the kernels alone:           {m / kernel:8.3g} points/s  "
          f"{kernel_cpu / m * 1e6:8.2f} us/point (one thread)")


def fresh(points: int, seed: int) -> None:
    import webfem
    from webfem.models import fit_groups as fg
    from webfem.models.readout import READ_QUANTITIES, error_scale
    from webfem.studies import fit_campaign as fc
    from webfem.studies.fit_build import DN_EDGES
    G = fc.design(points, seed=seed)
    errs = {q: [] for q in READ_QUANTITIES}
    ratio = {q: [] for q in READ_QUANTITIES}
    Dn = []
    failed = 0
    t0 = time.perf_counter()
    for i, row in enumerate(G):
        g = dict(zip(fg.GROUPS, row))
        case = fc.case_of_groups(g)
        ref = fc.solve_point(i, g, timeout=30.0, options=fc.FE2D_OPTIONS)
        if not ref["converged"]:
            failed += 1
            continue
        r = webfem.solve(case, model="fitted")
        Dn.append(g["Dn"])
        for q in READ_QUANTITIES:
            e = abs(r[q] - ref[q]) / error_scale(case, q, ref[q])
            errs[q].append(e)
            ratio[q].append(e / r[f"error_{q}"])
    print(f"{points} fresh points (seed {seed}), {failed} without an fe2d answer, "
          f"{time.perf_counter() - t0:.0f} s")
    for q in READ_QUANTITIES:
        e, k = np.array(errs[q]), np.array(ratio[q])
        print(f"  {q:<14} error 50/90/95 %: " + " ".join(
            f"{v:.3g}" for v in np.percentile(e, [50, 90, 95]))
              + f"; within stated {np.mean(k <= 1):.0%}, within 2x stated {np.mean(k <= 2):.0%}")
    # the stated table's Dn bands (fit_build.DN_EDGES): the share within the stated error
    Dn = np.array(Dn)
    band = np.searchsorted(DN_EDGES, Dn)
    for b, name in enumerate(("Dn < 1", "Dn 1-100", "Dn > 100")):
        m = band == b
        print(f"  {name:<9} ({m.sum()} points) within stated: " + " / ".join(
            f"{np.mean(np.array(ratio[q])[m] <= 1):.0%}" for q in READ_QUANTITIES)
              + " (" + " / ".join(READ_QUANTITIES) + ")")


def maps(out: str) -> None:
    """The hold-out errors of the shipped fit against each group (docs/fit.md)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from webfem.models import fit_groups as fg
    from webfem.models import fitted
    from webfem.models.readout import error_scale
    from webfem.studies import fit_campaign as fc
    data = np.load(fitted.COEFFICIENTS)
    G, V = data["holdout_groups"], data["holdout_values"]
    pr = fitted.predict(G)
    E = np.empty(V.shape)
    for i, g in enumerate(G):
        case = fc.case_of_groups(dict(zip(fg.GROUPS, g)))
        v = fitted.read_profile(case, pr["H"][i], pr["P"][i], pr["H_min"][i], pr["s_min"][i],
                                *(None if pr.get(k) is None else pr[k][i]
                                  for k in ("H_center", "share")))
        for j, q in enumerate(fitted.QUANTITIES):
            E[i, j] = abs(v[q] - V[i, j]) / error_scale(case, q, V[i, j])
    fig, axes = plt.subplots(2, 4, figsize=(14, 6.5), sharey=True)
    for ax, k in zip(axes.ravel(), range(len(fg.GROUPS))):
        x = np.where(G[:, k] > 0, G[:, k], fg.KB_FLOOR / 3)
        for j, q in enumerate(fitted.QUANTITIES):
            ax.loglog(x, np.maximum(E[:, j], 1e-6), ".", ms=4, label=q)
        ax.set_xlabel(fg.GROUPS[k] + (" (0 plotted at 3e-4)" if fg.GROUPS[k] == "Kb" else ""))
        ax.axhline(0.01, color="k", lw=0.6)
        if fg.GROUPS[k] == "Dn":     # the stated table's Dn bands
            from webfem.studies.fit_build import DN_EDGES
            for edge in DN_EDGES:
                ax.axvline(edge, color="grey", lw=0.8, ls="--")
            ax.set_xlabel("Dn (dashed: the stated table's bands)")
    axes[0, 0].set_ylabel("hold-out error")
    axes[1, 0].set_ylabel("hold-out error")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle(f"fitted model: hold-out error against each group ({len(G)} points never "
                 "used in fitting; line: 1 %; errors below 1e-6 drawn at 1e-6)")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")


def methods(store: str) -> None:
    from webfem.models import fit_groups as fg
    from webfem.studies import fit_build as fb
    from webfem.sweeps.table import read_table, typed
    rows = [r for r in typed(read_table(store).rows) if r["converged"] and not r["holdout"]]
    check, train = rows[3::4], [r for i, r in enumerate(rows) if i % 4 != 3]
    lo, hi = fg.box()
    lo = lo.copy()
    lo[fg.GROUPS.index("Kb")] -= 0.3
    x = fb.unit(np.array([[r[f"g_{g}"] for g in fg.GROUPS] for r in train]), lo, hi)
    y = fb.targets(train)
    gaps = np.r_[np.arange(len(fg.NODES)), 2 * len(fg.NODES)]
    yc = y.copy()
    yc[:, gaps] = np.clip(yc[:, gaps], -fb.CLIP, fb.CLIP)
    n = len(fg.NODES)
    mean = np.r_[np.zeros(n), y[:, n:2 * n].mean(0), 0.0, y[:, -1].mean()]
    gp = fb.fit_kernel(x, yc, trend=False)
    from webfem.models.fit_kernel import Kernel

    def components(k):
        """The GP with its outputs kept in their first k principal components (rank-k
        weights: a cheaper weight product if it kept the accuracy)."""
        _, _, Vt = np.linalg.svd((yc - gp.y_mean) / gp.y_std, full_matrices=False)
        V = Vt[:k].T
        return Kernel(gp.centres, gp.scales, gp.trend, gp.weights @ V @ V.T, gp.y_mean,
                      gp.y_std)
    cols_g = list(range(n)) + [2 * n]           # the gap variables, then the rest
    cols_p = list(range(n, 2 * n)) + [2 * n + 1]
    kg, kp = (fb.fit_kernel(x, yc[:, c], trend=False) for c in (cols_g, cols_p))

    def two(X):
        out = np.empty((len(X), y.shape[1]))
        out[:, cols_g], out[:, cols_p] = kg(X), kp(X)
        return out
    candidates = {
        "baseline alone": lambda X: np.zeros((len(X), y.shape[1])) + mean,
        "GP Matern-5/2, no trend, clipped (chosen)": gp,
        "GP Matern-5/2, no trend, not clipped": fb.fit_kernel(x, y, trend=False),
        "GP Matern-5/2, linear trend, clipped": fb.fit_kernel(x, yc, trend=True),
        "thin-plate spline, isotropic, clipped": fb.fit_thin_plate(x, yc, np.ones(x.shape[1])),
        "thin-plate spline, GP length scales, clipped": fb.fit_thin_plate(x, yc, gp.scales),
        "GP, outputs in their first 10 principal components": components(10),
        "GP, outputs in their first 24 principal components": components(24),
        "two GPs, gaps and pressures apart": two}
    print(f"{len(train)} fit, {len(check)} check; median / 95th percentile")
    for name, kern in candidates.items():
        e = fb.holdout_errors(check, {"kernel": kern, "lo": lo, "hi": hi,
                                      "edges": fb.REGION_EDGES})
        print(f"| {name} | " + " | ".join(
            f"{np.percentile(e[q], 50):.2g} / {np.percentile(e[q], 95):.2g}"
            for q in ("h_center", "h_min", "mu", "contact_share")) + " |")


def holdout_percentiles(npz: str) -> dict[str, np.ndarray]:
    """Per hold-out row of a coefficients file, its fit's errors (as the build states them)."""
    from webfem.models import fit_groups as fg
    from webfem.models import fitted
    from webfem.studies import fit_build as fb
    fit = fitted.coefficients(npz)
    data = np.load(npz)
    rows = [{**{f"g_{g}": v for g, v in zip(fg.GROUPS, G)}, **dict(zip(fitted.QUANTITIES, V))}
            for G, V in zip(data["holdout_groups"], data["holdout_values"])]
    return fb.holdout_errors(rows, fit)


def kernels(store: str) -> None:
    import tempfile
    from webfem import Case
    from webfem.models import fit_groups as fg
    from webfem.models import fitted
    from webfem.studies import fit_build as fb
    kinds = ("matern52", "gaussian", "cauchy")
    errs, fits = {}, {}
    with tempfile.TemporaryDirectory() as tmp:
        for kind in kinds:
            out = f"{tmp}/{kind}.npz"
            t0 = time.perf_counter()
            fb.build(store, out, kind=kind)
            errs[kind], fits[kind] = holdout_percentiles(out), fitted.coefficients(out)
            print(f"{kind}: built in {time.perf_counter() - t0:.0f} s; hold-out 50 / 90 / 95 "
                  "% / max")
            for q in fitted.QUANTITIES:
                print(f"  {q:<14}" + " / ".join(
                    f"{v:.3g}" for v in np.percentile(errs[kind][q], [50, 90, 95, 100])))
    rng = np.random.default_rng(0)
    a = errs[kinds[0]]
    idx = rng.integers(0, len(a["mu"]), (2000, len(a["mu"])))
    for kind in kinds[1:]:
        print(f"{kind} - {kinds[0]}: change and its paired bootstrap's 95 % interval")
        for q in fitted.QUANTITIES:
            A, B = a[q][idx], errs[kind][q][idx]
            for name, f in (("median", np.median), ("95th", lambda v, axis=None:
                                                      np.percentile(v, 95, axis=axis))):
                d = f(B, axis=1) - f(A, axis=1)
                print(f"  {q:<14} {name:<6} {f(errs[kind][q]) - f(a[q]):+.3g} "
                      f"[{np.percentile(d, 2.5):+.3g}, {np.percentile(d, 97.5):+.3g}]")
    G = np.repeat(fg.group_array(fg.groups_of(Case())), 100_000, axis=0)
    G *= np.exp(np.random.default_rng(0).uniform(-0.1, 0.1, G.shape))
    speed = {k: [] for k in kinds}
    for _ in range(3):                   # alternated: the machine's load moves
        for kind in kinds:
            for n in (1, None):
                t0 = time.perf_counter()
                fitted.predict(G, fits[kind], n_threads=n)
                speed[kind].append((n, len(G) / (time.perf_counter() - t0)))
    for kind, v in speed.items():
        one = [s for n, s in v if n == 1]
        many = [s for n, s in v if n is None]
        print(f"{kind}: predict {min(one):.3g}-{max(one):.3g} points/s on one thread, "
              f"{min(many):.3g}-{max(many):.3g} on {fitted.threads()}")


#: The bundled cases ``bundled`` varies: (case, whether the web moves with the roller).
BUNDLED = (("idler", True), ("pet_idler", True), ("board", True), ("press_idler", True),
           ("base", False), ("driven_roller", False), ("foil_roller", False),
           ("pet_idler", False), ("press_idler", False), ("idler", False))


def bundled(points: int, seed: int) -> None:
    """The fitted model against fe2d on the bundled cases at random speeds 3-25 m/s and
    tensions 0.6-1.6 times the case's: idlers as idlers (nothing slides: mu's stated error
    is the contact share's carried through, ``fitted.onset_error``) and sliding (the web at
    0-0.8 times the roller's speed, or at the case's own ratio for a driven roller or a
    foil roller); per point the true and stated errors, then how often each quantity's
    true error exceeds its stated one."""
    import warnings

    import webfem
    from webfem.errors import ConvergenceError, InputError
    from webfem.models.fitted import QUANTITIES
    from webfem.models.readout import error_scale

    warnings.simplefilter("ignore")
    rng = np.random.default_rng(seed)
    counts = {idle: [0, {q: 0 for q in QUANTITIES}, {q: 0 for q in QUANTITIES}]
              for idle in (True, False)}
    for name, idle in BUNDLED:
        base = webfem.load_case(f"cases/{name}.toml")
        for _ in range(points):
            u = float(rng.uniform(3.0, 25.0))
            ratio = (1.0 if idle else base.web.speed / base.roller.speed
                     if name in ("driven_roller", "foil_roller") else rng.uniform(0.0, 0.8))
            case = base.updated({"roller.speed": u, "web.speed": float(u * ratio),
                                 "web.tension": float(base.web.tension
                                                      * rng.uniform(0.6, 1.6))})
            try:
                fit, fe = webfem.solve(case, "fitted"), webfem.solve(case, "fe2d")
            except (InputError, ConvergenceError) as e:
                print(f"{name:13s} U = {u:5.1f} m/s: not compared ({str(e)[:70]})")
                continue
            c = counts[idle]
            c[0] += 1
            text = []
            for q in QUANTITIES:
                true = abs(fit[q] - fe[q]) / error_scale(case, q, fe[q])
                c[1][q] += true > fit[f"error_{q}"]
                c[2][q] += true > 2.0 * fit[f"error_{q}"]
                text.append(f"{q} {true:.2f}/{fit[f'error_{q}']:.2f}")
            print(f"{name:13s} {'idler  ' if idle else 'sliding'} U_r = {u:5.1f}, U_s = "
                  f"{case.U_slide:5.1f} m/s; error true/stated: " + ", ".join(text))
    for idle, (n, over, over2) in counts.items():
        print(f"{'idlers (nothing slides)' if idle else 'sliding webs'}: {n} points; true "
              f"error above the stated one: " + ", ".join(f"{q} {over[q]}" for q in over)
              + "; above twice it: " + ", ".join(f"{q} {over2[q]}" for q in over2))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("coverage", "speed", "fresh", "maps", "methods",
                                     "kernels", "bundled"))
    ap.add_argument("--store", default="out/fit/campaign.csv")
    ap.add_argument("--out", default="docs/fit_errors.png")
    ap.add_argument("--points", type=int, default=None)
    ap.add_argument("--seed", type=int, default=2024)
    ap.add_argument("--coefficients", default=None, help="speed: another fit's .npz file")
    a = ap.parse_args()
    if a.what == "coverage":
        coverage(a.points or 2000)
    elif a.what == "speed":
        speed(a.coefficients)
    elif a.what == "maps":
        maps(a.out)
    elif a.what == "methods":
        methods(a.store)
    elif a.what == "kernels":
        kernels(a.store if a.store != "out/fit/campaign.csv"
                else "benchmarks/fit_campaign/campaign.csv")
    elif a.what == "bundled":
        bundled(a.points or 3, a.seed if a.seed != 2024 else 5)
    else:
        fresh(a.points or 40, a.seed)


if __name__ == "__main__":
    main()
