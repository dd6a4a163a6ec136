"""Whether the fitted model's stated errors bound its true ones, in every quantity, on data
never used to choose how they are stated: families of the bundled cases and fresh design
points, each solved once by fe2d into a cache (docs/fit.md, "Stated errors per point").

    python benchmarks/fit_stated_check.py solve CACHE.jsonl [--fresh 160 --seed 4242]
        [--families base,idler]          # fe2d references, resumable (minutes to an hour)
    python benchmarks/fit_stated_check.py check CACHE.jsonl OLD.npz NEW.npz ... [--scale
        reference]
    python benchmarks/fit_stated_check.py envelope OLD.npz NEW.npz   # stated over the envelope
    python benchmarks/fit_stated_check.py holdout [NPZ] [--scale reference]
        # the hold-out split in two

``solve`` solves with fe2d (default options, its own stated error kept) the bundled cases
base, driven_roller, foil_roller, idler, pet_idler and press_idler at 5-30 m/s and 0.6-1.6
times their tension (the points inside the fitted domain; the web at the case's own speed
ratio), then the first ``--fresh`` points of a design of seed ``--seed`` (the campaign's
seed is 24, the extra hold-out's 7; fe2d without its estimate, as the campaign); each
answer is appended to the cache as it comes, so an interrupted run continues. ``check``
prints, per coefficients file, set and quantity, how often the true error exceeds the
stated one, the worst ratio and the median stated/true; the true error is measured as
benchmarks/model_error_families.py measures it (against the fitted answer's scale, less the
reference's own stated error; ``--scale reference``: against the reference's, as the
hold-out's errors are measured). ``holdout`` splits the coefficients file's hold-out points
into the campaign's (the first 321) and the extra design's and states each half's errors
from the other half alone, by the table per region and per point
(:mod:`webfem.models.fit_stated`, calibrated on that half as the build calibrates it on
all), and prints the same figures: the hold-out by cross-validation (the errors against
the smaller of the reference's and the answer's scales; ``--scale reference``: the
reference's alone). ``envelope`` prints, over the envelope benchmark's first 2000 points
that are smooth, possible and inside the domain, the median stated errors and the share of
points whose every stated error is within tol (where auto, judging every quantity, takes
the fit if the closed form has no answer within it).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
import warnings
from pathlib import Path

import numpy as np

FAMILIES = ("base", "driven_roller", "foil_roller", "idler", "pet_idler", "press_idler")
QUANTITIES = ("h_center", "h_min", "mu", "contact_share")


def _family_cases(name):
    import webfem
    base = webfem.load_case(f"cases/{name}.toml")
    ratio = base.web.speed / base.roller.speed if base.roller.speed else 0.0
    for U in (5.0, 10.0, 15.0, 20.0, 25.0, 30.0):
        for f in (0.6, 0.8, 1.0, 1.3, 1.6):
            yield f"{name} {U:g} {f:g}", {"roller.speed": U, "web.speed": U * ratio,
                                          "web.tension": base.web.tension * f}


def case_of(key: str):
    """The case a cache row's key names ("base 20 0.8" or "seed 4242 17")."""
    import webfem
    from webfem.models import fit_groups as fg
    from webfem.studies import fit_campaign as fc
    parts = key.split()
    if parts[0] == "seed":
        seed, i = int(parts[1]), int(parts[2])
        return fc.case_of_groups(dict(zip(fg.GROUPS, fc.design(i + 1, seed=seed)[i])))
    base = webfem.load_case(f"cases/{parts[0]}.toml")
    ratio = base.web.speed / base.roller.speed if base.roller.speed else 0.0
    U, f = float(parts[1]), float(parts[2])
    return base.updated({"roller.speed": U, "web.speed": U * ratio,
                         "web.tension": base.web.tension * f})


def solve(cache: Path, fresh: int, seed: int, families) -> None:
    import webfem
    from webfem.errors import ConvergenceError, InputError, NoAdmissibleSolution
    from webfem.models import fit_groups as fg
    from webfem.studies import fit_campaign as fc
    done = {json.loads(line)["key"] for line in cache.open()} if cache.exists() else set()
    t0, c0, n = time.perf_counter(), time.process_time(), 0

    def keep(row):
        with cache.open("a") as f:
            f.write(json.dumps(row) + "\n")

    for name in families:
        for key, values in _family_cases(name):
            if key in done:
                continue
            row = {"key": key, "converged": False}
            try:
                case = case_of(key)
                if fg.outside(case) is None:
                    ref = webfem.solve(case, model="fe2d")
                    row.update(converged=True, **{q: ref[q] for q in QUANTITIES},
                               **{f"error_{q}": ref[f"error_{q}"] or 0.0 for q in QUANTITIES})
                else:
                    row["message"] = "outside the fitted domain"
            except (InputError, ConvergenceError, NoAdmissibleSolution) as err:
                row["message"] = str(err)[:200]
            keep(row)
            n += 1
    G = fc.design(fresh, seed=seed) if fresh else []
    for i, g in enumerate(G):
        key = f"seed {seed} {i}"
        if key in done:
            continue
        ref = fc.solve_point(i, dict(zip(fg.GROUPS, g)), timeout=30.0,
                             options=fc.FE2D_OPTIONS)
        row = {"key": key, "converged": bool(ref["converged"])}
        if ref["converged"]:
            row.update({q: ref[q] for q in QUANTITIES}, **{f"error_{q}": 0.0 for q in QUANTITIES})
        keep(row)
        n += 1
    print(f"{n} points solved in {time.perf_counter() - t0:.0f} s "
          f"({time.process_time() - c0:.0f} s CPU)")


