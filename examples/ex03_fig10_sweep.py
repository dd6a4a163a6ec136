"""The paper's Fig. 10 family: friction against roller speed for three wrap angles (fe1d).

``cases/fig10_wrap.toml`` sweeps the roller speed from 0.5 to 40 m/s for wrap angles of 20,
40 and 60 deg. At low speed the web rests on its asperities and mu is the boundary friction,
rising with the sliding speed as atan(U_s/C); as the speed rises air lifts the web and mu
falls to the small film friction. Air also leaves through the permeable web along the wrap,
so the gap shrinks from inlet to outlet in proportion to the wrap length (Eq. 21's kappa
term): a longer wrap brings the web back onto its asperities near the outlet and keeps its
traction to higher speeds.

The sweep is respaced to 6 log-spaced speeds and solved with the 1-D FE model, each point
continued from the previous one of its series (``webfem.sweep``). Prints mu per series and
speed, then the speed band where each series' mu falls through 0.1; the last line is the
60 deg series' mu at the second-highest speed (16.7 m/s).

Run from the repository root: ``python examples/ex03_fig10_sweep.py``
(the full family: ``webfem sweep cases/fig10_wrap.toml --model fe1d --out DIR``).
"""

import webfem

spec = webfem.load_sweep("cases/fig10_wrap.toml").respaced(6, log=True)
mu = {}                                                     # label -> [mu per speed]
for label, speed, result in webfem.sweep(spec, model="fe1d"):
    mu.setdefault(label, []).append(result["mu"] if result["converged"] else float("nan"))

print("U_r m/s  " + "  ".join(f"{label:>10s}" for label in mu))
for i, speed in enumerate(spec.values):
    print(f"{speed:7.2f}  " + "  ".join(f"{mu[label][i]:10.4f}" for label in mu))

for label, values in mu.items():
    falls = [i for i in range(1, len(values)) if values[i - 1] >= 0.1 > values[i]]
    where = (f"between {spec.values[falls[0] - 1]:.1f} and {spec.values[falls[0]]:.1f} m/s"
             if falls else "not in this range")
    print(f"{label}: mu falls through 0.1 {where}")

print("mu at 16.7 m/s, B = 60 deg:", mu["B = 60 deg"][-2])
