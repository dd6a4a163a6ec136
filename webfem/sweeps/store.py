"""Where a sweep keeps its results: the CSV, its sidecar, its lock.

* ``NAME.csv``: one row per finished point, appended (and forced to disk) as each finishes;
  rewritten in sweep order at the end.
* ``NAME.sweep.json`` (sidecar): the sweep's signature (parameter, values, series, model,
  changed options, webfem version). What a sweep does with a CSV already there
  (:meth:`Store.decide`):

  - the same sweep: **resume** (keep the converged rows, solve the rest);
  - a sweep that holds every point of the old one, with the same model, options, swept
    parameter, webfem version and case per series label (more values or series):
    **extend** (keep the old converged rows, solve the new points);
  - anything else (another model or case, values that drop old points, a CSV without its
    sidecar or with other columns): **refuse** with an InputError saying what differs,
    unless ``replace`` is given: then start over in that file, keeping only the rows of
    points this sweep shares with a compatible old one.

  The three cases are told to the caller (``notice``), never done silently.
* ``.NAME.csv.lock`` (hidden): held while a sweep writes, holding its pid, host, start time
  and signature hash. A second sweep into the same CSV, identical or not, is refused while
  the first runs (two writers would mix their rows); a lock whose process has ended on this
  host is stale and taken over.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from ..errors import InputError
from ..files import remove_stale_temps, write_text
from .lock import signature_hash
from .table import ROW_KEYS, Table, format_row, read_table, write_csv

__all__ = ["signature", "signature_hash", "Store", "point_key"]



def signature(spec, model: str, options) -> dict:
    """What makes two sweeps the same sweep (JSON-ready)."""
    from .. import __version__
    return {"parameter": spec.parameter, "values": [float(v) for v in spec.values],
            "model": model, "webfem": __version__,
            "options": json.loads(json.dumps(options.changed(), sort_keys=True, default=str)),
            "series": [[label, case.to_dict()] for label, case in spec.series]}


def point_key(label, value) -> tuple[str, str]:
    """A point's identity in the CSV: series label and the value's exact text."""
    return str(label), repr(float(value))


def _sweep_key(row: dict) -> tuple[str, str]:
    return point_key(row["series"], row["value"])


def _by_point(rows, keys: dict, row_key=_sweep_key) -> dict[int, dict]:
    """Rows by point index (the last row of a point wins); rows of no point are left out."""
    out = {}
    for row in rows:
        try:
            index = keys.get(row_key(row))
        except (KeyError, TypeError, ValueError):
            continue
        if index is not None:
            out[index] = row
    return out


def _old_points(sig: dict) -> set[tuple[str, str]]:
    """The point keys of the sweep a signature describes."""
    return {point_key(label, v) for label, _ in sig.get("series", [])
            for v in sig.get("values", [])}


def _extent(sig: dict) -> str:
    """``40 values of roller.speed 0.5 .. 40 x 2 series``: a sweep's size for messages."""
    values = [float(v) for v in sig.get("values", [])]
    span = f" {min(values):g} .. {max(values):g}" if values else ""
    n = len(sig.get("series", []))
    return (f"{len(values)} values of {sig.get('parameter', '?')}{span} x {n} series")


def _differences(old: dict, new: dict) -> list[str]:
    """What keeps the rows of sweep ``old`` from being rows of sweep ``new`` (empty when
    they may be kept: the same model, options, parameter, webfem version, and the same case
    for every series label of ``old``, which ``new`` must have)."""
    why = []
    for key, what in (("model", "model"), ("parameter", "swept parameter"),
                      ("options", "model options"), ("webfem", "webfem version")):
        if old.get(key) != new.get(key):
            why.append(f"{what} {old.get(key)!r}, not {new.get(key)!r}")
    cases = {label: case for label, case in new.get("series", [])}
    for label, case in old.get("series", []):
        if label not in cases:
            why.append(f"series {label!r}, which this sweep does not have")
        elif not _same_case(case, cases[label]):
            why.append(f"series {label!r} with other case values "
                       f"({_case_changes(case, cases[label])})")
    return why


def _case_changes(old, new, prefix: str = "", most: int = 3) -> str:
    """The case keys whose values differ, old -> new (``web.tension 80 -> 120``), the first
    ``most`` of them: a refused sweep names what changed, not only that something did.

    >>> _case_changes({"web": {"tension": 80.0, "speed": 0.0}}, {"web": {"tension": 120.0,
    ...                                                                  "speed": 0.0}})
    'web.tension 80 -> 120'
    """
    changes = _changed_keys(old, new, prefix)
    text = "; ".join(f"{key} {_shown(a, b)} -> {_shown(b, a)}" for key, a, b in changes[:most])
    return text + (f"; and {len(changes) - most} more" if len(changes) > most else "")


