"""Sweep tables: one CSV row per operating point, written atomically."""

from __future__ import annotations

import csv
import os
import tempfile
from pathlib import Path

from ..result import SUMMARY_KEYS

__all__ = ["ROW_KEYS", "sweep_rows", "write_csv", "read_csv"]

EXTRA_KEYS = ("h_c", "sigma", "share_boundary", "share_mixed", "share_fluid", "contact_share",
              "eps", "kappa", "U", "U_slide", "residual", "solver_message", "mesh", "warnings")
#: The columns of a sweep CSV, in order.
ROW_KEYS = ("series", "parameter", "value") + SUMMARY_KEYS + EXTRA_KEYS


def sweep_rows(points, parameter: str) -> list[dict]:
    """Rows from ``(label, value, Result)`` triples: series, swept value, summary keys."""
    rows = []
    for label, value, res in points:
        data = res.to_json()
        row = {"series": label, "parameter": parameter, "value": value}
        for key in SUMMARY_KEYS + EXTRA_KEYS:
            v = data.get(key)
            row[key] = "; ".join(v) if isinstance(v, list) else v
        rows.append(row)
    return rows


def write_csv(rows: list[dict], path: str | Path) -> Path:
    """Write rows to ``path`` through a temporary file, so a failure leaves no half file."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.name, suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", newline="") as fh:
            writer = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
            writer.writeheader()
            writer.writerows(rows)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise
    return path


def read_csv(path: str | Path) -> list[dict]:
    """Rows of a sweep CSV with numbers converted back to float."""
    out = []
    with open(path, newline="") as fh:
        for row in csv.DictReader(fh):
            conv = {}
            for k, v in row.items():
                try:
                    conv[k] = float(v)
                except (TypeError, ValueError):
                    conv[k] = v
            out.append(conv)
    return out
