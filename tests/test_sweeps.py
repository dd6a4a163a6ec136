"""Sweeps lose nothing: resume after a kill or a torn line, one writer per CSV (a lock),
Ctrl-C reports what is saved, VTU files per series and point, files with the user's umask;
local processes and Dask give the serial rows in the serial order."""

import csv
import dataclasses
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

import webfem
from webfem import Case, load_sweep
from webfem.sweepspec import Sweep
from webfem.errors import InputError
from webfem.io.vtu import SweepVtu, read_field_data
from webfem.models import registry
from webfem.sweeps import SweepInterrupted, run

ROOT = Path(__file__).resolve().parents[1]
SWEEP = ('[sweep]\nparameter = "roller.speed"\n'
         'values = [30.0, 32.0, 34.0, 36.0, 38.0, 40.0, 42.0, 44.0]\n'
         '[[series]]\nlabel = "T = 80"\nweb = { tension = 80.0 }\n'
         '[[series]]\nlabel = "T = 120"\nweb = { tension = 120.0 }\n')


def small(values=(30.0, 34.0, 38.0), labels=("T = 80", "T = 120")):
    """A few fe1d points: two series of three speeds."""
    return Sweep("roller.speed", tuple(values),
                 tuple((lab, Case().updated({"web.tension": 80.0 + 40.0 * i}))
                       for i, lab in enumerate(labels)))


@pytest.fixture
def case_file(tmp_path):
    p = tmp_path / "s.toml"
    p.write_text(SWEEP)
    return p


def by_key(rows):
    return {(r["series"], float(r["value"])): r for r in rows}


def assert_same(a, b, rel=1e-9):
    """Same points in the same order, same answers."""
    assert [(r["series"], float(r["value"])) for r in a] == \
        [(r["series"], float(r["value"])) for r in b]
    for ra, rb in zip(a, b):
        for key in ("h_center", "h_min", "mu", "delta_T"):
            assert float(ra[key]) == pytest.approx(float(rb[key]), rel=rel), (ra["value"], key)
        assert ra["converged"] in (True, "True") and rb["converged"] in (True, "True")


def leftovers(folder):
    """Temporary and lock files anywhere under ``folder``."""
    return sorted(p.name for p in Path(folder).rglob(".*"))


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    out = tmp_path_factory.mktemp("serial") / "s.csv"
    return run(small(), "fe1d", out)


def counter():
    calls = []
    return calls, lambda done, total: calls.append((done, total))


# ---- the sweep and its execution ----------------------------------------------------------

def test_serial_sweep_writes_every_point_in_order(case_file, tmp_path):
    rows = run(load_sweep(case_file), "fe1d", tmp_path / "serial" / "s.csv")
    assert len(rows) == 16
    assert [r["series"] for r in rows[:8]] == ["T = 80"] * 8   # sweep order
    assert [r["value"] for r in rows[:8]] == [30.0 + 2 * i for i in range(8)]
    assert (tmp_path / "serial" / "s.sweep.json").exists()
    assert leftovers(tmp_path) == []            # no temporary file, no lock


def test_processes_equal_serial(serial, tmp_path):
    rows = run(small(), "fe1d", tmp_path / "pool" / "s.csv", workers=2, chunk=2)
    assert_same(rows, serial)


def test_dask_local_cluster_equals_serial(serial, tmp_path):
    pytest.importorskip("distributed")
    rows = run(small(), "fe1d", tmp_path / "dask" / "s.csv", workers=2, dask="local")
    assert_same(rows, serial)


def test_closed_form_sweep_resumes_nothing_to_do(tmp_path):
    spec = small(values=(10.0, 20.0, 30.0))
    rows = run(spec, "closed-form", tmp_path / "c.csv")
    calls, progress = counter()
    again = run(spec, "closed-form", tmp_path / "c.csv", progress=progress)
    assert calls == [] and again == rows


