"""Base case: the paper's closed form against the 1-D and 2-D finite-element models.

Newsprint (T = 80 N/m, L = 35 mm) wrapped 60 deg on a 55 mm roller turning at 20 m/s
(``cases/base.toml``). The closed form (Eq. 21) gives the air gap in microseconds; the 1-D
model solves the foil-bearing equations for an infinitely wide web (no air escapes at the
edges, so the web flies higher); the 2-D model adds the edge leakage. Where the gap falls
towards the asperity heights (h_c = 4.9 um, 3 sigma = 12 um) contact carries load and the
friction coefficient mu rises, so the three gap predictions give three different mu.

Prints a table (gaps, regime, mu, tension increase before slip, unknowns, time) and how
much each model costs against the closed form; the last line is the 2-D model's mu.

Run from the repository root: ``python examples/ex01_base_case.py``.
"""

import warnings

import webfem

case = webfem.load_case("cases/base.toml")
results = {}
with warnings.catch_warnings():
    # the closed form warns that Eq. 21's gap falls below h_c at the outlet, where it rests the
    # web on its asperities; the table shows it
    warnings.simplefilter("ignore", webfem.errors.ValidityWarning)
    for model in ("closed-form", "fe1d", "fe2d"):
        results[model] = webfem.solve(case, model=model)

um = 1e6
print(f"{'model':12s} {'h_inlet':>8s} {'h_center':>8s} {'h_min':>8s}  {'regime':8s} "
      f"{'mu':>6s} {'dT N/m':>7s} {'unknowns':>8s} {'time s':>8s}")
for model, r in results.items():
    print(f"{model:12s} {r['h_inlet'] * um:8.2f} {r['h_center'] * um:8.2f} "
          f"{r['h_min'] * um:8.2f}  {r['regime']:8s} {r['mu']:6.3f} {r['delta_T']:7.2f} "
          f"{r['n_dofs']:8d} {r['solve_time_s']:8.4f}")
print("(gaps in um)")

cheap = results["closed-form"]["solve_time_s"]
for model in ("fe1d", "fe2d"):
    print(f"{model} costs {results[model]['solve_time_s'] / cheap:.0f} closed-form solves")

print("fe2d mu:", results["fe2d"]["mu"])
