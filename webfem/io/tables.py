"""Sweep tables: one CSV row per operating point.

The columns and the rows come from :mod:`webfem.sweeps.table` (the sweep writes its own CSV
as it runs); this module writes whole tables (temporary file, the user's umask, rename),
reads them back for charts, and writes a table's copy in metric or US units beside it.

The CSV files webfem writes are SI, always under their usual names and columns: scripts
read them, and a sweep resumes from its own. With ``--units metric|us`` a command adds a
copy ``NAME_metric.csv`` or ``NAME_us.csv`` (:func:`write_in_units`) whose dimensional
columns are converted and named with their unit (``h_center_mil``, ``value_ft_per_min``,
see :func:`webfem.units.table_in_units`).
"""

from __future__ import annotations

from pathlib import Path

from ..sweeps.table import ROW_KEYS, read_table, sweep_rows, typed, write_csv
from ..units import ROLES, table_in_units

__all__ = ["ROW_KEYS", "sweep_rows", "write_csv", "read_csv", "units_path", "write_in_units",
           "sweep_roles"]


def read_csv(path: str | Path) -> list[dict]:
    """Complete rows of a sweep CSV, numbers as floats and True/False as booleans (a torn
    last line and rows that do not parse are left out)."""
    return typed(read_table(path).rows)


def units_path(path: str | Path, system: str) -> Path:
    """Where the copy of the SI table ``path`` in ``system`` goes: ``NAME_SYSTEM.csv``."""
    path = Path(path)
    return path.with_name(f"{path.stem}_{system}{path.suffix}")


def sweep_roles(parameter: str) -> dict:
    """The roles of a sweep table's columns beyond :data:`webfem.units.ROLES`: the swept
    ``value`` measures what ``parameter`` does (none for a key without a unit)."""
    return {"value": ROLES.get(parameter)}


def write_in_units(rows: list[dict], path: str | Path, system: str, keys=None,
                   roles: dict | None = None) -> Path | None:
    """Beside the SI table ``path``, its copy in ``system`` (:func:`units_path`); ``keys``:
    the SI columns in order (default: the first row's), ``roles``: as for
    :func:`webfem.units.table_in_units`. Nothing for SI (returns None): the SI table is
    the one written anyway.

    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> out = write_in_units([{"mu": 0.2, "h_min": 4.5e-6}], folder / "t.csv", "us")
    >>> out.name, out.read_text().splitlines()[0]
    ('t_us.csv', 'mu,h_min_mil')
    """
    if system == "si":
        return None
    keys = list(keys if keys is not None else (rows[0].keys() if rows else ROW_KEYS))
    names, converted = table_in_units(rows, keys, system, roles)
    return write_csv(converted, units_path(path, system), names)