def test_a_sweep_stored_before_a_new_case_key_resumes(tmp_path):
    """A case key added later with nothing set (its value left out: None) is not a
    difference: the sweep stored without it resumes (make run refused its own out/ after
    wrap.span was added: "holds another sweep (series 'base' with other case values)"). A
    key added later whose default is a value (wrap.ends = "span", which moves the answers)
    is one: the sweep stored before it is another sweep."""
    import json

    spec = small(values=(10.0, 20.0, 30.0))
    rows = run(spec, "closed-form", tmp_path / "c.csv")
    sidecar = tmp_path / "c.sweep.json"
    sig = json.loads(sidecar.read_text())
    for _, case in sig["series"]:
        assert case["web"].pop("bending_stiffness") is None
    sidecar.write_text(json.dumps(sig))
    calls, progress = counter()
    again = run(spec, "closed-form", tmp_path / "c.csv", progress=progress)
    assert calls == [] and again == rows
    for _, case in sig["series"]:            # a value set where it was not: another sweep
        case["web"]["bending_stiffness"] = 1e-4
    sidecar.write_text(json.dumps(sig))
    with pytest.raises(InputError, match="other case values"):
        run(spec, "closed-form", tmp_path / "c.csv")
    for _, case in sig["series"]:            # stored before wrap.ends existed
        case["web"]["bending_stiffness"] = None
        assert case["wrap"].pop("ends") == "span"
    sidecar.write_text(json.dumps(sig))
    with pytest.raises(InputError, match="other case values"):
        run(spec, "closed-form", tmp_path / "c.csv")


def test_bad_arguments_refused_before_anything_runs(tmp_path):
    out = tmp_path / "x" / "s.csv"
    for kw, match in (({"dask": "foo"}, "dask = 'foo' is not valid"),
                      ({"workers": 0}, "workers = 0 is out of range"),
                      ({"chunk": 2.5}, "chunk = 2.5 is out of range"),
                      ({"options": {"levle": 1}}, "did you mean 'level'")):
        with pytest.raises(InputError, match=match):
            run(small(), "fe1d", out, **kw)
    assert not out.parent.exists()
    (tmp_path / "afile").write_text("")
    with pytest.raises(InputError, match="a file is in the way"):
        run(small(), "closed-form", tmp_path / "afile" / "s.csv")
    (tmp_path / "d.sweep.json").mkdir()
    with pytest.raises(InputError, match="is a folder"):
        run(small(), "closed-form", tmp_path / "d.csv")


