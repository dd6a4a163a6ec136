"""Sweeps that survive interruption and scale out: serial, local processes or Dask.

Every finished point is appended to the sweep's CSV at once (flushed to disk), its VTU files
written under a temporary name and renamed; a sidecar ``.sweep.json`` records what the sweep
is (parameter, values, series, model, options, webfem version). Re-running the same sweep
finds the sidecar, keeps the converged points already in the CSV and solves the rest (points
that failed are tried again); a changed sweep starts over.
At the end the CSV is rewritten in sweep order (atomically).

Execution:

* ``workers=1`` (serial): each series in order, every point started from the previous one
  (continuation; the cheapest path for the FE models).
* ``workers=N > 1``: a pool of N local processes; the points go out in chunks of consecutive
  points of a series, continuation inside each chunk, a cold start at each chunk's first point.
* ``dask="local"`` starts a ``dask.distributed.LocalCluster``; ``dask="tcp://host:port"`` joins
  an existing scheduler; chunks are submitted as tasks.

The closed form is vectorised and always runs in-process.
"""

from __future__ import annotations

import csv
import json
import os
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Callable

from .api import solve, sweep as sweep_in_process
from .case import Case, Sweep
from .errors import ConvergenceError
from .io.tables import ROW_KEYS, sweep_rows, write_csv

__all__ = ["run", "solve_point"]


def _signature(spec: Sweep, model: str, options: dict) -> dict:
    from . import __version__
    return {"parameter": spec.parameter, "values": list(spec.values), "model": model,
            "webfem": __version__,
            "options": {k: options[k] for k in sorted(options)},
            "series": [[label, case.to_dict()] for label, case in spec.series]}


def _key(label, value) -> tuple[str, str]:
    return str(label), repr(float(value))


def solve_point(case: Case, model: str, options: dict, initial=None):
    """Solve one point; returns the full result, failures included (``converged`` False)."""
    try:
        return solve(case, model=model, initial=initial, **options)
    except ConvergenceError as err:
        return err.result


def solve_chunk(cases, model: str, options: dict):
    """Solve consecutive points of one series in a worker, each from the previous converged
    one (continuation); returns slim (picklable) results."""
    out, previous = [], None
    for case in cases:
        res = solve_point(case, model, options, previous)
        previous = res if res["converged"] else None
        out.append(res.slim())
    return out


def _load_done(csv_path: Path, sidecar: Path, signature: dict) -> dict:
    """Rows already finished by an earlier run of the same sweep, by (series, value)."""
    if not (csv_path.exists() and sidecar.exists()):
        return {}
    try:
        if json.loads(sidecar.read_text()) != json.loads(json.dumps(signature)):
            return {}
        with csv_path.open(newline="") as fh:
            rows = list(csv.DictReader(fh))
    except (OSError, ValueError):
        return {}
    # points that did not converge are tried again
    return {_key(r["series"], r["value"]): r for r in rows
            if r.get("model") and r.get("converged") == "True"}


class _Appender:
    """Appends one CSV row per finished point and forces it to disk."""

    def __init__(self, path: Path, fieldnames, fresh: bool):
        self.path = path
        self.fieldnames = list(fieldnames)
        if fresh:
            with path.open("w", newline="") as fh:
                csv.DictWriter(fh, fieldnames=self.fieldnames).writeheader()

    def write(self, row: dict) -> None:
        with self.path.open("a", newline="") as fh:
            csv.DictWriter(fh, fieldnames=self.fieldnames).writerow(row)
            fh.flush()
            os.fsync(fh.fileno())


def _chunks(todo, size):
    """Consecutive points of one series, at most ``size`` each (continuation inside)."""
    out = []
    for label, value, case in todo:
        if out and out[-1][-1][0] == label and len(out[-1]) < size:
            out[-1].append((label, value, case))
        else:
            out.append([(label, value, case)])
    return out


