"""``webfem cases`` lists the cases that ship with webfem; ``webfem init NAME [DIR]`` copies
one to edit. Any command that takes a case file also takes a bundled name (``webfem solve
base``), from any folder."""

from __future__ import annotations

import sys
from pathlib import Path

from ..errors import InputError, unknown_name
from .common import bundled_cases, output_folder


def add_parser(subparsers) -> None:
    subparsers.add_parser("cases", help="list the cases that ship with webfem (a name works "
                                        "wherever a case file does: `webfem solve base`)")
    p = subparsers.add_parser("init", help="copy a bundled case into a folder to edit "
                                           "(never overwrites)")
    p.add_argument("name", help="bundled case name (see `webfem cases`)")
    p.add_argument("dir", nargs="?", default=".", help="folder to copy into (default: here)")


def _first_comment(path: Path) -> str:
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("#"):
            return line.lstrip("#").strip()
    return ""


def _list() -> int:
    cases = bundled_cases()
    width = max(map(len, cases), default=0)
    for name, path in cases.items():
        print(f"{name:<{width}}  {_first_comment(path)}")
    return 0


def _init(args) -> int:
    cases = bundled_cases()
    name = args.name.removesuffix(".toml")
    if name not in cases:
        raise unknown_name("bundled case", name, list(cases))
    folder = output_folder(args.dir, "init DIR")
    target = folder / f"{name}.toml"
    try:
        with open(target, "x", encoding="utf-8") as out:   # "x": never overwrite
            out.write(cases[name].read_text(encoding="utf-8"))
    except FileExistsError:
        raise InputError(f"init: '{target}' exists: it is left as it is (remove it, or give "
                         "another DIR)") from None
    print(f"wrote {target}", file=sys.stderr)
    return 0


def run(args) -> int:
    return _init(args) if args.command == "init" else _list()
