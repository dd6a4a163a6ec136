"""The stated mesh error bounds the true one (issue 20): every FE result states ``error_h_center``,
``error_h_min``, ``error_mu`` and ``error_contact_share`` from a second mesh with cells twice
as long; checked here against mesh-converged solutions of webfem's own (the same case with
the estimate's target tightened, so the driver bisects every cell until the estimates meet
it), on smooth and grooved cases. The true error may be at most twice the stated one."""

import pytest

import webfem
from webfem import Case
from webfem.models.readout import READ_QUANTITIES, error_scale

from conftest import BASE, FLYING, GROOVED, PET_IDLER_GROOVED

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")

#: A grooved PET film whose land film is thin and whose exit constriction lies where the
#: smooth start's mesh is coarse: its h_min was 1.1 % off on the starting mesh while the old
#: summary said "mesh error about 1e-4" (issue 20).
PET_GROOVED = {"roller.groove_depth": 1e-3, "roller.groove_pitch": 3e-3,
               "roller.speed": 20.0, "web.speed": 20.0}
SHALLOW_GROOVES = {"roller.groove_depth": 0.2e-3, "roller.groove_pitch": 3e-3,
                   "roller.speed": 20.0, "web.speed": 20.0}

CASES = {
    "base fe1d": (BASE, "fe1d"),
    "base fe2d": (BASE, "fe2d"),
    "grooved base": (GROOVED, "fe2d"),
    "grooved PET, deep": (PET_IDLER_GROOVED.updated(PET_GROOVED), "fe2d"),
    "grooved PET, shallow": (PET_IDLER_GROOVED.updated(SHALLOW_GROOVES), "fe2d"),
}
SLOW = {"base fe2d", "grooved PET, shallow"}


def true_errors(case, answer, reference):
    return {q: abs(answer[q] - reference[q]) / error_scale(case, q, answer[q])
            for q in READ_QUANTITIES}


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW
                                  else n for n in CASES])
def test_the_stated_error_bounds_the_true_error(name):
    case, model = CASES[name]
    answer = webfem.solve(case, model=model)
    reference = webfem.solve(case, model=model, error_tol=2e-5)
    assert reference["n_dofs"] > answer["n_dofs"]
    true = true_errors(case, answer, reference)
    for q in READ_QUANTITIES:
        stated = answer[f"error_{q}"]
        # the reference's own error, which it states, may add to the difference
        assert true[q] <= 2.0 * stated + reference[f"error_{q}"], (q, true[q], stated)
        if model == "fe2d":          # fe1d's stated errors add the edge leakage it leaves out
            assert stated <= 1e-3 or answer["warnings"]


def test_the_estimate_refines_where_the_start_mesh_is_coarse():
    """The grooved PET film's exit constriction: the starting mesh states an h_min error
    above the target, so cells are bisected until the estimates meet it: on a grooved film
    only along the direction whose estimated error is the larger (here x: the film needs
    its x cells halved, its width nodes are fine enough), and along x only the cells where
    the change was (the exit constriction), the other cells' share of it added to the
    stated error."""
    case = PET_IDLER_GROOVED.updated(PET_GROOVED)
    coarse = webfem.solve(case, model="fe2d", error_tol=0.5)
    fine = webfem.solve(case, model="fe2d")
    assert coarse["error_h_min"] > 1e-3           # 1.1 % off on the starting mesh
    assert all(fine[f"error_{q}"] <= 1e-3 for q in READ_QUANTITIES)
    assert 2 * coarse["n_dofs"] > fine["n_dofs"] > coarse["n_dofs"] > 0
    assert fine["width_cells"] == coarse["width_cells"]     # the width was not bisected
    assert "error estimate asked for" in fine["solver_message"]
    assert "twice as long" in fine["error_basis"]
    assert "of the change along x was" in fine["error_basis"]


def test_a_smooth_roller_bisects_only_the_direction_whose_error_is_larger():
    """On a smooth roller too, an estimate above the target bisects only the direction whose
    error is the larger (from one more solve, on the mesh coarser across the width only):
    the base case at 30 m/s with a target of 5e-4 states more than that on the mesh its cold
    start decides up front, all of it along x, so its x cells are doubled and the width's
    kept, where bisecting every cell quadrupled the unknowns (the speed sweep's 22.6 m/s:
    35,927 -> 18,745)."""
    from webfem.fem.scaling import FoilParameters
    from webfem.models import fe2d
    from webfem.models.options import FE2DOptions

    case, target = BASE.updated({"roller.speed": 30.0}), 5e-4
    o = FE2DOptions(error_tol=target)
    up_front = fe2d.FILM.start(case, FoilParameters.from_case(case, o.compressible, o.contact,
                                                              o.floor), o, None).problem
    fe2d.FILM.forget_lines()
    fine = webfem.solve(case, model="fe2d", error_tol=target)
    assert all(fine[f"error_{q}"] <= target for q in READ_QUANTITIES)
    assert fine["width_cells"] == up_front.Z.size - 1
    assert fine["n_cells"] == 2 * (up_front.X.size - 1) * (up_front.Z.size - 1)
    assert "the last bisection along x" in fine["error_basis"]
    assert "along x and across the width, summed" in fine["error_basis"]
    # the finer answer is within a coarser one's stated error (the default target's)
    start = webfem.solve(case, model="fe2d")
    assert start["n_dofs"] < fine["n_dofs"]
    true = true_errors(case, start, fine)
    assert all(true[q] <= start[f"error_{q}"] + fine[f"error_{q}"] for q in READ_QUANTITIES)


