"""The closed form says when it has no answer (issue 20, item 5).

A wrap landed from edge to edge, mu beyond what the asperities and the air between them can
carry, a gap above R/100 or a film thicker than R/100: one solve refuses with
NoAdmissibleSolution (exit 2) naming the reason; the vectorised path (sweeps) keeps the point
with converged = False and the same reason; auto never returns it. A partly landed wrap stays
an answer (the paper's boundary lubrication), and so, since the contact law continues past
full asperity compression (issue 22), does a web resting on the roller with h_c <= 0.
"""

import numpy as np
import pytest

import webfem
from webfem import Case
from webfem.cli import main
from webfem.errors import NoAdmissibleSolution
from webfem.models import closed
from webfem.models.options import ClosedFormOptions
from webfem.sweeps.table import read_table, typed

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")

from conftest import BASE


def code(case: Case) -> str:
    """The NO_ANSWER name of ``case`` from the vectorised evaluation."""
    values = closed.evaluate(**closed.case_arrays([case]), variant=case.friction_variant,
                             distribution=case.friction.distribution,
                             roughness=case.roughness_flow_model == "mean-gap")
    return closed.NO_ANSWER[int(values["no_answer"][0])]


# -- each reason, on the single solve and the vectorised path --------------------------------
def test_a_web_above_what_the_asperities_carry_rests_on_the_roller(capsys):
    """T = 500 N/m on R = 55 mm: T/R = 9091 Pa against E_b sigma/(2t) = 175e3 * 4e-6 / 140e-6
    = 5000 Pa at h = 0. Refused before (h_c <= 0 where Eq. 21 lands the web, mu 0.456 above
    mu_cc); on the continued contact law h_c solves (E_b/t)(-h + (sigma/2) exp(h/sigma)) =
    T/R (3.636 um of compression): h_c = -2.59 um (2.59 + 2 exp(-0.647) = 3.637), the web
    resting with its surface compressed, mu near mu_c = 0.296."""
    assert main(["solve", "base", "--model", "closed-form", "--set", "web.tension=500",
                 "--json"]) == 0
    import json
    data = json.loads(capsys.readouterr().out)
    assert data["resting"] and data["h_c"] == pytest.approx(-2.5895e-6, rel=1e-4)
    assert data["compression"] == pytest.approx(-data["h_min"]) and data["h_min"] <= data["h_c"] + 1e-15
    assert 0.29 < data["mu"] < 0.31
    assert code(BASE.updated({"web.tension": 500.0})) == ""


def test_a_resting_web_at_crawling_speed_is_answered_by_auto_too():
    """U_r = 1e-5 m/s, T = 300 N/m: the wrap is 6820 entry lengths long (beyond the FE
    models), h_c = -0.35 um; auto answered with the closed form's gap 0 and mu 0 (issue 20),
    then refused; now the web rests on the roller, boundary lubrication: mu = mu_c."""
    r = webfem.solve(BASE.updated({"roller.speed": 1e-5, "web.tension": 300.0}))
    assert r["model_used"] == "closed-form" and r["resting"]
    assert r["h_min"] == pytest.approx(r["h_c"]) and r["h_c"] == pytest.approx(-3.49e-7, rel=2e-3)
    mu_c = 2.0 / np.pi * 0.3 * np.arctan(1e-5 / 0.4)
    assert r["mu"] == pytest.approx(mu_c, rel=0.05)


def test_h_c_below_zero_is_an_answer_while_the_film_flies():
    """An impermeable web at T = 400 N/m: h_c = -1.5 um, but Eq. 21's gap (8.6 um) is
    positive over the whole wrap, so the film carries T/R (fe1d agrees: mu 0.019 against
    0.030, both mixed)."""
    r = webfem.solve(BASE.updated({"web.tension": 400.0, "web.permeability": 0.0}),
                     model="closed-form")
    assert r["converged"] and r["h_c"] < 0.0 < r["h_min"] and not r["resting"]
    assert closed.no_answer(r) is None


def test_mu_beyond_asperities_and_valley_air_is_refused():
    """T = 250 N/m at 20 m/s: h_c = 4e-6 ln(5000/4545) = 0.38 um rests the web far below its
    roughness, and the Couette shear eta U_s/(h_c + 2 a lambda) there lifts mu to 0.417,
    above mu_cc + c eta U_s / (sigma T/R) = 0.3 + 2.029 * 1.81e-5 * 20 / (4e-6 * 4545) =
    0.340, with c = 0.5 ln(1 + 4e-6 / (2 * 65e-9)) + 0.3 = 2.029 bounding the shear of the
    air between the asperities (its peak, by quadrature: 1.55 eta U_s / sigma). The smooth
    film's shear is what air.roughness_flow = "none" keeps; the default shears the air only
    where it wets the roller (mu 0.305 here, an answer)."""
    case = BASE.updated({"web.tension": 250.0, "air.roughness_flow": "none"})
    assert code(BASE.updated({"web.tension": 250.0})) == ""
    assert closed.mu_bound(0.3, 1.81e-5, 20.0, 4e-6, 250.0 / 0.055, 65e-9) == pytest.approx(
        0.3 + 2.0293 * 1.81e-5 * 20.0 / (4e-6 * 250.0 / 0.055), rel=1e-4)
    assert code(case) == "mu"
    with pytest.raises(NoAdmissibleSolution, match=r"mu = 0\.417 is above .* mu <= 0\.34;"):
        closed.solve(case)


