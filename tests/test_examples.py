"""Every script of examples/ runs from the repository root and prints the number it promises.

Each example ends with a line ``label: NUMBER``; the checks below compare that number with an
expectation found another way (the library called directly here, a physics bound or the
constants the example started from), so an example that drifts from what its docstring says
fails here.
"""

import ast
import os
import re
import subprocess
import sys
from pathlib import Path

import meshio
import numpy as np
import pytest

import webfem

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")


def run_example(name: str, *args: str) -> tuple[float, str]:
    """Run ``examples/NAME`` as a user would; return its last number and all its output."""
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run([sys.executable, str(EXAMPLES / name), *args], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr[-3000:]
    last = proc.stdout.strip().splitlines()[-1]
    return float(last.rsplit(maxsplit=1)[-1]), proc.stdout


def base(**changes) -> webfem.Case:
    return webfem.load_case(ROOT / "cases" / "base.toml").updated(changes)


def test_ex01_base_case():
    """The last number is the 2-D model's mu of the base case, a friction coefficient
    between the film's and the boundary's."""
    value, out = run_example("ex01_base_case.py")
    assert value == pytest.approx(webfem.solve(base(), model="fe2d")["mu"], rel=1e-9)
    assert 0.0 < value < base().friction.mu_cc
    assert {"closed-form", "fe1d", "fe2d"} <= {ln.split()[0] for ln in out.splitlines()
                                               if ln.strip()}


def test_ex02_width_study():
    """Edge leakage of an impermeable web: about 1.48/lambda (tests/test_fe2d.py finds it in
    the Eshel-Elrod setting)."""
    value, _ = run_example("ex02_width_study.py")
    assert value == pytest.approx(1.48, abs=0.05)


def test_ex03_fig10_sweep():
    """The swept (continued) point equals a cold solve of the same case: continuation changes
    the cost, never the answer."""
    value, out = run_example("ex03_fig10_sweep.py")
    spec = webfem.load_sweep(ROOT / "cases" / "fig10_wrap.toml").respaced(6, log=True)
    label, case = spec.series[-1]
    assert label == "B = 60 deg"
    cold = webfem.solve(case.updated({"roller.speed": spec.values[-2]}), model="fe1d")
    assert value == pytest.approx(cold["mu"], rel=1e-6)
    assert "nan" not in out                           # every point converged


def test_ex04_vtu_paraview(tmp_path):
    """The files land in the folder given; in the straight middle of the wrap film and
    contact carry T/R (within 0.5 %), read back from the file here."""
    value, _ = run_example("ex04_vtu_paraview.py", str(tmp_path))
    film = meshio.read(tmp_path / "base_fe2d_film.vtu")
    web = meshio.read(tmp_path / "base_fe2d_web.vtu")
    assert "p-p_a [Pa]" in film.point_data and len(film.cells[0].data) > 100
    centre = np.argmin(np.abs(web.points[:, 0]))
    case = base(**{"roller.speed": 40.0})
    load = (web.point_data["p-p_a [Pa]"][centre] + web.point_data["p_contact [Pa]"][centre]) / (
        case.web.tension / case.roller.radius)
    assert value == pytest.approx(load, rel=1e-12)
    assert value == pytest.approx(1.0, abs=5e-3)


def test_ex05_calibration_csv():
    """The fit recovers the mu_cc the synthetic data were made with (1 % noise)."""
    value, out = run_example("ex05_calibration_csv.py")
    assert value == pytest.approx(0.35, abs=0.01)
    C = float(re.search(r"speed_constant = ([0-9.]+)", out).group(1))
    assert C == pytest.approx(0.6, abs=0.05)


def readme_snippet() -> str:
    text = (ROOT / "README.md").read_text()
    section = text.split("## Python API", 1)[1]
    return section.split("```python\n", 1)[1].split("```", 1)[0]


def test_ex06_is_the_readme_snippet():
    source = (EXAMPLES / "ex06_readme_api.py").read_text()
    block = source.split("# --- README: Python API ---\n", 1)[1].split("# --- end", 1)[0]
    assert block == readme_snippet()


def test_ex06_readme_api():
    """The snippet's mu: the closed form at 30 m/s, where the web flies over most of the
    wrap (fluid and mixed lubrication), so mu lies well below the boundary value mu_cc."""
    value, out = run_example("ex06_readme_api.py")
    case = base(**{"roller.speed": 30.0})
    assert value == pytest.approx(webfem.solve(case, model="closed-form")["mu"], rel=1e-12)
    assert 0.0 < value < 0.5 * case.friction.mu_cc
    assert "webfem closed-form:" in out                   # r.describe() printed


def test_every_example_is_checked_and_documented():
    """At least six numbered scripts, each with a test above and a docstring that says
    what it prints."""
    names = sorted(p.stem for p in EXAMPLES.glob("ex[0-9][0-9]_*.py"))
    assert len(names) >= 6
    tested = {name.removeprefix("test_") for name in globals() if name.startswith("test_ex")}
    for name in names:
        assert name in tested, f"examples/{name}.py has no test"
        doc = ast.get_docstring(ast.parse((EXAMPLES / f"{name}.py").read_text()))
        assert doc and re.search(r"\bprints?\b", doc, re.I), name
