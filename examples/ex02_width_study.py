"""Width study: how much air escapes at the web edges (2-D film against the 1-D model).

The 1-D model treats the web as infinitely wide. A real web of width L loses air at its
edges, over a band about R eps^(1/3) wide, so the 2-D film's central gap falls below the
1-D gap by a fraction that decays as 1/lambda, lambda = L / (2 R eps^(1/3)). For an
impermeable web the loss is about 1.48/lambda (the paper's Eq. 21 fit takes 2.74/lambda).

The base case at 40 m/s (the web flies: fluid film everywhere) with an impermeable web is
solved with fe1d once and with fe2d for a few widths. Prints, per width, lambda, both central
gaps and lambda (1 - h_2d/h_1d); then fits (1 - h_2d/h_1d) = a/lambda + b/lambda^2 and
prints the leading coefficient a on the last line. The permeable base web (last line of the
table) loses more at the centre: air leaving through the web also thins the film there.

Run from the repository root: ``python examples/ex02_width_study.py``.
"""

import numpy as np

import webfem

case = webfem.load_case("cases/base.toml").updated({"roller.speed": 40.0,
                                                      "web.permeability": 0.0})
wide = webfem.solve(case, model="fe1d")
widths = (0.1, 0.3, 1.0)                        # m: lambda = 24, 72, 240

um = 1e6
print("  L m  lambda  h_1d um  h_2d um  lambda (1 - h_2d/h_1d)")
lams, losses = [], []
for width in widths:
    r = webfem.solve(case.updated({"web.width": width}), model="fe2d")
    loss = 1.0 - r["h_center"] / wide["h_center"]
    lams.append(r["lambda"])
    losses.append(loss)
    print(f"{width:5.2f} {r['lambda']:7.1f} {wide['h_center'] * um:8.2f} "
          f"{r['h_center'] * um:8.2f} {loss * r['lambda']:23.3f}")

base = case.updated({"web.permeability": 5e-15})
r1, r2 = webfem.solve(base, model="fe1d"), webfem.solve(base, model="fe2d")
print(f"base web (permeable), lambda = {r2['lambda']:.1f}: lambda (1 - h_2d/h_1d) = "
      f"{(1.0 - r2['h_center'] / r1['h_center']) * r2['lambda']:.2f}")

lam = np.array(lams)
a, b = np.linalg.lstsq(np.column_stack([1 / lam, 1 / lam**2]), np.array(losses),
                       rcond=None)[0]
print(f"fit: 1 - h_2d/h_1d = {a:.3f}/lambda + {b:.2f}/lambda^2")
print("edge-leakage coefficient a:", a)
