"""``webfem traction-loss``: the roller speed at which mu falls below a threshold, and a chart
of that speed against the paper's operating parameters."""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

import numpy as np

from ..traction import (CHART_POINTS, SPEED_RANGE, chart_parameters, mu_curve,
                        traction_loss_speed, traction_loss_table)
from ..errors import InputError
from ..keys import key_meta
from ..units import ROLES, display
from .summary import in_units
from .common import (DEFAULT_MODEL, HELP_FORMATTER, Progress, Ticker, add_case_arguments,
                     add_quiet_argument, add_units_argument, case_from, local_workers,
                     model_options, options_epilog, output_folder, positive_int, print_json,
                     speed_value)

#: Processes of the speed scan unless told (at most the machine's cores): this one walks
#: the low speeds while a worker walks the rest and refines its crossing. The base case's
#: fe2d search on 2 quiet cores: 3.35-3.85 -> 2.32-3.16 s, for about 10 % more CPU (the
#: worker's cold start, its fork); with one core busy with another job they lost, 3.6-3.9 s
#: serial against 4.0-4.5 s, and with two it was a toss-up (3.5-6.5 against 3.2-6.9 s).
DEFAULT_WORKERS = 2


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("traction-loss",
                              help="roller speed at which mu falls below a threshold",
                              description=textwrap.fill(
                                  "Scan the line's speed: the roller speed U_r with the web "
                                  "following at the case's ratio U_w/U_r (at rest in the "
                                  "paper's rig, at U_r on an idler, 0.99 U_r for a 1 % draw; "
                                  "the web speed used to stay fixed, adding a sliding speed "
                                  "the line does not have), up to where the web can no "
                                  "longer be held or the thin-film model holds no more; "
                                  "report where mu falls below --mu-min after its peak.", 88),
                              formatter_class=HELP_FORMATTER, epilog=options_epilog())
    add_case_arguments(p, default_model=DEFAULT_MODEL)
    p.add_argument("--mu-min", type=float, required=True, help="friction threshold, e.g. 0.1")
    p.add_argument("--min-speed", type=speed_value, default=SPEED_RANGE[0],
                   help=f"scan from (m/s or with a unit, e.g. '30 m/min'; default "
                        f"{SPEED_RANGE[0]:g} m/s)")
    p.add_argument("--max-speed", type=speed_value, default=SPEED_RANGE[1],
                   help=f"scan to (m/s or with a unit; default {SPEED_RANGE[1]:g} m/s)")
    p.add_argument("--json", action="store_true",
                   help="one JSON object: speed (U_r in m/s, null if none), model, mu_min, "
                        "mu_peak, speed_peak, bracket, scanned, evaluations, message, "
                        "web_speed_ratio (U_w/U_r kept; null: roller at rest, web speed "
                        "kept), scan_limit (why the speeds above scanned[1] were not "
                        "scanned: T_eff <= 0, a film thicker than R/100, the model's "
                        "refusal; null: the range or a crossing ended the scan), "
                        "speed_interval (the speeds where mu's stated error band reaches "
                        "mu_min; an end null where the speeds solved do not show it), "
                        "error_speed (the interval's larger half over speed; null without "
                        "both ends); units: SI")
    p.add_argument("--chart", metavar="DIR",
                   help="also chart the traction-loss speed against T, B, L and R (closed "
                        "form and --model) into DIR: each over the paper's range where that "
                        "holds the case's value, else the value / 2 to the value * 2; a point "
                        "without an answer is an x on the panel's floor, named on stderr")
    p.add_argument("--points", type=positive_int, default=CHART_POINTS,
                   help=f"points per parameter in the chart (default {CHART_POINTS})")
    p.add_argument("--workers", type=positive_int, default=None,
                   help="local processes for the speed scan and the chart's searches "
                        f"(default {DEFAULT_WORKERS} where the machine has {DEFAULT_WORKERS} "
                        "cores or more, else 1: they pay only where both are idle; the same "
                        "answers: the scan's to the bit, its second run starting cold either "
                        "way, the chart's to rounding)")
    p.add_argument("--full-scan", action="store_true",
                   help="solve every speed up to --max-speed (the peak is then the whole "
                        "range's) instead of stopping at the first speed below --mu-min")
    add_units_argument(p)
    add_quiet_argument(p)


def _speed_range(low, high) -> tuple[float, float]:
    """``(--min-speed, --max-speed)``, checked against the roller speeds a case allows
    before anything is solved: an error names the flag and the text given."""
    top = key_meta("roller.speed")["hi"]

    def said(value) -> str:
        return value.shown("m/s") if hasattr(value, "shown") else f"{value:g} m/s"

    if not 0.0 < high <= top:
        raise InputError(f"--max-speed = {said(high)} is out of range: must be > 0 and <= "
                         f"{top:g} m/s (the roller speeds a case allows, roller.speed)")
    if not 0.0 <= low < high:
        raise InputError(f"--min-speed = {said(low)} is out of range: must be >= 0 and below "
                         f"--max-speed = {said(high)}")
    return float(low), float(high)


def run(args) -> int:
    case = case_from(args)
    options = model_options(args)
    # a folder this command makes is removed again should the chart fail: never an empty
    # folder left beside a printed answer
    made = args.chart and not Path(args.chart).exists()
    chart_dir = output_folder(args.chart, "--chart") if args.chart else None
    try:
        return _run(args, case, options, chart_dir)
    except BaseException:
        if made and chart_dir is not None and not any(chart_dir.iterdir()):
            chart_dir.rmdir()
        raise


def _run(args, case, options, chart_dir) -> int:
    speed_range = _speed_range(args.min_speed, args.max_speed)
    workers = local_workers(args.workers, DEFAULT_WORKERS)
    with Ticker(f"scanning roller speeds with {args.model}", args.quiet):
        out = traction_loss_speed(case, args.mu_min, model=args.model,
                                  speed_range=speed_range, options=options,
                                  workers=workers, full_scan=args.full_scan)
    if args.json:
        print_json(out.to_dict())
    else:
        message = out.message if args.units == "si" else in_units(out.message, args.units)
        print(f"webfem traction-loss ({out.answered()}): {message}; peak mu "
              f"{out.mu_peak:.4f} at {display(out.speed_peak, 'speed', args.units, 3)}; "
              f"{out.evaluations} solves")
    if chart_dir:
        from ..io.charts import traction_loss_chart

        models = list(dict.fromkeys(["closed-form", args.model]))
        parameters = chart_parameters(case)
        rows = traction_loss_table(case, out.mu_min, models, n=args.points, options=options,
                                   progress=Progress(args.quiet), workers=workers,
                                   parameters=parameters, speed_range=speed_range)
        speeds = np.geomspace(max(args.min_speed, 1e-3), args.max_speed, 40)
        curves = {m: mu_curve(case, m, speeds, options if m == args.model else None)
                  for m in models}
        stem = Path(args.case).stem
        path = traction_loss_chart(rows, curves, out.mu_min,
                                   chart_dir / f"{stem}_traction_loss.png", parameters,
                                   units=args.units, title=stem,
                                   case_values={k: case.get(k) for k, *_ in parameters})
        for r in rows:
            if r.get("skipped"):
                role = ROLES.get(r["parameter"])
                value = (display(r["value"], role, args.units, 3) if role
                         else f"{r['value']:.3g}")
                print(f"webfem traction-loss: chart point {r['parameter']} = {value} "
                      f"({r['model']}) has no answer, marked x: {r['skipped']}",
                      file=sys.stderr)
        print(f"wrote {path}", file=sys.stderr)
    return 0 if out.speed is not None else 4
