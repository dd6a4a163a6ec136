"""What webfem prints says what its numbers mean: a negative gap is a web resting on its
asperities (said beside the gap), mu is labelled by the case's sliding speed."""

import re
import warnings

import pytest

import webfem
from webfem.bundled import as_case
from webfem.cli.summary import summary_text
from webfem.io.report import report_html


def closed(**values):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return webfem.solve(as_case("base").updated(values), model="closed-form")


@pytest.fixture(scope="module")
def resting():
    result = closed(**{"web.tension": 1000.0})
    assert result.summary.resting and result.summary.h_min < 0
    return result


def test_negative_gap_is_explained_where_printed(resting):
    s = resting.summary
    gap_line = next(ln for ln in summary_text(resting, "closed-form").splitlines()
                    if ln.strip().startswith("gap:"))
    depth = f"{s.compression * 1e6:.3g}"
    assert f"rests on the asperities, pressed {depth} um into them" in gap_line
    h_c_line = next(ln for ln in resting.describe().splitlines() if "h_c =" in ln)
    assert "below 0" in h_c_line


def test_positive_gap_prints_no_resting_note():
    result = closed()
    assert result.summary.h_min > 0
    assert "rests on the asperities" not in summary_text(result, "closed-form")
    assert "rests on the asperities" not in report_html(result)


def test_report_explains_negative_gap(resting):
    html = report_html(resting)
    head = re.search(r"<p class=sub>(.*?)</p>", html).group(1)
    assert "smallest gap" in head and "rests on the asperities" in head
    warnings_section = re.search(r'<section id="warnings">(.*?)</section>', html, re.S).group(1)
    assert "Note: The web rests on the asperities" in warnings_section
    # in US units the depth is converted with the gap
    assert "mil into them" in report_html(resting, units="us")


def test_report_labels_mu_by_sliding_speed():
    sliding = report_html(closed())       # base: U_r = 20 m/s, U_w = 0
    row = re.search(r"<td>mu</td>.*?</tr>", sliding).group(0)
    assert "onset of slip" not in row and "slides 20 m/s" in row
    still = report_html(closed(**{"web.speed": 20.0}))
    row = re.search(r"<td>mu</td>.*?</tr>", still).group(0)
    assert "nothing sliding: at the onset of slip" in row


def test_plot_under_auto_draws_what_the_chosen_model_has(tmp_path, capsys):
    from webfem.cli import main
    out = tmp_path / "v3"
    assert main(["solve", "idler", "--opt", "tol=0.99", "--plot", "--vtu", str(out),
                 "--quiet"]) == 0
    err = capsys.readouterr().err
    assert (out / "idler_auto_film.png").is_file() and "error" not in err
    assert "answered: no 2-D film" in err
    # a model named without a film is refused before anything is solved or written
    assert main(["solve", "idler", "--model", "fitted", "--plot", "--vtu",
                 str(tmp_path / "v4")]) == 2
    assert not (tmp_path / "v4").exists()


def _regime_line(**changes):
    """describe()'s regime lines for the base case's closed-form answer with ``changes``
    to its summary."""
    import dataclasses

    from webfem.describe import regime_text
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = webfem.solve(webfem.Case(), model="closed-form")
    return regime_text(dataclasses.replace(result.summary, **changes), result.case)


def test_regime_words_name_the_gap_and_the_contact_load_apart():
    """The new-user trial: a grooved PET idler printed 'regime fluid (... fluid 1.00)' and,
    further down, 'contact carries 5.8 %'; a foil printed h_c = 2.22 um 'boundary below' over
    3 sigma = 0.600 um 'fluid above'. The regime is the paper's label by the gap; the
    contact model's load share is said beside it where they disagree, and where h_c lies
    above 3 sigma the bands say there is no mixed one."""
    text = _regime_line(regime="fluid", h_c=0.938e-6, sigma=0.1413e-6, share_boundary=0.0,
                        share_mixed=0.0, share_fluid=1.0, contact_share=0.058)
    assert "regime fluid by the gap" in text and "no mixed band" in text
    assert "asperities carry 5.8 % of the wrap load" in text
    assert "mu follows this load share" in text      # the default "loads" friction
    plain = _regime_line()        # the base case: mixed, h_c 4.94 um below 3 sigma 12 um
    assert "mixed up to 3 sigma" in plain and "asperities carry" not in plain
    dry = _regime_line(regime="fluid", contact_share=0.001)   # below CONTACT_NOTED
    assert "asperities carry" not in dry


def test_film_picture_level_words_agree_when_h_c_is_above_3_sigma():
    from webfem.describe import level_words
    assert level_words(2.22e-6, 0.2e-6) == ("boundary below, fluid above",
                                            "no mixed band: below h_c")
    assert level_words(4.94e-6, 4e-6) == ("boundary below", "fluid above")


def test_a_mu_above_mu_cc_is_explained_where_printed():
    """mu is the traction over T_eff/R: above mu_cc it is an answer (the air's drag adds to
    the boundary friction), and the summary says so on its own line; below it, no line."""
    above = closed(**{"web.tension": 120.0, "roller.speed": 9.0})
    assert above.summary.mu > above.case.friction.mu_cc
    text = summary_text(above, "closed-form")
    line = next(ln for ln in text.splitlines() if "above friction.mu_cc" in ln)
    assert "traction over the wrap load T_eff/R" in line and "drag" in line
    assert "above friction.mu_cc" not in summary_text(closed(), "closed-form")
