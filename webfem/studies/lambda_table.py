"""Eq. 21 against the converged 2-D solution over the width parameter lambda = 7 ... 100.

For the base case at a roller speed where the web flies (fluid film everywhere), the web width
sets lambda; the 2-D central gap on the default mesh and on one refinement (their difference is
the discretisation error estimate) is compared with Eq. 21, for the paper's permeable newsprint
and for an impermeable web (which isolates Eq. 21's width fit from its permeation term).

Run: ``python -m webfem.studies.lambda_table --out docs`` (about a minute).
Writes ``lambda_table.csv``, ``lambda_table.md`` and ``lambda_table.png``.
"""

from __future__ import annotations

import argparse
import csv
from pathlib import Path


from .. import Case, solve

LAMBDAS = (7.0, 10.0, 15.0, 20.0, 30.0, 50.0, 70.0, 100.0)


def run(out: Path, speed: float = 40.0, lambdas=LAMBDAS) -> list[dict]:
    rows = []
    for k in (5e-15, 0.0):
        base = Case().updated({"roller.speed": speed, "web.permeability": k})
        for lam in lambdas:
            width = lam * 2.0 * base.x_scale
            case = base.updated({"web.width": width})
            cf = solve(case, model="closed-form")
            r0 = solve(case, model="fe2d")
            r1 = solve(case, model="fe2d", level=1)
            err = (cf["h_center"] / r1["h_center"] - 1.0) * 100.0
            rows.append({"permeability": k, "lambda": case.lam, "beta": case.beta,
                         "width_m": width, "h_center_fe2d_um": r1["h_center"] * 1e6,
                         "fe2d_mesh_error_pct": abs(r0["h_center"] / r1["h_center"] - 1) * 100,
                         "h_center_eq21_um": cf["h_center"] * 1e6, "eq21_error_pct": err,
                         "h_center_fe1d_um": solve(case, model="fe1d")["h_center"] * 1e6})
            print(f"k = {k:g}, lambda = {case.lam:6.1f}: fe2d {r1['h_center'] * 1e6:7.3f} um, "
                  f"Eq. 21 {cf['h_center'] * 1e6:7.3f} um ({err:+.1f} %)", flush=True)
    out.mkdir(parents=True, exist_ok=True)
    with (out / "lambda_table.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    _markdown(rows, out / "lambda_table.md", speed)
    _chart(rows, out / "lambda_table.png", speed)
    return rows


def _markdown(rows, path, speed):
    lines = [f"Base case at U_r = {speed:g} m/s (beta = {rows[0]['beta']:.1f}), web width set "
             "to give lambda; 2-D central gap at mesh level 1 (its difference from level 0 in "
             "the mesh column), Eq. 21's central gap, and Eq. 21's error against the 2-D "
             "solution.", "",
             "| web | lambda | L [mm] | fe2d h_center [um] | mesh [%] | Eq. 21 [um] | "
             "Eq. 21 error [%] | fe1d (infinite width) [um] |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        web = "newsprint k = 5e-15" if r["permeability"] else "impermeable"
        lines.append(f"| {web} | {r['lambda']:.0f} | {r['width_m'] * 1e3:.1f} | "
                     f"{r['h_center_fe2d_um']:.3f} | {r['fe2d_mesh_error_pct']:.1e} | "
                     f"{r['h_center_eq21_um']:.3f} | {r['eq21_error_pct']:+.1f} | "
                     f"{r['h_center_fe1d_um']:.3f} |")
    path.write_text("\n".join(lines) + "\n")


def _chart(rows, path, speed):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4.2), constrained_layout=True)
    for k, style in ((5e-15, "o-"), (0.0, "s--")):
        sel = [r for r in rows if r["permeability"] == k]
        ax.semilogx([r["lambda"] for r in sel], [r["eq21_error_pct"] for r in sel], style,
                    label="newsprint (k = 5e-15 m^2)" if k else "impermeable web")
    ax.axhline(0.0, color="0.5", lw=0.8)
    ax.set_xlabel("lambda = L / (2 R eps^(1/3))")
    ax.set_ylabel("Eq. 21 central gap error vs 2-D FE [%]")
    ax.set_title(f"Eq. 21 against the 2-D solution, base case at {speed:g} m/s", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="docs")
    p.add_argument("--speed", type=float, default=40.0)
    args = p.parse_args(argv)
    run(Path(args.out), args.speed)


if __name__ == "__main__":
    main()
