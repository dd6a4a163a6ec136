"""``webfem sweep``: a parameter sweep ([sweep] and [[series]] tables) into a CSV and a chart;
resumable (a re-run of the same sweep solves only what is missing)."""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

from ..bundled import load_sweep
from ..errors import InputError
from .common import (DEFAULT_MODEL, HELP_FORMATTER, Progress, add_case_arguments, announce_case,
                     add_dask_argument, add_quiet_argument, add_units_argument, model_options,
                     options_epilog,
                     output_folder, overrides, positive_int, saved_if_interrupted)


#: What ``webfem sweep --help`` says before the arguments: the rule for a CSV already there.
DESCRIPTION = textwrap.fill(
    "Solve the case at each value of the [sweep] table (per [[series]]) and write "
    "OUT/CASE_MODEL.csv (SI, a row per point, each saved as it finishes; model_used names "
    "the model that answered it) and the chart OUT/CASE_MODEL.png (a log axis for log-spaced "
    "values). A CSV already there: the same sweep is resumed (its converged rows kept, the "
    "rest solved); a sweep holding every point of the old one, with the same model, "
    "options and case per series (more values or series), extends it; any other sweep is "
    "refused (exit 2, the message says what differs) unless --replace, which starts over in "
    "that file, keeping only the points it shares with a compatible old sweep. The command "
    "says on stderr which it did.", 88)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("sweep", help="sweep a parameter ([sweep] table): CSV and chart; "
                                            "each point is saved as it finishes and a re-run "
                                            "of the same sweep resumes where it stopped",
                              description=DESCRIPTION,
                              formatter_class=HELP_FORMATTER, epilog=options_epilog())
    add_case_arguments(p, default_model=DEFAULT_MODEL)
    p.add_argument("--out", required=True, help="output folder for CASE_MODEL.csv (SI) and "
                                                "CASE_MODEL.png (and CASE_MODEL_us.csv with "
                                                "--units us, CASE_MODEL_metric.csv with "
                                                "--units metric)")
    add_units_argument(p)
    add_quiet_argument(p)
    p.add_argument("--vtu", metavar="DIR",
                   help="also write VTU files per point and a .pvd collection per series")
    p.add_argument("--parameter", metavar="KEY",
                   help="sweep KEY instead of [sweep]'s parameter, over its values where "
                        "they measure the same quantity, else over --start..--stop; e.g. "
                        "line.speed: roller and web together at the case's U_w/U_r (the "
                        "web's speed where the roller stands still), where roller.speed "
                        "moves the roller alone")
    p.add_argument("--start", metavar="VALUE",
                   help="with --stop: sweep from VALUE (SI or with a unit, e.g. "
                        "'300 m/min'), in [sweep]'s num (default 40) evenly spaced values")
    p.add_argument("--stop", metavar="VALUE", help="with --start: sweep to VALUE")
    p.add_argument("--num", type=int,
                   help="override the number of swept values (same range)")
    p.add_argument("--log", action="store_true",
                   help="with --num: logarithmic spacing (the range must be > 0), drawn on a "
                        "log axis")
    p.add_argument("--replace", action="store_true",
                   help="start over in a CSV that holds another sweep (default: refuse it; "
                        "the same sweep is resumed and a larger one extended either way)")
    p.add_argument("--workers", type=positive_int, default=1,
                   help="local worker processes (default 1: serial with continuation from "
                        "point to point; > 1: chunks of points in parallel)")
    add_dask_argument(p)


def run(args) -> int:
    from ..io.vtu import SweepVtu
    from ..sweeps import run as run_sweep

    spec = load_sweep(args.case, overrides(args), parameter=args.parameter,
                      start=args.start, stop=args.stop)
    announce_case(args)
    held = spec.held_web_speed()
    if held:   # roller.speed on an idler or a moving web: a draw the user may not mean
        print(f"webfem: warning: {held}", file=sys.stderr)
    if args.num is not None or args.log:
        spec = spec.respaced(args.num, log=args.log)   # --log without --num is an error
    options = model_options(args)
    out = output_folder(args.out, "--out")
    vtu_dir = output_folder(args.vtu, "--vtu") if args.vtu else None
    stem = f"{Path(args.case).stem}_{args.model}"
    where = ("Dask " + args.dask) if args.dask else (
        f"{args.workers} processes" if args.workers > 1 else "serial, with continuation")
    if not args.quiet:
        print(f"webfem sweep: {args.case}, model {args.model}, {spec.parameter} over "
              f"{len(spec.values)} values x {len(spec.series)} series ({where})",
              file=sys.stderr)
    csv_path = out / f"{stem}.csv"
    rows = run_sweep(spec, args.model, csv_path, options=options, workers=args.workers,
                     dask=args.dask, progress=Progress(args.quiet), replace=args.replace,
                     notice=lambda text: print(f"webfem: {text}", file=sys.stderr),
                     vtu=SweepVtu(vtu_dir, stem, spec.parameter) if vtu_dir else None)
    with saved_if_interrupted(rows, csv_path):
        return _chart(args, spec, rows, out, stem, csv_path)


def _chart(args, spec, rows, out, stem, csv_path) -> int:
    """The closed-form reference, the copy in --units and the chart of a finished sweep."""
    from ..api import sweep as sweep_in_memory
    from ..io.charts import answered, sweep_chart
    from ..io.tables import ROW_KEYS, sweep_roles, sweep_rows, write_in_units

    reference, without = None, ""
    if args.model != "closed-form":   # the paper's model beside the field solution
        try:
            reference = sweep_rows(sweep_in_memory(spec, "closed-form"), spec.parameter)
        except InputError as err:   # e.g. a grooved roller: the chart goes without it
            without = " (no closed-form curve: it refuses this case)"
            print(f"webfem: the chart has no closed-form curve beside {args.model}: {err}",
                  file=sys.stderr)
    # the CSV above is the sweep's store and stays SI (a re-run with other --units resumes
    # it); the units asked for get a copy beside it
    units_csv = write_in_units(rows, csv_path, args.units, ROW_KEYS,
                               sweep_roles(spec.parameter))
    png_path = sweep_chart(rows, out / f"{stem}.png",
                           title=f"{Path(args.case).stem}: {answered(rows, args.model)}"
                           + (" (thin: closed form, Eq. 21)" if reference else without),
                           beside=reference, units=args.units,
                           log_x=True if args.log else None)
    for path in (csv_path, units_csv, png_path):
        if path is not None:
            print(f"wrote {path}")
    failed = [r for r in rows if not r["converged"]]
    if failed:
        print(f"webfem: {len(failed)} of {len(rows)} points have no converged, admissible "
              "answer (see converged and solver_message in the CSV)", file=sys.stderr)
        return 3
    return 0
