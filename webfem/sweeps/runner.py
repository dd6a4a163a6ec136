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

from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from ..api import sweep as sweep_in_memory
from ..errors import InputError
from ..models.registry import make_options
from ..result import Result
from .interrupt import SweepInterrupted, hold_interrupts
from .lock import SweepLock
from .store import Store, point_key, signature
from .table import failure_row, sweep_rows, typed
from .workers import MAX_WORKERS, Dask, PointError, Processes, check_dask, solve_path

__all__ = ["run", "SweepInterrupted", "CHUNK"]

#: Default most points per parallel task: each chunk's first point starts cold, which costs
#: iterations; longer chunks cost balance at the end and more work lost to Ctrl-C.
CHUNK = 10


@dataclass(frozen=True)
class _Point:
    series: int
    index: int
    label: str
    value: float
    case: object


def _checked(spec, workers, chunk, dask) -> list[_Point]:
    """The sweep's points, after checking the arguments (input errors before any work)."""
    for name, value, hi in (("workers", workers, MAX_WORKERS), ("chunk", chunk, None)):
        if name == "chunk" and value is None:
            continue
        if isinstance(value, bool) or not isinstance(value, int) or value < 1 or (
                hi is not None and value > hi):
            raise InputError(f"{name} = {value!r} is out of range: must be an integer >= 1"
                             + (f" and <= {hi}" if hi else ""))
    check_dask(dask)
    points = [_Point(si, pi, label, float(value), spec.case_at(base, value))
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


def _auto_chunk(points: int, workers: int) -> int:
    """At most :data:`CHUNK`, and at least three chunks per worker when points are few (the
    workers finish closer together; a chunk's cold first point now costs little more than a
    continued one: 24-point fe2d sweep on 2 processes 3.5 s in chunks of 6, 3.3 s of 4)."""
    return max(1, min(CHUNK, -(-points // (3 * workers))))


def _chunks(todo: list[int], points: list[_Point], size: int) -> list[list[int]]:
    """Consecutive points of one series in chunks of at most ``size``, of equal lengths
    (10 points in chunks of at most 4: 4, 3, 3), so the workers finish together."""
    runs: list[list[int]] = []
    for n in todo:
        if runs and points[runs[-1][-1]].series == points[n].series:
            runs[-1].append(n)
        else:
            runs.append([n])
    out = []
    for series in runs:
        parts = -(-len(series) // size)
        bounds = [round(i * len(series) / parts) for i in range(parts + 1)]
        out += [series[a:b] for a, b in zip(bounds, bounds[1:])]
    return out


def run(spec, model: str, out_csv, *, options=None, workers: int = 1,
        dask: str | None = None, chunk: int | None = None,
        progress: Callable[[int, int], None] | None = None, vtu=None,
        replace: bool = False, notice: Callable[[str], None] | None = None) -> list[dict]:
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
        and solves the rest (a torn last line included: resume); a sweep holding every
        point of the old one with the same settings keeps them and solves the new ones
        (extend); a CSV of any other sweep is refused (InputError) unless ``replace``
        (:meth:`webfem.sweeps.store.Store.decide`).
    options : Options or dict, optional
        The model's options.
    workers, dask, chunk
        ``workers`` local processes (1: serial with continuation) or a Dask cluster
        (``"local"`` or ``"tcp://host:port"``); parallel runs send chunks of up to
        ``chunk`` consecutive points of a series (default: :data:`CHUNK`, fewer when
        there are few points), solved with
        continuation inside (an interruption loses at most the running chunks).
    progress : callable, optional
        ``progress(finished, total)`` after each point solved.
    vtu : optional
        An object with ``missing(series_index, point_index)``, ``write(series_index,
        point_index, label, value, result)`` and ``close()`` (e.g.
        :class:`webfem.io.vtu.SweepVtu`); points whose files are missing are solved again.
    replace : bool
        Start over in a CSV that holds another sweep (keeping only the converged rows of
        points this sweep shares with a compatible one) instead of refusing.
    notice : callable, optional
        ``notice(text)``: told, in one line, when the CSV is resumed, extended or replaced.

    Returns
    -------
    list of dict
        The CSV's rows in sweep order, numbers as floats, ``converged`` as bool.

    Raises
    ------
    InputError
        Bad arguments, an output that cannot be written, the CSV locked by a running
        sweep (the message names it), or a CSV of another sweep without ``replace``; all
        before anything is solved.
    SweepInterrupted
        Ctrl-C (a ``KeyboardInterrupt``): says how many points are saved (a second Ctrl-C
        during the clean-up is ignored: :mod:`webfem.sweeps.interrupt`).

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
    saved: set[int] = set()
    engine = None
    restore = None
    try:
        lock.acquire()
        done = store.decide(keys, replace=replace, notice=notice)
        saved.update(done)
        todo = [n for n, p in enumerate(points) if n not in done
                or (vtu is not None and vtu.missing(p.series, p.index))]
        if todo and model != "closed-form" and (dask is not None or workers > 1):
            engine = Dask(dask, workers) if dask is not None else Processes(workers)
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
            if row["converged"] or n not in done:   # a failed re-solve keeps the old row
                store.append(row)
            if row["converged"]:
                saved.add(n)
            finished += 1
            if progress:
                progress(finished, total)

        if not todo:
            pass
        elif model == "closed-form" and vtu is None:   # vectorised: every point at once
            # (its results carry the gap at the wrap's ends only: VTU files go point by point)
            wanted = set(todo)
            for label, value, res in sweep_in_memory(spec, model, options=opts):
                n = keys[point_key(label, value)]
                if n in wanted:
                    record(n, res)
        elif engine is None:
            for si in sorted({points[n].series for n in todo}):
                mine = [n for n in todo if points[n].series == si]
                for n, res in zip(mine, solve_path([points[n].case for n in mine],
                                                    model, opts)):
                    record(n, res)
        else:
            tasks = [(ch, ([points[n].case for n in ch], model, opts, vtu is not None))
                     for ch in _chunks(todo, points, chunk or _auto_chunk(len(todo), workers))]

            def record_chunk(ch, results):
                for n, res in zip(ch, results):
                    record(n, res)
            engine.run(tasks, record_chunk)
        return typed(store.finish(keys))
    except KeyboardInterrupt as err:
        restore = hold_interrupts()   # a second Ctrl-C must not cut the clean-up or the count
        raise SweepInterrupted(len(saved), total, out_csv) from err
    finally:
        try:
            store.close()
            if engine is not None:
                engine.close()
            if vtu is not None and lock.held:
                vtu.close()
        finally:
            lock.release()
            if restore is not None:
                restore()
