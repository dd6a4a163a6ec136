"""Sweep specifications: one swept case key, its values, and the series (curve families).

A :class:`Sweep` is checked on creation, like a :class:`~webfem.case.Case`: the swept key
is a numeric case key or ``line.speed`` (:data:`webfem.line_speed.LINE_SPEED`: roller and web
together at the case's U_w/U_r, where ``roller.speed`` moves the roller alone), the values are distinct finite numbers, the series labels are
distinct non-empty text, and every point is a valid case, so a long sweep never fails half
way on its input. Sizes are bounded: at most :data:`MAX_VALUES` values per series,
:data:`MAX_SERIES` series and :data:`MAX_POINTS` points in all (each point is a solve).

Examples
--------
>>> from webfem.case import Case
>>> s = Sweep("roller.speed", (1.0, 4.0), (("base", Case()),))
>>> s.respaced(3, log=True).values
(1.0, 2.0, 4.0)
>>> s.respaced(2.7)
Traceback (most recent call last):
...
webfem.errors.InputError: --num = 2.7 is not a whole number: must be an integer from 1 to 10000
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import numbers
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterator

import numpy as np

from .case import AcrossKeys, Case, case_from_tables, read_toml
from .errors import InputError, show
from .keys import flatten, is_key, is_numeric, key_meta, unknown_key, valid_keys
from .line_speed import LINE_SPEED, holds_web_speed, line_at
from .physics.effects import states_load
from .units import examples, to_si

__all__ = ["MAX_POINTS", "MAX_SERIES", "MAX_VALUES", "Sweep", "load_sweep",
           "is_numeric_parameter"]

#: Most values per series (``values``, ``num``, ``--num``).
MAX_VALUES = 10_000
#: Most ``[[series]]`` per sweep.
MAX_SERIES = 100
#: Most points (values x series) per sweep: each point is one solve.
MAX_POINTS = 100_000

_SWEEP_KEYS = ("parameter", "values", "start", "stop", "num", "spacing")
_DEFAULT_NUM = 40


def _count(name: str, value: Any, where: str = "") -> int:
    """A number of points: a true integer from 1 to MAX_VALUES (2.7, "8", True refused)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InputError(f"{name} = {show(value)}{where} is not a whole number: "
                         f"must be an integer from 1 to {MAX_VALUES}")
    if not 1 <= value <= MAX_VALUES:
        raise InputError(f"{name} = {show(value)}{where} is out of range: "
                         f"must be from 1 to {MAX_VALUES} (points per series)")
    return int(value)


def _finite(name: str, value: Any, where: str = "", key: str | None = None) -> float:
    """A finite number; with the swept ``key``, text with a unit ("600 m/min") is converted
    to the key's SI unit, as a case file's keys are."""
    if isinstance(value, str) and key is not None:
        unit = key_meta(_unit_key(key))["unit"]
        try:
            value = to_si(key, value, unit)
        except InputError as err:
            raise InputError(f"{name} = {show(value)}{where} is not a value of the swept "
                             f"{key} (a number in {unit}, or text with a unit): {err}") \
                from None
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        meta = key_meta(_unit_key(key)) if key is not None else None
        unit = f" in {meta['unit']} or text with a unit such as " \
               f"'{examples(_unit_key(key), meta['unit'])[0]}'" if meta else ""
        raise InputError(f"{name} = {show(value)}{where} is not a number: "
                         f"must be a finite number{unit}")
    try:
        x = float(value)
    except OverflowError:
        x = math.inf
    if not math.isfinite(x):
        raise InputError(f"{name} = {show(value)}{where} is out of range: "
                         "must be a finite number")
    return x


def _unit_key(parameter: str) -> str:
    """The case key whose unit and spellings ``parameter`` takes: roller.speed's for
    :data:`~webfem.line_speed.LINE_SPEED`, else the key itself."""
    return "roller.speed" if parameter == LINE_SPEED else parameter


