"""The grooves tables' copies in other units hold the SI tables' columns (user38: the _us
copy renamed solver_message to message, added feasible and wrote warnings as '[]')."""

from webfem.groove_sizing import LOSS_COLUMNS, MAP_COLUMNS, GrooveDesign, LossSpeed
from webfem.io.tables import write_in_units
import csv


def test_the_map_copy_has_the_csv_columns_then_the_old_ones(tmp_path):
    d = GrooveDesign(20.0, 1.27e-3, 0.25e-3, 0.25e-3, 0.8, 0.34, 4e-6, 0.9, True, True,
                     "", h_min=2e-6, warnings=("a", "b"))
    path = write_in_units([d.csv_row()], tmp_path / "g.csv", "us",
                          MAP_COLUMNS + ("feasible", "message"))
    with open(path, newline="") as f:
        header, values = list(csv.reader(f))
    assert header[:len(MAP_COLUMNS)] == ["speed_ft_per_min", "pitch_in", "width_in", "depth_in",
                                         *MAP_COLUMNS[4:6], "h_center_mil",
                                         *MAP_COLUMNS[7:10], "h_min_mil", *MAP_COLUMNS[11:]]
    assert header[len(MAP_COLUMNS):] == ["feasible", "message"]
    row = dict(zip(header, values))
    assert row["warnings"] == "a | b" and row["solver_message"] == ""
    assert row["feasible"] == "True"


def test_the_loss_copy_names_the_loss_speed(tmp_path):
    x = LossSpeed(1.27e-3, 0.25e-3, 0.25e-3, 0.8, 30.0, 0.4, 10.0, 12, True, "")
    row = x.csv_row()
    assert set(LOSS_COLUMNS) <= set(row)
    assert row["loss_speed"] == row["speed"] == 30.0