@pytest.mark.parametrize("ratio", [3.0, 30.0, 300.0, 1e4])
def test_valley_shear_bound_is_above_the_shear_of_the_air_between_asperities(ratio):
    """tau(h) = E[eta U_s / ((h - z) + 2 a lambda); z < h] over the Laplace heights
    exp(-|z|/sigma)/(2 sigma) (physics.md), maximised over h by quadrature, lies below
    valley_shear_bound and within 0.6 of it (sigma / (2 a lambda) = ``ratio``)."""
    from scipy.integrate import quad
    from scipy.optimize import minimize_scalar

    from webfem.physics.friction import valley_shear_bound

    cut = 1.0 / ratio    # in units of sigma

    def tau(h):
        f = lambda z: 0.5 * np.exp(-abs(z)) / ((h - z) + cut)   # noqa: E731
        out = quad(f, -60.0, min(h, 0.0), limit=400)[0]
        return out + (quad(f, 0.0, h, limit=400, points=[h * (1 - 1e-3)])[0] if h > 0 else 0)

    peak = -minimize_scalar(lambda h: -tau(h), bounds=(0.0, 3.0), method="bounded").fun
    bound = float(valley_shear_bound(ratio * 130e-9, 65e-9))
    assert peak < bound < peak + 0.6


def test_mu_a_little_above_mu_cc_is_an_answer():
    """T = 120 N/m at 9 m/s (the paper's tension range): boundary friction 0.296 plus the
    air's drag gives mu = 0.301, just above mu_cc = 0.3; that is an answer (fe1d: 0.281),
    so the paper's tension trend still has its traction-loss speeds."""
    r = webfem.solve(BASE.updated({"web.tension": 120.0, "roller.speed": 9.0}), model="closed-form")
    assert r["converged"] and 0.3 < r["mu"] < 0.31


def test_film_thicker_than_R_over_100_is_flagged_in_sweeps():
    """T = 0.01 N/m at 20 m/s: eps = 6 * 1.81e-5 * 20 / 0.01 = 0.217, R eps^(2/3) = 20 mm,
    far above R/100 = 0.55 mm. A single solve refused it already; the vectorised path (every
    closed-form sweep) returned it as converged, with gaps of millimetres."""
    case = BASE.updated({"web.tension": 0.01})
    assert code(case) == "thin-film"
    r = closed.solve_many([case])[0]
    assert r["converged"] is False
    assert "more than R/100 = 0.00055 m" in r["solver_message"]
    with pytest.raises(NoAdmissibleSolution, match="more than R/100"):
        closed.solve(case)


def test_gap_above_R_over_100_is_no_answer():
    """Asperities 1 m tall (sigma = 1 m, called directly: such a key may become an input
    error): h_c = 1 * ln(175e3 * 1 / (140e-6 * 1454.5)) = 13.7 m, where the web would rest,
    25000 times R/100."""
    arrays = closed.case_arrays([BASE])
    arrays["sigma"] = np.array([1.0])
    values = closed.evaluate(**arrays, variant="loads")
    assert values["h_c"][0] == pytest.approx(13.66, rel=1e-3)
    assert closed.NO_ANSWER[int(values["no_answer"][0])] == "gap"
    # the coarsest roughness a case accepts, 1 mm: h_c = 1e-3 ln(175e3 1e-3 / (140e-6
    # 1454.5)) = 6.76 mm, still 12 times R/100
    r = closed.solve_many([BASE.updated({"friction.roughness": "composite",
                                         "roller.roughness": 1e-3})])[0]
    assert not r["converged"]
    assert "h_c = 0.00676 m" in r["solver_message"] and "roller.roughness = 0.001 m" in \
        r["solver_message"]


def test_landed_from_edge_to_edge_is_no_answer():
    """Eq. 21's inlet gap R eps^(2/3) (0.589 - 1.614/lambda + 1.764/lambda^2) is positive for
    every lambda (the quadratic has no real root), so only U = 0, which a Case refuses,
    lands the whole wrap; evaluate() is called with arrays and must say so too."""
    arrays = closed.case_arrays([BASE])
    arrays["U_r"] = np.array([0.0])
    with np.errstate(all="ignore"):
        values = closed.evaluate(**arrays, variant="loads")
    assert closed.NO_ANSWER[int(values["no_answer"][0])] == "landed"


