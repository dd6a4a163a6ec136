"""The idler's verdict, said once and everywhere (new-user trial, idler37):

1. the HTML report opens with it and lists it among the warnings where it slips (the page
   said "No warnings." beside a margin of 0.038);
2. a case whose web slides has no idler film: the hypothetical "an idler would ..." comes
   from a second solve at U_r = U_w (it was read from the sliding film: margin 5.3 where the
   idler's own fe2d film gives 1.2);
3. the film picture's friction panel says which traction its dashed line is, in a legend
   clear of the curves and the title;
4. a margin of 1e-112 prints as "< 0.001" (the JSON keeps the number).
"""

import json
import re
from pathlib import Path

import numpy as np
import pytest

import webfem
from webfem.cli import main

from conftest import IDLER, inspect_before_save

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")

ROOT = Path(__file__).resolve().parents[1]
#: press_idler at 1500 m/min: the closed form's idler slips (margin 0.089)
FAST = ["--set", "roller.speed=1500 m/min", "--set", "web.speed=1500 m/min"]


def verdict_line(out: str) -> str:
    return next(ln.strip() for ln in out.splitlines() if ln.strip().startswith("idler"))


def test_report_opens_with_the_verdict_solve_prints(tmp_path, capsys):
    assert main(["solve", "press_idler", "--model", "closed-form", *FAST]) == 0
    said = verdict_line(capsys.readouterr().out)
    assert said.startswith("idler slips: needs 6.67 N/m, can carry")
    assert main(["report", "press_idler", "--model", "closed-form", *FAST,
                 "--out", str(tmp_path), "--quiet"]) == 0
    solved = webfem.solve(webfem.load_case("press_idler").updated(
        {"roller.speed": 25.0, "web.speed": 25.0}), model="closed-form")
    count = len(solved.summary.warnings) + 1      # the solve's and the verdict
    assert f"{count} warning(s), listed in the page" in capsys.readouterr().err
    html = (tmp_path / "press_idler_closed-form.html").read_text()
    text = re.sub(r"<[^>]+>", "", html)
    head = html[html.index("<h1>"):html.index("<nav>")]
    assert 'class="warn" id="idler"' in head and "Idler slip check: SLIPS." in head
    sentence = said[0].upper() + said[1:]
    assert sentence in re.sub(r"<[^>]+>", "", head)
    warnings = html[html.index('<section id="warnings">'):html.index('<section id="computed">')]
    assert sentence in warnings and "No warnings." not in warnings
    assert text.count(sentence) == 2     # the headline and the warnings, the same words


def test_report_of_an_idler_that_holds_says_so_in_green(tmp_path):
    result = webfem.solve(webfem.load_case("press_idler"), model="closed-form")
    from webfem.describe import idler_verdict
    from webfem.io.report import page_warnings, report_html
    word, sentence = idler_verdict(result.summary, result.case)
    assert word == "holds"
    html = report_html(result)
    assert '<p class="ok" id="idler"><b>Idler slip check: HOLDS.</b>' in html
    assert not any("holds" in w for w in page_warnings(result))
    # no idler load, no headline
    assert 'id="idler"' not in report_html(webfem.solve(webfem.Case(), model="closed-form"))


