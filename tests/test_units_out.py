"""Units out (issue 13 item 2): ``--units si|metric|us`` reaches charts and CSV files.

The SI files are a contract: same names, same columns, same values whatever ``--units``
says; metric and US units get a converted copy beside them whose columns name their unit,
and charts are labelled and drawn in the units asked for.
"""

import csv
import re

import numpy as np
import pytest

import webfem
from webfem.cli import main
from webfem.errors import InputError
from webfem.io import charts
from webfem.io.tables import units_path, write_in_units
from webfem.sweeps.table import ROW_KEYS
from webfem.units import ROLES, column_name, convert, table_in_units

FT_PER_MIN = 0.3048 / 60
MIL = 2.54e-5
PLI = 4.4482216152605 / 0.0254


def read(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


# -- the one conversion ---------------------------------------------------------------------
def test_table_in_units_converts_and_names_the_unit():
    rows = [{"series": "a", "value": 20.0, "mu": 0.2, "h_min": 4.5e-6, "delta_T": 80.0,
             "converged": True, "warnings": None, "iterations": 7}]
    keys = list(rows[0])
    assert table_in_units(rows, keys, "si") == (keys, rows)    # SI: exactly as given
    names, [row] = table_in_units(rows, keys, "us", {"value": "speed"})
    assert names == ["series", "value_ft_per_min", "mu", "h_min_mil", "delta_T_pli",
                     "converged", "warnings", "iterations"]
    assert row["value_ft_per_min"] == pytest.approx(20.0 / FT_PER_MIN)
    assert row["h_min_mil"] == pytest.approx(4.5e-6 / MIL)
    assert row["delta_T_pli"] == pytest.approx(80.0 / PLI)
    # what has no unit keeps its name and value, text, booleans and empty cells included
    assert (row["series"], row["mu"], row["converged"], row["warnings"],
            row["iterations"]) == ("a", 0.2, True, None, 7)
    names, [row] = table_in_units(rows, keys, "metric", {"value": "speed"})
    assert names[1] == "value_m_per_min" and row["value_m_per_min"] == pytest.approx(1200.0)
    assert names[3] == "h_min_um" and row["h_min_um"] == pytest.approx(4.5)
    assert column_name("delta_T", "tension", "metric") == "delta_T_N_per_m"
    with pytest.raises(InputError, match="units = 'imperial' is not valid"):
        table_in_units(rows, keys, "imperial")


def test_every_dimensional_summary_key_has_a_role():
    """A summary key in m, m/s, N/m or N m that ROLES forgot would be written as SI into a
    file whose other columns are converted."""
    dimensional = {"h_center", "h_inlet", "h_outlet", "h_min", "h_c", "sigma", "x_min",
                   "delta_T", "T_eff", "delta_T_required", "delta_T_available", "U",
                   "U_slide", "bending_stiffness_used"}
    assert dimensional <= set(ROLES)
    assert not {"mu", "lambda", "beta", "eps", "kappa", "residual", "solve_time_s",
                "slip_margin", "mu_onset", "contact_share"} & set(ROLES)


# -- sweep ----------------------------------------------------------------------------------
def test_sweep_csv_stays_si_and_gets_a_converted_copy(tmp_path, capsys):
    si, us = tmp_path / "si", tmp_path / "us"
    argv = ["sweep", "base", "--model", "closed-form", "--num", "5"]
    assert main([*argv, "--out", str(si)]) == 0
    assert main([*argv, "--out", str(us), "--units", "us"]) == 0
    out = capsys.readouterr().out
    assert "base_closed-form_us.csv" in out
    assert not list(si.glob("*_us.csv")) and not list(si.glob("*_metric.csv"))
    a, b = read(si / "base_closed-form.csv"), read(us / "base_closed-form.csv")
    assert list(a[0]) == list(ROW_KEYS) == list(b[0])         # the contract: same columns
    for ra, rb in zip(a, b):                                   # and the same SI values
        assert {k: v for k, v in ra.items() if k != "solve_time_s"} == \
            {k: v for k, v in rb.items() if k != "solve_time_s"}
    conv = read(us / "base_closed-form_us.csv")
    assert len(conv) == len(b) == 5
    assert list(conv[0]) == [column_name(k, ROLES.get(k) if k != "value" else "speed", "us")
                             for k in ROW_KEYS]
    for r, s in zip(conv, b):
        assert float(r["value_ft_per_min"]) == pytest.approx(float(s["value"]) / FT_PER_MIN)
        assert float(r["h_c_mil"]) == pytest.approx(float(s["h_c"]) / MIL)
        assert float(r["delta_T_pli"]) == pytest.approx(float(s["delta_T"]) / PLI)
        assert r["mu"] == s["mu"] and r["regime"] == s["regime"]


def test_a_sweep_resumed_in_other_units_reuses_its_si_rows(tmp_path, capsys, monkeypatch):
    """The sweep's CSV is its store: asking for other units later solves nothing again."""
    argv = ["sweep", "base", "--model", "closed-form", "--num", "4", "--out", str(tmp_path)]
    assert main(argv) == 0
    first = (tmp_path / "base_closed-form.csv").read_text()
    from webfem.sweeps import runner
    monkeypatch.setattr(runner, "sweep_in_memory",
                        lambda *a, **k: pytest.fail("the sweep solved again"))
    assert main([*argv, "--units", "metric"]) == 0
    assert (tmp_path / "base_closed-form.csv").read_text() == first
    assert len(read(tmp_path / "base_closed-form_metric.csv")) == 4


def sweep_rows(n=6):
    return [{"series": "base", "parameter": "roller.speed", "value": u, "model": "fe1d",
             "mu": 0.3 - u / 200, "h_center": 8e-6, "h_inlet": 2e-5, "h_outlet": 6e-6,
             "converged": True, "h_c": 4.94e-6, "sigma": 4e-6} for u in np.linspace(5, 30, n)]


def capture(monkeypatch, module):
    """The figure a chart function of ``module`` saves, looked at before it is saved."""
    seen = {}
    real = module.save_figure

    def keep(fig, target, *a):
        fig.canvas.draw()
        seen["fig"] = fig
        seen["labels"] = [(ax.get_xlabel(), ax.get_ylabel()) for ax in fig.axes]
        seen["texts"] = [t.get_text() for ax in fig.axes for t in ax.texts]
        seen["x"] = [line.get_xdata() for line in fig.axes[0].lines]
        seen["y2"] = [line.get_ydata() for ax in fig.axes[1:2] for line in ax.lines]
        return real(fig, target)
    for name in ("_save", "save_figure"):   # the charts call one or the other
        if hasattr(module, name):
            monkeypatch.setattr(module, name, keep)
    return seen


def test_sweep_chart_draws_and_labels_the_units(tmp_path, monkeypatch):
    seen = capture(monkeypatch, charts)
    charts.sweep_chart(sweep_rows(), tmp_path / "us.png", units="us")
    (x1, y1), (_, y2) = seen["labels"][:2]
    assert x1 == "roller speed U_r [ft/min]" and "[mil]" in y2
    assert np.nanmax(seen["x"][0]) == pytest.approx(30 / FT_PER_MIN)
    assert np.nanmax(np.concatenate(seen["y2"])) == pytest.approx(2e-5 / MIL)
    assert any(re.fullmatch(r"h_c = 0\.194 mil", t) for t in seen["texts"])
    assert any(t.startswith("3 sigma = 0.472 mil") for t in seen["texts"])
    charts.sweep_chart(sweep_rows(), tmp_path / "si.png")     # SI: as it always was
    (x1, _), (_, y2) = seen["labels"][:2]
    assert x1 == "roller speed U_r [m/s]" and "[um]" in y2
    assert any(t == "h_c = 4.94 um" for t in seen["texts"])


# -- other commands -------------------------------------------------------------------------
def test_traction_loss_chart_in_us_units(tmp_path, monkeypatch, capsys):
    seen = capture(monkeypatch, charts)
    assert main(["traction-loss", "base", "--model", "closed-form", "--mu-min", "0.1",
                 "--chart", str(tmp_path), "--points", "2", "--units", "us"]) == 0
    xs = [x for x, _ in seen["labels"]]
    ys = [y for _, y in seen["labels"]]
    assert xs[0] == "roller speed U_r [ft/min]"
    assert "web tension T [pli]" in xs and "web width L [in]" in xs and \
        "roller radius R [in]" in xs and "wrap angle B [deg]" in xs
    assert all(y == "traction-loss speed [ft/min]" for y in ys[1:])


def test_idler_table_and_chart_in_us_units(tmp_path, capsys):
    argv = ["idler", "cases/idler.toml", "--model", "closed-form", "--num", "3",
            "--min-speed", "600 ft/min", "--max-speed", "3000 ft/min"]
    assert main([*argv, "--units", "us", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "line speed [ft/min]" in out and "[pli]" in out and "m/s" not in out
    lines = out.splitlines()
    assert lines[1].split() == ["line", "speed", "required", "available", "margin", "range",
                                "verdict"]
    assert lines[2].split() == ["[ft/min]", "[pli]", "[pli]", "[-]", "[-]"]
    first = lines[3].split()
    assert float(first[0]) == pytest.approx(600, rel=1e-3)
    assert (tmp_path / "idler_idler.png").exists()
    assert main(argv) == 0   # SI, the speeds given with units all the same
    assert "line speed [m/s]" in capsys.readouterr().out


def test_groove_designs_copy_and_chart(tmp_path, monkeypatch):
    """The groove map's CSV copy and charts, from designs as the command gets them."""
    from webfem.groove_sizing import GrooveDesign, LossSpeed
    from webfem.io import groove_charts
    designs = [GrooveDesign(20.0, 1.27e-3, 0.3e-3, 0.5e-3, lf, 0.2 + lf / 10, 6e-6, 0.3,
                            True, lf > 0.5) for lf in (0.4, 0.6, 0.8)]
    path = tmp_path / "g.csv"
    copy = write_in_units([d.to_dict() for d in designs], path, "us")
    assert copy == units_path(path, "us") and copy.name == "g_us.csv"
    (row, *_) = read(copy)
    assert list(row) == ["speed_ft_per_min", "pitch_in", "width_in", "depth_in",
                         "land_fraction", "mu", "h_center_mil", "contact_share",
                         "converged", "feasible", "message",
                         # extended: the stated errors are relative, not converted
                         "h_min_mil", "error_h_center", "error_h_min", "error_mu",
                         "error_contact_share", "warnings", "flag"]
    assert float(row["pitch_in"]) == pytest.approx(0.05)
    assert write_in_units([d.to_dict() for d in designs], path, "si") is None
    seen = capture(monkeypatch, groove_charts)
    groove_charts.groove_chart(designs, 0.25, tmp_path / "g.png", units="us")
    fig = seen["fig"]
    assert fig.axes[0].get_title() == "roller speed 3937 ft/min"
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "pitch 0.05 in, depth 0.0197 in" in labels
    losses = [LossSpeed(1.27e-3, 0.3e-3, 0.5e-3, 0.8, 30.0, 0.3, 5.0, 12, True, ""),
              LossSpeed(0.0, 0.0, 0.0, 1.0, 15.0, 0.3, 5.0, 12, True, "")]
    (row, *_) = read(write_in_units([x.to_dict() for x in losses], path, "us"))
    assert float(row["speed_ft_per_min"]) == pytest.approx(30.0 / 0.00508)
    assert float(row["speed_peak_ft_per_min"]) == pytest.approx(5.0 / 0.00508)
    groove_charts.loss_speed_chart(losses, 0.2, tmp_path / "l.png", (1.0, 100.0), units="us")
    fig = seen["fig"]
    assert fig.axes[0].child_axes[0].get_ylabel() == "traction-loss speed [ft/min]"
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert "pitch 0.05 in, depth 0.0197 in" in labels


@pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")
def test_film_picture_in_us_units(tmp_path, monkeypatch):
    from webfem.io import pictures
    seen = {}
    real = pictures._save

    def keep(fig, target):
        fig.canvas.draw()
        seen["labels"] = [(a.get_xlabel(), a.get_ylabel()) for a in fig.axes]
        seen["texts"] = [t.get_text() for a in fig.axes for t in a.texts]
        return real(fig, target)
    monkeypatch.setattr(pictures, "_save", keep)
    result = webfem.solve(webfem.Case(), model="closed-form")
    pictures.film_figure(result, tmp_path / "f.png", units="us")
    labels = [v for pair in seen["labels"] for v in pair]
    assert "gap h [mil]" in labels and "x along the arc from the wrap centre [in]" in labels
    assert any(t.startswith("h_c = 0.194 mil") for t in seen["texts"])
    assert not any(" um" in t or "[mm]" in t for t in labels + seen["texts"])


def test_report_in_us_units(tmp_path, capsys):
    assert main(["report", "base", "--model", "closed-form", "--units", "us", "--quiet",
                 "--out", str(tmp_path)]) == 0
    page = (tmp_path / "base_closed-form.html").read_text()
    summary = page[page.index('id="summary"'):page.index('id="pictures"')]
    inputs = page[page.index('id="inputs"'):page.index('id="model"')]
    assert "<td>mil</td>" in summary and "<td>pli</td>" in summary and "um<" not in summary
    assert "roller.speed" in inputs and "<td>ft/min</td>" in inputs
    speed = re.search(r"roller\.speed</td><td class=\"n\">([^<]+)<", inputs).group(1)
    assert float(speed) == pytest.approx(convert(20.0, "speed", "us"), rel=1e-4)
    assert "<th>unit</th>" in inputs


def test_help_says_what_units_change(capsys):
    with pytest.raises(SystemExit):
        main(["sweep", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "NAME_us.csv" in text and "CSV files stay SI" in text and "JSON stays SI" in text


def test_stated_errors_print_two_digits():
    """A stated error of 1.62 printed as '2' (README quotes 1.6): two significant digits."""
    from webfem.describe import error_text
    text = error_text({"error_h_center": 1.62, "error_h_min": 0.00043, "error_mu": None,
                       "error_contact_share": 8.5e-05})
    assert text.startswith("h_center 1.6, h_min 0.00043, contact share 8.5e-05 (")
