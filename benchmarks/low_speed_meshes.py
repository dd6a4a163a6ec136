"""Stated against true mesh errors of fe2d's length rule at two ratios (issue 23, lowspeed10).

Run: ``python benchmarks/low_speed_meshes.py [SPEEDS] [--ratios 1,4] [--case PATH]``
(default: the base case at 0.5, 1, 2 and 5 m/s, ratios 1 and 4; about a minute a speed).
For each speed: the cold fe2d answer at each ``adapt_ratio``, its unknowns and its stated
errors; the true errors against the first ratio's answer with every cell halved once and
twice, Richardson-extrapolated (the order from the two changes; where they do not shrink,
the twice-halved answer itself).
"""

from __future__ import annotations

import argparse
import warnings

import webfem
from webfem import load_case
from webfem.fem.scaling import FoilParameters
from webfem.models.mesh_error import bisected_nodes
from webfem.models.options import FE2DOptions
from webfem.models.readout import error_scale, read_out

QUANTITIES = ("h_min", "h_center", "mu")


def extrapolated(case, result) -> dict:
    """The quantities of ``result``'s mesh halved once and twice, extrapolated."""
    o = FE2DOptions()
    prm = FoilParameters.from_case(case, o.compressible, o.contact, o.floor)
    p, u = result.state("problem"), result.state("state")
    levels = [read_out(case, p, u, prm)]
    for _ in range(2):
        finer = p.variant(X=bisected_nodes(p.X), Z=bisected_nodes(p.Z))
        u, info = finer.solve_newton(p.transfer(u, prm, finer), prm, o)
        if not info.converged:
            raise RuntimeError(f"the halved mesh did not converge: {info.reason}")
        levels.append(read_out(case, finer, u, prm))
        p = finer
    out = {}
    for q in QUANTITIES:
        v = [level.value(q) for level in levels]
        d1, d2 = abs(v[0] - v[1]), abs(v[1] - v[2])
        out[q] = v[2] + (v[2] - v[1]) / (d1 / d2 - 1.0) if 0 < d2 < d1 else v[2]
    return out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("speeds", nargs="?", default="0.5,1,2,5")
    ap.add_argument("--ratios", default="1,4")
    ap.add_argument("--case", default="cases/base.toml")
    args = ap.parse_args(argv)
    warnings.simplefilter("ignore")
    base = load_case(args.case)
    ratios = [float(r) for r in args.ratios.split(",")]
    for speed in (float(s) for s in args.speeds.split(",")):
        case = base.updated({"roller.speed": speed})
        answers = [webfem.solve(case, "fe2d", adapt_ratio=r) for r in ratios]
        true = extrapolated(case, answers[0])
        for ratio, r in zip(ratios, answers):
            print(f"U = {speed:g} m/s, adapt_ratio {ratio:g}: {r['n_dofs']:,} unknowns | "
                  + " | ".join(f"{q} stated {r['error_' + q]:.1e} true "
                               f"{abs(r[q] - true[q]) / error_scale(case, q, true[q]):.1e}"
                               for q in QUANTITIES), flush=True)


if __name__ == "__main__":
    main()
