"""The sweep table: one CSV row per operating point, its columns, and reading it back.

Rows are written whole: a row is formatted first and appended with one ``write`` call, and
a reader keeps only complete records (a last line without its newline, cut by a kill, is
dropped; so is any record whose fields do not parse).

Examples
--------
>>> row = failure_row("base", "roller.speed", 40.0, "fe1d", "LinAlgError: Singular matrix")
>>> text = format_header() + format_row(row)
>>> [(r["series"], r["value"], r["converged"]) for r in typed(parse_csv(text).rows)]
[('base', 40.0, False)]
>>> parse_csv(text[:-5]).dropped   # a last line cut short
1
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from pathlib import Path

from ..result import SUMMARY_KEYS
from ..files import replacing

__all__ = ["ROW_KEYS", "EXTRA_KEYS", "ANSWER_KEYS", "sweep_rows", "failure_row", "format_header",
           "format_row", "parse_csv", "read_table", "typed", "write_csv"]

EXTRA_KEYS = ("h_c", "sigma", "share_boundary", "share_mixed", "share_fluid", "contact_share",
              "eps", "kappa", "U", "U_slide", "residual", "solver_message", "mesh", "warnings",
              "model_used", "why", "error_h_center", "error_h_min", "error_mu",
              "error_contact_share")
#: Columns that say which model answered a row: ``model_used`` (auto's choice at that
#: point, else the model itself) and ``why`` (auto's reason; empty for a named model).
ANSWER_KEYS = ("model_used", "why")
#: The columns of a sweep CSV, in order.
ROW_KEYS = ("series", "parameter", "value") + SUMMARY_KEYS + EXTRA_KEYS
#: Columns holding text (``message``: the traction-loss table of webfem.groove_sizing, kept
#: in the same store); ``BOOL_KEYS`` hold True/False, ``INT_KEYS`` counts; others numbers.
TEXT_KEYS = frozenset({"series", "parameter", "model", "regime", "solver_message", "mesh",
                       "warnings", "message", "model_used", "why", "flag", "scan_limit"})
BOOL_KEYS = frozenset({"eq21_valid", "converged"})
INT_KEYS = frozenset({"iterations", "n_dofs"})


def sweep_rows(points, parameter: str) -> list[dict]:
    """Rows from ``(label, value, Result)`` triples: series, swept value, summary keys."""
    rows = []
    for label, value, res in points:
        data = res.to_dict()
        row = {"series": label, "parameter": parameter, "value": float(value)}
        for key in SUMMARY_KEYS + EXTRA_KEYS:
            v = data.get(key)
            row[key] = "; ".join(v) if isinstance(v, list) else v
        # every row names the model that answered it, auto's choice or the model itself
        row["model_used"] = data.get("model_used") or data.get("model")
        rows.append(row)
    return rows


def failure_row(label: str, parameter: str, value: float, model: str, message: str) -> dict:
    """The row of a point whose solve raised instead of answering (not converged)."""
    row = {k: None for k in ROW_KEYS}
    row.update(series=label, parameter=parameter, value=float(value), model=model,
               converged=False, solver_message=" ".join(message.split()),
               model_used=None if model == "auto" else model)
    return row


def _writer(buf):
    return csv.writer(buf, lineterminator="\n")


def format_header(keys=ROW_KEYS) -> str:
    buf = io.StringIO()
    _writer(buf).writerow(keys)
    return buf.getvalue()


def format_row(row: dict, keys=ROW_KEYS) -> str:
    """One CSV record (with its newline); missing keys and None are empty cells."""
    buf = io.StringIO()
    _writer(buf).writerow(["" if row.get(k) is None else row[k] for k in keys])
    return buf.getvalue()


def _cell_ok(key: str, text: str) -> bool:
    if key in TEXT_KEYS or text == "":
        return True
    if key in BOOL_KEYS:
        return text in ("True", "False")
    try:
        float(text)
    except ValueError:
        return False
    return True


@dataclass
class Table:
    """What :func:`parse_csv` found: the header, the complete rows (string cells) and how
    many records it dropped (torn or not parsing)."""

    header: list[str] = field(default_factory=list)
    rows: list[dict] = field(default_factory=list)
    dropped: int = 0


def parse_csv(text: str) -> Table:
    """Complete, well-formed records of a sweep CSV's text (see the module notes)."""
    table = Table()
    text = text.split("\x00", 1)[0]   # a crash can leave zeros at the end of a file
    if not text.endswith("\n"):       # the last record was cut mid-way
        cut = text.rfind("\n")
        table.dropped += bool(text[cut + 1:].strip())
        text = text[:cut + 1]
    records = csv.reader(io.StringIO(text, newline=""))
    try:
        table.header = next(records)
    except (StopIteration, csv.Error):
        return table
    try:
        for record in records:
            if not record:
                continue
            if len(record) != len(table.header) or not all(
                    _cell_ok(k, v) for k, v in zip(table.header, record)):
                table.dropped += 1
                continue
            table.rows.append(dict(zip(table.header, record)))
    except csv.Error:   # e.g. an unterminated quote: nothing after it is trusted
        table.dropped += 1
    return table


def read_table(path: str | Path) -> Table:
    """:func:`parse_csv` of a file (undecodable bytes are replaced, then fail to parse)."""
    return parse_csv(Path(path).read_bytes().decode("utf-8", errors="replace"))


def typed(rows: list[dict]) -> list[dict]:
    """CSV strings back to numbers and booleans (empty cells to None; text columns stay
    text, so a series labelled "80" stays "80")."""
    out = []
    for row in rows:
        conv = {}
        for key, v in row.items():
            if isinstance(v, str) and key not in TEXT_KEYS:
                if v == "":
                    v = None
                elif key in BOOL_KEYS:
                    v = v == "True"
                else:
                    try:
                        v = float(v)
                        if key in INT_KEYS and math.isfinite(v) and v == int(v):
                            v = int(v)
                    except ValueError:
                        pass
            conv[key] = v
        out.append(conv)
    return out


def write_csv(rows: list[dict], path: str | Path, keys=None) -> Path:
    """Write rows to ``path`` at once (temporary file, umask mode, rename); the columns are
    ``keys`` or the first row's keys."""
    path = Path(path)
    keys = list(keys if keys is not None else (rows[0].keys() if rows else ROW_KEYS))
    with replacing(path) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="") as fh:
            fh.write(format_header(keys))
            for row in rows:
                fh.write(format_row(row, keys))
    return path
