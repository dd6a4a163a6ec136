"""The README's Python snippet, as the README shows it ("Python API").

Loads the base case, raises the roller speed to 30 m/s and evaluates the paper's closed form
(the web flies: mostly fluid film, some mixed lubrication near the outlet). Prints the
friction coefficient mu, the smallest gap h_min [m] and the readable summary, then reads the
fields along the web. tests/test_examples.py checks that the block between the markers below
is the README's snippet, character for character.

The last line prints mu again, labelled, for the test.

Run from the repository root: ``python examples/ex06_readme_api.py``.
"""

# --- README: Python API ---
import webfem
case = webfem.load_case("cases/base.toml").updated({"roller.speed": 30.0})
r = webfem.solve(case, model="closed-form")     # or model="fe1d"
print(r["mu"], r["h_min"], r.describe())
r.fields["x"], r.fields["h"], r.fields["mu"]     # fields along the web
# --- end of the README's snippet ---

print("mu:", r["mu"])
