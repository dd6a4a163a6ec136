"""How much the friction model's options move mu for the base case.

The paper's Eqs. 13 and 29 jump at h = 3 sigma and h = h_c (``friction.variant = "paper"``);
the continuous variant removes the jumps. The paper's exponential asperity heights (Eq. 2)
against the Gaussian of Eq. 1 (``friction.distribution``). Four combinations, mu against
roller speed, closed form and an FE model; a table of mu at a few speeds.

Run: ``python -m webfem.studies.variants --out docs/figures [--model fe2d] [--num 24]``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from .. import Case, solve

COMBOS = (("paper", "exponential"), ("continuous", "exponential"), ("paper", "gaussian"),
          ("continuous", "gaussian"))


def run(out: Path, model: str = "fe2d", num: int = 24):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    speeds = np.geomspace(0.5, 40.0, num)
    data = {}
    for variant, dist in COMBOS:
        base = Case().updated({"friction.variant": variant, "friction.distribution": dist})
        for m in ("closed-form", model):
            mu, prev = [], None
            for u in speeds:
                kw = {"initial": prev} if prev is not None and m != "closed-form" else {}
                prev = solve(base.updated({"roller.speed": float(u)}), model=m, **kw)
                mu.append(prev["mu"])
            data[(variant, dist, m)] = np.array(mu)
            print(f"{variant:10s} {dist:11s} {m:11s} done", flush=True)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2), constrained_layout=True, sharey=True)
    styles = {"exponential": "-", "gaussian": "--"}
    colours = {"paper": "C0", "continuous": "C3"}
    for ax, m in zip(axes, ("closed-form", model)):
        for variant, dist in COMBOS:
            ax.plot(speeds, data[(variant, dist, m)], styles[dist], color=colours[variant],
                    label=f"{variant}, {dist}")
        ax.set_xlabel("roller speed U_r [m/s]")
        ax.set_title(f"base case, {m}", fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("mu [-]")
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "variants.png", dpi=110)
    plt.close(fig)
    pick = [i for i, u in enumerate(speeds) if i % max(num // 6, 1) == 0]
    lines = ["| model | variant | heights | " + " | ".join(f"{speeds[i]:.1f} m/s"
                                                        for i in pick) + " |",
             "|---|---|---|" + "---|" * len(pick)]
    for (variant, dist, m), mu in data.items():
        lines.append(f"| {m} | {variant} | {dist} | "
                     + " | ".join(f"{mu[i]:.4f}" for i in pick) + " |")
    (out / "variants.md").write_text("mu of the base case for the friction model's options "
                                     "(`python -m webfem.studies.variants`).\n\n"
                                     + "\n".join(lines) + "\n")
    return data


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="docs/figures")
    p.add_argument("--model", default="fe2d")
    p.add_argument("--num", type=int, default=24)
    a = p.parse_args(argv)
    run(Path(a.out), a.model, a.num)


if __name__ == "__main__":
    main()