def test_unreachable_scheduler_is_one_line(tmp_path, monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.setattr("webfem.sweeps.workers.DASK_TIMEOUT_S", 2)
    with pytest.raises(InputError, match="no Dask scheduler answered") as err:
        run(small(), "fe1d", tmp_path / "s.csv", dask="tcp://127.0.0.1:1")
    assert "\n" not in str(err.value)
    assert not (tmp_path / "s.csv").exists()


def test_a_point_that_raises_does_not_stop_the_sweep(tmp_path, monkeypatch):
    """A model error at one point (here a LinAlgError) is recorded as a failed row; the
    other points are solved, and the next run tries that point again."""
    spec = registry.MODELS["fe1d"]

    def broken(case, options, *, initial=None):
        if case.roller.speed == 34.0:
            raise np.linalg.LinAlgError("Singular matrix")
        return spec.solve(case, options, initial=initial)

    monkeypatch.setitem(registry.MODELS, "fe1d", dataclasses.replace(spec, solve=broken))
    rows = run(small(), "fe1d", tmp_path / "s.csv")
    failed = [r for r in rows if not r["converged"]]
    assert [(r["series"], r["value"]) for r in failed] == [("T = 80", 34.0), ("T = 120", 34.0)]
    assert failed[0]["solver_message"] == "LinAlgError: Singular matrix"
    assert sum(r["converged"] for r in rows) == 4
    monkeypatch.setitem(registry.MODELS, "fe1d", spec)
    calls, progress = counter()
    rows = run(small(), "fe1d", tmp_path / "s.csv", progress=progress)
    assert len(calls) == 2 and all(r["converged"] for r in rows)


# ---- resuming -----------------------------------------------------------------------------

KILL_SCRIPT = textwrap.dedent("""
    import sys
    from webfem import load_sweep
    from webfem.sweeps import run
    run(load_sweep(sys.argv[1]), "fe1d", sys.argv[2])
""")


def test_killed_sweep_resumes(case_file, tmp_path):
    """A sweep killed midway keeps its finished points; the same call completes it with the
    results of an uninterrupted run, solving only what was missing."""
    reference = run(load_sweep(case_file), "fe1d", tmp_path / "ref.csv")
    csv_path = tmp_path / "killed" / "s.csv"
    proc = subprocess.Popen([sys.executable, "-c", KILL_SCRIPT, str(case_file), str(csv_path)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=ROOT)
    deadline = time.time() + 120
    n = 0
    while time.time() < deadline and n < 3:
        if csv_path.exists():
            n = csv_path.read_text().count("\n") - 1
        time.sleep(0.02)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    with csv_path.open() as fh:
        partial = list(csv.DictReader(fh))
    assert 3 <= len(partial) < 16, len(partial)
    calls, progress = counter()
    rows = run(load_sweep(case_file), "fe1d", csv_path, progress=progress)  # stale lock
    assert len(calls) == 16 - len(partial)          # only the missing points
    assert_same(rows, reference)
    assert leftovers(csv_path.parent) == []


def test_changed_sweep_is_refused_unless_replace(tmp_path):
    """A sweep that would drop points of the CSV's sweep is refused, saying what differs,
    and the file is left as it was; with replace=True it starts over in the file, keeping
    the converged points the two share (same model, options and cases: the same answers)."""
    out = tmp_path / "s.csv"
    run(small(), "fe1d", out)
    before = out.read_bytes()
    with pytest.raises(InputError, match=r"s.csv holds another sweep \(2 of its 6 points are "
                                         r"not in this sweep.*--replace"):
        run(small(values=(30.0, 34.0, 37.0)), "fe1d", out)
    assert out.read_bytes() == before
    with pytest.raises(InputError, match=r"model 'fe1d', not 'closed-form'"):
        run(small(), "closed-form", out)
    calls, progress = counter()
    told = []
    rows = run(small(values=(30.0, 34.0, 37.0)), "fe1d", out, progress=progress,
               replace=True, notice=told.append)
    assert [r["value"] for r in rows[:3]] == [30.0, 34.0, 37.0] and len(rows) == 6
    assert len(calls) == 2                         # only the two points at 37
    assert len(told) == 1 and "replacing its 6 rows of another sweep" in told[0]
    assert "keeping the 4 converged points" in told[0]


def test_larger_sweep_extends_and_same_sweep_resumes_saying_so(tmp_path):
    """More values (every old point kept) extend the CSV; the same sweep resumes; each says
    what it does."""
    out = tmp_path / "s.csv"
    run(small(values=(30.0, 38.0)), "fe1d", out)
    told, (calls, progress) = [], counter()
    rows = run(small(), "fe1d", out, progress=progress, notice=told.append)
    assert len(calls) == 2 and [r["value"] for r in rows[:3]] == [30.0, 34.0, 38.0]
    assert told and "extending the sweep it holds" in told[0] and "keeping its 4" in told[0]
    told.clear()
    run(small(), "fe1d", out, notice=told.append)
    assert told == [f"{out}: resuming this sweep: 6 of 6 points already there, nothing to "
                    "solve"]


def test_a_csv_without_its_sidecar_is_not_replaced(tmp_path):
    out = tmp_path / "s.csv"
    out.write_text("my,own,table\n1,2,3\n")
    with pytest.raises(InputError, match="holds another sweep .*columns"):
        run(small(), "closed-form", out)
    assert out.read_text() == "my,own,table\n1,2,3\n"


def test_failed_points_are_retried(serial, tmp_path):
    """A point recorded as not converged is solved again on the next run, not kept."""
    out = tmp_path / "s.csv"
    run(small(), "fe1d", out)
    with out.open(newline="") as fh:
        rows = list(csv.DictReader(fh))
    rows[0]["converged"] = "False"
    with out.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    calls, progress = counter()
    again = run(small(), "fe1d", out, progress=progress)
    assert len(calls) == 1
    assert_same(again, serial)


def test_torn_last_line_and_bad_rows_are_solved_again(serial, tmp_path):
    """A kill mid-write leaves a last line cut short; rows that do not parse (extra fields,
    a number that is not one) are not fatal either: those points are solved again and the
    CSV ends with the uninterrupted answers."""
    out = tmp_path / "s.csv"
    run(small(), "fe1d", out)
    lines = out.read_text().splitlines(keepends=True)
    bad_number = lines[2].split(",")
    bad_number[5] = "0.0x1"                       # h_inlet
    no_value = lines[3].split(",")
    no_value[2] = ""
    torn = lines[-1][: len(lines[-1]) // 2]       # no newline: cut by the kill
    out.write_text(lines[0] + lines[1] + ",".join(bad_number) + ",".join(no_value) + lines[4]
                   + lines[5].rstrip("\n") + ",extra,fields\n" + torn)
    calls, progress = counter()
    rows = run(small(), "fe1d", out, progress=progress)
    assert len(calls) == 4                        # bad number, no value, extra fields, torn
    assert_same(rows, serial)
    with out.open(newline="") as fh:
        assert len(list(csv.DictReader(fh))) == 6   # clean: no None field


# ---- the lock -----------------------------------------------------------------------------

def test_concurrent_sweeps_one_writer(serial, tmp_path):
    """While a sweep runs, a different sweep into its CSV is refused with a message naming
    the running one, and so is an identical one (two writers); the running sweep completes
    correctly; after it ends, the identical re-run resumes (nothing left to solve)."""
    out = tmp_path / "s.csv"
    refusals = []

    def meddle(done, total):
        if done == 2:
            for spec in (small(values=(30.0, 34.0, 39.0)), small()):
                with pytest.raises(InputError) as err:
                    run(spec, "fe1d", out)
                refusals.append(str(err.value))

    rows = run(small(), "fe1d", out, progress=meddle)
    assert f"pid {os.getpid()}" in refusals[0] and "another sweep is writing" in refusals[0]
    assert "fe1d over roller.speed, 6 points" in refusals[0]
    assert "same sweep is already running" in refusals[1]
    assert_same(rows, serial)
    calls, progress = counter()
    assert_same(run(small(), "fe1d", out, progress=progress), serial)
    assert calls == []


def test_lock_of_an_ended_process_is_taken_over(tmp_path):
    out = tmp_path / "s.csv"
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True).stdout.strip()
    lock = tmp_path / ".s.csv.lock"
    lock.write_text('{"pid": %s, "host": "%s", "time": 0, "signature": "x"}'
                    % (dead, os.uname().nodename))
    assert len(run(small(values=(20.0,)), "closed-form", out)) == 2
    assert not lock.exists()
    lock.write_text('{"pid": %d, "host": "%s", "time": 0, "token": "left behind"}'
                    % (os.getpid(), os.uname().nodename))   # e.g. by a Ctrl-C while taken
    assert len(run(small(values=(20.0,)), "closed-form", out)) == 2
    lock.write_text('{"pid": 1, "host": "elsewhere", "time": 0, "signature": "x"}')
    with pytest.raises(InputError, match=r"pid 1 on elsewhere.*delete .*\.s\.csv\.lock"):
        run(small(values=(20.0,)), "closed-form", out)


# ---- Ctrl-C -------------------------------------------------------------------------------

@pytest.mark.parametrize("workers", [1, 2])
def test_ctrl_c_saves_reports_and_cleans_up(serial, tmp_path, workers):
    out = tmp_path / "s.csv"

    def interrupt(done, total):
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(SweepInterrupted) as err:
        run(small(), "fe1d", out, progress=interrupt, workers=workers, chunk=2)
    assert isinstance(err.value, KeyboardInterrupt)
    assert (err.value.saved, err.value.total, err.value.csv_path) == (2, 6, out)
    assert str(err.value) == (f"interrupted: 2 of 6 points saved in {out}; "
                              "run the same command to continue")
    assert leftovers(tmp_path) == []              # no temporary file, lock released
    calls, progress = counter()
    assert_same(run(small(), "fe1d", out, progress=progress, workers=workers), serial)
    assert len(calls) == 4


# ---- VTU files and modes ------------------------------------------------------------------

def test_vtu_names_unique_by_series_and_point(tmp_path):
    """Labels that sanitise alike ("x y", "x_y") and values equal to 6 digits get their own
    files; label and value are in each file and in the collections."""
    spec = small(values=(30.0, 30.0000001, 30.0000002), labels=("x y", "x_y"))
    vtu = SweepVtu(tmp_path / "vtu", "s", "roller.speed")
    run(spec, "closed-form", tmp_path / "s.csv", vtu=vtu)
    webs = sorted((tmp_path / "vtu").glob("*_web.vtu"))
    assert [p.name for p in webs] == [f"s_s{s:02d}_p{p:03d}_web.vtu"
                                      for s in (1, 2) for p in (1, 2, 3)]
    data = [read_field_data(p) for p in webs]
    assert [(d[f"series: {lab}"], d["value"]) for d, (lab, v) in zip(
        data, [(lab, v) for lab in ("x y", "x_y") for v in spec.values])] == [
        (s, v) for s in (1, 2) for v in spec.values]
    assert data[4]["roller.speed"] == 30.0000001 and data[4]["series"] == 2
    pvds = sorted(p.name for p in (tmp_path / "vtu").glob("*.pvd"))
    assert pvds == ["s_s01_x_y_web.pvd", "s_s02_x_y_web.pvd"]
    text = (tmp_path / "vtu" / "s_s01_x_y_web.pvd").read_text()
    assert 'timestep="30.0000001"' in text and 'name="x y"' in text
    assert leftovers(tmp_path) == []


def test_vtu_files_read_in_vtk_and_meshio(tmp_path):
    """The field data written beside meshio's output is valid VTK and meshio reads it."""
    vtk = pytest.importorskip("vtk")
    import meshio
    spec = small(values=(30.0,))
    run(spec, "fe1d", tmp_path / "s.csv", vtu=SweepVtu(tmp_path, "s", "roller.speed"))
    path = tmp_path / "s_s02_p001_web.vtu"
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    fd = reader.GetOutput().GetFieldData()
    assert fd.GetArray("series: T = 120").GetValue(0) == 2
    assert fd.GetArray("roller.speed").GetValue(0) == 30.0
    mesh = meshio.read(path)
    x = webfem.solve(spec.series[1][1].updated({"roller.speed": 30.0}), "fe1d").fields["x"]
    assert reader.GetOutput().GetNumberOfPoints() == len(mesh.points) == len(x)


def test_resumed_sweep_writes_missing_vtu(serial, tmp_path):
    """Re-running a finished sweep with VTU output writes the files (solving those points
    again); deleting one file and re-running writes just that one."""
    out = tmp_path / "s.csv"
    run(small(), "fe1d", out)
    folder = tmp_path / "vtu"
    calls, progress = counter()
    rows = run(small(), "fe1d", out, progress=progress, vtu=SweepVtu(folder, "s", "U"))
    assert len(calls) == 6 and len(list(folder.glob("s_s0?_p00?_web.vtu"))) == 6
    assert_same(rows, serial)
    (folder / "s_s02_p003_web.vtu").unlink()
    calls, progress = counter()
    vtu = SweepVtu(folder, "s", "U")
    run(small(), "fe1d", out, progress=progress, vtu=vtu)
    assert len(calls) == 1 and (folder / "s_s02_p003_web.vtu").exists()
    pvd = (folder / "s_s02_T___120_web.pvd").read_text()   # every point, old and new
    assert pvd.count("<DataSet") == 3 and vtu.close()[1].name == "s_s02_T___120_web.pvd"


@pytest.mark.parametrize("umask", [0o022, 0o027])
def test_file_modes_follow_the_umask(tmp_path, umask):
    old = os.umask(umask)
    try:
        run(small(values=(20.0, 30.0)), "closed-form", tmp_path / "out" / "s.csv",
            vtu=SweepVtu(tmp_path / "vtu", "s", "roller.speed"))
    finally:
        os.umask(old)
    files = list((tmp_path / "out").iterdir()) + list((tmp_path / "vtu").iterdir())
    assert {p.suffix for p in files} == {".csv", ".json", ".vtu", ".pvd"}
    assert {p.stat().st_mode & 0o777 for p in files} == {0o666 & ~umask}


def _blas_threads():
    from threadpoolctl import threadpool_info
    return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]


def test_local_workers_run_one_blas_thread_each():
    """N processes with a BLAS thread per core each oversubscribe the machine (the 24-point
    fe2d sweep on 2 processes was slower than serial); each local worker runs one."""
    from webfem.sweeps.workers import Processes

    got = {}
    pool = Processes(2)
    try:
        pool.run([(k, ()) for k in range(2)], got.__setitem__, task=_blas_threads)
    finally:
        pool.close()
    assert len(got) == 2 and all(v and set(v) == {1} for v in got.values()), got
