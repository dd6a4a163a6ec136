"""A solve above its tolerance says why where it is printed: the rounding floor's reason in
the text summary, a strict tolerance's stall without a floor of 0, a failed result's
warnings and (under auto) the model it used and why."""

import dataclasses

import numpy as np
import pytest
import scipy.sparse as sp

import webfem
from webfem.describe import describe
from webfem.errors import ConvergenceError
from webfem.fem import newton as nw

RNG = np.random.default_rng(1)
N = 40
#: a linear system whose residual's rounding floor (~1e-4) is far above 1e-9
A = 1e8 * (RNG.standard_normal((N, N)) + N * np.eye(N))
B = A @ (10 * RNG.standard_normal(N))


def solve(tol):
    return nw.newton(lambda u: A @ u - B, lambda u: sp.csr_matrix(A), np.zeros(N), tol=tol)


def test_strict_tolerance_stall_names_no_floor_of_zero():
    r = solve(1e-10)
    assert not r.converged
    assert "rounding floor 0" not in r.reason
    assert "taken strictly" in r.reason and "1e-10" in r.reason
    at_default = solve(nw.STRICT_BELOW)
    assert at_default.converged and "rounding floor" in at_default.reason


def test_summary_prints_the_rounding_floor_reason():
    r = webfem.solve(webfem.Case(), model="fe1d")
    plain = r.summary.replace(solver_message="residual below tolerance")
    assert "solver:" not in describe(dataclasses.replace(r, summary=plain))
    floor = solve(nw.STRICT_BELOW).reason
    at_floor = r.summary.replace(solver_message=floor)
    assert f"solver: {floor}" in describe(dataclasses.replace(r, summary=at_floor))
    balanced = "algebraic error negligible against the mesh error target (balanced stopping)"
    early = r.summary.replace(solver_message=balanced)
    assert f"solver: {balanced}" in describe(dataclasses.replace(r, summary=early))


@pytest.fixture(scope="module")
def failed():
    case = webfem.Case().updated({"roller.speed": 0.01})
    with pytest.raises(ConvergenceError) as err:
        webfem.solve(case, model="auto", fe_tol=1e-12)
    return err.value.result


def test_failed_result_says_so_in_warnings_and_names_auto_choice(failed):
    s = failed.summary
    assert not s.converged
    assert s.warnings and s.warnings[0].startswith("NOT converged")
    assert s.model == "auto" and s.model_used == "fe2d"
    assert "did not converge" in s.why
    assert "solver:" in describe(failed)
