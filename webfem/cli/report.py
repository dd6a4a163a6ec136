"""``webfem report``: solve one case and write a self-contained HTML page to share."""

from __future__ import annotations

import sys
from pathlib import Path

from ..api import solve
from ..idler import idler_at_web_speed
from .common import (HELP_FORMATTER, Ticker, add_case_arguments, add_quiet_argument,
                     add_units_argument, case_from, model_options, options_epilog,
                     output_folder)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "report", help="solve a case and write one HTML page to share (inputs, model, "
                       "summary, pictures, warnings, how it was computed)",
        description="Solve CASE and write DIR/CASE_MODEL.html (MODEL: the model asked for, "
                    "base_auto.html by default): a single page with the pictures embedded, "
                    "that opens in any browser without webfem. The page says which model "
                    "answered and why.",
        formatter_class=HELP_FORMATTER, epilog=options_epilog())
    add_case_arguments(p)
    p.add_argument("--out", required=True, metavar="DIR", help="output folder for the page")
    add_units_argument(p)
    add_quiet_argument(p)


def run(args) -> int:
    from ..io.report import write_report

    case = case_from(args)
    options = model_options(args)
    folder = output_folder(args.out, "--out")
    stem = f"{Path(args.case).stem}_{args.model}"
    # a ConvergenceError reaches main (exit 3): a report of an unconverged solve would be
    # shared as if it were an answer
    with Ticker(f"solving with {args.model}", args.quiet):
        result = solve(case, model=args.model, options=options)
        # a sliding web's film is not an idler's: the check needs the idler's own
        result = idler_at_web_speed(result, args.model, options)
    used = result.summary.model_used or args.model
    asked = (f"asked for by name (--model {args.model})" if args.model_given
             else f"the default of webfem report (--model {args.model})")
    # the file keeps the model asked for (base_auto.html): a re-run replaces its own page
    # whichever model auto picks; the title and the page say which answered
    path = write_report(result, folder, name=f"{stem}.html",
                        title=f"webfem report: {Path(args.case).stem} ("
                              + (args.model if used == args.model else f"{args.model}: {used}")
                              + ")", units=args.units, asked=asked)
    print(f"wrote {path}")
    from ..io.report import page_warnings
    said = page_warnings(result)
    if said:
        print(f"webfem: {len(said)} warning(s), listed in the page", file=sys.stderr)
    return 0
