"""``webfem idler``: will an idler slip? Its slip margin against line speed, and a chart."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from ..describe import SMALL, small_text
from ..idler import margin_curve
from ..physics.contact import TAIL_SIGMAS
from ..units import convert, display, unit_label
from .common import (HELP_FORMATTER, Progress, add_case_arguments, add_quiet_argument,
                     add_units_argument, case_from, model_options, options_epilog,
                     output_folder, positive_int, print_json, speed_value)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "idler", formatter_class=HELP_FORMATTER, epilog=options_epilog(),
        help="an idler's slip margin (traction available / required) against line speed")
    add_case_arguments(p)
    p.add_argument("--min-speed", type=speed_value, default=1.0,
                   help="from (m/s or with a unit, e.g. '60 m/min'; default 1 m/s)")
    p.add_argument("--max-speed", type=speed_value, default=20.0,
                   help="to (m/s or with a unit; default 20 m/s)")
    p.add_argument("--num", type=positive_int, default=20, help="speeds (default 20)")
    p.add_argument("--out", metavar="DIR",
                   help="write CASE_idler.csv (SI: speed, delta_T_required, "
                        "delta_T_available, slip_margin, mu_onset, converged, model_used, "
                        "error_mu, margin_low, margin_high: the margin's range from mu's "
                        "stated error, verdict, exponential_tail: the margin rests on "
                        "asperities the exponential heights put beyond 5 sigma; with "
                        "--units metric|us also a converted copy) and CASE_idler.png into "
                        "DIR")
    p.add_argument("--json", action="store_true", help="the curve as JSON (SI units)")
    add_units_argument(p)
    add_quiet_argument(p)


def run(args) -> int:
    case = case_from(args)
    folder = output_folder(args.out, "--out") if args.out else None
    from ..errors import InputError
    if not 0.0 < args.min_speed < args.max_speed:
        raise InputError(f"--min-speed {args.min_speed:g} and --max-speed {args.max_speed:g}"
                         ": need 0 < min < max [m/s]")
    speeds = np.linspace(args.min_speed, args.max_speed, args.num)
    curve = margin_curve(case, speeds, args.model, model_options(args),
                         progress=Progress(args.quiet, "speeds"))
    if args.json:
        print_json(curve.to_dict() | {"slip_speed": curve.slip_speed(),
                                      "verdicts": curve.verdicts()})
    else:
        print(_table(curve, args.units))
    if folder is not None:
        from ..io.idler_chart import idler_chart
        from ..io.tables import write_csv, write_in_units
        stem = f"{Path(args.case).stem}_idler"
        rows = curve.rows()
        paths = [write_csv(rows, folder / f"{stem}.csv", curve.COLUMNS),
                 write_in_units(rows, folder / f"{stem}.csv", args.units, curve.COLUMNS),
                 idler_chart(curve, folder / f"{stem}.png",
                             title=f"{Path(args.case).stem}: will the idler slip? "
                                   f"({curve.answered()})", units=args.units)]
        for path in paths:
            if path is not None:
                print(f"wrote {path}", file=sys.stderr)
    return 0


def _table(curve, units: str) -> str:
    """The slip check as a table with a header naming each column and its unit, one row
    per line speed (the model per row when auto chose per speed), and the verdict."""
    speed, tension = unit_label("speed", units), unit_label("tension", units)
    mixed = any(m != curve.model for m in curve.models_used)   # auto: its choice per row
    lines = [f"idler slip check ({curve.answered()}): line speed [{speed}], delta_T "
             f"required and available [{tension}] at the onset of slip, margin, the "
             f"margin's range from mu's stated error",
             (f"  {'line speed':>10} {'required':>10} {'available':>10} {'margin':>9} "
              f"{'range':>19}  {'verdict':<7}" + ("  model" if mixed else "")).rstrip(),
             f"  {f'[{speed}]':>10} {f'[{tension}]':>10} {f'[{tension}]':>10} {'[-]':>9} "
             f"{'[-]':>19}"]
    used = curve.models_used or (curve.model,) * len(curve.speeds)
    low = curve.margin_low or curve.slip_margin
    high = curve.margin_high or curve.slip_margin
    verdicts = curve.verdicts()
    for u, r, a, m, lo, hi, name, verdict in zip(
            curve.speeds, curve.delta_T_required, curve.delta_T_available,
            curve.slip_margin, low, high, used, verdicts):
        u, r, a = (convert(u, "speed", units), convert(r, "tension", units),
                   convert(a, "tension", units))
        # SI as it always printed; ft/min and m/min run to 4 digits, pli to 0.0001
        su, st = (3, 3) if units == "si" else (4, 3 if units == "metric" else 4)
        # a margin of 1e-112 is no figure to read: "< 0.001" (the JSON and CSV keep it)
        span = (f"< {SMALL:g}" if 0.0 < hi < SMALL else
                f"{small_text(lo, '.3g')} - {small_text(hi, '.3g')}")
        lines.append((f"  {u:10.{su}g} {r:10.{st}f} {a:10.{st}f} {small_text(m, '.3g'):>9} "
                      f"{span:>19}  "
                      f"{verdict:<7}" + (f"  {name}" if mixed else "")).rstrip())
    slip = curve.slip_speed()
    unsure = [u for u, v in zip(curve.speeds, verdicts) if v == "unsure"]
    by_tail = [u for u, t in zip(curve.speeds, curve.tail_unsure()) if t]
    by_range = [u for u in unsure if u not in by_tail]
    extent = curve.slip_extent()
    answered = [u for u, ok in zip(curve.speeds, curve.converged) if ok]
    tried = (f"{display(answered[0], 'speed', units, 3)} to "
             f"{display(answered[-1], 'speed', units, 3)}" if answered else "")
    hedge = " (by the margins; their stated ranges leave it unsure)" if unsure else ""
    if extent == "every":   # no speed tried holds: where it starts slipping is below them
        lines.append(f"  the idler slips at every speed tried ({tried}){hedge}")
    elif extent == "lowest":
        lines.append(f"  the idler slips at the lowest speed tried, "
                     f"{display(answered[0], 'speed', units, 3)} (where it starts slipping "
                     f"lies below the speeds tried), and holds at some above: see the "
                     f"table{hedge}")
    elif slip is not None:
        lines.append(f"  the idler slips above about {display(slip, 'speed', units, 3)}"
                     + hedge)
    elif not unsure and all(v == "holds" for v in verdicts):
        lines.append(f"  the idler holds at every speed tried ({tried})")
    elif not unsure and "holds" in verdicts:
        lines.append("  the idler holds wherever an answer was found")
    elif not unsure:
        lines.append("  no speed was answered: no verdict")
    if by_range:
        at = ", ".join(display(u, "speed", units, 3) for u in by_range)
        lines.append(f"  unsure at {at}: the answer's stated error of mu puts the margin on "
                     "both sides of 1; a finer model decides (--model fe1d or fe2d; under "
                     "auto, a lower --opt tol)")
    if any(curve.exponential_tail):
        lines.extend(_tail_lines(curve, by_tail, units))
    return "\n".join(lines)


def _tail_lines(curve, by_tail, units: str) -> list[str]:
    """Where an answer's contact comes from the exponential heights' tail: the speeds whose
    margin holds only by it (unsure, as ``webfem solve`` words its verdict there) and the
    first such speed's warning in full (each speed's is in ``--json``'s
    ``tail_warnings``)."""
    lines = []
    if by_tail:
        at = ", ".join(display(u, "speed", units, 3) for u in by_tail)
        lines.append(f"  unsure at {at}: the margin holds only by the exponential heights' "
                     f"tail (h_c beyond {TAIL_SIGMAS:g} sigma, where no surface has "
                     "asperities); friction.distribution = \"gaussian\" decides")
    tails = [u for u, t in zip(curve.speeds, curve.exponential_tail) if t]
    first = curve.speeds.index(tails[0])
    more = ", ".join(display(u, "speed", units, 3) for u in tails[1:])
    lines.append(f"  warning at {display(tails[0], 'speed', units, 3)}: "
                 f"{curve.tail_warnings[first]}"
                 + (f" (so at {more} too, each with its own numbers: --json's "
                    "tail_warnings)" if more else ""))
    return lines
