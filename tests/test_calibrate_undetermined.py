"""A constant the data do not determine is not printed as a number (issue: gauss37): three
rows at 2, 5 and 10 m/s leave C flat (the closed form's mu does not change with it there),
so the fit leaves it at its bound, 1e-9 of the start (4e-10 m/s), which main printed as
`speed_constant = 4e-10 m/s`. The JSON says so per constant in `determined`."""

import json

from webfem.cli import main


def test_an_unidentified_constant_has_no_value(tmp_path, capsys):
    data = tmp_path / "three.csv"
    data.write_text("roller_speed,tension,wrap_deg,mu\n2,80,60,0.27\n5,80,60,0.26\n"
                    "10,80,60,0.22\n")
    assert main(["calibrate", str(data), "--case", "base", "--model", "closed-form"]) == 0
    out = capsys.readouterr().out
    line = next(x for x in out.splitlines() if x.strip().startswith("speed_constant"))
    assert "not determined by these data" in line
    assert not any(c.isdigit() for c in line), line
    assert main(["calibrate", str(data), "--case", "base", "--model", "closed-form",
                 "--json"]) == 0
    fit = json.loads(capsys.readouterr().out)
    assert fit["identified"]["speed_constant"] is False
    assert fit["determined"] == {"mu_cc": False, "speed_constant": False}
