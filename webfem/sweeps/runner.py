"""Running a sweep into its CSV: serial with continuation, local processes or Dask.

Execution:

* ``workers=1`` (serial): each series in order through :func:`webfem.api.solve_along`,
  every point started from the previous one (continuation; the cheapest path for the FE
  models). The closed form is vectorised and always runs in-process.
* ``workers=N > 1``: a pool of N local processes; the points go out in chunks of
  consecutive points of a series, each chunk solved with ``solve_along`` in a worker.
* ``dask="local"`` starts a ``dask.distributed.LocalCluster`` of ``workers`` processes;
  ``dask="tcp://host:port"`` joins a running scheduler; the chunks are its tasks.

The models do not depend on the path (a continued solve gives the cold start's answer), so
serial, resumed, process and Dask sweeps write the same rows, in sweep order.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from ..api import solve_along, sweep as sweep_in_memory
from ..errors import InputError
from ..models.registry import make_options
from ..result import Result
from .store import Store, SweepLock, point_key, signature
from .table import failure_row, sweep_rows, typed

__all__ = ["run", "solve_chunk", "SweepInterrupted", "PointError"]

#: Upper bound on ``workers`` (each is a process holding a model's matrices).
MAX_WORKERS = 256
_DASK_ADDRESS = re.compile(r"^(tcp|tls|ws|wss|ucx)://[^\s/]+$")
#: Seconds to wait for a Dask scheduler before giving up.
DASK_TIMEOUT_S = 10


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during :func:`run`: the files are closed and the lock released; ``saved`` of
    ``total`` points are in ``csv_path`` and the same call continues from there."""

    def __init__(self, saved: int, total: int, csv_path: Path):
        super().__init__(f"interrupted: {saved} of {total} points saved in {csv_path}; "
                         "run the same command to continue")
        self.saved, self.total, self.csv_path = saved, total, Path(csv_path)


@dataclass(frozen=True)
class PointError:
    """A point whose solve raised instead of answering (recorded as not converged)."""

    message: str


@dataclass(frozen=True)
class _Point:
    series: int
    index: int
    label: str
    value: float
    case: object


def _solve_path(cases, model: str, options):
    """``solve_along`` over ``cases``, going on after a point that raises: it becomes a
    :class:`PointError` and the next point starts cold (one bad point must not cost the
    rest of the sweep). Input errors are the caller's and propagate."""
    i = 0
    while i < len(cases):
        try:
            for res in solve_along(cases[i:], model, options):
                i += 1
                yield res
        except InputError:
            raise
        except Exception as err:   # noqa: BLE001 - recorded in the row, the sweep goes on
            i += 1
            yield PointError(f"{type(err).__name__}: {err}")


def solve_chunk(cases, model: str, options, fields: bool = True) -> list:
    """Solve consecutive points of one series in a worker, with continuation.

    Returns one item per case: the slim (picklable) :class:`~webfem.result.Result`, only
    its summary when ``fields`` is False (less to send back), or a :class:`PointError`.
    """
    out = []
    for res in _solve_path(list(cases), model, options):
        if isinstance(res, Result):
            res = res.slim() if fields else res.summary
        out.append(res)
    return out


def _checked(spec, workers, chunk, dask) -> list[_Point]:
    """The sweep's points, after checking the arguments (input errors before any work)."""
    for name, value, hi in (("workers", workers, MAX_WORKERS), ("chunk", chunk, None)):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1 or (
                hi is not None and value > hi):
            raise InputError(f"{name} = {value!r} is out of range: must be an integer >= 1"
                             + (f" and <= {hi}" if hi else ""))
    if dask is not None and dask != "local" and not (
            isinstance(dask, str) and _DASK_ADDRESS.match(dask)):
        raise InputError(f"dask = {dask!r} is not valid: must be 'local' (a cluster on this "
                         "machine) or a scheduler address such as 'tcp://host:8786'")
    points = [_Point(si, pi, label, float(value), base.updated({spec.parameter: value}))
              for si, (label, base) in enumerate(spec.series)
              for pi, value in enumerate(spec.values)]
    if not points:
        raise InputError("the sweep has no points: it needs at least one value and one series")
    seen = set()
    for p in points:
        key = point_key(p.label, p.value)
        if key in seen:
            raise InputError(f"the sweep has the point (series {p.label!r}, {spec.parameter} "
                             f"= {p.value:g}) twice: series labels and values must be unique")
        seen.add(key)
    return points