def run(spec: Sweep, model: str, out_csv, *, options: dict | None = None, workers: int = 1,
        dask: str | None = None, vtu_dir=None, vtu_stem: str = "sweep", chunk: int = 4,
        progress: Callable[[int, int], None] | None = None) -> list[dict]:
    """Run (or resume) a sweep, writing each point as it finishes; returns the rows in order.

    In parallel (``workers > 1`` or ``dask``) the points go out in chunks of up to ``chunk``
    consecutive points of a series, solved with continuation inside the chunk; a chunk's
    points are written when it returns (an interruption loses at most the running chunks).

    Returns a list of row dicts (strings and numbers as in the CSV, ``converged`` as bool).
    """
    options = dict(options or {})
    out_csv = Path(out_csv)
    out_csv.parent.mkdir(parents=True, exist_ok=True)
    sidecar = out_csv.with_suffix(".sweep.json")
    signature = _signature(spec, model, options)
    points = list(spec.points())
    order = {_key(label, value): i for i, (label, value, _) in enumerate(points)}

    if model == "closed-form":   # vectorised: all points at once, nothing to resume
        rows = sweep_rows(sweep_in_process(spec, model=model), spec.parameter)
        write_csv(rows, out_csv)
        if progress:
            progress(len(rows), len(rows))
        return _typed(rows)

    done = _load_done(out_csv, sidecar, signature)
    if not done:
        tmp = sidecar.with_suffix(".tmp")
        tmp.write_text(json.dumps(signature, indent=1))
        os.replace(tmp, sidecar)
        appender = _Appender(out_csv, ROW_KEYS, fresh=True)
    else:
        with out_csv.open(newline="") as fh:
            appender = _Appender(out_csv, next(csv.reader(fh)), fresh=False)
    todo = [(label, value, case) for label, value, case in points
            if _key(label, value) not in done]
    total, finished = len(points), len(points) - len(todo)
    vtu_files: dict[tuple, list] = {}

    def record(label, value, result):
        nonlocal finished
        row = sweep_rows([(label, value, result)], spec.parameter)[0]
        appender.write(row)
        if vtu_dir is not None:
            tag = "".join(ch if ch.isalnum() else "_" for ch in label).strip("_")
            for path in result.save_vtu(vtu_dir, f"{vtu_stem}_{tag}_{value:g}"):
                vtu_files.setdefault((label, tag), []).append((value, path))
        finished += 1
        if progress:
            progress(finished, total)

    if todo and dask is None and workers <= 1:
        previous: dict[str, object] = {}
        for label, value, case in todo:
            res = solve_point(case, model, options, previous.get(label))
            if res["converged"]:
                previous[label] = res
            else:
                previous.pop(label, None)
            record(label, value, res)
        chunks = []
    else:
        chunks = _chunks(todo, chunk)
    if chunks and dask is None:
        with ProcessPoolExecutor(max_workers=workers) as pool:
            futures = {pool.submit(solve_chunk, [c for _, _, c in ch], model, options): ch
                       for ch in chunks}
            for fut in as_completed(futures):
                for (label, value, _), res in zip(futures[fut], fut.result()):
                    record(label, value, res)
    elif chunks:
        from dask.distributed import Client, LocalCluster
        from dask.distributed import as_completed as dask_completed

        cluster = LocalCluster(n_workers=max(workers, 1), threads_per_worker=1,
                               processes=True, dashboard_address=None) \
            if dask == "local" else None
        client = Client(cluster if cluster is not None else dask)
        try:
            futures = {client.submit(solve_chunk, [c for _, _, c in ch], model, options,
                                     pure=False): ch for ch in chunks}
            for fut in dask_completed(list(futures)):
                for (label, value, _), res in zip(futures[fut], fut.result()):
                    record(label, value, res)
        finally:
            client.close()
            if cluster is not None:
                cluster.close()

    if vtu_dir is not None:
        from .io.vtu import write_pvd
        for (label, tag), items in vtu_files.items():
            for part in ("web", "film"):
                sel = sorted((v, p) for v, p in items if p.stem.endswith("_" + part))
                if sel:
                    write_pvd(sel, Path(vtu_dir) / f"{vtu_stem}_{tag}_{part}.pvd")
    with out_csv.open(newline="") as fh:
        latest = {_key(r["series"], r["value"]): r for r in csv.DictReader(fh)}  # last wins
    rows = sorted(latest.values(),
                  key=lambda r: order.get(_key(r["series"], r["value"]), len(order)))
    write_csv(rows, out_csv)
    return _typed(rows)


def _typed(rows: list[dict]) -> list[dict]:
    """CSV strings back to numbers and booleans."""
    out = []
    for row in rows:
        conv = {}
        for k, v in row.items():
            if isinstance(v, str):
                if v in ("True", "False"):
                    v = v == "True"
                elif v == "":
                    v = None
                else:
                    try:
                        v = float(v)
                    except ValueError:
                        pass
            conv[k] = v
        out.append(conv)
    return out
