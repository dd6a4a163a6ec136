"""What the subcommands share: case arguments (a file or a bundled name), model options,
display units, output folders, JSON, progress.

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
import threading
import time
from importlib import resources
from pathlib import Path

from ..case import Case, load_case, parse_assignment
from ..errors import InputError
from ..models.options import Options
from ..models.registry import MODELS, model_spec

__all__ = ["HELP_FORMATTER", "DEFAULT_MODEL", "add_case_arguments", "add_units_argument",
           "add_quiet_argument", "bundled_cases", "case_path", "options_epilog", "case_from",
           "overrides", "positive_int", "speed_value", "model_options", "output_folder",
           "print_json", "Progress", "Ticker", "error_line"]

#: The model a subcommand uses unless told: the cheapest whose estimated error meets the
#: tolerance, and it says which answered and why.
DEFAULT_MODEL = "auto"


def bundled_cases() -> dict[str, Path]:
    """The cases that ship inside the package: ``{name: path}``, sorted by name."""
    folder = resources.files("webfem") / "cases"
    return {Path(p.name).stem: Path(str(p)) for p in sorted(folder.iterdir(),
                                                             key=lambda p: p.name)
            if p.name.endswith(".toml")}


def case_path(text: str) -> str:
    """An argparse type: a case file as given, or the path of a bundled case when ``text``
    names one (``base``, ``base.toml``) and no such file exists here."""
    if Path(text).exists():
        return text
    name = text.removesuffix(".toml")
    if "/" not in text and os.sep not in text:
        path = bundled_cases().get(name)
        if path is not None:
            return str(path)
    return text   # load_case names the missing file

#: Keeps the options listed in the epilog one per line.
HELP_FORMATTER = argparse.RawDescriptionHelpFormatter


def add_case_arguments(parser: argparse.ArgumentParser, *, positional: bool = True,
                       model: bool = True, default_model: str = "closed-form") -> None:
    """The case file or bundled name (positional, or ``--case`` when ``positional`` is
    False), ``--set``, and with ``model`` also ``--model`` (the registry's names, default
    ``default_model``; :data:`DEFAULT_MODEL` for the commands that answer an engineer's
    question: solve, sweep, traction-loss) and ``--opt``."""
    if positional:
        parser.add_argument("case", type=case_path,
                            help="case TOML file, or the name of a bundled case (`webfem "
                                 "cases`); keys: `webfem keys`")
    else:
        parser.add_argument("--case", required=True, type=case_path,
                            help="case TOML file (or bundled case name) for everything the "
                                 "data leave out")
    parser.add_argument("--set", action="append", metavar="SECTION.KEY=VALUE",
                        help="override a case value, in SI or with a unit, e.g. --set "
                             "roller.speed=30 --set 'roller.speed=1200 m/min' (repeatable)")
    if model:
        why = {"auto": "the cheapest model whose estimated error meets its tolerance; the "
                       "summary says which answered and why",
               "closed-form": "the paper's Eq. 21"}.get(default_model, "")
        parser.add_argument("--model", default=default_model, choices=list(MODELS),
                            help=f"model to use (default: {default_model}"
                                 + (f", {why})" if why else ")"))
        parser.add_argument("--opt", action="append", metavar="NAME=VALUE",
                            help="model option, e.g. --opt method=picard --opt level=2 "
                                 "(repeatable; each model's options are listed below)")


def add_units_argument(parser: argparse.ArgumentParser) -> None:
    """``--units si|metric|us`` for what is printed (JSON stays SI)."""
    from ..units import SYSTEMS
    parser.add_argument("--units", default="si", choices=SYSTEMS,
                        help="units of the printed summary: si (m, m/s, N/m), metric (mm, "
                             "m/min, N/m, um) or us (in, ft/min, pli, mil); JSON stays SI")


def add_quiet_argument(parser: argparse.ArgumentParser) -> None:
    """``--quiet``: no progress on stderr (there is none when stderr is not a terminal)."""
    parser.add_argument("--quiet", action="store_true",
                        help="no progress display (none either when stderr is not a terminal)")


def speed_value(text: str) -> float:
    """An argparse type: a speed in m/s, or with a unit (``"1200 m/min"``)."""
    try:
        return float(text)
    except ValueError:
        pass
    from ..units import to_si
    try:
        return to_si("speed", text, "m/s")
    except InputError as err:
        raise argparse.ArgumentTypeError(str(err).removeprefix("speed = ")) from None


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


def print_json(data, units: bool = True) -> None:
    """Strict JSON (no NaN or Infinity) on stdout; with ``units`` an object says its numbers
    are SI (``"units": "SI"``), whatever ``--units`` asked for the terminal."""
    if units and isinstance(data, dict) and "units" not in data:
        data = {"units": "SI", **data}
    print(json.dumps(data, indent=2, allow_nan=False))


def error_line(text: str) -> None:
    """``webfem: error: TEXT`` on stderr, on one line."""
    print("webfem: error: " + " ".join(str(text).split()), file=sys.stderr)


def _live(quiet: bool) -> bool:
    return not quiet and sys.stderr.isatty()


class Progress:
    """Progress of counted work on stderr with the time left, as one live line; silent with
    ``quiet`` or when stderr is not a terminal (logs and pipes stay clean)."""

    def __init__(self, quiet: bool = False, what: str = "points"):
        self.t0 = time.perf_counter()
        self.on = _live(quiet)
        self.what = what

    def __call__(self, done: int, total: int) -> None:
        if not self.on:
            return
        elapsed = time.perf_counter() - self.t0
        left = elapsed / max(done, 1) * (total - done)
        end = "\n" if done == total else "\r"
        print(f"  {done}/{total} {self.what}, {_clock(elapsed)} elapsed, about "
              f"{_clock(left)} left   ", end=end, file=sys.stderr, flush=True)


def _clock(seconds: float) -> str:
    seconds = int(round(seconds))
    return f"{seconds // 60}:{seconds % 60:02d}" if seconds >= 60 else f"{seconds} s"


class Ticker:
    """``with Ticker("solving with fe2d"):`` shows the time elapsed (and ``expected`` seconds,
    when known, as time left) on a live stderr line while a call of unknown length runs, and
    clears it after; silent with ``quiet`` or when stderr is not a terminal."""

    def __init__(self, text: str, quiet: bool = False, expected: float | None = None,
                 after: float = 1.0):
        self.text, self.expected, self.after = text, expected, after
        self.on = _live(quiet)
        self._stop = threading.Event()
        self._thread = None
        self._width = 0

    def _line(self, elapsed: float) -> str:
        line = f"  {self.text}: {_clock(elapsed)} elapsed"
        if self.expected:
            line += f", about {_clock(max(self.expected - elapsed, 0.0))} left"
        return line

    def _run(self) -> None:
        t0 = time.perf_counter()
        if self._stop.wait(self.after):   # quick calls show nothing
            return
        while True:
            line = self._line(time.perf_counter() - t0)
            self._width = max(self._width, len(line))
            print(line.ljust(self._width), end="\r", file=sys.stderr, flush=True)
            if self._stop.wait(1.0):
                return

    def __enter__(self) -> "Ticker":
        if self.on:
            self._thread = threading.Thread(target=self._run, daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        if self._thread is not None:
            self._stop.set()
            self._thread.join()
            if self._width:
                print(" " * self._width, end="\r", file=sys.stderr, flush=True)
