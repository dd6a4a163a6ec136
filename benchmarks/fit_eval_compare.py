"""The fitted model's evaluation against another tree's (e.g. main's), in one process: its
CPU time a point and how far its answers moved (docs/fit.md, "Speed").

    python benchmarks/fit_eval_compare.py speed OTHER_TREE [--rounds 200]
    python benchmarks/fit_eval_compare.py accuracy OTHER_TREE [--points 100000]

OTHER_TREE is a checkout of webfem (a worktree of main, say); its ``webfem`` package is
copied to a temporary directory and imported as ``webfem_other`` beside this tree's.

``speed`` times ``fitted._predict`` and the kernels (``Stack.evaluate``) of each on blocks
of 2048 points of the speed benchmark's (``bench_fitted.py speed``: the base case's groups
scattered by +-10 %), one BLAS thread, interleaved round by round with the order
alternating, so the machine's load falls on both alike: CPU time a point (min / median /
90th percentile) and the median of the paired ratios, the figure to trust on a loaded
machine (wall times there follow the other jobs).

``accuracy`` predicts the hold-out rows and ``--points`` random points of the fit's box
(uniform in its coordinates, seed 38; a point whose case is outside the keys' ranges or
the domain is left out) with each, reads them out as the model does (h_center, h_min, mu,
contact share) and prints the largest difference in webfem's error measures
(``readout.error_scale``) and relative to each point's stated error, and whether every
point keeps its stated-error cell.
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

BLOCK = 2048


def _other(tree: str):
    """The other tree's webfem, imported as ``webfem_other`` (its imports are relative)."""
    tmp = Path(tempfile.mkdtemp(prefix="webfem_other_"))
    shutil.copytree(Path(tree) / "webfem", tmp / "webfem_other",
                    ignore=shutil.ignore_patterns("__pycache__"))
    sys.path.insert(0, str(tmp))
    from webfem_other.models import fitted
    return fitted


def speed(tree: str, rounds: int) -> None:
    from webfem import Case
    from webfem.models import fit_groups as fg, fitted
    from webfem.models.fit_kernel import blas_one_thread
    other = _other(tree)
    fit, fit_o = fitted.coefficients(), other.coefficients()
    G = np.repeat(fg.group_array(fg.groups_of(Case())), 100_000, axis=0)
    G *= np.exp(np.random.default_rng(0).uniform(-0.1, 0.1, G.shape))
    x = (fg.coordinates(G) - fit["lo"]) / (fit["hi"] - fit["lo"])
    runs = {"other predict": lambda g, xb: other._predict(g, fit_o, fit_o["stack"]),
            "this predict": lambda g, xb: fitted._predict(g, fit, fit["stack"]),
            "other kernels": lambda g, xb: fit_o["stack"].evaluate(xb),
            "this kernels": lambda g, xb: fit["stack"].evaluate(xb)}
    t = {k: [] for k in runs}
    nb = len(G) // BLOCK
    load = os.getloadavg()[0]
    with blas_one_thread():
        for j in range(rounds):
            rows = slice((j % nb) * BLOCK, (j % nb + 1) * BLOCK)
            for k in (runs if j % 2 else list(runs)[::-1]):
                c = time.thread_time()
                runs[k](G[rows], x[rows])
                t[k].append(time.thread_time() - c)
    t = {k: np.array(v) / BLOCK * 1e6 for k, v in t.items()}
    print(f"load average {load:.1f} -> {os.getloadavg()[0]:.1f}; {rounds} rounds of {BLOCK} "
          "points, one thread; CPU us a point, min / median / 90th percentile")
    for k, v in t.items():
        print(f"  {k:14s} {v.min():.3f} / {np.median(v):.3f} / {np.percentile(v, 90):.3f}")
    for what in ("predict", "kernels"):
        r = t[f"this {what}"] / t[f"other {what}"]
        print(f"  this / other {what}: median of the paired ratios {np.median(r):.3f} "
              f"(25-75 %: {np.percentile(r, 25):.3f}-{np.percentile(r, 75):.3f})")


def _answers(fitted, G, v):
    fit = fitted.coefficients()
    pr = fitted.predict(G, fit)
    r = fitted.read_profiles(v, pr["H"], pr["P"], pr["H_min"], pr["s_min"], pr.get("H_center"),
                             pr.get("share"))
    return r, fit["errors"][pr["region"]], pr["region"]


def accuracy(tree: str, points: int) -> None:
    from webfem.errors import InputError
    from webfem.models import fit_groups as fg, fitted
    from webfem.physics.effects import MU_SCALE
    from webfem.studies import fit_campaign as fc
    other = _other(tree)
    lo, hi = fg.box()
    x = lo + np.random.default_rng(38).uniform(size=(points, len(lo))) * (hi - lo)
    G = 10.0 ** x
    kb = fg.GROUPS.index("Kb")
    G[:, kb] = np.maximum(G[:, kb] - fg.KB_FLOOR, 0.0)
    holdout = np.load(fitted.COEFFICIENTS)["holdout_groups"]
    G = np.vstack([holdout, G])
    cases, made = [], np.zeros(len(G), bool)
    for i, g in enumerate(G):
        try:
            cases.append(fc.case_of_groups(dict(zip(fg.GROUPS, g))))
            made[i] = True
        except InputError:        # a group the keys' ranges cannot reach
            pass
    v = fg.case_columns(cases)
    Gc = fg.groups_of_columns(v)
    inside = fg.outside_rows(Gc) < 0
    v, Gc = {k: a[inside] for k, a in v.items()}, Gc[inside]
    n_hold = int(inside[:int(made[:len(holdout)].sum())].sum())
    (a, ea, ra), (b, eb, rb) = _answers(fitted, Gc, v), _answers(other, Gc, v)
    print(f"{n_hold} hold-out rows and {len(Gc) - n_hold} of {points} random points; "
          f"stated-error cells equal: {np.array_equal(ra, rb)} "
          f"({int(np.sum(ra != rb))} differ)")
    print("largest |this - other| in the error measures; relative to each point's stated "
          "error (hold-out / random)")
    for j, q in enumerate(fitted.QUANTITIES):
        if q == "contact_share":
            scale = np.ones(len(Gc))
        elif q == "mu":
            scale = np.maximum(np.abs(b[q]), MU_SCALE * v["mu_cc"])
        else:
            scale = np.maximum(np.abs(b[q]), v["sigma"])
        e = np.abs(a[q] - b[q]) / scale
        rel = e / np.minimum(ea[:, j], eb[:, j])
        print(f"  {q:14s} {e[:n_hold].max():.2g} / {e[n_hold:].max():.2g}; relative "
              f"{rel[:n_hold].max():.2g} / {rel[n_hold:].max():.2g}")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="what", required=True)
    s = sub.add_parser("speed")
    s.add_argument("tree")
    s.add_argument("--rounds", type=int, default=200)
    s = sub.add_parser("accuracy")
    s.add_argument("tree")
    s.add_argument("--points", type=int, default=100_000)
    a = p.parse_args()
    if a.what == "speed":
        speed(a.tree, a.rounds)
    else:
        accuracy(a.tree, a.points)


if __name__ == "__main__":
    main()
