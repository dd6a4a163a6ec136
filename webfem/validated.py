"""Validated frozen dataclasses: fields that state their meaning and valid range, checked on
creation.

The one machinery behind the case sections (:mod:`webfem.sections`) and the model options
(:mod:`webfem.models.options`). Each field carries :func:`spec` metadata: its kind, what it
means, its valid interval or words, whether None is allowed. :class:`Validated` checks every
field when an object is made, builds one from keywords (:meth:`Validated.from_mapping`: an
unknown name is an error naming the closest valid one) and makes checked copies
(:meth:`Validated.replace`). A subclass says how its fields are named in messages
(:meth:`Validated.label`), may word what is valid its own way
(:meth:`Validated.valid_text`) and may read more kinds of value (a section reads text with
a unit, an options type a mesh file).

Examples
--------
>>> from dataclasses import dataclass, field
>>> @dataclass(frozen=True)
... class Grid(Validated):
...     cells: int = field(default=4, metadata=spec("cells per side", "int", lo=1, hi=100))
>>> Grid(cells=8.0).cells
8
>>> Grid(cells=0)
Traceback (most recent call last):
...
webfem.errors.InputError: cells = 0 is out of range: must be an integer >= 1 and <= 100
>>> Grid.from_mapping({"cels": 3})
Traceback (most recent call last):
...
webfem.errors.InputError: unknown name 'cels'; did you mean 'cells'?
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from typing import Any, Mapping

import numpy as np

from .errors import InputError, show, unknown_name

__all__ = ["KINDS", "Validated", "interval_text", "outside", "spec"]

#: The kinds of value :class:`Validated` checks itself; a subclass may add its own.
KINDS = ("float", "int", "bool", "choice")


def spec(doc: str, kind: str = "float", *, lo: float | None = None, hi: float | None = None,
         lo_open: bool = False, hi_open: bool = False, choices: tuple = (),
         none: bool = False, unit: str = "", absent: str = "", cli: bool = True,
         **extra: Any) -> dict[str, Any]:
    """The metadata of a validated field.

    Parameters
    ----------
    doc : str
        What the field means (messages, ``--help``, ``webfem keys``, reports).
    kind : str
        ``"float"``, ``"int"``, ``"bool"``, ``"choice"`` or a subclass's own kind.
    lo, hi : float or None
        Bounds of a number (None: unbounded); ``lo_open``/``hi_open`` exclude them.
    choices : tuple of str
        The valid words of a ``"choice"``.
    none : bool
        None is allowed (its meaning stated in ``doc``, or in ``absent``).
    unit : str
        SI unit of a number ("" when it has none to state).
    absent : str
        What the field means when it is left out (None); implies ``none``.
    cli : bool
        Settable from the command line.
    **extra
        Further entries a subclass reads (e.g. the equations' own bounds of a case key).
    """
    return {"doc": doc, "kind": kind, "lo": lo, "hi": hi, "lo_open": lo_open,
            "hi_open": hi_open, "choices": tuple(choices), "none": none or bool(absent),
            "unit": unit, "absent": absent, "cli": cli, **extra}


def interval_text(meta: Mapping[str, Any]) -> str:
    """The interval of ``meta`` as messages state it, ``">= 0.001 and <= 10"`` ("" when
    unbounded)."""
    parts = []
    if meta["lo"] is not None:
        parts.append(f"{'>' if meta['lo_open'] else '>='} {meta['lo']:g}")
    if meta["hi"] is not None:
        parts.append(f"{'<' if meta['hi_open'] else '<='} {meta['hi']:g}")
    return " and ".join(parts)


def outside(number: float, meta: Mapping[str, Any]) -> bool:
    """True when ``number`` is not finite or lies outside the interval of ``meta``."""
    lo, hi = meta["lo"], meta["hi"]
    return (not math.isfinite(number)
            or (lo is not None and (number <= lo if meta["lo_open"] else number < lo))
            or (hi is not None and (number >= hi if meta["hi_open"] else number > hi)))


class Validated:
    """Base of frozen dataclasses whose fields carry :func:`spec` metadata: every field is
    checked (and numbers made floats or ints) when an object is made."""

    def __post_init__(self):
        cls = type(self)
        for f in dataclasses.fields(self):
            object.__setattr__(self, f.name, cls.check(f.name, getattr(self, f.name),
                                                       f.metadata))

    # -- how a subclass names and words things -------------------------------------------
    @classmethod
    def label(cls, name: str) -> str:
        """How messages name field ``name`` (e.g. ``roller.speed``, ``fe1d option level``)."""
        return name

    @classmethod
    def noun(cls) -> str:
        """What a field is called in "unknown ..." messages."""
        return "name"

    @classmethod
    def what_is_valid(cls, meta: Mapping[str, Any]) -> str:
        """What a valid value is, e.g. ``"an integer >= 0 and <= 3"``."""
        kind = meta["kind"]
        if kind == "choice":
            text = "one of " + ", ".join(repr(c) for c in meta["choices"])
        elif kind == "bool":
            text = "true or false"
        else:
            interval = interval_text(meta)
            text = ("an integer" if kind == "int" else "a finite number") + (
                " " + interval if interval else "")
        return text + (" (or none)" if meta["none"] else "")

    @classmethod
    def valid_text(cls, meta: Mapping[str, Any]) -> str:
        """The end of a message about an invalid value: ``"must be ..."``."""
        return "must be " + cls.what_is_valid(meta)

    @classmethod
    def invalid(cls, name: str, value: Any, why: str, meta: Mapping[str, Any]) -> InputError:
        """The error for ``value`` of field ``name`` (as given): ``why`` is "is not valid",
        "is not a number", "is not an integer" or "is out of range"."""
        return InputError(f"{cls.label(name)} = {show(value)} {why}: {cls.valid_text(meta)}")

    # -- checks ------------------------------------------------------------------------
    @classmethod
    def check(cls, name: str, value: Any, meta: Mapping[str, Any]) -> Any:
        """``value`` of field ``name`` as stored (a float, an int, a bool, a word or None),
        or the error saying what is valid."""
        kind = meta["kind"]
        if value is None and meta["none"]:
            return None
        if kind in ("float", "int"):
            return cls.number(name, value, meta)
        if kind == "choice":
            if not isinstance(value, str) or value not in meta["choices"]:
                raise cls.invalid(name, value, "is not valid", meta)
            return value
        if kind == "bool":
            if not isinstance(value, (bool, np.bool_)):
                raise cls.invalid(name, value, "is not valid", meta)
            return bool(value)
        raise TypeError(f"{cls.__name__}.{name}: no check for kind {kind!r}")

    @classmethod
    def number(cls, name: str, value: Any, meta: Mapping[str, Any]) -> float | int:
        """``value`` as a float (an int for kind ``"int"``) inside the interval."""
        if type(value) is float:   # the common case, without the slower ABC checks below
            number = value
        elif value is None:
            raise cls.invalid(name, value, "is not valid", meta)
        elif isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
            raise cls.invalid(name, value, "is not a number", meta)
        else:
            try:
                number = float(value)
            except OverflowError:   # an integer beyond float range (TOML allows 10**400)
                raise cls.invalid(name, value, "is out of range", meta) from None
        if meta["kind"] == "int" and math.isfinite(number):
            if number != int(number):
                raise cls.invalid(name, value, "is not an integer", meta)
            number = int(number)
        if outside(number, meta):
            raise cls.invalid(name, value, "is out of range", meta)
        return number

    # -- construction --------------------------------------------------------------------
    @classmethod
    def names(cls) -> list[str]:
        """Every field name."""
        return [f.name for f in dataclasses.fields(cls)]

    @classmethod
    def unknown(cls, name: Any, valid, where: str = "") -> InputError:
        """The error for ``name``, which is no field: the closest valid name, else the
        list (``where``, e.g. " (--opt)", says where it was given)."""
        return unknown_name(cls.noun(), name, valid, where)

    @classmethod
    def from_mapping(cls, values: Mapping[str, Any] | None = None, where: str = ""):
        """An object from keywords; an unknown name is an error naming the closest valid
        one."""
        values = dict(values or {})
        valid = cls.names()
        for key in values:
            if key not in valid:
                raise cls.unknown(key, valid, where)
        return cls(**values)

    def replace(self, **changes):
        """A copy with some fields changed (checked again)."""
        valid = self.names()
        for key in changes:
            if key not in valid:
                raise self.unknown(key, valid)
        return dataclasses.replace(self, **changes)
