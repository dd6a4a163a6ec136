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
import shutil
import sys
import tempfile
import textwrap
import threading
import time
from pathlib import Path

from ..bundled import bundled_cases, locate_case
from ..case import Case, load_case, parse_assignment
from ..errors import InputError
from ..models.options import Options
from ..models.registry import MODELS, model_spec
from ..progress import iterations_left, reporting

__all__ = ["HELP_FORMATTER", "DEFAULT_MODEL", "UNITS_HELP", "add_case_arguments",
           "add_units_argument", "add_quiet_argument", "bundled_cases", "case_path",
           "CaseArgument", "announce_case",
           "options_epilog", "case_from", "overrides", "positive_int", "speed_value",
           "model_options", "output_folder", "print_json", "Progress", "Ticker",
           "progress_line", "error_line"]

#: The model a subcommand uses unless told: the cheapest whose estimated error meets the
#: tolerance, and it says which answered and why.
DEFAULT_MODEL = "auto"


class CaseArgument(str):
    """The path of a case as the command line resolved it; ``note`` says which file a bare
    name (``base``) stands for, for the user to read (None for a path given as such)."""

    note: str | None = None

    def __new__(cls, path: str, note: str | None = None):
        self = super().__new__(cls, path)
        self.note = note
        return self


def case_path(text: str) -> str:
    """An argparse type: a case file as given; for a bare name (``base`` or ``base.toml``,
    no folder) the file of that name here, else the bundled case of that name.

    A file here comes first, so that a case copied with ``webfem init base`` and edited is
    what ``webfem solve base`` reads; either way the returned :class:`CaseArgument` carries
    a note saying which file was read (printed by :func:`case_from`)."""
    path, note = locate_case(text)
    return CaseArgument(str(path) if note else text, note)


def announce_case(args) -> None:
    """Say on stderr which file a bare case name stood for (once per command), after the
    case was read whole: an input error stays the one line of a failure."""
    for attr in ("case",):
        note = getattr(getattr(args, attr, None), "note", None)
        if note and not getattr(args, "_case_announced", False):
            print(f"webfem: {note}", file=sys.stderr)
            args._case_announced = True


#: Keeps the options listed in the epilog one per line.
HELP_FORMATTER = argparse.RawDescriptionHelpFormatter


class _ModelAction(argparse.Action):
    """``--model NAME``: stores the name and notes that it was given (``model_given``), so
    an output can say "asked for by name" only when it was."""

    def __call__(self, parser, namespace, values, option_string=None):
        setattr(namespace, self.dest, values)
        namespace.model_given = True


def add_case_arguments(parser: argparse.ArgumentParser, *, positional: bool = True,
                       model: bool = True, default_model: str = DEFAULT_MODEL) -> None:
    """The case file or bundled name (positional, or ``--case`` when ``positional`` is
    False), ``--set``, and with ``model`` also ``--model`` (the registry's names, default
    ``default_model``: :data:`DEFAULT_MODEL` for every command that answers a question
    about a case, so that they all answer it alike; ``args.model_given`` says whether it
    was given) and ``--opt``."""
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
                            action=_ModelAction,
                            help=f"model to use (default: {default_model}"
                                 + (f", {why})" if why else ")"))
        parser.set_defaults(model_given=False)
        parser.add_argument("--opt", action="append", metavar="NAME=VALUE",
                            help="model option, e.g. --opt method=picard --opt level=2 "
                                 "(repeatable; each model's options are listed below)")


#: What ``--units`` changes, for the help of every command that takes it.
UNITS_HELP = ("units of what is printed and drawn: si (m, m/s, N/m, gaps in um), metric (mm, "
              "m/min, N/m, um, kPa) or us (in, ft/min, pli, mil, psi). CSV files stay SI under "
              "their usual names and columns; metric or us adds a copy NAME_metric.csv or "
              "NAME_us.csv whose columns end in their unit (h_center_mil, value_ft_per_min). "
              "JSON stays SI")


def add_units_argument(parser: argparse.ArgumentParser) -> None:
    """``--units si|metric|us`` for what is printed, charts and CSV copies (JSON and the
    CSV files themselves stay SI)."""
    from ..units import SYSTEMS
    parser.add_argument("--units", default="si", choices=SYSTEMS, help=UNITS_HELP)


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
    """The case of ``args.case`` with the ``--set`` overrides; a bare name's file is
    announced on stderr (:func:`announce_case`)."""
    case = load_case(args.case, overrides(args))
    announce_case(args)
    return case


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


def _time_left(track) -> float | None:
    """Seconds until the solve of ``track`` reaches its tolerance: the iterations
    :func:`webfem.progress.iterations_left` extrapolates from its residuals (Picard: at its
    mean linear rate; Newton: at its observed order) times the mean time per iteration so
    far. None while there is no rate to extrapolate."""
    step, points = track
    if len(points) < 2 or points[-1][2] <= points[0][2]:
        return None
    n = iterations_left([r for _, r, _ in points], step.tol,
                        order=1.0 if step.solver == "picard" else None)
    if n is None:
        return None
    per = (points[-1][0] - points[0][0]) / (points[-1][2] - points[0][2])
    return n * per


