"""Sweeps: resume after a kill, local processes and Dask give the serial answers."""

import csv
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from webfem import load_sweep
from webfem.sweeps import run

SWEEP = '[sweep]\nparameter = "roller.speed"\nvalues = [26.0, 28.0, 30.0, 32.0, 34.0, 36.0, 38.0, 40.0]\n' \
        '[[series]]\nlabel = "T = 80"\nweb = { tension = 80.0 }\n' \
        '[[series]]\nlabel = "T = 120"\nweb = { tension = 120.0 }\n'


@pytest.fixture
def case_file(tmp_path):
    p = tmp_path / "s.toml"
    p.write_text(SWEEP)
    return p


def by_key(rows):
    return {(r["series"], float(r["value"])): r for r in rows}


def assert_same(a, b, rel=1e-6):
    A, B = by_key(a), by_key(b)
    assert A.keys() == B.keys()
    for k in A:
        for key in ("h_center", "h_min", "mu"):
            assert float(A[k][key]) == pytest.approx(float(B[k][key]), rel=rel), (k, key)
        assert A[k]["converged"] in (True, "True") and B[k]["converged"] in (True, "True")


@pytest.fixture
def serial(case_file, tmp_path):
    return run(load_sweep(case_file), "fe1d", tmp_path / "serial" / "s.csv")


def test_serial_sweep_writes_every_point(serial, tmp_path):
    assert len(serial) == 16
    assert [r["series"] for r in serial[:8]] == ["T = 80"] * 8   # sweep order
    assert (tmp_path / "serial" / "s.sweep.json").exists()


def test_processes_equal_serial(case_file, serial, tmp_path):
    rows = run(load_sweep(case_file), "fe1d", tmp_path / "pool" / "s.csv", workers=2)
    assert_same(rows, serial)


def test_dask_local_cluster_equals_serial(case_file, serial, tmp_path):
    pytest.importorskip("distributed")
    rows = run(load_sweep(case_file), "fe1d", tmp_path / "dask" / "s.csv", workers=2,
               dask="local")
    assert_same(rows, serial)


def test_killed_sweep_resumes(case_file, serial, tmp_path):
    """A sweep killed midway keeps its finished points; the same command completes it with the
    results of an uninterrupted run, solving only what was missing."""
    out = tmp_path / "killed"
    cmd = [sys.executable, "-m", "webfem", "sweep", str(case_file), "--model", "fe1d",
           "--out", str(out), "--quiet"]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            cwd=Path(__file__).resolve().parents[1])
    csv_path = out / "s_fe1d.csv"
    deadline = time.time() + 120
    n = 0
    while time.time() < deadline:
        if csv_path.exists():
            with csv_path.open() as fh:
                n = sum(1 for _ in fh) - 1
            if n >= 3:
                break
        time.sleep(0.05)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    with csv_path.open() as fh:
        partial = list(csv.DictReader(fh))
    assert 3 <= len(partial) < 16, len(partial)
    solved = []
    rows = run(load_sweep(case_file), "fe1d", csv_path,
               progress=lambda done, total: solved.append(done))
    assert len(solved) == 16 - len(partial)          # only the missing points
    assert_same(rows, serial)


def test_changed_sweep_starts_over(case_file, tmp_path):
    out = tmp_path / "s.csv"
    run(load_sweep(case_file), "fe1d", out)
    case_file.write_text(SWEEP.replace("40.0]", "39.0]"))
    calls = []
    rows = run(load_sweep(case_file), "fe1d", out, progress=lambda d, t: calls.append(d))
    assert len(calls) == 16 and any(float(r["value"]) == 39.0 for r in rows)


def test_failed_points_are_retried(case_file, tmp_path):
    """A point recorded as not converged is solved again on the next run, not kept."""
    out = tmp_path / "r" / "s.csv"
    rows = run(load_sweep(case_file), "fe1d", out)
    text = out.read_text().splitlines()
    header, first = text[0], text[1].split(",")
    conv = header.split(",").index("converged")
    first[conv] = "False"
    out.write_text("\n".join([header, ",".join(first)] + text[2:]) + "\n")
    calls = []
    again = run(load_sweep(case_file), "fe1d", out, progress=lambda d, t: calls.append(d))
    assert len(calls) == 1 and len(again) == len(rows)
    assert all(r["converged"] for r in again)