def _line(q, true, stated) -> str:
    over = true > stated
    return (f"    {q:14s} {over.sum():3d} ({over.mean():.3f}, worst "
            f"{np.max(true / stated):.2f}); {np.median(stated / np.maximum(true, 1e-12)):8.3g}; "
            f"{np.median(stated):.3g}")


def holdout(npz: str, first: int = 321, either: bool = False) -> None:
    from webfem.models import fit_groups as fg
    from webfem.models import fit_stated as fs
    from webfem.models.fitted import coefficients
    from webfem.studies import fit_build as fb
    fit = coefficients.__wrapped__(npz)
    with np.load(npz) as d:
        G, V = d["holdout_groups"], d["holdout_values"]
    rows = [{**{f"g_{g}": v for g, v in zip(fg.GROUPS, g_)}, **dict(zip(QUANTITIES, v_))}
            for g_, v_ in zip(G, V)]
    errs = fb.holdout_errors(rows, fit)
    E = np.column_stack([errs[q + (fb.EITHER if either else "")] for q in QUANTITIES])
    halves = np.arange(len(G)) < first
    for name, pool in (("campaign's -> extra design's", halves),
                       ("extra design's -> campaign's", ~halves)):
        test = ~pool
        sub = {q: a[pool] for q, a in errs.items() if q != "region"}
        sub["region"] = errs["region"][pool]
        table = fb.region_errors(sub)[errs["region"][test]]
        local = fb.local_arrays(G[pool], sub, fit)
        pr = __import__("webfem.models.fitted", fromlist=["predict"]).predict(G[test], fit)
        coords = fs.coordinates(fb.unit(G[test], fit["lo"], fit["hi"]),
                                pr["H_min"] / G[test, fg.GROUPS.index("S")], pr["share"])
        per_point = fs.stated(coords, local)
        for how, st in (("table per region", table), ("per point", per_point)):
            print(f"  {name} ({pool.sum()} -> {test.sum()}), {how}: true > stated at n "
                  "(fraction, worst ratio); median stated/true; median stated")
            for j, q in enumerate(QUANTITIES):
                print(_line(q, E[test, j], st[:, j]))


def envelope(files) -> None:
    sys.path.insert(0, str(Path(__file__).parent))
    import envelope_sample as es
    from webfem.models import fit_groups as fg
    from webfem.models import fitted
    from webfem.models.options import FittedOptions
    cases = [c for c in es.smooth_possible(2000) if fg.outside(c) is None]
    print(f"{len(cases)} envelope points inside the domain")
    for path in files:
        res = fitted.solve_many(cases, FittedOptions(coefficients=path))
        S = np.array([[r[f"error_{q}"] for q in QUANTITIES] for r in res])
        print(f"{path}: median stated " + " / ".join(f"{v:.3f}" for v in np.median(S, 0))
              + "; every stated error within tol 0.3 / 0.5 / 0.7 / 1: "
              + " / ".join(f"{np.mean(S.max(1) <= t):.1%}" for t in (0.3, 0.5, 0.7, 1.0)))


def check(cache: Path, files, scale: str = "answer") -> None:
    from webfem.models import fitted
    from webfem.models.options import FittedOptions
    from webfem.models.readout import error_scale
    rows = [r for r in map(json.loads, cache.open()) if r["converged"]]
    cases = [case_of(r["key"]) for r in rows]
    group = np.array([" ".join(r["key"].split()[:2]) if r["key"].startswith("seed")
                      else "families" for r in rows])
    base = np.array([r["key"].startswith("base ") for r in rows])
    for path in files:
        res = fitted.solve_many(cases, FittedOptions(coefficients=path))
        print(path)
        for name in ["families", "of which base"] + sorted(set(group) - {"families"}):
            m = base if name == "of which base" else group == name
            if not m.any():
                continue
            print(f"  {name} ({m.sum()} points): true > stated at n (fraction, worst ratio); "
                  "median stated/true; median stated")
            for q in QUANTITIES:
                true = np.array([max(abs(x[q] - r[q]) / error_scale(
                                         c, q, x[q] if scale == "answer" else r[q])
                                     - r[f"error_{q}"], 0.0)
                                 for x, r, c, k in zip(res, rows, cases, m) if k])
                stated = np.array([x[f"error_{q}"] for x, k in zip(res, m) if k])
                print(_line(q, true, stated))


def main() -> int:
    warnings.simplefilter("ignore")
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("solve", "check", "holdout", "envelope"))
    ap.add_argument("cache", nargs="?", type=Path)
    ap.add_argument("files", nargs="*")
    ap.add_argument("--fresh", type=int, default=0)
    ap.add_argument("--seed", type=int, default=4242)
    ap.add_argument("--families", default=",".join(FAMILIES),
                    help="solve: the bundled cases whose families to solve (comma-separated)")
    ap.add_argument("--scale", choices=("answer", "reference"), default="answer",
                    help="check: measure the error against the fitted answer's value (as "
                         "model_error_families.py) or the reference's (as the hold-out)")
    a = ap.parse_args()
    if a.what == "solve":
        solve(a.cache, a.fresh, a.seed, tuple(f for f in a.families.split(",") if f))
    elif a.what == "envelope":
        envelope([str(a.cache), *a.files])
    elif a.what == "holdout":
        holdout(str(a.cache or "webfem/models/fitted_coefficients.npz"),
                either=a.scale == "answer")
    else:
        check(a.cache, a.files, a.scale)
    return 0


if __name__ == "__main__":
    sys.exit(main())