def _changed_keys(old, new, prefix: str) -> list[tuple[str, object, object]]:
    if isinstance(old, dict) and isinstance(new, dict):
        out = []
        for k in list(old) + [k for k in new if k not in old]:
            a, b = old.get(k, None), new.get(k, None)
            if k not in old and b is None:    # a key added later, left out: the same
                continue
            out += _changed_keys(a, b, f"{prefix}{k}.")
        return out
    return [] if old == new else [(prefix.rstrip("."), old, new)]


def _shown(value, other=None) -> str:
    """``value`` as a refusal prints it: a float to as many digits as it takes to differ
    from ``other`` (80 -> 80.0000001, not 80 -> 80)."""
    if value is None:
        return "(not set)"
    if not isinstance(value, float):
        return str(value)
    digits = next((d for d in range(6, 18) if not isinstance(other, float)
                   or f"{value:.{d}g}" != f"{other:.{d}g}"), 17)
    return f"{value:.{digits}g}"


def _same_case(old, new) -> bool:
    """Whether the case values ``old`` (a stored signature's) are ``new``'s, where a key
    ``old`` lacks counts as the same while ``new`` leaves it out (None): a case key added
    later (``wrap.span``) keeps the sweeps stored before it resumable."""
    if isinstance(old, dict) and isinstance(new, dict):
        return all(k in new for k in old) and all(
            _same_case(old[k], new[k]) if k in old else new[k] is None for k in new)
    return old == new