class _Dask:
    """A Dask client (and the LocalCluster it started), connected before any file is
    touched: an unreachable scheduler is an input error within ``DASK_TIMEOUT_S``."""

    def __init__(self, address: str, workers: int):
        try:
            from dask.distributed import Client, LocalCluster
        except ImportError:
            raise InputError(f"dask = {address!r} needs the 'distributed' package "
                             "(pip install distributed)") from None
        self.cluster = None
        if address == "local":
            self.cluster = LocalCluster(n_workers=workers, threads_per_worker=1,
                                        processes=True, dashboard_address=None)
            self.client = Client(self.cluster)
            return
        try:
            self.client = Client(address, timeout=f"{DASK_TIMEOUT_S}s")
        except Exception as err:   # noqa: BLE001 - refused, timed out, or not a scheduler
            reason = (str(err).strip().splitlines() or [type(err).__name__])[0]
            raise InputError(f"dask = {address!r}: no Dask scheduler answered within "
                             f"{DASK_TIMEOUT_S} s ({reason})") from None

    def run(self, tasks, record):
        from dask.distributed import as_completed
        futures = {}
        try:
            futures = {self.client.submit(solve_chunk, *args, pure=False): chunk
                       for chunk, args in tasks}
            for fut in as_completed(list(futures)):
                record(futures[fut], fut.result())
        finally:
            for fut in futures:
                fut.cancel()

    def close(self):
        try:
            self.client.close()
        finally:
            if self.cluster is not None:
                self.cluster.close()


class _Processes:
    """A pool of local worker processes, ended at once on Ctrl-C."""

    def __init__(self, workers: int):
        from concurrent.futures import ProcessPoolExecutor
        self.pool = ProcessPoolExecutor(max_workers=workers)

    def run(self, tasks, record):
        from concurrent.futures import as_completed
        futures = {}
        try:
            futures = {self.pool.submit(solve_chunk, *args): chunk for chunk, args in tasks}
            for fut in as_completed(futures):
                record(futures[fut], fut.result())
        except BaseException:
            for fut in futures:
                fut.cancel()
            # running chunks would finish first: end the workers (no public API before 3.14)
            for proc in list((getattr(self.pool, "_processes", None) or {}).values()):
                proc.terminate()
            raise

    def close(self):
        self.pool.shutdown(wait=True, cancel_futures=True)


def _chunks(todo: list[int], points: list[_Point], size: int) -> list[list[int]]:
    """Consecutive points of one series, at most ``size`` each (continuation inside)."""
    out: list[list[int]] = []
    for n in todo:
        if out and points[out[-1][-1]].series == points[n].series and len(out[-1]) < size:
            out[-1].append(n)
        else:
            out.append([n])
    return out