def _check_parameter(parameter: Any, where: str = "") -> None:
    if not isinstance(parameter, str):
        raise InputError(f"sweep.parameter = {show(parameter)}{where} is not valid: "
                         "must be a case key such as 'roller.speed'")
    if parameter == LINE_SPEED:   # the line: roller and web at the case's ratio
        return
    if not is_key(parameter):
        if difflib.get_close_matches(parameter, [LINE_SPEED], n=1, cutoff=0.8):
            raise InputError(f"unknown sweep parameter '{parameter}'{where}; did you mean "
                             f"'{LINE_SPEED}'?")
        raise unknown_key(parameter, where or " (sweep.parameter)")
    if not is_numeric(parameter):
        raise InputError(f"sweep.parameter = {parameter!r}{where} is not a numeric key: "
                         f"a sweep varies a number; numeric keys: {LINE_SPEED} (the line), "
                         + ", ".join(k for k in valid_keys() if is_numeric(k)))


def _check_values(values: Any, key: str | None = None) -> tuple[float, ...]:
    if isinstance(values, np.ndarray) and values.ndim == 1:
        values = values.tolist()
    if isinstance(values, (str, bytes)) or not isinstance(values, Sequence):
        raise InputError(f"sweep.values = {show(values)} is not a list of numbers: "
                         f"write e.g. values = [1.0, 2.5, 5.0] (1 to {MAX_VALUES} numbers)")
    if not 1 <= len(values) <= MAX_VALUES:
        raise InputError(f"sweep.values holds {len(values)} numbers: "
                         f"must hold 1 to {MAX_VALUES}")
    out, seen = [], set()
    for i, v in enumerate(values):
        x = _finite(f"sweep.values item {i + 1}", v, f" (of {show(values)})", key)
        if x in seen:
            raise InputError(f"sweep.values holds {x:g} twice: each value may appear once "
                             "(results are keyed by series and value)")
        seen.add(x)
        out.append(x)
    return tuple(out)


def _check_series(series: Any) -> tuple[tuple[str, Case], ...]:
    if isinstance(series, (str, bytes)) or not isinstance(series, Sequence):
        raise InputError(f"series = {show(series)} is not valid: "
                         "must be a list of (label, Case) pairs")
    if not 1 <= len(series) <= MAX_SERIES:
        raise InputError(f"a sweep has {len(series)} series: must have 1 to {MAX_SERIES}")
    out, first = [], {}
    for i, entry in enumerate(series, 1):
        if not (isinstance(entry, Sequence) and len(entry) == 2):
            raise InputError(f"series {i} = {show(entry)} is not a (label, Case) pair")
        label, case = entry
        if not isinstance(label, str) or not label.strip():
            raise InputError(f"series label = {show(label)} (series {i}) is not valid: "
                             "must be non-empty text")
        if label in first:
            raise InputError(f"series label '{label}' is used twice (series {first[label]} "
                             f"and {i}): labels must be unique (results are keyed by label)")
        if not isinstance(case, Case):
            raise InputError(f"series '{label}' holds {show(case)}: "
                             "must hold a webfem.case.Case")
        first[label] = i
        out.append((label, case))
    return tuple(out)