def test_without_estimate_the_keys_are_null_and_nothing_is_refined():
    r = webfem.solve(Case(), model="fe1d", estimate=False)
    assert all(r[f"error_{q}"] is None for q in READ_QUANTITIES)
    assert r["error_basis"] in (None, "")


def test_every_model_states_its_errors():
    """Through the same keys; fe1d's include the edge leakage it leaves out, so they are
    far above its mesh error on the base case (lambda = 13)."""
    base = FLYING
    for model in ("closed-form", "fe1d", "fe2d", "auto"):
        r = webfem.solve(base, model=model)
        assert all(isinstance(r[f"error_{q}"], float) for q in READ_QUANTITIES), model
    assert webfem.solve(base, model="fe1d")["error_h_center"] > 0.1


def test_an_unconfirmed_estimate_says_so(monkeypatch):
    """When the finer mesh the estimate asks for gives no admissible answer, nor the one with
    the cells along x quartered instead of halved, the stated errors stay the
    change from the coarser mesh, and the basis and a warning say that it is unconfirmed and
    may understate the error (issue 22). Forced here on the base case: an error target
    below its estimate and every finer answer refused."""
    import webfem.models.mesh_error as mesh_error
    refused = []

    def refuse(case, problem, u, prm):
        refused.append(problem.n_dofs)
        return "refused by the test"

    monkeypatch.setattr(mesh_error, "admissibility", refuse)
    r = webfem.solve(BASE, model="fe1d", error_tol=1e-8)
    # the halved mesh and the one with the cells along x quartered both refused: the
    # answer's mesh is kept
    assert len(refused) == 2 and r["n_dofs"] < min(refused)
    # the estimate from the coarser mesh is still stated, above the target
    assert max(r[f"error_{q}"] for q in READ_QUANTITIES) > 1e-8
    assert "twice as long" in r["error_basis"] and "unconfirmed" in r["error_basis"]
    assert any("could not be confirmed" in w and "refused by the test" in w
               for w in r["warnings"])
    monkeypatch.undo()
    assert "unconfirmed" not in webfem.solve(BASE, model="fe1d")["error_basis"]


def test_the_cells_along_x_quartered_where_halving_them_fails(monkeypatch):
    """1 mm board on the base roller (issue 22): the mesh with every cell halved (29,487
    unknowns) does not converge from the 7,705-unknown answer, the one with its cells along x
    quartered instead does; that is then the answer, its stated errors the change
    from the mesh with cells four times as long along x, and it is not refined further.
    Forced here on the base case by refusing the first finer answer only."""
    import webfem.models.mesh_error as mesh_error
    real, tried = mesh_error.admissibility, []

    def refuse_first(case, problem, u, prm):
        tried.append(problem.n_dofs)
        return "refused by the test" if len(tried) == 1 else real(case, problem, u, prm)

    monkeypatch.setattr(mesh_error, "admissibility", refuse_first)
    r = webfem.solve(BASE, model="fe1d", error_tol=1e-8)
    assert len(tried) == 2 and r["n_dofs"] == tried[1] > tried[0]
    assert "four times as long along x" in r["error_basis"]
    assert "quartered instead of halved" in r["solver_message"]
    assert any("quartered" in w and "not refined further" in w for w in r["warnings"])
    monkeypatch.undo()
    # the statement bounds the error: against the mesh-converged answer
    reference = webfem.solve(BASE, model="fe1d", error_tol=2e-5)
    true = true_errors(BASE, r, reference)
    for q in READ_QUANTITIES:
        assert true[q] <= r[f"error_{q}"] + reference[f"error_{q}"], (q, true[q])


def test_the_worst_error_names_an_unmeasured_change_instead_of_failing():
    """A note about an unconfirmed estimate whose changes could not be measured (None: no
    answer on the coarser mesh either) said nothing and raised a TypeError (traceback to
    the user: 1 mm newsprint on the base roller with free web ends, entry = 80)."""
    from webfem.models.mesh_error import _worst

    assert _worst({"h_center": None, "mu": 3e-3}) == "h_center unknown"
    assert _worst({"h_center": 1e-4, "mu": 3e-3}) == "mu 0.003"


def test_no_estimate_at_all_is_said_once_and_plainly():
    """The trial's board on a 30 mm roller (fe1d): neither the coarser nor the finer mesh
    gave an answer. The warnings said "mesh error estimate h_center unknown exceeds
    error_tol", then "the stated errors are the change from the mesh with cells twice as
    long", then "no mesh error estimate": one note now says there is none, and why."""
    from webfem.models.mesh_error import MeshError, _unconfirmed

    out = MeshError()
    _unconfirmed(out, 2755, "did not converge", 1e-3)
    assert out.confirmed is False and len(out.notes) == 1
    note = out.notes[0]
    assert note.startswith("no mesh error estimate") and "2,755 unknowns" in note
    assert "did not converge" in note and "no error is stated" in note
    assert "unknown exceeds" not in note and "twice as long alone" not in note