def progress_line(text: str, elapsed: float, track=None, expected: float | None = None,
                  width: int | None = None) -> str:
    """The live line of :class:`Ticker`: ``text``, the time elapsed and, when the solvers
    report (``track``: the last :class:`webfem.progress.Step` and ``(time, residual,
    iteration)`` of its solve), the stages, the iteration, its residual against the
    tolerance and the estimated time left until that solve converges (:func:`_time_left`);
    else the time left of ``expected`` seconds, if given. At most ``width`` characters (a
    wrapped line cannot be redrawn in place): the outer stages, then ``text``, then the
    stage are left out until it fits, and then it is cut.

    >>> from webfem.progress import Step
    >>> step = Step(("fe2d start", "fe1d newton"), "newton", 2, 1e-4, 1e-9)
    >>> line = progress_line("solving", 75.0, (step, ((0.0, 1e-1, 0), (1.0, 1e-2, 1),
    ...                                              (2.0, 1e-4, 2))))
    >>> line.split(" | ")  # doctest: +NORMALIZE_WHITESPACE
    ['  solving: 1:15', 'fe2d start > fe1d newton', 'newton 2: residual 1.0e-04 -> 1e-09,
     about 2 s left (estimate)']
    """
    if track is None:
        line = f"  {text}: {_clock(elapsed)} elapsed" + (
            f", about {_clock(max(expected - elapsed, 0.0))} left" if expected else "")
        return _cut(line, width)
    step = track[0]
    now = f"{step.solver} {step.iteration}: residual {step.residual:.1e} -> {step.tol:.0e}"
    left = _time_left(track)
    if step.residual <= step.tol:
        now += ", converged"
    elif left is not None:
        now += (", under 1 s" if left < 1.0 else f", about {_clock(left)}") + \
            " left (estimate)"
    # on a narrow terminal, in turn: the outer stages, the text, the stage go; then the end
    clock = _clock(elapsed)
    for first, where in ((f"  {text}: {clock}", step.stage),
                         (f"  {text}: {clock}", step.stage[-1:]),
                         (f"  {clock}", step.stage[-1:]), (f"  {clock}", ())):
        line = " | ".join([first] + ([" > ".join(where)] if where else []) + [now])
        if width is None or len(line) <= width:
            break
    return _cut(line, width)


def _cut(line: str, width: int | None) -> str:
    """``line`` cut to ``width`` characters (a wrapped line cannot be redrawn in place)."""
    if width is not None and len(line) > width:
        line = line[:max(width - 3, 0)] + "..."
    return line


class Ticker:
    """``with Ticker("solving with fe2d"):`` shows a live stderr line while a call of unknown
    length runs, and clears it after: the time elapsed and what the solvers report through
    :mod:`webfem.progress` (the stage, the iteration, the residual against its tolerance and
    an estimate of the time to converge; see :func:`progress_line`), or, before any report,
    the time left of ``expected`` seconds when given. Silent with ``quiet`` or when stderr
    is not a terminal; the solvers then report to no one."""

    def __init__(self, text: str, quiet: bool = False, expected: float | None = None,
                 after: float = 1.0):
        self.text, self.expected, self.after = text, expected, after
        self.on = _live(quiet)
        self._stop = threading.Event()
        self._thread = None
        self._width = 0
        self._reporting = None
        #: (last Step, ((time, residual, iteration), ...) of its solve), replaced whole so
        #: the drawing thread always reads a consistent pair
        self.track = None

    def record(self, step) -> None:
        """A :class:`webfem.progress.Step` from the solving thread: a later iteration of the
        same solve is added to its track, anything else starts a new one. A Newton solve
        inside a Picard iteration's stage (the staggered scheme's sub-solves) is not shown:
        the Picard iteration is what converges."""
        now = time.perf_counter()
        point = (now, step.residual, step.iteration)
        last = self.track
        if last is not None:
            prev, points = last
            same = prev.stage == step.stage
            if same and step.solver == "newton" and prev.solver == "picard":
                return
            if same and step.solver == prev.solver and step.iteration > prev.iteration:
                self.track = (step, points[-7:] + (point,))
                return
        self.track = (step, (point,))

    def _line(self, elapsed: float) -> str:
        columns = shutil.get_terminal_size((100, 24)).columns
        return progress_line(self.text, elapsed, self.track, self.expected, columns - 1)

    def _run(self) -> None:
        t0 = time.perf_counter()
        if self._stop.wait(self.after):   # quick calls show nothing
            return
        while True:
            line = self._line(time.perf_counter() - t0)
            self._width = max(self._width, len(line))
            print(line.ljust(self._width), end="\r", file=sys.stderr, flush=True)
            if self._stop.wait(0.5):
                return

    def __enter__(self) -> "Ticker":
        if self.on:
            self._reporting = reporting(self.record)
            self._reporting.__enter__()
            self._thread = threading.Thread(target=self._run, daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        if self._reporting is not None:
            self._reporting.__exit__(*exc)
            self._reporting = None
        if self._thread is not None:
            self._stop.set()
            self._thread.join()
            if self._width:
                print(" " * self._width, end="\r", file=sys.stderr, flush=True)