class Store:
    """The CSV and sidecar of one sweep: which points are done, appending new rows, and the
    final rewrite in sweep order.

    ``columns`` and ``row_key`` (a row's point key, from its string cells) default to the
    sweep table's; other resumable tables (e.g. the groove sizing map) give their own, with
    a ``converged`` column. ``sig`` must then name ``model``, ``parameter`` and ``points``
    for the lock's message. ``keep_failures``: a row that did not converge counts as done
    too (for points solved from cold, whose failure a re-run would only repeat); by
    default it is solved again (a sweep's continuation may fail where a cold start does
    not).
    """

    def __init__(self, csv_path: Path, sig: dict, columns=ROW_KEYS, row_key=_sweep_key,
                 keep_failures: bool = False):
        self.csv_path = csv_path
        self.sidecar = csv_path.with_suffix(".sweep.json")
        self.sig = sig
        self.columns = tuple(columns)
        self.row_key = row_key
        self.keep_failures = keep_failures
        self._fd: int | None = None
        #: Whether :meth:`load` found the table of this same sweep (its sidecar and header),
        #: and how many rows it held (kept or not).
        self.same_sweep = False
        self.rows_found = 0

    def check_paths(self) -> None:
        """Input errors for outputs that cannot be written, before anything runs."""
        for path, what in ((self.csv_path, "the sweep CSV"), (self.sidecar, "the sidecar")):
            if path.is_dir():
                raise InputError(f"{what} {path} is a folder; it must be a file path")
        parent = self.csv_path.parent
        try:
            parent.mkdir(parents=True, exist_ok=True)
        except (FileExistsError, NotADirectoryError):
            raise InputError(f"cannot create the folder {parent}: a file is in the way") \
                from None
        except PermissionError:
            raise InputError(f"cannot create the folder {parent}: permission denied") from None
        if not os.access(parent, os.W_OK | os.X_OK):
            raise InputError(f"cannot write in {parent}: permission denied")

    def decide(self, keys: dict, *, replace: bool = False, notice=None) -> dict[int, dict]:
        """What to do with a CSV already at the path (see the module notes): the rows kept,
        by point index, after telling ``notice(text)`` what is done with the file (resume,
        extend, or replace). Raises InputError (refuse) when the CSV holds another sweep
        and ``replace`` is False. A sweep's store only: ``sig`` must have ``values`` and
        ``series``."""
        remove_stale_temps(self.csv_path.parent, self.csv_path.name)
        remove_stale_temps(self.sidecar.parent, self.sidecar.name)
        try:
            table = read_table(self.csv_path)
        except FileNotFoundError:
            return {}
        except OSError as err:
            raise InputError(f"{self.csv_path}: cannot be read ({err.strerror or err})") \
                from None
        if not table.header and not table.rows:
            return {}                       # an empty file: nothing to keep or lose
        try:
            old = json.loads(self.sidecar.read_text())
        except (OSError, ValueError):
            old = None
        new = json.loads(json.dumps(self.sig))
        held = len(table.rows)
        if table.header != list(self.columns):
            why = ["its columns are not those of a webfem sweep of this version"]
        elif not isinstance(old, dict):
            why = [f"it has no readable sidecar {self.sidecar.name} saying which sweep "
                   "wrote it"]
        else:
            why = _differences(old, new)
        converged = {i: r for i, r in _by_point(table.rows, keys, self.row_key).items()
                     if r["converged"] == "True"}
        if not why:
            if old == new or _old_points(old) == set(keys):
                if converged and notice:
                    rest = len(keys) - len(converged)
                    notice(f"{self.csv_path}: resuming this sweep: {len(converged)} of "
                           f"{len(keys)} points already there, "
                           + (f"solving the other {rest}" if rest else "nothing to solve"))
                return converged
            dropped = _old_points(old) - set(keys)
            if not dropped:
                if notice:
                    notice(f"{self.csv_path}: extending the sweep it holds ("
                           f"{_extent(old)}) to this one ({_extent(new)}): keeping its "
                           f"{len(converged)} converged points, solving the "
                           f"{len(keys) - len(converged)} others")
                return converged
            why = [f"{len(dropped)} of its {len(_old_points(old))} points "
                   f"{'is' if len(dropped) == 1 else 'are'} not in this sweep: it ran "
                   f"{_extent(old)}, this sweep {_extent(new)}"]
            compatible = True
        else:
            compatible = False
        if not replace:
            raise InputError(
                f"{self.csv_path} holds another sweep ({'; '.join(why)}): its {held} rows "
                "are left as they are. Write elsewhere (another --out), or start over in "
                "this file with --replace (replace=True)")
        kept = converged if compatible else {}
        if notice:
            notice(f"{self.csv_path}: replacing its {held} rows of another sweep "
                   f"({'; '.join(why)})"
                   + (f"; keeping the {len(kept)} converged points this sweep shares with it"
                      if kept else ""))
        return kept

    def load(self, keys: dict) -> dict[int, dict]:
        """Converged rows (with ``keep_failures`` every row) of an earlier run of the same
        sweep, by point index (``keys``: point key -> index); {} when there is none or the
        sweep changed."""
        remove_stale_temps(self.csv_path.parent, self.csv_path.name)
        remove_stale_temps(self.sidecar.parent, self.sidecar.name)
        try:
            same = json.loads(self.sidecar.read_text()) == json.loads(json.dumps(self.sig))
            table = read_table(self.csv_path) if same else Table()
        except (OSError, ValueError):
            return {}
        if table.header != list(self.columns):
            return {}
        self.same_sweep, self.rows_found = same, len(table.rows)
        done = _by_point(table.rows, keys, self.row_key)
        return {i: r for i, r in done.items()
                if r["converged"] == "True"
                or (self.keep_failures and r["converged"] == "False")}

    def start(self, kept: dict[int, dict]) -> None:
        """Write the CSV afresh with the ``kept`` rows (a clean file: a torn last line or
        rows that did not parse are gone), then the sidecar, and open for appending."""
        if not kept:   # a new sweep: the old sidecar goes first, so old rows never match it
            self.sidecar.unlink(missing_ok=True)
        write_csv([kept[i] for i in sorted(kept)], self.csv_path, self.columns)
        write_text(self.sidecar, json.dumps(self.sig, indent=1))
        self._fd = os.open(self.csv_path, os.O_WRONLY | os.O_APPEND)

    def append(self, row: dict) -> None:
        """Append one row with a single write and force it to disk."""
        data = format_row(row, self.columns).encode("utf-8")
        while data:
            data = data[os.write(self._fd, data):]
        os.fsync(self._fd)

    def close(self) -> None:
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None

    def finish(self, keys: dict) -> list[dict]:
        """Rewrite the CSV with the latest row of every point, in sweep order; returns them
        (strings as in the file)."""
        self.close()
        latest = _by_point(read_table(self.csv_path).rows, keys, self.row_key)
        rows = [latest[i] for i in sorted(latest)]
        write_csv(rows, self.csv_path, self.columns)
        return rows

