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
from contextlib import contextmanager
from pathlib import Path

from ..bundled import bundled_cases, load_case, locate_case
from ..case import Case, parse_assignment
from ..cores import usable_cores
from ..errors import InputError
from ..models.options import Options
from ..models.registry import MODELS, model_spec
from .live import Progress, Ticker, progress_line   # shared by the subcommands, as the rest

__all__ = ["HELP_FORMATTER", "DEFAULT_MODEL", "UNITS_HELP", "add_case_arguments",
           "add_units_argument", "add_quiet_argument", "add_dask_argument", "bundled_cases", "case_path",
           "CaseArgument", "announce_case",
           "options_epilog", "case_from", "overrides", "positive_int", "speed_value",
           "local_workers",
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
    case was read whole: an input error stays the one line of a failure; and, unless
    ``--quiet``, which web material keys a user's case file left to the defaults
    (:func:`defaults_note`)."""
    if getattr(args, "_case_announced", False):
        return
    note = getattr(getattr(args, "case", None), "note", None)
    if note:
        print(f"webfem: {note}", file=sys.stderr)
    if not getattr(args, "quiet", False) and getattr(args, "case", None) is not None:
        said = defaults_note(locate_case(args.case)[0], overrides(args))
        if said:
            print(f"webfem: {said}", file=sys.stderr)
    args._case_announced = True


#: The web's material keys: a case file that leaves them out describes the base case's
#: newsprint, whatever web it meant (a 12 um PET film given its thickness alone keeps
#: newsprint's E_b 175 kPa and sigma 4 um).
WEB_MATERIAL = ("thickness", "modulus_thickness", "modulus_md", "roughness", "permeability",
                "density")


def defaults_note(path, overrides_: dict) -> str | None:
    """One line naming the web material keys (:data:`WEB_MATERIAL`) a user's case file
    at ``path`` leaves out (and ``--set`` does not give), with the base case's values it
    then takes; None for a bundled case (each states what it leaves out, on purpose), a
    copy of one whose [web] table is unchanged (`webfem init`), or a file that gives them
    all."""
    from ..bundled import bundled_cases
    from ..case import read_toml
    from ..keys import key_unit
    path = Path(path)
    try:
        bundled = bundled_cases().values()
        if path.resolve() in {p.resolve() for p in bundled}:
            return None
        web = read_toml(path)[0].get("web", {})
        # a copy of a bundled case (`webfem init`) keeps that case's web, on purpose; only
        # a [web] table edited away from every bundled one is a user's own web
        if any(web == read_toml(p)[0].get("web", {}) for p in bundled):
            return None
    except (InputError, OSError):
        return None
    missing = [k for k in WEB_MATERIAL if k not in web and f"web.{k}" not in overrides_]
    if not missing:
        return None
    base = Case().web
    values = ", ".join(f"web.{k} = {getattr(base, k):g} {key_unit('web.' + k)}"
                       for k in missing)
    return (f"{path} leaves out {len(missing)} of the web's {len(WEB_MATERIAL)} material "
            f"keys, which take the base case's newsprint values: {values} (give the web's "
            "own; --quiet drops this line)")


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


class Given(float):
    """A number read from the command line that keeps the text it was given as, so a
    later range check names what the user typed (``'1000 m/min'``), not only its SI value."""

    text: str

    def __new__(cls, value: float, text: str):
        out = super().__new__(cls, value)
        out.text = text
        return out

    def shown(self, unit: str) -> str:
        """``'1000 m/min' (16.67 m/s)``, or ``300 m/s`` where the text was a bare number."""
        try:
            float(self.text)
        except ValueError:
            return f"{self.text!r} ({float(self):.4g} {unit})"
        return f"{self.text} {unit}"


def speed_value(text: str) -> float:
    """An argparse type: a speed in m/s, or with a unit (``"1200 m/min"``); a :class:`Given`
    (the text kept for messages)."""
    try:
        return Given(float(text), text)
    except ValueError:
        pass
    from ..units import to_si
    try:
        return Given(to_si("speed", text, "m/s"), text)
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


def local_workers(asked: int | None, default: int) -> int:
    """``asked`` when given, else ``default`` but at most the cores this process may use."""
    return asked if asked is not None else max(1, min(default, usable_cores()))


def add_dask_argument(p) -> None:
    """``--dask``, the same for every command whose points may run on a Dask cluster (its
    value checked in one place: :func:`webfem.sweeps.workers.check_dask`)."""
    p.add_argument("--dask", metavar="local|tcp://HOST:PORT",
                   help="run the points on Dask: 'local' starts a LocalCluster (with --workers "
                        "workers), an address joins an existing scheduler")


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


@contextmanager
def saved_if_interrupted(rows, csv_path, what: str = "points"):
    """Ctrl-C after a resumable run finished (while its chart or table is drawn) still says
    how many of its ``rows`` are saved in ``csv_path`` (the converged ones, or every row
    where ``what`` is "designs" or "geometries": a map keeps its failures), as an
    interruption during the run does (:class:`webfem.sweeps.SweepInterrupted`)."""
    from ..sweeps.interrupt import SweepInterrupted, saved_count
    try:
        yield
    except KeyboardInterrupt as err:
        if saved_count(err) is not None:
            raise
        kept = len(rows) if what != "points" else sum(
            1 for r in rows if (r.get("converged") if isinstance(r, dict) else r.converged))
        raise SweepInterrupted(kept, len(rows), csv_path, what) from err
