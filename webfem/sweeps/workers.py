"""What runs in the workers: :func:`solve_chunk`, and the two ways of running chunks in
parallel, a local process pool and a Dask cluster.

Worker processes ignore Ctrl-C: the terminal sends SIGINT to the whole process group, and
the main process alone stops the sweep, then ends its workers (no worker tracebacks).
"""

from __future__ import annotations

import logging
import re
import signal
from contextlib import contextmanager
from dataclasses import dataclass

from ..api import solve_along
from ..errors import InputError, NoAdmissibleSolution
from ..result import Result

__all__ = ["solve_chunk", "PointError", "solve_path", "Processes", "Dask", "DASK_TIMEOUT_S",
           "check_workers", "check_dask"]

#: Seconds to wait for a Dask scheduler before giving up.
DASK_TIMEOUT_S = 10
_DASK_ADDRESS = re.compile(r"^(tcp|tls|ws|wss|ucx)://[^\s/]+$")


def check_dask(dask) -> str | None:
    """``dask`` when it is None, ``"local"`` or a scheduler address, else an input error
    naming it (before any work: a typo must not cost a campaign's first points)."""
    if dask is not None and dask != "local" and not (
            isinstance(dask, str) and _DASK_ADDRESS.match(dask)):
        raise InputError(f"dask = {dask!r} is not valid: must be 'local' (a cluster on this "
                         "machine) or a scheduler address such as 'tcp://host:8786'")
    return dask


@dataclass(frozen=True)
class PointError:
    """A point whose solve raised instead of answering (recorded as not converged)."""

    message: str


def solve_path(cases, model: str, options):
    """``solve_along`` over ``cases``, going on after a point that raises: it becomes a
    :class:`PointError` and the next point starts cold (one bad point must not cost the
    rest of the sweep). Input errors are the caller's and propagate, except a point the
    models cannot answer (:class:`~webfem.errors.NoAdmissibleSolution`), which is kept
    with its message like a failure."""
    i = 0
    while i < len(cases):
        try:
            for res in solve_along(cases[i:], model, options):
                i += 1
                yield res
        except NoAdmissibleSolution as err:
            i += 1
            yield PointError(str(err))
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
    for res in solve_path(list(cases), model, options):
        if isinstance(res, Result):
            res = res.slim() if fields else res.summary
        out.append(res)
    return out


class Dask:
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
            # ":0": any free port (the scheduler serves HTTP even without a dashboard)
            with _sigint_ignored():
                self.cluster = LocalCluster(n_workers=workers, threads_per_worker=1,
                                            processes=True, dashboard_address=":0",
                                            silence_logs=logging.ERROR)
            self.client = Client(self.cluster)
            return
        try:
            self.client = Client(address, timeout=f"{DASK_TIMEOUT_S}s")
        except Exception as err:   # noqa: BLE001 - refused, timed out, or not a scheduler
            reason = (str(err).strip().splitlines() or [type(err).__name__])[0]
            raise InputError(f"dask = {address!r}: no Dask scheduler answered within "
                             f"{DASK_TIMEOUT_S} s ({reason})") from None

    def run(self, tasks, record, task=solve_chunk):
        """``task(*args)`` for each ``(key, args)`` of ``tasks`` on the cluster (``task``
        must be importable by its workers); ``record(key, value)`` as each finishes (in the
        calling process)."""
        from dask.distributed import as_completed
        futures = {}
        try:
            futures = {self.client.submit(task, *args, pure=False): chunk
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


def _worker_start() -> None:
    """Set up a local worker process: Ctrl-C is the main process's to handle (SIGTERM ends
    it, as by default), and one BLAS thread. N worker processes on N cores, each with BLAS
    threads of its own (numpy and scipy start one per core), oversubscribe the machine: the
    24-point fe2d speed sweep of the base case took 5.0-7.8 s on 2 processes against 6.2 s
    serial, 3.4 s with one BLAS thread per worker (benchmarks/bench_sweeps.py). Dask's workers get the same from its
    nanny (OPENBLAS_NUM_THREADS=1 and the like)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # a forked worker inherits the command's SIGTERM handler (webfem.cli.main): the pool
    # stops its workers with SIGTERM, which must end them, not raise inside them
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    from threadpoolctl import threadpool_limits

    global _BLAS_LIMIT
    _BLAS_LIMIT = threadpool_limits(limits=1)


#: The worker's BLAS thread limit (kept for the process's life).
_BLAS_LIMIT = None


@contextmanager
def _sigint_ignored():
    """SIGINT ignored while worker processes start: they inherit the disposition and never
    see Ctrl-C, which is the main process's to handle (it stops the workers: no worker
    tracebacks). A Ctrl-C during these seconds is lost (blocking the signal instead is
    not inherited by Dask's workers)."""
    try:
        old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    except ValueError:   # not the main thread: leave signals alone
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)


#: Upper bound on ``workers`` (each is a process holding a model's matrices).
MAX_WORKERS = 256


def check_workers(workers) -> int:
    """``workers`` when it is an integer from 1 to :data:`MAX_WORKERS`, else an input error
    naming it."""
    if isinstance(workers, bool) or not isinstance(workers, int) or \
            not 1 <= workers <= MAX_WORKERS:
        raise InputError(f"workers = {workers!r} is out of range: must be an integer from 1 "
                         f"to {MAX_WORKERS}")
    return workers


class Processes:
    """A pool of local worker processes (ignoring Ctrl-C), ended at once on Ctrl-C."""

    def __init__(self, workers: int):
        from concurrent.futures import ProcessPoolExecutor
        self.pool = ProcessPoolExecutor(max_workers=workers, initializer=_worker_start)

    def run(self, tasks, record, task=solve_chunk):
        """``task(*args)`` for each ``(key, args)`` of ``tasks`` in the workers;
        ``record(key, value)`` as each finishes (in the calling process)."""
        from concurrent.futures import as_completed
        futures = {}
        try:
            futures = {self.pool.submit(task, *args): chunk for chunk, args in tasks}
            for fut in as_completed(futures):
                record(futures[fut], fut.result())
        except BaseException:
            for fut in futures:
                fut.cancel()
            self.stop()
            raise

    def stop(self):
        """End the workers now (Ctrl-C, an error): running tasks would finish first."""
        # no public API before 3.14
        for proc in list((getattr(self.pool, "_processes", None) or {}).values()):
            proc.terminate()

    def close(self):
        self.pool.shutdown(wait=True, cancel_futures=True)
