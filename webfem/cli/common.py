"""What the subcommands share: case arguments, model options, output folders, JSON, progress.

A subcommand is a module of this package with two functions:

``add_parser(subparsers) -> None``
    adds its parser to ``subparsers`` (``argparse``'s ``add_subparsers()`` object), using
    :func:`add_case_arguments` and :data:`HELP_FORMATTER` with :func:`options_epilog` where
    it takes model options;
``run(args) -> int``
    parses what argparse left as text, calls the library, prints, and returns the exit code.

:mod:`webfem.cli.main` lists the modules and turns what ``run`` raises into exit codes:
InputError 2, ConvergenceError 3, OSError on an output path 2, Ctrl-C 130, each with one
line on stderr. So a subcommand does no library work and catches nothing it cannot add to.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import textwrap
import time
from pathlib import Path

from ..case import Case, load_case, parse_assignment
from ..errors import InputError
from ..models.options import Options
from ..models.registry import MODELS, model_spec

__all__ = ["HELP_FORMATTER", "add_case_arguments", "options_epilog", "case_from",
           "overrides", "positive_int", "model_options", "output_folder", "print_json",
           "Progress", "error_line"]

#: Keeps the options listed in the epilog one per line.
HELP_FORMATTER = argparse.RawDescriptionHelpFormatter


def add_case_arguments(parser: argparse.ArgumentParser, *, positional: bool = True,
                       model: bool = True) -> None:
    """The case file (positional, or ``--case`` when ``positional`` is False), ``--set``,
    and with ``model`` also ``--model`` (the registry's names) and ``--opt``."""
    if positional:
        parser.add_argument("case", help="case TOML file (see cases/ and `webfem keys`)")
    else:
        parser.add_argument("--case", required=True,
                            help="case TOML file for everything the data leave out")
    parser.add_argument("--set", action="append", metavar="SECTION.KEY=VALUE",
                        help="override a case value, e.g. --set roller.speed=30 (repeatable)")
    if model:
        parser.add_argument("--model", default="closed-form", choices=list(MODELS),
                            help="model to use (default: closed-form, the paper's Eq. 21)")
        parser.add_argument("--opt", action="append", metavar="NAME=VALUE",
                            help="model option, e.g. --opt method=picard --opt level=2 "
                                 "(repeatable; each model's options are listed below)")


def options_epilog(models=None) -> str:
    """Each model's one-line summary and options (default, meaning, valid values), from
    :data:`webfem.models.registry.MODELS`, for a parser's epilog."""
    lines = ["model options (--opt NAME=VALUE): default, meaning, valid values"]
    for name in models or MODELS:
        spec = model_spec(name)
        lines.append(f"  {name}: {spec.summary}")
        for line in spec.options.describe().splitlines():
            lines.append(textwrap.fill(line, width=98, initial_indent="    ",
                                       subsequent_indent="        "))
    return "\n".join(lines)


def positive_int(text: str) -> int:
    """An argparse type: an integer >= 1 (a usage error otherwise)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{value} is out of range: must be >= 1")
    return value


def overrides(args) -> dict:
    """``--set`` assignments as ``{dotted key: value}``."""
    return dict(parse_assignment(p) for p in args.set or [])


def case_from(args) -> Case:
    """The case of ``args.case`` with the ``--set`` overrides."""
    return load_case(args.case, overrides(args))


def model_options(args, model: str | None = None) -> Options:
    """The typed options of ``model`` (default ``args.model``) from ``--opt`` strings; an
    unknown name or a bad value is an InputError naming it."""
    return model_spec(model or args.model).options.from_strings(args.opt or [])


def output_folder(path, flag: str) -> Path:
    """Create folder ``path`` if needed and check it can be written, before any solving:
    an InputError naming ``flag`` and the path otherwise."""
    folder = Path(path)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise InputError(f"{flag} '{path}' is a file, not a folder: give a folder to write "
                         "into") from None
    except NotADirectoryError:
        raise InputError(f"{flag} '{path}' lies under a file, not a folder: give a folder "
                         "to write into") from None
    except OSError as err:
        raise InputError(f"{flag} '{path}': cannot create the folder ({err.strerror})") \
            from None
    try:
        fd, probe = tempfile.mkstemp(prefix=".webfem-probe-", dir=folder)
        os.close(fd)
        os.unlink(probe)
    except OSError as err:
        raise InputError(f"{flag} '{path}': cannot write into the folder ({err.strerror})") \
            from None
    return folder


def print_json(data) -> None:
    """Strict JSON (no NaN or Infinity) on stdout."""
    print(json.dumps(data, indent=2, allow_nan=False))


def error_line(text: str) -> None:
    """``webfem: error: TEXT`` on stderr, on one line."""
    print("webfem: error: " + " ".join(str(text).split()), file=sys.stderr)


class Progress:
    """Progress on stderr with the time left: a live line on a terminal, else every 10 %."""

    def __init__(self):
        self.t0 = time.perf_counter()
        self.last = -1

    def __call__(self, done: int, total: int) -> None:
        tty = sys.stderr.isatty()
        decile = 10 * done // max(total, 1)
        if not tty and decile == self.last and done != total:
            return
        self.last = decile
        elapsed = time.perf_counter() - self.t0
        left = elapsed / max(done, 1) * (total - done)
        end = "\n" if (done == total or not tty) else "\r"
        print(f"  {done}/{total} points, {elapsed:.1f} s elapsed, about {left:.1f} s left",
              end=end, file=sys.stderr, flush=True)