def test_the_headline_renders_above_the_sections_in_chromium(tmp_path):
    """In a real browser the verdict box is drawn, above the navigation."""
    from test_report import chromium, run_chromium
    chromium()
    assert main(["report", "press_idler", "--model", "closed-form", *FAST,
                 "--out", str(tmp_path), "--quiet"]) == 0
    page = tmp_path / "press_idler_closed-form.html"
    probe = tmp_path / "probe.html"
    probe.write_text(page.read_text().replace("</body>", """<script>
window.addEventListener("load", function () {
  var v = document.getElementById("idler").getBoundingClientRect();
  var n = document.querySelector("nav").getBoundingClientRect();
  document.body.setAttribute("data-probe", "h=" + (v.height > 10) + ";above=" +
    (v.bottom <= n.top));
});
</script></body>"""))
    done = run_chromium(["--virtual-time-budget=10000", "--dump-dom", probe.as_uri()],
                        tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    assert 'data-probe="h=true;above=true"' in done.stdout


def test_a_sliding_case_is_checked_on_the_idlers_own_film(capsys):
    """idler.toml with the roller stopped (U_s = 10 m/s): its film is not an idler's. The
    summary states no margin from it; `webfem solve` checks the idler by a second solve at
    U_r = U_w, whose numbers are those of the idler solved directly (closed form: on main
    the sliding film gave margin 6 against the idler's 2.2)."""
    sliding = IDLER.updated({"roller.speed": 0.0})
    r = webfem.solve(sliding, model="closed-form")
    assert r["delta_T_required"] == pytest.approx(3.8, abs=0.05)
    assert r["slip_margin"] is r["mu_onset"] is r["delta_T_available"] is None
    from webfem.describe import idler_verdict
    word, text = idler_verdict(r.summary, r.case)
    assert word == "not judged" and "film is not an idler's" in text
    idler = webfem.solve(IDLER, model="closed-form")
    assert main(["solve", "idler", "--model", "closed-form", "--set", "roller.speed=0",
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    for key in ("slip_margin", "mu_onset", "delta_T_available", "delta_T_required"):
        assert data[key] == pytest.approx(idler[key], rel=1e-12)
    assert data["error_mu_onset"] == pytest.approx(idler["error_mu"], rel=1e-12)
    assert data["idler_basis"] == "a second closed-form solve at U_r = U_w = 10 m/s"
    assert data["mu"] == pytest.approx(r["mu"], rel=1e-12)     # the sliding answer stays
    assert main(["solve", "idler", "--model", "closed-form", "--set", "roller.speed=0"]) == 0
    line = verdict_line(capsys.readouterr().out)
    assert "from a second closed-form solve at U_r = U_w = 10 m/s" in line
    assert f"margin {idler['slip_margin']:.2g}" in line and "an idler would" in line


def test_sliding_points_of_a_vectorised_model_state_no_margin():
    """The fitted model's vectorised path nulls the same keys."""
    from webfem.physics.effects import traction_summaries, traction_summary
    sliding = IDLER.updated({"roller.speed": 0.0})
    many = traction_summaries([sliding, IDLER], [0.25, 0.0], [0.8, 0.2])
    assert many[0]["slip_margin"] is None and many[0]["delta_T_required"] > 0
    assert many[1]["slip_margin"] > 0
    assert traction_summary(sliding, 0.25, 0.8)["mu_onset"] is None


def test_the_friction_panel_names_its_dashed_line_clear_of_curve_and_title(monkeypatch,
                                                                           tmp_path):
    """An idler (nothing slides): the dashed line is the traction available at the onset of
    slip, not the average of the local friction (the film's drag, about 0); the labels sit
    in a legend above every line and below the panel's title."""
    from webfem.io import pictures
    from matplotlib.transforms import Bbox
    seen = {}

    def measure(fig, renderer):
        ax = fig.axes[-1]
        legend = ax.get_legend()
        seen["labels"] = [t.get_text() for t in legend.texts]
        seen["legend"] = legend.get_window_extent(renderer)
        seen["title"] = ax.title.get_window_extent(renderer)
        # the labelled lines (the wrap edges are vertical, in axes fractions)
        ys = [y for line in ax.get_lines() if not line.get_label().startswith("_")
              for y in np.atleast_1d(line.get_ydata())]
        seen["top_line"] = ax.transData.transform((0.0, max(ys)))[1]

    inspect_before_save(monkeypatch, pictures, measure, "_save")
    r = webfem.solve(webfem.load_case("press_idler").updated(
        {"roller.speed": 5.0, "web.speed": 5.0}), model="closed-form")
    pictures.film_figure(r, tmp_path / "f.png")
    assert any(t.startswith(f"mu_onset = {r['mu']:.3f}: traction available at the onset")
               for t in seen["labels"])
    assert any("nothing slides" in t and "mu_film" in t for t in seen["labels"])
    assert not any(t.startswith("wrap average mu") for t in seen["labels"])
    assert not Bbox.intersection(seen["legend"], seen["title"])
    assert seen["legend"].y0 > seen["top_line"]
    r = webfem.solve(webfem.Case(), model="closed-form")      # a sliding web: as before
    pictures.film_figure(r, tmp_path / "g.png")
    assert f"wrap average mu = {r['mu']:.3f}" in seen["labels"]
    assert seen["legend"].y0 > seen["top_line"]


def test_tiny_margins_print_as_below_a_thousandth(capsys):
    """pet_idler at 20 m/s: margin 9.3e-124 (closed form) printed as such in the verdict and
    the idler table; now "< 0.001", the JSON keeping the number."""
    sets = ["--set", "roller.speed=20", "--set", "web.speed=20"]
    assert main(["solve", "pet_idler", "--model", "closed-form", *sets]) == 0
    line = verdict_line(capsys.readouterr().out)
    assert "margin < 0.001" in line and "e-1" not in line
    assert main(["solve", "pet_idler", "--model", "closed-form", *sets, "--json"]) == 0
    assert 0.0 < json.loads(capsys.readouterr().out)["slip_margin"] < 1e-100
    assert main(["idler", "pet_idler", "--model", "closed-form", "--num", "3"]) == 0
    out = capsys.readouterr().out
    assert not re.search(r"\de-\d", out), out
    assert out.count("< 0.001") >= 4


def test_the_tail_rule_reads_the_idlers_own_solve_where_the_web_slides():
    """An overspeeding roller entrains more air: its own contact share (0.3 %) is below the
    tail rule's 0.5 %, but the idler's (the second solve at U_r = U_w: 91 %) rests on the
    exponential law's tail. The verdict is 'unsure' as for the idler solved directly, and
    the second solve's tail warning is carried (the review found 'would hold' instead)."""
    from webfem.describe import idler_verdict
    from webfem.idler import idler_at_web_speed

    case = webfem.load_case("idler").updated({"web.modulus_thickness": 2e7,
                                               "roller.speed": 40.0})
    first = webfem.solve(case, model="closed-form")
    assert first.summary.contact_share < 0.005
    r = idler_at_web_speed(first, "closed-form")
    word, said = idler_verdict(r.summary, r.case)
    assert word == "unsure" and "exponential heights' tail" in said
    assert r.summary.idler_contact_share > 0.5
    assert any("exponential heights" in w for w in r.summary.warnings)


def test_no_answer_or_a_standing_web_is_not_judged():
    """A closed-form point with no answer (its margin NaN) read 'idler slips ... can carry
    nan N/m'; a web standing still was advised to solve at roller.speed = web.speed = 0."""
    from webfem.describe import idler_verdict

    r = webfem.solve_many([webfem.load_case("idler").updated(
        {"roller.radius": 0.005, "web.roughness": 2e-4})], model="closed-form")[0]
    word, said = idler_verdict(r.summary, r.case)
    assert word == "not judged" and "nan" not in said
    still = webfem.solve(webfem.load_case("idler").updated({"web.speed": 0.0}),
                         model="closed-form")
    word, said = idler_verdict(still.summary, still.case)
    assert word == "not judged" and "stands still" in said


def test_the_effects_table_says_why_its_slip_margin_column_is_missing():
    from webfem.effects import effects_table

    sliding = effects_table(webfem.load_case("idler").updated({"roller.speed": 0.0}),
                            "closed-form")
    assert "slip margin" not in sliding.text().splitlines()[1]
    assert "slip margin: not judged, the web slides" in sliding.text()
    held = effects_table(webfem.load_case("idler"), "closed-form")
    assert held.margin_note is None and "slip margin" in held.text()


def test_a_refused_sweep_prints_a_change_to_the_digits_where_it_differs():
    from webfem.sweeps.store import _shown

    assert (_shown(80.0, 80.0000001), _shown(80.0000001, 80.0)) == ("80", "80.0000001")
    assert _shown(80.0, 120.0) == "80" and _shown(None) == "(not set)"
