"""Bad input is refused up front with a clear error naming the parameter, its value and
what is valid: never a traceback, never a sweep of failed rows."""

import numpy as np
import pytest

import webfem
from webfem.cli import main
from webfem.errors import InputError
from webfem.models.options import FittedOptions

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def bad_files(tmp_path_factory):
    d = tmp_path_factory.mktemp("coefficients")
    np.savez(d / "nokeys.npz", a=np.arange(3))
    np.save(d / "array.npy", np.arange(3))
    (d / "junk.npz").write_bytes(b"PK\x03\x04 not a zip")
    return {"toml": ROOT / "cases" / "base.toml", "nokeys": d / "nokeys.npz",
            "npy": d / "array.npy", "junk": d / "junk.npz", "missing": d / "missing.npz"}


@pytest.mark.parametrize("kind, says", [("toml", "not a NumPy .npz archive"),
                                         ("nokeys", "lacks the arrays k_centres"),
                                         ("npy", "single NumPy array"),
                                         ("junk", "not a NumPy .npz archive"),
                                         ("missing", "is no file")])
def test_bad_coefficients_file_is_an_input_error(bad_files, kind, says):
    with pytest.raises(InputError) as err:
        FittedOptions(coefficients=str(bad_files[kind]))
    text = str(err.value)
    assert "fitted option coefficients" in text and str(bad_files[kind]) in text
    assert says in text and "webfem fit build" in text


def test_solve_and_sweep_refuse_bad_coefficients_up_front(bad_files, tmp_path, capsys):
    opt = f"coefficients={bad_files['nokeys']}"
    assert main(["solve", str(ROOT / "cases" / "base.toml"), "--model", "fitted",
                 "--opt", opt]) == 2
    assert main(["sweep", str(ROOT / "cases" / "fig10_wrap.toml"), "--model", "fitted",
                 "--opt", opt, "--out", str(tmp_path / "sweep"), "--quiet"]) == 2
    assert "lacks the arrays" in capsys.readouterr().err
    assert not (tmp_path / "sweep").exists() or not any((tmp_path / "sweep").iterdir())
    with pytest.raises(InputError):
        webfem.solve(ROOT / "cases" / "base.toml", model="fitted",
                     coefficients=str(bad_files["toml"]))


def test_coefficients_help_says_what_the_file_is():
    text = FittedOptions.valid_text(
        {f.name: f for f in __import__("dataclasses").fields(FittedOptions)}
        ["coefficients"].metadata)
    assert "mesh file" not in text and ".npz" in text


# -- bad-input messages name the flag or key, the value given, the range and the unit --------

def test_traction_loss_max_speed_named_as_given(capsys):
    assert main(["traction-loss", "base", "--mu-min", "0.1", "--model", "closed-form",
                 "--max-speed", "30000 m/min"]) == 2
    err = capsys.readouterr().err
    assert "--max-speed = '30000 m/min' (500 m/s) is out of range" in err
    assert "<= 300 m/s" in err and "371" not in err


def test_traction_loss_api_refuses_a_range_above_the_roller_speeds():
    from webfem.traction import traction_loss_speed
    with pytest.raises(InputError, match="high end must be <= 300 m/s"):
        traction_loss_speed(webfem.Case(), 0.1, model="closed-form",
                            speed_range=(0.5, 1000.0))


@pytest.mark.parametrize("table, values", [
    ('start = "5 m/s"\nstop = "1200 m/min"\nnum = 3', (5.0, 12.5, 20.0)),
    ('values = ["600 m/min", 20.0]', (10.0, 20.0)),
])
def test_sweep_table_reads_unit_strings(tmp_path, table, values):
    from webfem.sweepspec import load_sweep
    path = tmp_path / "s.toml"
    path.write_text(f'[sweep]\nparameter = "roller.speed"\n{table}\n')
    assert load_sweep(path).values == pytest.approx(values)


def test_sweep_table_bad_unit_names_key_value_and_unit(tmp_path):
    from webfem.sweepspec import load_sweep
    path = tmp_path / "s.toml"
    path.write_text('[sweep]\nparameter = "web.tension"\nstart = "5 m/s"\nstop = 100\n')
    with pytest.raises(InputError) as err:
        load_sweep(path)
    text = str(err.value)
    assert "sweep.start = '5 m/s'" in text and "web.tension" in text and "N/m" in text


@pytest.mark.parametrize("flag, text, says", [
    ("--pitches", "1.27 furlong", "--pitches = '1.27 furlong': 1.27 furlong = 255.484 m is "
                                  "out of range; give lengths > 0 and <= 0.1 m"),
    ("--pitches", "abc", "--pitches = 'abc'"),
    ("--lands", "1.5", "--lands = '1.5': 1.5 is out of range; give land fractions"),
    ("--depths", "0.3", "<= 0.02 m"),
])
def test_groove_lists_name_flag_value_range_and_unit(capsys, tmp_path, flag, text, says):
    assert main(["grooves", "base", "--mu-min", "0.2", flag, text, "--out",
                 str(tmp_path / "g")]) == 2
    assert says in capsys.readouterr().err
    assert not (tmp_path / "g").exists()


def test_groove_pitches_read_unit_strings():
    from webfem.cli.grooves import _floats
    assert _floats("pitches", "1.27 mm, 0.005") == pytest.approx([1.27e-3, 5e-3])


def test_groove_lands_read_percent():
    from webfem.cli.grooves import _floats
    assert _floats("lands", "50 %, 0.8,65%") == pytest.approx([0.5, 0.8, 0.65])
    with pytest.raises(InputError, match=r"120 % = 1\.2 is out of range"):
        _floats("lands", "120 %")
    with pytest.raises(InputError, match="'half' is not a number"):
        _floats("lands", "half")
