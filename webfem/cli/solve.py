"""``webfem solve``: one operating point; a summary (or JSON), VTU files, film pictures."""

from __future__ import annotations

import sys
from pathlib import Path

from ..api import solve
from ..idler import idler_at_web_speed
from ..errors import ConvergenceError, InputError
from .common import (DEFAULT_MODEL, HELP_FORMATTER, Ticker, add_case_arguments,
                     add_quiet_argument, add_units_argument, case_from, error_line,
                     model_options, options_epilog, output_folder, print_json)
from .summary import summary_text

#: Models whose results never carry a 2-D film (``--plot`` is refused before solving).
NO_FILM = ("closed-form", "fe1d", "fitted")


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("solve", help="solve one operating point and print a summary",
                              formatter_class=HELP_FORMATTER, epilog=options_epilog())
    add_case_arguments(p, default_model=DEFAULT_MODEL)
    p.add_argument("--vtu", metavar="DIR",
                   help="write VTU files of the web (and film, fe2d) into DIR for ParaView")
    p.add_argument("--plot", action="store_true",
                   help="draw the film (pressure, gap, friction; fe2d) as a PNG in --units, "
                        "into the --vtu DIR (or the current folder); where auto answers with "
                        "a model without a 2-D film, its gap and friction along the wrap")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (keys: model, h_center, h_inlet, h_outlet, h_min, "
                        "mu, delta_T, regime, lambda, beta, eq21_valid, converged, iterations, "
                        "n_dofs, solve_time_s, ..., and units: SI)")
    add_units_argument(p)
    add_quiet_argument(p)


def _write_vtu(result, folder, stem) -> list[Path]:
    from ..io.vtu import write_result
    return write_result(result, folder, stem)


def run(args) -> int:
    case = case_from(args)
    options = model_options(args)
    if args.plot and args.model in NO_FILM:
        raise InputError(f"--plot draws the 2-D film, which model {args.model} does not "
                         "solve: use --model fe2d (or drop --plot)")
    vtu = output_folder(args.vtu, "--vtu") if args.vtu else None
    pictures = output_folder(args.vtu or ".", "--vtu" if args.vtu else "--plot (current "
                             "folder)") if args.plot else None
    stem = f"{Path(args.case).stem}_{args.model}"
    try:
        with Ticker(f"solving with {args.model}", args.quiet):
            result = solve(case, model=args.model, options=options)
            # a sliding web's film is not an idler's: the check needs the idler's own
            result = idler_at_web_speed(result, args.model, options)
    except ConvergenceError as err:
        error_line(err)
        if err.result is not None:
            if args.json:
                print_json(err.result.to_dict())
            if vtu:   # the last iterate, for inspection, marked in its file names
                for path in _write_vtu(err.result, vtu, stem):
                    print(f"wrote {path} (NOT converged)", file=sys.stderr)
        return 3
    if args.json:
        print_json(result.to_dict())
    else:
        print(summary_text(result, args.model, args.units))
    for path in _write_vtu(result, vtu, stem) if vtu else []:
        print(f"wrote {path}", file=sys.stderr)
    if pictures:
        from ..io.pictures import film_pictures
        # auto may answer with a model without a 2-D film, known only now: draw what it
        # has (gap and friction along the wrap) rather than fail after writing the rest
        note = "" if result.film is not None else (
            f" ({result.get('model_used', args.model)} answered: no 2-D film, the gap and "
            "friction along the wrap only; --model fe2d draws the film)")
        for path in film_pictures(result, pictures, stem, units=args.units):
            print(f"wrote {path}{note}", file=sys.stderr)
    return 0
