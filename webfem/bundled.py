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

import os
from importlib import resources
from pathlib import Path

from .case import Case, load_case
from .errors import InputError

__all__ = ["bundled_cases", "find_case", "as_case"]


def bundled_cases() -> dict[str, Path]:
    """The cases that ship inside the package: ``{name: path}``, sorted by name."""
    folder = resources.files("webfem") / "cases"
    return {Path(p.name).stem: Path(str(p)) for p in sorted(folder.iterdir(),
                                                             key=lambda p: p.name)
            if p.name.endswith(".toml")}


def find_case(text: str | os.PathLike) -> Path:
    """The case file ``text`` names: the file itself, ``text.toml`` in the current folder,
    else the bundled case of that name (``base``, ``base.toml``). A name that is none of
    these is returned as given (:func:`~webfem.case.load_case` then says it is missing)."""
    path = Path(text)
    if path.is_file():
        return path
    name = str(text)
    if "/" not in name and os.sep not in name:
        local = Path(name if name.endswith(".toml") else name + ".toml")
        if local.is_file():
            return local
        bundled = bundled_cases().get(name.removesuffix(".toml"))
        if bundled is not None:
            return bundled
    return path


def as_case(case: Case | str | os.PathLike) -> Case:
    """A :class:`Case` from a Case, a case file or a bundled case's name."""
    if isinstance(case, Case):
        return case
    if isinstance(case, (str, os.PathLike)):
        return load_case(find_case(case))
    raise InputError(f"case = {case!r} is not valid: must be a webfem.Case, a case file "
                     "or the name of a bundled case (`webfem cases`)")
