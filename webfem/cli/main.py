"""The ``webfem`` command: the parser, dispatch to one module per subcommand, exit codes.

Exit codes: 0 done; 2 bad input (an InputError, an unusable output path, a usage error);
3 no converged solution; 4 traction-loss found no speed in range; 130 interrupted (Ctrl-C).
Every failure is one line on stderr, never a traceback. Output cut short by the reader
(``webfem keys | head``) ends quietly.
"""

from __future__ import annotations

import argparse
import importlib
import os
import signal
import sys
import warnings
from contextlib import contextmanager

from ..errors import ConvergenceError, InputError, ValidityWarning
from .common import error_line

__all__ = ["main", "build_parser", "SUBCOMMANDS"]

#: The subcommand modules of this package, in the order ``webfem --help`` lists them.
SUBCOMMANDS = ("solve", "sweep", "mesh", "traction_loss", "calibrate", "study", "effects",
               "idler", "grooves", "fit", "keys", "cases", "report")


def _modules():
    for name in SUBCOMMANDS:
        yield importlib.import_module(f"{__package__}.{name}")


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("webfem")
    except PackageNotFoundError:   # run from a source tree without an install
        from .. import __version__
        return __version__


def build_parser() -> argparse.ArgumentParser:
    """The ``webfem`` parser: each module's ``add_parser`` adds its subcommand, and the
    parsed arguments carry the module's ``run``."""
    parser = argparse.ArgumentParser(
        prog="webfem",
        description="Air film and traction between a moving web and a roller "
                    "(Hashimoto's model: closed form and finite elements).",
        epilog="Start with `webfem cases`, `webfem solve base` and `webfem keys`.")
    parser.add_argument("--version", action="version", version=f"webfem {_version()}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for module in _modules():
        before = set(sub.choices)
        module.add_parser(sub)
        for name in set(sub.choices) - before:
            sub.choices[name].set_defaults(_run=module.run)
    return parser


def _stdout_gone() -> None:
    """The reader closed the pipe: send what is still buffered nowhere, so the interpreter's
    last flush does not complain."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):   # no real file descriptor (tests)
        pass


def _interrupted(err: KeyboardInterrupt) -> None:
    """One line; a sweep's interruption (webfem.sweeps.SweepInterrupted, also under a
    second Ctrl-C that came on top of it) says what is saved."""
    from ..sweeps.interrupt import saved_count
    counted = saved_count(err)
    start = "\n" if sys.stderr.isatty() else ""   # after a live progress line
    if counted is not None:
        print(f"{start}webfem: {counted}", file=sys.stderr)
    else:
        print(f"{start}webfem: interrupted", file=sys.stderr)


class Terminated(KeyboardInterrupt):
    """SIGTERM (a job scheduler, ``kill``, a closing terminal session) taken as Ctrl-C is:
    files closed, a sweep's lock released and what is saved said, instead of dying with a
    stale lock and nothing printed."""


def _terminate(signum, frame):
    # a scheduler or a kill loop sends it again: the clean-up (files, the sweep's lock) runs
    # once, uncut; the handler before this command's comes back when it ends
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    raise Terminated()


@contextmanager
def _sigterm_as_interrupt():
    """SIGTERM raises :class:`Terminated` in this process while a command runs (worker
    processes reset it: :func:`webfem.sweeps.workers._worker_start`)."""
    try:
        old = signal.signal(signal.SIGTERM, _terminate)
    except ValueError:   # not the main thread (a caller's thread): leave signals alone
        yield
        return
    try:
        yield
    finally:
        if old is not None:     # None: a handler not installed from Python, left as it is
            signal.signal(signal.SIGTERM, old)


def main(argv=None) -> int:
    """Run ``webfem`` with ``argv`` (default: the command line); returns the exit code."""
    args = build_parser().parse_args(argv)
    try:
        with warnings.catch_warnings(), _sigterm_as_interrupt():
            # the summary (or the JSON "warnings" key) already carries each validity warning
            warnings.simplefilter("ignore", ValidityWarning)
            code = args._run(args)
        sys.stdout.flush()   # a closed pipe shows here, inside the handlers below
        return code
    except InputError as err:
        error_line(err)
        return 2
    except ConvergenceError as err:
        error_line(err)
        return 3
    except KeyboardInterrupt as err:
        from ..sweeps.interrupt import hold_interrupts
        restore = hold_interrupts()     # a second Ctrl-C must not cut the one line short
        try:
            _interrupted(err)
        finally:
            restore()
        return 143 if isinstance(err.__cause__ or err, Terminated) else 130
    except BrokenPipeError:
        _stdout_gone()
        return 0
    except MemoryError:
        error_line("out of memory: the problem is too large for this machine; a lower "
                   "--opt level, a larger --opt error_tol or a narrower web needs less")
        return 3
    except OSError as err:   # e.g. an output path that cannot be written after all
        where = f"'{err.filename}': " if err.filename else ""
        error_line(f"{where}{err.strerror or err}")
        return 2
