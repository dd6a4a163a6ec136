"""Pictures, charts and ParaView files that explain themselves: panels, markers, level labels,
units in the array names, integer regimes with their names, the full width, the in-wrap flag."""

import meshio
import numpy as np
import pytest
from matplotlib.text import Text
from PIL import Image

import webfem
from webfem.io.charts import needs_markers, sweep_chart
from webfem.io.meshes import write_meshes
from webfem.io.pictures import film_figure, film_pictures
from webfem.io.vtu import ARRAY_NAMES, FILM_FIELDS, WEB_FIELDS, read_field_data, write_result
from webfem.io.vtu import write_pvd

from conftest import inspect_before_save

# a narrow web on a small wrap: a quick fe2d solve
FAST = webfem.Case().updated({"web.width": 0.025, "wrap.angle_deg": 30.0,
                              "roller.speed": 30.0})


@pytest.fixture(scope="module")
def film_result():
    return webfem.solve(FAST, model="fe2d")


def test_film_picture_has_three_panels_and_full_width(film_result, tmp_path):
    [path] = film_pictures(film_result, tmp_path, "fast")
    assert path.name == "fast_film.png"
    with Image.open(path) as im:
        width, height = im.size
    assert 600 < width < 1000 and 0.9 * width < height < 1.2 * width   # 3 panels, compact
    import matplotlib.pyplot as plt
    from webfem.io import pictures
    seen = {}
    real_save = pictures._save

    def keep(fig, target):
        seen["fig"] = fig
        seen["axes"] = [(a.get_xlim(), a.get_ylim(), a.get_ylabel(), a.get_xlabel())
                        for a in fig.axes]
        return real_save(fig, target)

    pictures._save = keep
    try:
        film_figure(film_result, tmp_path / "again.png")
    finally:
        pictures._save = real_save
    panels = [a for a in seen["axes"] if a[2]]   # the colour bar's label is set on itself
    xlims = {a[0] for a in panels if "[mm]" in a[2] or "[um]" in a[2] or "[-]" in a[2]}
    assert len(xlims) == 1   # shared arc axis: the panels are aligned
    z_axis = next(a for a in panels if a[2].startswith("z across"))
    half_width = FAST.web.width / 2 * 1e3
    assert z_axis[1][0] <= -0.99 * half_width and z_axis[1][1] >= 0.99 * half_width
    assert any("[um]" in a[2] for a in panels) and any("mu" in a[2] for a in panels)
    assert seen["axes"][-1][3] == "" or any("[mm]" in a[3] for a in seen["axes"])
    plt.close("all")


def test_line_picture_without_film(tmp_path):
    result = webfem.solve(webfem.Case(), model="closed-form")
    path = film_figure(result, tmp_path / "cf.png")
    with Image.open(path) as im:
        assert im.size[1] < im.size[0]   # two panels only


def test_markers_on_sparse_or_log_sweeps():
    assert needs_markers(np.linspace(1, 40, 10))
    assert needs_markers(np.geomspace(0.5, 40, 80))
    assert not needs_markers(np.linspace(0.5, 40, 80))


def rows(series, h_c, n=40):
    out = []
    for label, hc in zip(series, h_c):
        for u in np.linspace(1, 40, n):
            out.append({"series": label, "parameter": "web.tension", "value": u,
                        "model": "fe1d", "mu": 0.3 - u / 200, "h_center": 1e-6 * u,
                        "h_inlet": 1.2e-6 * u, "h_outlet": 0.9e-6 * u, "converged": True,
                        "h_c": hc, "sigma": 4e-6})
    return out


def test_sweep_chart_labels_each_level_once_on_the_gap_axis(tmp_path, monkeypatch):
    from webfem.io import charts
    seen = {}
    real_save = charts._save

    def keep(fig, target):
        seen["texts"] = [(t.get_text(), t.axes) for a in fig.axes for t in a.texts]
        seen["axes"] = fig.axes
        seen["legends"] = fig.legends
        fig.canvas.draw()
        # the labels' text alone (an annotation's extent includes its leader line)
        seen["positions"] = [Text.get_window_extent(t) for a in fig.axes for t in a.texts]
        return real_save(fig, target)

    monkeypatch.setattr(charts, "_save", keep)
    sweep_chart(rows(["a", "b", "c"], [4.94e-6, 4.95e-6, 3.3e-6]), tmp_path / "c.png")
    texts = [t for t, _ in seen["texts"]]
    assert sum(t.startswith("h_c = 4.94") for t in texts) == 1
    assert sum(t.startswith("h_c = 4.95") for t in texts) == 1
    assert sum(t.startswith("3 sigma = 12.00") for t in texts) == 1   # shared: one label
    gap_axis = seen["axes"][1]
    assert all(ax is gap_axis for _, ax in seen["texts"])
    boxes = seen["positions"]   # no two labels on top of each other
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            assert not a.overlaps(b)
    assert seen["legends"] and not seen["axes"][0].get_legend()   # outside the data


