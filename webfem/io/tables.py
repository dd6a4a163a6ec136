"""Sweep tables: one CSV row per operating point.

The columns and the rows come from :mod:`webfem.sweeps.table` (the sweep writes its own CSV
as it runs); this module writes whole tables (temporary file, the user's umask, rename) and
reads them back for charts.
"""

from __future__ import annotations

from pathlib import Path

from ..sweeps.table import ROW_KEYS, read_table, sweep_rows, typed, write_csv

__all__ = ["ROW_KEYS", "sweep_rows", "write_csv", "read_csv"]


def read_csv(path: str | Path) -> list[dict]:
    """Complete rows of a sweep CSV, numbers as floats and True/False as booleans (a torn
    last line and rows that do not parse are left out)."""
    return typed(read_table(path).rows)
