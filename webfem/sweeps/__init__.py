"""Sweeps that survive interruption and scale out: serial, local processes or Dask.

:func:`run` writes every finished point to the sweep's CSV at once; a re-run of the same
sweep continues where the last one stopped; a lock keeps two sweeps from writing one file.

* :mod:`~webfem.sweeps.runner`: :func:`run`: resume, lock, serial or parallel execution.
* :mod:`~webfem.sweeps.workers`: what runs in worker processes or on Dask.
* :mod:`~webfem.sweeps.store`: the CSV, its sidecar and lock, resuming.
* :mod:`~webfem.sweeps.interrupt`: what an interrupted run says it saved.
* :mod:`~webfem.sweeps.table`: the CSV's columns, rows from results, reading rows back.
* :mod:`webfem.files` (shared with io): atomic writes with the user's umask, hidden temporary files.
"""

from .interrupt import SweepInterrupted
from .runner import run
from .workers import PointError, solve_chunk
from .table import ROW_KEYS, sweep_rows

__all__ = ["run", "solve_chunk", "SweepInterrupted", "PointError", "ROW_KEYS", "sweep_rows"]