@dataclass(frozen=True)
class Sweep:
    """A parameter sweep: one swept dotted key (or ``line.speed``, :meth:`case_at`) and one
    or more curve families (series).

    TOML::

        [sweep]
        parameter = "roller.speed"   # or "line.speed": web and roller together
        start = 0.5
        stop = 40.0
        num = 60            # or: values = [1, 2, 5]; spacing = "linear" | "log"

        [[series]]
        label = "B = 20 deg"
        wrap = { angle_deg = 20 }
    """

    parameter: str
    values: tuple[float, ...]
    series: tuple[tuple[str, Case], ...]

    def __post_init__(self):
        _check_parameter(self.parameter)
        values = _check_values(self.values, self.parameter)
        series = _check_series(self.series)
        if len(values) * len(series) > MAX_POINTS:
            raise InputError(f"the sweep has {len(values)} values x {len(series)} series = "
                             f"{len(values) * len(series)} points: at most {MAX_POINTS}")
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "series", series)
        for label, base in series:  # every point now, so a long sweep never fails half way
            for value in values:
                try:
                    self.case_at(base, value)
                except InputError as err:
                    raise InputError(f"{err} (series '{label}', {self.parameter} = "
                                     f"{value:g})") from None

    def case_at(self, base: Case, value: float) -> Case:
        """``base`` at swept ``value``: the key set, or for :data:`LINE_SPEED` the line
        moved (:func:`webfem.line_speed.line_at`: roller and web at the case's ratio)."""
        if self.parameter == LINE_SPEED:
            return line_at(base, value)
        return base.updated({self.parameter: value})

    def points(self) -> Iterator[tuple[str, float, Case]]:
        """Yield ``(series_label, value, case)`` for every point of every series."""
        for label, base in self.series:
            for value in self.values:
                yield label, value, self.case_at(base, value)

    def held_web_speed(self) -> str | None:
        """One line of warning where this sweep moves ``roller.speed`` alone on an idler or
        a case with a web speed set (:func:`webfem.line_speed.holds_web_speed`): the web
        speed is held, so the sweep is one of the draw U_r - U_w too; else None."""
        if self.parameter != "roller.speed":
            return None
        held = [(label, c) for label, c in self.series if holds_web_speed(c)]
        if not held:
            return None
        label, c = held[0]
        where = "" if len(self.series) == 1 else f" (series '{label}')"
        if states_load(c):
            what = (f"on an idler{where}: the web speed is held at {c.web.speed:g} m/s, so "
                    "the roller slides under the web at every other speed, which an idler "
                    "(its roller driven by the web) does not do")
        else:
            what = (f"with web.speed = {c.web.speed:g} m/s{where}: the web speed is held, so "
                    "the sweep moves the roller alone and the sliding speed U_r - U_w with it")
        return (f"sweep.parameter = roller.speed {what}; to move web and roller together at "
                f"the case's U_w/U_r, sweep {LINE_SPEED} ([sweep] parameter = "
                f"\"{LINE_SPEED}\", or --parameter {LINE_SPEED})")

    def respaced(self, num: int | None, log: bool = False) -> "Sweep":
        """The same range (smallest to largest value) in ``num`` points, evenly spaced, or
        evenly in the logarithm with ``log``; ``num=None`` keeps the values (``log``
        then is an error: the command line's ``--log`` needs ``--num``).

        >>> from webfem.case import Case
        >>> Sweep("roller.speed", (2.0, 1.0), (("a", Case()),)).respaced(3).values
        (1.0, 1.5, 2.0)
        """
        if num is None:
            if log:
                raise InputError("--log needs --num: give the number of log-spaced points "
                                 f"(1 to {MAX_VALUES})")
            return self
        num = _count("--num", num)
        lo, hi = min(self.values), max(self.values)
        if log and lo <= 0:
            raise InputError(f"--log needs values > 0: the sweep spans {self.parameter} = "
                             f"{lo:g} .. {hi:g}; use linear spacing or a range above 0")
        if lo == hi and num > 1:
            raise InputError(f"--num = {num}: the sweep has the one value {self.parameter} = "
                             f"{lo:g}, no range to fill; give start and stop in [sweep]")
        space = np.geomspace if log else np.linspace
        return dataclasses.replace(self, values=tuple(space(lo, hi, num).tolist()))


