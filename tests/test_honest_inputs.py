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