# -- what stays an answer ----------------------------------------------------------------------
def test_partly_landed_low_speed_wrap_is_an_answer():
    """At 0.5 m/s Eq. 21 lands all but 0.2 % of the wrap (h_inlet 2.3 um, 2 R kappa 1.3 mm);
    the web rests on its asperities: boundary lubrication, mu = (2/pi) 0.3 atan(0.5/0.4) =
    0.1714 plus the air's shear over h_c, as in the paper and the FE models (0.17)."""
    r = webfem.solve(BASE.updated({"roller.speed": 0.5}), model="closed-form")
    assert r["converged"] and r["h_outlet"] == r["h_c"] and r["regime"] == "boundary"
    assert r["mu"] == pytest.approx(0.1714, abs=0.005)


def test_base_sweep_answers_at_every_speed():
    """The closed-form sweep of cases/base.toml (make run, the README's chart): every point
    from 0.5 to 40 m/s is an answer, the slow ones boundary lubrication."""
    spec = webfem.load_sweep("cases/base.toml")
    assert spec.values[0] == 0.5 and spec.values[-1] == 40.0
    results = [r for _, _, r in webfem.sweep(spec, "closed-form")]
    assert len(results) == 80 and all(r["converged"] for r in results)
    assert results[0]["regime"] == "boundary" and results[0]["mu"] > 0.15


# -- one rule for both paths, and for auto -----------------------------------------------------
CASES = [BASE.updated(v) for v in (
    {}, {"roller.speed": 0.5}, {"web.tension": 500.0}, {"web.tension": 250.0},
    {"web.tension": 250.0, "air.roughness_flow": "none"},
    {"web.tension": 0.01}, {"web.tension": 120.0, "roller.speed": 9.0},
    {"web.tension": 400.0, "web.permeability": 0.0},
    {"web.tension": 300.0, "friction.variant": "paper"},
    {"web.tension": 270.0, "roller.speed": 3.0, "friction.variant": "continuous"})]


def test_vectorised_and_single_solves_agree():
    """solve_many flags exactly the points solve_case refuses, with the same reason; with
    raise_on_failure=False solve_case returns them flagged, as auto reads them."""
    many = closed.solve_many(CASES)
    refused = 0
    for case, r in zip(CASES, many):
        flagged = closed.solve_case(case, ClosedFormOptions(), raise_on_failure=False)
        assert flagged["converged"] == r["converged"]
        assert closed.no_answer(flagged) == closed.no_answer(r)
        try:
            closed.solve(case)
        except NoAdmissibleSolution as err:
            refused += 1
            assert not r["converged"]
            assert closed.no_answer(r) in str(err)
            assert any(w.startswith("no closed-form answer: ") for w in r["warnings"])
        else:
            assert r["converged"] and closed.no_answer(r) is None
    # T = 0.01 (thin film), 250 without the roughness flow (mu), 300 with the paper's
    # friction (mu not finite): 500, and 250 with the roughness flow, now rest (issue 22)
    assert refused == 3


def test_sweep_keeps_no_answer_points_marked(tmp_path, capsys):
    """A closed-form sweep at T = 250 N/m with the smooth film's shear (air.roughness_flow =
    none): at 20 m/s Eq. 21 rests the web at h_c = 0.38 um, where eta U_s/(h_c + 2 a lambda)
    lifts mu to 0.417, beyond what asperities and air can carry (no answer); at 60 m/s the
    film flies. Every point is written; the one without an answer is not converged, with the
    reason in solver_message; exit 3 says some points have none."""
    case = tmp_path / "t.toml"
    case.write_text("[web]\ntension = 250.0\n[air]\nroughness_flow = 'none'\n[sweep]\n"
                    "parameter = 'roller.speed'\nvalues = [20.0, 60.0]\n")
    assert main(["sweep", str(case), "--model", "closed-form", "--out", str(tmp_path),
                 "--quiet"]) == 3
    err = capsys.readouterr().err
    assert "Traceback" not in err and "no converged, admissible answer" in err
    rows = typed(read_table(tmp_path / "t_closed-form.csv").rows)
    assert [r["converged"] for r in rows] == [False, True]
    assert "mu = 0.417 is above" in rows[0]["solver_message"]


def test_json_of_a_refusal_is_no_answer(capsys):
    """--json prints no answer on stdout for a refused point (no JSON a script could take for
    one); the message goes to stderr."""
    assert main(["solve", "base", "--model", "closed-form", "--json", "--set",
                 "web.tension=250", "--set", "air.roughness_flow=none"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and "no admissible closed-form answer" in err and "Traceback" not in err