def _values_from_spec(spec: Mapping[str, Any], where: str, parameter: str) -> Any:
    """The values a ``[sweep]`` table asks for (a list, checked by Sweep, or a range)."""
    if "values" in spec:
        extra = [k for k in ("start", "stop", "num", "spacing") if k in spec]
        if extra:
            raise InputError(f"sweep.values and sweep.{extra[0]}{where} cannot be combined: "
                             "give values, or start and stop (with num and spacing)")
        return spec["values"]
    if "start" not in spec or "stop" not in spec:
        raise InputError(f"[sweep]{where} needs 'values' or 'start' and 'stop'")
    start = _finite("sweep.start", spec["start"], where, parameter)
    stop = _finite("sweep.stop", spec["stop"], where, parameter)
    num = _count("sweep.num", spec.get("num", _DEFAULT_NUM), where)
    spacing = spec.get("spacing", "linear")
    if spacing not in ("linear", "log"):
        raise InputError(f"sweep.spacing = {show(spacing)}{where} is not valid: "
                         "must be 'linear' or 'log'")
    if spacing == "log" and min(start, stop) <= 0:
        raise InputError(f"sweep.spacing = 'log'{where} needs start and stop > 0, got "
                         f"sweep.start = {start:g}, sweep.stop = {stop:g}: "
                         "use spacing = 'linear' or a range above 0")
    if start == stop and num > 1:
        raise InputError(f"sweep.start = sweep.stop = {start:g}{where}: {num} equal points; "
                         "use num = 1 or different start and stop")
    space = np.geomspace if spacing == "log" else np.linspace
    return space(start, stop, num).tolist()


def _series_from_tables(case: Case | None, entries: Any, parameter: str, where: str,
                        build=None):
    """The ``[[series]]``' (label, case) pairs: ``case`` updated by each entry, or where
    the base case alone is refused (``case`` None), ``build(flat)``: the file's tables with
    the entry's keys, so the checks across keys see them (a series may mend the base)."""
    if not isinstance(entries, list) or not all(isinstance(e, Mapping) for e in entries):
        raise InputError(f"series = {show(entries)}{where} is not valid: must be [[series]] "
                         "tables (label = \"...\" and the case keys that differ)")
    if len(entries) > MAX_SERIES:
        raise InputError(f"[[series]]{where}: {len(entries)} tables, at most {MAX_SERIES}")
    series = []
    for i, entry in enumerate(entries, 1):
        entry = dict(entry)
        label = entry.pop("label", f"series {i}")
        if not isinstance(label, str) or not label.strip():
            raise InputError(f"series label = {show(label)}{where} (series {i}) is not "
                             "valid: must be non-empty text")
        at = f"{where} (series '{label}')"
        flat = flatten(entry, at)
        if parameter in flat:
            raise InputError(f"{parameter} = {show(flat[parameter])}{at}: {parameter} is the "
                             "swept parameter, set at every point; remove it from the series")
        try:
            series.append((label, case.updated(flat) if case is not None else build(flat)))
        except InputError as err:
            raise InputError(f"{err}{at}") from None
    return series or [("base", case)]


def _command_line(spec: Mapping[str, Any], where: str, parameter: str | None,
                  span: tuple | None) -> dict:
    """The ``[sweep]`` table as the command line changes it: ``parameter`` (--parameter)
    swept instead of the table's, over ``span`` (--start, --stop: numbers or text with a
    unit of the parameter; the table's num and spacing kept where it has them), or over the
    table's values where both measure the same quantity."""
    spec = dict(spec)
    table = spec.get("parameter", "roller.speed")
    if parameter is not None:
        _check_parameter(parameter, " (--parameter)")
        spec["parameter"] = parameter
    swept = spec["parameter"] if isinstance(spec.get("parameter"), str) else table
    if span is not None:
        if any(v is None for v in span):
            raise InputError("--start and --stop go together: give both ends of the range")
        start, stop = (_finite(name, _number(v), "", swept)
                       for name, v in zip(("--start", "--stop"), span))
        # the table's num where it has one; a values list's length is no count for a
        # range (values = [10.0] would make --start 5 --stop 15 one point)
        num = spec.get("num", _DEFAULT_NUM)
        spacing = spec.get("spacing", "linear") if "values" not in spec else "linear"
        spec = {"parameter": swept, "start": start, "stop": stop, "num": num,
                "spacing": spacing}
    elif parameter is not None and table != parameter and not (
            isinstance(table, str) and is_numeric_parameter(table)
            and key_meta(_unit_key(table))["unit"] == key_meta(_unit_key(parameter))["unit"]):
        raise InputError(f"--parameter {parameter}: the [sweep] values{where} are values of "
                         f"{table}, not of {parameter}; give the range with --start and "
                         "--stop")
    return spec


