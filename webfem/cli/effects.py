"""``webfem effects``: the case solved with each effect it includes switched off in turn."""

from __future__ import annotations

from ..effects import effects_table
from .common import (HELP_FORMATTER, Progress, add_case_arguments, add_units_argument,
                     case_from, model_options, options_epilog, print_json)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "effects", formatter_class=HELP_FORMATTER, epilog=options_epilog(),
        help="how much each effect beyond the paper (inertia, bending, slip, permeation, "
             "friction from the loads) moves h_center, h_min and mu",
        description="Solve CASE with every effect it includes, then with each switched off "
                    "in turn, and print how much each moves h_center, h_min and mu. With "
                    "auto (the default) the full case is solved with auto and every variant "
                    "with the model auto chose for it, as the table's heading says, so a row's "
                    "change is the effect's and not a change of model.")
    add_case_arguments(p)
    p.add_argument("--json", action="store_true", help="the table as JSON")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    add_units_argument(p)


def run(args) -> int:
    case = case_from(args)
    table = effects_table(case, args.model, model_options(args),
                          progress=None if args.quiet else Progress())
    if args.json:
        print_json(table.to_dict())
    else:
        print(table.text(args.units))
    return 0
