"""Where a case comes from: a :class:`~webfem.case.Case`, a file, or a bundled case's name.

A file in the current folder beats a bundled case of the same stem: after ``webfem init
base`` the user's edited ``./base.toml`` is what ``base`` means.

Examples
--------
>>> "base" in bundled_cases()
True
>>> as_case("base").roller.radius
0.055
"""

from __future__ import annotations

import difflib
import os
from importlib import resources
from pathlib import Path
from typing import Any, Mapping

from . import case as _case
from . import sweepspec as _sweepspec
from .case import Case
from .errors import InputError

__all__ = ["bundled_cases", "locate_case", "find_case", "as_case", "load_case", "load_sweep"]


def bundled_cases() -> dict[str, Path]:
    """The cases that ship inside the package: ``{name: path}``, sorted by name."""
    folder = resources.files("webfem") / "cases"
    return {Path(p.name).stem: Path(str(p)) for p in sorted(folder.iterdir(),
                                                             key=lambda p: p.name)
            if p.name.endswith(".toml")}


def locate_case(text: str | os.PathLike) -> tuple[Path, str]:
    """The case file ``text`` names and a note saying which file that is ("" when ``text``
    is a path): the file itself; for a bare name (``base``, ``base.toml``: no folder)
    ``NAME.toml`` in the current folder, else the bundled case of that name. A name that is
    none of these is returned as given (:func:`~webfem.case.load_case` then says it is
    missing)."""
    path = Path(text)
    if path.is_file():        # a file named as such: what was asked for
        return path, ""
    name = str(text)
    stem = name.removesuffix(".toml")
    if any(sep and sep in name for sep in ("/", os.sep, os.altsep)):
        return path, ""
    here = Path(f"{stem}.toml")
    bundled = bundled_cases().get(stem)
    if here.is_file():
        return here, (f"case '{name}' is ./{here}, the file here"
                      + (" (not the bundled case of that name)" if bundled else ""))
    if bundled is not None:
        return bundled, (f"case '{name}' is the bundled {bundled.name} ({bundled}); no "
                         f"{stem}.toml here (`webfem init {stem}` copies it to edit)")
    return path, ""


def find_case(text: str | os.PathLike) -> Path:
    """The case file ``text`` names (:func:`locate_case`)."""
    return locate_case(text)[0]


def existing_case(text: str | os.PathLike) -> Path:
    """The case file ``text`` names (:func:`locate_case`); where there is none, an input
    error saying so and naming the closest case it may have meant (a bundled case, or a
    .toml file in the folder it names)."""
    path = find_case(text)
    if path.exists():
        return path
    name = Path(text)
    stem = name.name.removesuffix(".toml")
    folder = name.parent
    here = {p.name.removesuffix(".toml") for p in folder.glob("*.toml")} if folder.is_dir() \
        else set()
    bare = str(folder) in ("", ".")
    near = difflib.get_close_matches(stem, sorted(here | (set(bundled_cases()) if bare
                                                          else set())), n=1)
    where = ("no such file here and no bundled case of that name" if bare
             else f"no such file in {folder}")
    hint = (f"; did you mean '{near[0] if bare else folder / (near[0] + '.toml')}'?"
            if near else "")
    raise InputError(f"case file '{text}' does not exist ({where}){hint} (`webfem cases` "
                     "lists the bundled cases)")


def load_case(case: str | os.PathLike, overrides: Mapping[str, Any] | None = None) -> Case:
    """Read a case file, or a bundled case's name (``"base"``), with ``overrides`` (dotted
    keys): :func:`webfem.case.load_case` of the file :func:`locate_case` finds.

    >>> load_case("base").web.tension
    80.0
    """
    return _case.load_case(existing_case(case), overrides)


def load_sweep(case: str | os.PathLike, overrides: Mapping[str, Any] | None = None,
               **command_line):
    """Read a case file's (or a bundled case's) ``[sweep]`` and ``[[series]]`` tables
    (:func:`webfem.sweepspec.load_sweep`; ``command_line``: its ``parameter``, ``start``
    and ``stop``)."""
    return _sweepspec.load_sweep(existing_case(case), overrides, **command_line)


def as_case(case: Case | str | os.PathLike) -> Case:
    """A :class:`Case` from a Case, a case file or a bundled case's name."""
    if isinstance(case, Case):
        return case
    if isinstance(case, (str, os.PathLike)):
        return load_case(case)
    raise InputError(f"case = {case!r} is not valid: must be a webfem.Case, a case file "
                     "or the name of a bundled case (`webfem cases`)")