def _number(text: Any) -> Any:
    """A bare number given as text on the command line ("5"), as a number; anything else
    as it is (text with a unit is read by :func:`_finite`)."""
    if isinstance(text, str):
        try:
            return float(text)
        except ValueError:
            pass
    return text


def is_numeric_parameter(parameter: str) -> bool:
    """True for a parameter a sweep may vary: a numeric case key or :data:`LINE_SPEED`."""
    return parameter == LINE_SPEED or (is_key(parameter) and is_numeric(parameter))


def _sweep_from_dict(case: Case | None, data: Mapping[str, Any], where: str,
                     overrides: Mapping[str, Any] | None = None,
                     parameter: str | None = None, span: tuple | None = None) -> Sweep:
    spec = data.get("sweep", {})
    if not isinstance(spec, Mapping):
        raise InputError(f"sweep = {show(spec)}{where} is not valid: must be a [sweep] "
                         "table (parameter, then values or start, stop, num, spacing)")
    for key in spec:
        if key not in _SWEEP_KEYS:
            close = difflib.get_close_matches(key, _SWEEP_KEYS, n=1)
            hint = (f"; did you mean '{close[0]}'?" if close
                    else "; valid: " + ", ".join(_SWEEP_KEYS))
            raise InputError(f"unknown key 'sweep.{key}'{where}{hint}")
    if parameter is not None or span is not None:
        spec = _command_line(spec, where, parameter, span)
        if "sweep" in data or span is not None:   # else the default range, as without
            data = {**data, "sweep": spec}
    parameter = spec.get("parameter", "roller.speed")
    _check_parameter(parameter, where)
    if overrides and parameter in overrides:
        raise InputError(f"--set {parameter} = {show(overrides[parameter])}: {parameter} is "
                         f"the swept parameter{where}, set at every point; change [sweep] "
                         "instead")
    if "sweep" in data:
        values = _values_from_spec(spec, where, parameter)
    else:  # default: the paper's speed range
        values = np.linspace(0.5, 40.0, 60).tolist()
    series = _series_from_tables(
        case, data.get("series", []), parameter, where,
        lambda flat: case_from_tables(data, "", {**(overrides or {}), **flat}))
    try:
        return Sweep(parameter, values, tuple(series))
    except InputError as err:
        raise InputError(f"{err}{where}") from None


def load_sweep(path: str | Path, overrides: Mapping[str, Any] | None = None,
               parameter: str | None = None, start=None, stop=None) -> Sweep:
    """Read a case TOML file with its ``[sweep]`` and ``[[series]]`` tables; ``parameter``,
    ``start`` and ``stop`` (the command line's --parameter, --start, --stop) change the
    table's: another parameter over the table's values (where they measure the same
    quantity, e.g. ``roller.speed`` to ``line.speed``) or over ``start..stop`` (both given;
    numbers in the parameter's SI unit or text with a unit, "600 m/min")."""
    data, where = read_toml(path)
    try:
        case = case_from_tables(data, where, overrides)
    except AcrossKeys:
        if not data.get("series"):
            raise
        # a check across keys, which each series may pass (built from its own keys); any
        # other error is the file's own, which no series mends
        case = None
    span = None if start is None and stop is None else (start, stop)
    return _sweep_from_dict(case, data, where, overrides, parameter, span)
