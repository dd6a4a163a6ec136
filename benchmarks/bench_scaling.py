"""Scaling: time and peak memory of a solve against its unknowns, with the fitted exponent.

Run: ``python benchmarks/bench_scaling.py [--quick]`` (about 4 minutes; ``--quick`` stops at
fe2d level 2 and 2e5 grooved unknowns). Each solve runs in its own process (peak memory is
that process's, imports included, about 90 MB), cold, with the default options except:

* fe2d on cases/base.toml at ``level`` 0-3 (each level bisects every cell: about 4x the
  unknowns), ``estimate=False`` so that the table is one mesh's cost (the default's error
  estimate adds a solve on a mesh with a quarter of the unknowns, and a finer one where it
  asks for it);
* full-width grooved webs (cases/base_grooved.toml, ``grooves="full"``) of growing width, up
  to about 5e5 unknowns.

For each family it fits time = a n^b and memory = c n^d by least squares on the logs and
prints b and d, so that a user can say what a wider or finer problem costs.
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import resource
import time
import warnings
from pathlib import Path

import numpy as np

CASES = Path(__file__).resolve().parent.parent / "webfem" / "cases"


def _child(name, changes, options, queue):
    warnings.simplefilter("ignore")
    from webfem import load_case
    from webfem.models import fe2d
    t0 = time.perf_counter()
    try:
        case = load_case(CASES / f"{name}.toml").updated(changes)
        r = fe2d.solve(case, **options)
        out = dict(n=r["n_dofs"], it=r["iterations"], ok=r["converged"])
    except Exception as err:  # noqa: BLE001 - reported in the table
        out = dict(n=0, it=0, ok=False, error=f"{type(err).__name__}: {err}"[:120])
    out["t"] = time.perf_counter() - t0
    out["mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    queue.put(out)


def run(name, changes, options, limit=600.0):
    """One solve in its own process: unknowns, iterations, time [s], peak memory [MB]."""
    ctx = mp.get_context("fork")
    queue = ctx.Queue()
    p = ctx.Process(target=_child, args=(name, changes, options, queue))
    p.start()
    p.join(limit)
    if p.is_alive():
        p.kill()
        p.join()
        return dict(n=0, it=0, ok=False, t=limit, mb=float("nan"), error="timeout")
    return queue.get() if not queue.empty() else dict(n=0, it=0, ok=False, t=0.0,
                                                      mb=float("nan"),
                                                      error=f"died ({p.exitcode})")


def fit(n, y):
    """Exponent and prefactor of y = a n^b (least squares on the logs)."""
    b, loga = np.polyfit(np.log(n), np.log(y), 1)
    return b, np.exp(loga)


def family(title, rows):
    print(title)
    print(f"  {'what':>22} {'unknowns':>9} {'iter':>5} {'time s':>8} {'peak MB':>8}")
    ok = []
    for label, r in rows:
        print(f"  {label:>22} {r['n']:>9,} {r['it']:>5} {r['t']:>8.2f} {r['mb']:>8.0f}"
              + ("" if r["ok"] else "  " + r.get("error", "not converged")))
        if r["ok"]:
            ok.append(r)
    if len(ok) >= 3:
        n = np.array([r["n"] for r in ok], float)
        bt, at = fit(n, [r["t"] for r in ok])
        bm, am = fit(n, [r["mb"] - 90.0 for r in ok])
        print(f"  fit: time = {at:.3g} s x n^{bt:.2f}; memory above imports = "
              f"{am:.3g} MB x n^{bm:.2f}")
        for m in (1e5, 1e6):
            print(f"    at {m:.0e} unknowns: {at * m ** bt:.3g} s, "
                  f"{90 + am * m ** bm:.0f} MB")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="levels 0-2 and up to 2e5 grooved")
    args = ap.parse_args()
    levels = range(3 if args.quick else 4)
    family("fe2d, cases/base.toml, estimate off, by level (cold, one process each)",
           [(f"level {lv}", run("base", {}, dict(level=lv, estimate=False)))
            for lv in levels])
    widths = (0.1, 0.2, 0.4) if args.quick else (0.1, 0.2, 0.4, 0.8)
    family("fe2d, cases/base_grooved.toml at full width, estimate off, by web width",
           [(f"L = {w:g} m", run("base_grooved", {"web.width": w},
                                 dict(grooves="full", estimate=False))) for w in widths])


if __name__ == "__main__":
    main()
