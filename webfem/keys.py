"""The dotted keys that name a case's fields (``roller.speed``), and what is said about them.

:mod:`webfem.sections` declares the sections and their fields; this module names them as
``SECTION.NAME``, reads nested tables into dotted keys (:func:`flatten`), states each
numeric key's range and unit (:func:`key_range`, :func:`key_unit`) and words the error for
a name that is no key, suggesting only names that exist (:func:`unknown_key`).

Examples
--------
>>> flatten({"roller": {"speed": 5.0}, "web.width": 0.1})
{'roller.speed': 5.0, 'web.width': 0.1}
>>> print(unknown_key("web.tensoin"))
unknown key 'web.tensoin'; did you mean 'web.tension'?
"""

from __future__ import annotations

import dataclasses
import difflib
from typing import Any, Mapping

from .errors import InputError, show
from .sections import ALIASES, SECTIONS, range_text, valid_keys

__all__ = ["KEYS", "flatten", "is_key", "is_numeric", "key_meta", "key_range", "key_unit",
           "section_keys", "unknown_key", "valid_keys"]


#: Every dotted case key (aliases not included).
KEYS = frozenset(valid_keys())


def is_key(key: Any) -> bool:
    """True when ``key`` is a dotted case key (an alias is not one)."""
    return isinstance(key, str) and key in KEYS


def key_meta(key: str) -> Mapping[str, Any]:
    """The field metadata of numeric case key ``key`` (an alias too): unit, valid interval,
    meaning (see :func:`webfem.validated.spec`)."""
    if key in ALIASES:
        return ALIASES[key][2]
    if not is_key(key):
        raise unknown_key(key)
    section, name = key.split(".", 1)
    meta = SECTIONS[section].__dataclass_fields__[name].metadata
    if meta["kind"] != "float":
        raise InputError(f"{key} takes a word ({', '.join(meta['choices'])}), not a number")
    return meta


def key_range(key: str) -> str:
    """The valid range of numeric case key ``key`` (an alias too) as the messages state it,
    e.g. ``'must be >= 0.001 and <= 10'``; its unit is :func:`key_unit`'s.

    >>> key_range("web.roughness")
    'must be >= 1e-09 and <= 0.001'
    """
    return range_text(key_meta(key))


def key_unit(key: str) -> str:
    """The SI unit of numeric case key ``key`` (``"m"``, ``"-"`` ...)."""
    return key_meta(key)["unit"]


def is_numeric(key: str) -> bool:
    """True when case key ``key`` holds a number (not a word)."""
    section, name = key.split(".", 1)
    return SECTIONS[section].__dataclass_fields__[name].metadata["kind"] != "choice"


def section_keys(section: str) -> list[str]:
    """The key names of ``section`` (its aliases included), e.g. ``width`` for ``web``."""
    names = [f.name for f in dataclasses.fields(SECTIONS[section])]
    return names + [a.split(".", 1)[1] for a in ALIASES if a.startswith(section + ".")]


def _where_named(name: str) -> list[str]:
    """The dotted keys (aliases included) whose name is ``name``, in any section."""
    return [f"{s}.{name}" for s in SECTIONS if name in section_keys(s)]


def _either(keys: list[str]) -> str:
    return " or ".join(f"'{k}'" for k in keys)


def unknown_key(key: Any, where: str = "", table: bool = False) -> InputError:
    """The error for a name that is no case key: a suggestion only where it exists (a
    section's own keys for ``web.tensoin``; the section that has the key for
    ``roller.tension``; the keys of a section given as a key, ``web=80``). ``table``: the
    name heads a TOML table, so a close section name is what to suggest."""
    key = key if isinstance(key, str) else show(key)
    head = f"unknown key '{key}'{where}"
    if key in SECTIONS and not table:
        return InputError(f"'{key}'{where} is a section, not a key: give {key}.KEY=VALUE with "
                         f"one of its keys: {', '.join(section_keys(key))}")
    if table:
        close = difflib.get_close_matches(key, list(SECTIONS), n=1, cutoff=0.5)
        hint = (f"; did you mean '{close[0]}'?" if close
                else "; sections: " + ", ".join(SECTIONS))
        return InputError(f"unknown section '{key}'{where}{hint}")
    section, dot, name = key.partition(".")
    if not dot:   # a bare name: the key of some section, or a misspelt one
        owners = _where_named(key)
        if owners:
            return InputError(f"{head}: '{key}' is a key of a section; did you mean "
                             f"{_either(owners)}?")
        names = sorted({n for s in SECTIONS for n in section_keys(s)})
        close = difflib.get_close_matches(key, names, n=1, cutoff=0.6)
        if close:
            return InputError(f"{head}; did you mean {_either(_where_named(close[0]))}?")
        return InputError(f"{head}; a key is SECTION.NAME, e.g. web.tension (`webfem keys` "
                         "lists them)")
    if section in SECTIONS:
        own = section_keys(section)
        owners = _where_named(name)   # an exact name elsewhere beats a near one here
        if owners:
            of = " and ".join(f"[{o.split('.')[0]}]" for o in owners)
            return InputError(f"{head}: '{name}' is not a key of [{section}] but of {of}; "
                             f"did you mean {_either(owners)}?")
        close = difflib.get_close_matches(name, own, n=1, cutoff=0.5)
        if close:
            return InputError(f"{head}; did you mean '{section}.{close[0]}'?")
        return InputError(f"{head}; the keys of [{section}]: {', '.join(own)}")
    owners = _where_named(name)   # a misspelt section: the key's own section
    close = difflib.get_close_matches(section, list(SECTIONS), n=1, cutoff=0.5)
    if owners:
        return InputError(f"{head}; did you mean {_either(owners)}?")
    if close:
        near = difflib.get_close_matches(name, section_keys(close[0]), n=1, cutoff=0.5)
        if near:
            return InputError(f"{head}; did you mean '{close[0]}.{near[0]}'?")
    return InputError(f"{head}; sections: {', '.join(SECTIONS)} (`webfem keys` lists their "
                     "keys)")


def flatten(data: Mapping[str, Any], where: str = "") -> dict[str, Any]:
    """``{"roller": {"speed": 1}}`` -> ``{"roller.speed": 1}``, rejecting unknown keys."""
    flat = {}
    for section, table in data.items():
        if section not in SECTIONS:
            if isinstance(table, Mapping):
                raise unknown_key(section, where, table=True)
            flat[section] = table  # dotted key already, checked below
            continue
        if not isinstance(table, Mapping):
            raise InputError(f"'{section}'{where} must be a table of keys, got {show(table)}")
        for key, value in table.items():
            flat[f"{section}.{key}"] = value
    for key in flat:
        if not is_key(key) and key not in ALIASES:
            raise unknown_key(key, where)
    return flat