def test_vtu_arrays_carry_units_and_meaning(film_result, tmp_path):
    web_path, film_path = write_result(film_result, tmp_path, "fast")
    web, film = meshio.read(web_path), meshio.read(film_path)
    assert set(WEB_FIELDS) <= set(web.point_data) and set(FILM_FIELDS) <= set(film.point_data)
    assert ARRAY_NAMES["h"] == "h [m]" and ARRAY_NAMES["p_rel"] == "p-p_a [Pa]"
    assert np.allclose(web.point_data["h [m]"], film_result.fields["h"])
    assert web.point_data["regime"].dtype.kind == "i"
    assert set(np.unique(web.point_data["regime"])) <= {0, 1, 2}
    flag = film.point_data["in_wrap"]
    half = FAST.roller.radius * FAST.B / 2
    assert np.array_equal(flag == 1, np.abs(film.points[:, 0]) <= half * (1 + 1e-12))
    # the full width, mirrored from the half solved, the centre line shared
    y = film.points[:, 1]
    assert y.min() == pytest.approx(-FAST.web.width / 2) and y.max() == pytest.approx(
        FAST.web.width / 2)
    assert len(film.points) < 2 * len(film_result.film["points"])
    p = film.point_data["p-p_a [Pa]"]
    key = np.round(film.points[:, :2] * 1e9).astype(np.int64)
    lookup = {tuple(k): v for k, v in zip(key, p)}
    assert all(lookup[(k[0], -k[1])] == pytest.approx(v) for k, v in zip(key, p))
    data = read_field_data(film_path)
    assert data["regime 2 = fluid (h > 3 sigma)"] == 2.0
    assert data["mu (wrap average) [-]"] == pytest.approx(film_result["mu"])
    assert any(k.startswith("X = arc") for k in data)


def test_pvd_names_the_swept_parameter(tmp_path):
    path = write_pvd([(1.0, tmp_path / "a.vtu")], tmp_path / "s.pvd", parameter="web.tension")
    text = path.read_text()
    assert 'parameter="web.tension"' in text and "time (timestep) = web.tension" in text


def test_stored_meshes_say_what_their_coordinates_mean(tmp_path):
    web, film = write_meshes(np.linspace(-0.03, 0.03, 7), np.linspace(0, 0.01, 3), tmp_path,
                             "m", half_wrap=0.02)
    mesh = meshio.read(film)
    assert np.array_equal(mesh.point_data["arc x [m]"], mesh.points[:, 0])
    assert np.array_equal(mesh.point_data["in_wrap"] == 1, np.abs(mesh.points[:, 0]) <= 0.02 * (1 + 1e-12))
    data = read_field_data(web)
    assert any(k.startswith("X = arc from the wrap centre [m]") for k in data)
    assert data["wrap edges at X = -+0.02 m (R B / 2)"] == 0.02


def test_sweep_chart_draws_a_level_that_moves_as_a_curve_and_its_labels_clear(
        tmp_path, monkeypatch):
    """The new-user trial's newsprint tension sweep: h_c falls with the tension (8.65 to
    1.12 um), and a flat line per point's h_c stacked four labels over the curves at the
    lower right. A level that moves along a series is one curve named in the legend; the
    constant 3 sigma keeps its one label, at the left end here: every gap ends at the right
    on the 3 sigma line, where the label would cover them."""
    from webfem.io import charts
    seen = {}
    real_save = charts._save

    def keep(fig, target):
        fig.canvas.draw()
        seen["texts"] = [t.get_text() for a in fig.axes for t in a.texts]
        seen["sides"] = [t.get_ha() for a in fig.axes for t in a.texts]
        seen["legend"] = [t.get_text() for t in fig.legends[0].texts]
        return real_save(fig, target)

    monkeypatch.setattr(charts, "_save", keep)
    data = []
    for label, scale in (("wrap 120", 1.0), ("wrap 60", 1.05)):
        for T, hc in zip((100.0, 200.0, 300.0, 500.0), (8.65e-6, 5.16e-6, 3.33e-6, 1.12e-6)):
            data.append({"series": label, "parameter": "web.tension", "value": T,
                         "model": "fe1d", "mu": T / 1e4, "h_center": scale * 6.2e-3 / T,
                         "h_inlet": scale * 6.6e-3 / T, "h_outlet": scale * 6e-3 / T,
                         "converged": True, "h_c": hc, "sigma": 4e-6})
    sweep_chart(data, tmp_path / "news.png")
    assert not any(t.startswith("h_c =") for t in seen["texts"])
    assert seen["texts"] == ["3 sigma = 12.00 um"] and seen["sides"] == ["left"]
    assert "h_c (contact gap): moves with the parameter" in seen["legend"]