def run(spec, model: str, out_csv, *, options=None, workers: int = 1,
        dask: str | None = None, chunk: int = 4,
        progress: Callable[[int, int], None] | None = None, vtu=None) -> list[dict]:
    """Run (or resume) a sweep, appending each point to ``out_csv`` as it finishes.

    Parameters
    ----------
    spec : Sweep
        Parameter, values and series (labels and values unique).
    model : str
        A name of :data:`webfem.models.registry.MODELS`.
    out_csv : path
        The CSV; beside it ``NAME.sweep.json`` (what the sweep is) and, while running, the
        hidden lock ``.NAME.csv.lock``. A re-run of the same sweep keeps its converged rows
        and solves the rest (a torn last line included); a different sweep starts over.
    options : Options or dict, optional
        The model's options.
    workers, dask, chunk
        ``workers`` local processes (1: serial with continuation) or a Dask cluster
        (``"local"`` or ``"tcp://host:port"``); parallel runs send chunks of up to
        ``chunk`` consecutive points of a series (an interruption loses at most the
        running chunks).
    progress : callable, optional
        ``progress(finished, total)`` after each point solved.
    vtu : optional
        An object with ``missing(series_index, point_index)``, ``write(series_index,
        point_index, label, value, result)`` and ``close()`` (e.g.
        :class:`webfem.io.vtu.SweepVtu`); points whose files are missing are solved again.

    Returns
    -------
    list of dict
        The CSV's rows in sweep order, numbers as floats, ``converged`` as bool.

    Raises
    ------
    InputError
        Bad arguments, an output that cannot be written, or the CSV locked by a running
        sweep (the message names it); all before anything is solved.
    SweepInterrupted
        Ctrl-C (a ``KeyboardInterrupt``): says how many points are saved.

    Examples
    --------
    >>> import tempfile, webfem
    >>> from webfem.sweepspec import Sweep
    >>> spec = Sweep("roller.speed", (20.0, 30.0), (("base", webfem.Case()),))
    >>> rows = run(spec, "closed-form", tempfile.mkdtemp() + "/s.csv")
    >>> [(r["value"], r["converged"]) for r in rows]
    [(20.0, True), (30.0, True)]
    """
    opts = make_options(model, options)
    points = _checked(spec, workers, chunk, dask)
    out_csv = Path(out_csv)
    sig = signature(spec, model, opts)
    store = Store(out_csv, sig)
    store.check_paths()
    keys = {point_key(p.label, p.value): n for n, p in enumerate(points)}
    total = len(points)
    lock = SweepLock(out_csv, sig)
    lock.acquire()
    saved: set[int] = set()
    engine = None
    try:
        done = store.load(keys)
        saved.update(done)
        todo = [n for n, p in enumerate(points) if n not in done
                or (vtu is not None and vtu.missing(p.series, p.index))]
        if todo and model != "closed-form" and (dask is not None or workers > 1):
            engine = _Dask(dask, workers) if dask is not None else _Processes(workers)
        store.start(done)
        finished = total - len(todo)

        def record(n: int, res) -> None:
            nonlocal finished
            p = points[n]
            if isinstance(res, PointError):
                row = failure_row(p.label, spec.parameter, p.value, model, res.message)
            else:
                if vtu is not None and isinstance(res, Result):
                    vtu.write(p.series, p.index, p.label, p.value, res)
                row = sweep_rows([(p.label, p.value, res)], spec.parameter)[0]
            if row["converged"]:
                saved.add(n)
            if row["converged"] or n not in done:   # a failed re-solve keeps the old row
                store.append(row)
            finished += 1
            if progress:
                progress(finished, total)

        if not todo:
            pass
        elif model == "closed-form":   # vectorised: every point at once
            wanted = set(todo)
            for label, value, res in sweep_in_memory(spec, model, options=opts):
                n = keys[point_key(label, value)]
                if n in wanted:
                    record(n, res)
        elif engine is None:
            for si in sorted({points[n].series for n in todo}):
                mine = [n for n in todo if points[n].series == si]
                for n, res in zip(mine, _solve_path([points[n].case for n in mine],
                                                    model, opts)):
                    record(n, res)
        else:
            tasks = [(ch, ([points[n].case for n in ch], model, opts, vtu is not None))
                     for ch in _chunks(todo, points, chunk)]

            def record_chunk(ch, results):
                for n, res in zip(ch, results):
                    record(n, res)
            engine.run(tasks, record_chunk)
        return typed(store.finish(keys))
    except KeyboardInterrupt as err:
        raise SweepInterrupted(len(saved), total, out_csv) from err
    finally:
        try:
            store.close()
            if engine is not None:
                engine.close()
            if vtu is not None:
                vtu.close()
        finally:
            lock.release()
