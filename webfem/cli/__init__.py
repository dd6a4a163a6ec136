"""Command line: ``webfem solve``, ``sweep``, ``mesh``, ``traction-loss``, ``calibrate``,
``study``, ``keys``, ``cases``, ``init``.

Run ``webfem --help`` or ``webfem COMMAND --help``. :mod:`.main` holds the parser and the
exit codes, :mod:`.common` what the subcommands share (and their two-function protocol), and
each subcommand has its own thin module.
"""

from .main import build_parser, main

__all__ = ["main", "build_parser"]