def test_sweep_chart_scales_its_gap_axis_to_the_centre_where_the_edges_lift_off(
        tmp_path, monkeypatch):
    """The trial's board tension sweep: the stiff board leaves the roller at the wrap's
    edges (inlet 2.9 mm, exit 2.2 mm at 100 N/m) while its centre gap is tens of microns; a
    gap axis to 3000 um flattened the centre gap and h_c to its floor. The axis is scaled
    to the centre gap and the levels, and the legend says how far the edge gaps run off;
    a sweep without such edges keeps the axis from 0 to its largest gap."""
    from webfem.io import charts
    seen = {}
    real_save = charts._save

    def keep(fig, target):
        seen["top"] = fig.axes[1].get_ylim()[1]
        seen["legend"] = [t.get_text() for t in fig.legends[0].texts]
        return real_save(fig, target)

    monkeypatch.setattr(charts, "_save", keep)

    def board(edge):
        return [{"series": "base", "parameter": "web.tension", "value": T, "model": "fe2d",
                 "mu": T / 3e4, "h_center": 4e-3 / T, "h_inlet": edge / T,
                 "h_outlet": 0.8 * edge / T, "converged": True, "h_c": 1e-6, "sigma": 3e-6}
                for T in (100.0, 300.0, 960.0)]

    sweep_chart(board(0.29), tmp_path / "board.png")
    assert 40.0 <= seen["top"] <= 80.0                   # 1.5 x the 40 um centre gap
    assert "(edge gaps up to 2900 um: off the top of the gap axis)" in seen["legend"]
    assert "mu (fe2d)" in seen["legend"]                 # one series: no "base:" prefix
    sweep_chart(board(6e-3), tmp_path / "flat.png")
    assert seen["top"] >= 60.0 and not any("off the top" in t for t in seen["legend"])

def _idler_figure(monkeypatch, tmp_path, margins, speeds=None):
    """The idler chart of a curve with these margins: its right panel's y limits, its
    legend's texts, and the boxes of its words (measured before the save closes it)."""
    from webfem.idler import MarginCurve
    from webfem.io import idler_chart as module

    n = len(margins)
    speeds = speeds or tuple(np.linspace(1.0, 10.0, n))
    curve = MarginCurve("fe1d", speeds, (1.25,) * n, tuple(1.25 * m for m in margins),
                        tuple(margins), (0.0,) * n, (True,) * n)
    seen = {}

    def measure(fig, renderer):
        b = fig.axes[1]
        seen.update(ylim=b.get_ylim(), legend=[t.get_text() for t in b.get_legend().texts]
                    if b.get_legend() else [],
                    words={t.get_text(): t.get_window_extent(renderer) for t in b.texts})

    inspect_before_save(monkeypatch, module, measure)
    module.idler_chart(curve, tmp_path / "i.png")
    return seen


def test_idler_chart_shows_margins_far_below_its_floor(monkeypatch, tmp_path):
    """The new-user trial's PET idler: margins 1e-16 to 1e-89 lay below the axis (1e-4) and
    no mark said so. Now they sit on the floor (at most six decades below the slip line)
    as triangles a legend explains with the smallest margin; a margin within the floor is
    drawn where it is (the axis reaches it); the words never overlap."""
    seen = _idler_figure(monkeypatch, tmp_path, [9.3e-17, 1e-30, 3.2e-42, 5.3e-89])
    assert seen["ylim"][0] == pytest.approx(1e-6)
    assert any("below 1e-06" in t and "5.3e-89" in t for t in seen["legend"])
    words = seen["words"]
    assert "slips at every speed shown" in words
    boxes = list(words.values())
    for i, one in enumerate(boxes):
        for other in boxes[i + 1:]:
            assert not one.overlaps(other), list(words)
    seen = _idler_figure(monkeypatch, tmp_path, [8.0, 2.0, 0.5, 8.4e-5])
    assert seen["ylim"][0] < 8.4e-5 and seen["legend"] == []
    assert any(t.startswith("slips above") for t in seen["words"])


