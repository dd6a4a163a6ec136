"""Resumable tables of points that are not a one-parameter sweep (e.g. the groove sizing map:
pitch x land fraction x depth x speed), with the sweep's store and lock.

Each point is identified by the exact text of its ``key_columns`` (floats, ``repr``); its row
is appended to the CSV (and forced to disk) as soon as it is solved, beside the sidecar
holding the table's signature. A re-run with the same signature keeps the converged rows (and
with ``keep_failures`` the others) and solves the rest; a different signature starts over; a
second writer is refused by the lock (:mod:`webfem.sweeps.store`).

Examples
--------
>>> import tempfile, pathlib
>>> path = pathlib.Path(tempfile.mkdtemp()) / "squares.csv"
>>> sig = {"model": "none", "parameter": "x", "points": 2}
>>> solve = lambda n: {"x": [1.0, 2.0][n], "mu": [1.0, 2.0][n] ** 2, "converged": True}
>>> rows = run_points(path, sig, ("x", "mu", "converged"), ("x",), [(1.0,), (2.0,)], solve)
>>> [(r["x"], r["mu"]) for r in rows]
[(1.0, 1.0), (2.0, 4.0)]
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable, Sequence

from .interrupt import SweepInterrupted, hold_interrupts
from .lock import SweepLock
from .store import Store
from .table import typed
from .workers import Dask, Processes, check_dask, check_workers

__all__ = ["run_points", "exact_key"]


def exact_key(values) -> tuple[str, ...]:
    """A point's identity: the exact text of each of its key values."""
    return tuple(repr(float(v)) for v in values)


def run_points(csv_path, sig: dict, columns: Sequence[str], key_columns: Sequence[str],
               points: Sequence[Sequence[float]], solve: Callable[[int], dict], *,
               progress: Callable[[int, int], None] | None = None,
               keep_failures: bool = False, workers: int = 1,
               dask: str | None = None, what: str = "points",
               notice: Callable[[str], None] | None = None) -> list[dict]:
    """Solve (or resume) every point, saving each row as it finishes.

    Parameters
    ----------
    csv_path : path
        The table; beside it ``NAME.sweep.json`` (``sig``) and, while running, the lock.
    sig : dict
        What makes two runs the same table (JSON-ready), with ``model`` and ``parameter``
        for the lock's message. A run whose ``sig`` differs starts the table afresh: leave
        out of it what may change between runs whose rows stay valid (the fit campaign's
        number of design points: more extend the same design).
    columns, key_columns : sequences of str
        The CSV's columns (one of them ``converged``) and those identifying a point.
    points : sequence of sequences of float
        Each point's values of ``key_columns``, in table order (unique).
    solve : callable
        ``solve(n)``: the row of point n (a dict with ``columns``).
    progress : callable, optional
        ``progress(finished, total)`` after each point (finished counts the kept ones).
    keep_failures : bool
        False: a re-run solves the points that did not converge again (as a sweep does);
        True: their rows are kept (points solved from cold fail again the same way).
    workers : int
        1: the points in order in this process; N > 1: in a pool of N local processes
        (``solve`` must then be picklable, and each point independent of the others), each
        row saved as it arrives (the CSV is in point order at the end; an interrupted
        run's is in the order the rows finished).
    dask : str, optional
        Run the points on Dask instead, one task per point: ``"local"`` starts a
        LocalCluster of ``workers`` processes, ``"tcp://host:port"`` joins a running
        scheduler (connected before the table is touched; ``solve`` must be importable by
        the cluster's workers). A Dask worker solves in a thread, not its main one.
    what : str
        What a point is called in messages ("designs", "geometries").
    notice : callable, optional
        ``notice(text)``: told, in one line, when the table is resumed (how many ``what``
        are there, how many are left) or an existing table of another run is started over.

    Returns
    -------
    list of dict
        The rows in point order, numbers as floats (None where empty), ``converged`` bool.

    Raises
    ------
    InputError
        An output that cannot be written, or a table locked by a running writer.
    SweepInterrupted
        Ctrl-C: the files are closed, the lock released; says how many ``what`` are saved
        (a second Ctrl-C during the clean-up is ignored).
    """
    check_workers(workers)
    check_dask(dask)
    csv_path = Path(csv_path)
    keys = {exact_key(p): n for n, p in enumerate(points)}
    if len(keys) != len(points):
        raise ValueError("run_points: two points have the same key")
    store = Store(csv_path, sig, columns,
                  row_key=lambda row: exact_key(row[k] for k in key_columns),
                  keep_failures=keep_failures)
    store.check_paths()
    lock = SweepLock(csv_path, sig, len(points))
    saved = 0
    engine = None
    restore = None
    try:
        lock.acquire()
        held = csv_path.is_file() and csv_path.stat().st_size > 0
        done = store.load(keys)
        saved = len(done)                       # the rows a re-run keeps
        total = len(points)
        todo = [n for n in range(total) if n not in done]
        if notice and done:
            notice(f"{csv_path}: resuming: {len(done)} of {total} {what} already there, "
                   + (f"solving the other {len(todo)}" if todo else "nothing to solve"))
        elif notice and held and store.same_sweep:
            why = ("the earlier run was stopped before any was solved" if not store.rows_found
                   else f"its {store.rows_found} rows did not converge: solved again")
            notice(f"{csv_path}: resuming: none of its {total} {what} kept ({why}), "
                   "solving them all")
        elif notice and held:
            notice(f"{csv_path}: starting afresh: the table there is not this run's (other "
                   "arguments or case, or no readable sidecar), its rows are replaced")
        if dask is not None and todo:
            engine = Dask(dask, workers)        # an unreachable scheduler: before any write
        elif workers > 1 and len(todo) > 1:
            engine = Processes(min(workers, len(todo)))
        store.start(done)
        finished = len(done)
        if progress and done:
            progress(finished, total)

        def record(n: int, row: dict) -> None:
            nonlocal saved, finished
            store.append(row)
            saved += bool(row["converged"] or keep_failures)
            finished += 1
            if progress:
                progress(finished, total)

        if engine is not None:
            engine.run([(n, (n,)) for n in todo], record, task=solve)
        else:
            for n in todo:
                record(n, solve(n))
        return typed(store.finish(keys))
    except KeyboardInterrupt as err:
        restore = hold_interrupts()   # a second Ctrl-C must not cut the clean-up or the count
        raise SweepInterrupted(saved, len(points), csv_path, what) from err
    finally:
        try:
            store.close()
            if engine is not None:
                engine.close()
        finally:
            lock.release()
            if restore is not None:
                restore()
