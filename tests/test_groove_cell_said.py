"""What a periodic groove cell's files and pictures say they show (issue 38, items 2-4):
``webfem mesh`` writes the mesh fe2d solves (the cell, not the smooth half width), the
report's caption and the VTU field data name one groove pitch, not the web's width, the
report says "periodic cell, edges estimated to change it by ...", and the sweep chart draws
gaps below 0 (a web resting compressed) with its legend clear of its title."""

import numpy as np
import pytest

from webfem.cli import main
from webfem.io import charts
from webfem.io.report import write_report
from webfem.io.vtu import read_field_data, write_result
from webfem.models import fe2d

from conftest import GROOVED, inspect_before_save


@pytest.fixture(scope="module")
def cell():
    """base_grooved's periodic cell (a few seconds at error_tol 1 %)."""
    return fe2d.solve(GROOVED, grooves="cell", error_tol=0.01)


def _film_y(path):
    import meshio
    return meshio.read(path).points[:, 1]


def test_mesh_writes_the_periodic_cell_fe2d_solves(tmp_path, capsys):
    """main wrote base's smooth half width (17.5 mm, byte-identical to base's film mesh)."""
    assert main(["mesh", "base_grooved", "--out", str(tmp_path / "g")]) == 0
    out = capsys.readouterr().out
    assert "the periodic groove cell, a land centre to a groove centre" in out
    y = _film_y(tmp_path / "g" / "base_grooved_film.vtu")
    assert y.min() == 0.0 and y.max() == pytest.approx(0.5 * 1.27e-3, rel=1e-9)
    # the land/groove edge is a node line, as in the solve
    assert np.any(np.isclose(y, 0.5 * (1.27e-3 - 0.25e-3), rtol=1e-9))
    assert any(k.startswith("Y = across one periodic groove cell")
               for k in read_field_data(tmp_path / "g" / "base_grooved_film.vtu"))
    assert main(["mesh", "base_grooved", "--out", str(tmp_path / "f"),
                 "--opt", "grooves=full"]) == 0
    assert "grooved half width" in capsys.readouterr().out
    assert _film_y(tmp_path / "f" / "base_grooved_film.vtu").max() == pytest.approx(
        0.5 * GROOVED.web.width, rel=1e-9)


def test_a_cells_vtu_and_report_say_one_groove_pitch(cell, tmp_path):
    """main: the caption said "Film pressure over the full width" and the field data "Y =
    across the width from the centre line"; the report never said "periodic cell"."""
    _web, film = write_result(cell, tmp_path, "cell")
    names = read_field_data(film)
    assert not any("across the width from the centre line" in k for k in names)
    assert any(k.startswith("Y = across one groove pitch") for k in names)
    y = _film_y(film)
    assert y.max() - y.min() == pytest.approx(1.27e-3, rel=1e-9)     # mirrored: one pitch
    html = write_report(cell, tmp_path).read_text()
    assert "Film pressure over the full width" not in html
    assert "Film pressure over one groove pitch (the periodic cell" in html
    est = cell["error_edges"] / 2.0
    assert f"periodic cell, edges estimated to change it by {est:.3g}" in html


def test_sweep_chart_draws_gaps_below_zero_and_keeps_its_legend_off_the_title(
        tmp_path, monkeypatch):
    """The grooved sweep over groove widths 0-1.2 mm: at 1.2 mm the web rests compressed
    (h_center -10.4 um); main cut the gap axis at 0 without a word and its legend, on the
    right, ran over the two-line title."""
    seen = {}

    def inspect(fig, renderer):
        ax, ax2 = fig.axes[:2]
        seen["bottom"] = ax2.get_ylim()[0]
        legend = fig.legends[0]
        seen["legend"] = [t.get_text() for t in legend.texts]
        lg, tt = legend.get_window_extent(renderer), ax.title.get_window_extent(renderer)
        # clear of the title: below it, or 20 px beside it (main: 5 px apart at the canvas's
        # 100 dpi, overlapping in the PNG written at 110)
        seen["overlap"] = not (lg.y1 <= tt.y0 or lg.x0 >= tt.x1 + 20 or lg.x1 <= tt.x0 - 20)
        box = fig.bbox
        seen["inside"] = all(box.x0 - 1 <= b.x0 and b.x1 <= box.x1 + 1 for b in (
            legend.get_window_extent(renderer), ax.title.get_window_extent(renderer)))

    inspect_before_save(monkeypatch, charts, inspect, "_save")
    rows = [{"series": "base", "parameter": "roller.groove_width", "value": g,
             "model": "auto", "model_used": "fe2d", "converged": True, "mu": mu,
             "h_center": hc, "h_inlet": hi, "h_outlet": ho, "h_c": 4.94e-6, "sigma": 4e-6,
             "error_h_center": 3e-4, "error_h_min": 4e-4, "error_mu": 3e-4}
            for g, mu, hc, hi, ho in ((0.0, 0.15, 10.3e-6, 53e-6, 5.4e-6),
                                      (0.4e-3, 0.34, 3.4e-6, 16.7e-6, 2.4e-6),
                                      (1.2e-3, 0.30, -10.4e-6, -1.0e-6, -4.8e-6))]
    charts.sweep_chart(rows, tmp_path / "s.png",
                       title="base_grooved: auto: fe2d at every point (no closed-form "
                             "curve: it refuses this case)")
    assert seen["bottom"] <= -10.4 * 1.05
    assert any(t.startswith("h = 0 (below: the web rests compressed") and "-10.4 um" in t
               for t in seen["legend"])
    assert not seen["overlap"] and seen["inside"]