def test_idler_table_says_it_slips_all_along_when_it_slips_at_the_lowest_speed():
    """Slipping at the lowest speed answered is no onset: the PET idler's table said 'slips
    above about 1 m/s', as if it held below."""
    from webfem.cli.idler import _table
    from webfem.idler import MarginCurve

    def text(margins):
        n = len(margins)
        return _table(MarginCurve("fe1d", tuple(np.linspace(1.0, 10.0, n)), (1.25,) * n,
                                  tuple(1.25 * m for m in margins), tuple(margins),
                                  (0.0,) * n, (True,) * n), "si")
    assert "slips at every speed tried (1 m/s to 10 m/s)" in text([1e-16, 1e-30, 1e-42])
    assert "slips above about" in text([3.0, 2.0, 0.5])


# --- the gap panel's level labels clear of the data (issue tail38, 3) ---

def _gap_labels(monkeypatch, tmp_path, result):
    """The gap panel's level labels (their boxes), its other lines and its gap curve as
    drawn (display coordinates), and its legend's texts, measured before the save."""
    from matplotlib.path import Path as LinePath
    from webfem.io import pictures
    seen = {}

    def measure(fig, renderer):
        ax = fig.axes[-2]
        seen["labels"] = {t.get_text(): t.get_window_extent(renderer) for t in ax.texts
                          if t.get_text().startswith(("h_c =", "3 sigma ="))}
        lines = ax.get_lines()
        seen["curve"] = LinePath(ax.transData.transform(lines[0].get_xydata()))
        seen["lines"] = [(line.get_color(), LinePath(line.get_transform().transform(
            line.get_xydata()))) for line in lines[1:]]
        seen["frame"] = ax.bbox
        legend = ax.get_legend()
        seen["legend"] = [t.get_text() for t in legend.texts] if legend else []

    inspect_before_save(monkeypatch, pictures, measure, "_save")
    pictures.film_figure(result, tmp_path / "f.png")
    return seen


@pytest.mark.parametrize("name, speed, model", [
    ("press_idler", 5.0, "fe1d"),       # main: both labels over the inlet's falling gap
    ("idler", 10.0, "fe1d"),
    ("base", 20.0, "closed-form")])
def test_the_level_labels_cross_no_line_of_the_gap_panel(monkeypatch, tmp_path, name,
                                                         speed, model):
    """Each level's label (h_c, 3 sigma) is on the panel, crossing neither the gap curve
    nor another level's line nor a wrap edge (main put both at the left end, over the
    inlet, where the gap falls through them: press_idler at 300 m/min)."""
    case = webfem.load_case(name).updated({"roller.speed": speed, "web.speed": speed}
                                          if name != "base" else {"roller.speed": speed})
    r = webfem.solve(case, model=model)
    seen = _gap_labels(monkeypatch, tmp_path, r)
    assert len(seen["labels"]) + sum(t.startswith(("h_c =", "3 sigma ="))
                                     for t in seen["legend"]) == 2
    assert len(seen["labels"]) == 2          # these cases have room on the panel
    for text, box in seen["labels"].items():
        assert seen["frame"].contains(box.x0, box.y0) and seen["frame"].contains(box.x1,
                                                                                 box.y1)
        assert not seen["curve"].intersects_bbox(box, filled=False), text
        own = "tab:orange" if text.startswith("h_c") else "tab:blue"
        for colour, line in seen["lines"]:
            if colour != own:
                assert not line.intersects_bbox(box, filled=False), (text, colour)
    a, b = seen["labels"].values()
    assert not a.overlaps(b)


def test_a_level_below_zero_is_named_in_the_legend(monkeypatch, tmp_path):
    """A web resting compressed (h_c < 0: board on its idler) has no place on the log gap
    axis: the legend names it (main annotated it at a log of a negative number, off the
    panel, and the layout shrank the picture around it)."""
    r = webfem.solve("board", model="closed-form")
    assert r["h_c"] < 0
    seen = _gap_labels(monkeypatch, tmp_path, r)
    assert [t for t in seen["legend"] if t.startswith("h_c =")] == [
        f"h_c = {r['h_c'] * 1e6:.2f} um (boundary below): below 0, off the log axis"]
    assert not any(t.startswith("h_c") for t in seen["labels"])
