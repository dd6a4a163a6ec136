"""``webfem idler``: will an idler slip? Its slip margin against line speed, and a chart."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from ..idler import margin_curve
from ..units import convert, display, unit_label
from .common import (HELP_FORMATTER, add_case_arguments, add_units_argument, case_from,
                     model_options, options_epilog, output_folder, positive_int, print_json,
                     speed_value)


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
    p.add_argument("--out", metavar="DIR", help="write CASE_idler.png into DIR")
    p.add_argument("--json", action="store_true", help="the curve as JSON (SI units)")
    add_units_argument(p)


def run(args) -> int:
    case = case_from(args)
    folder = output_folder(args.out, "--out") if args.out else None
    from ..errors import InputError
    if not 0.0 < args.min_speed < args.max_speed:
        raise InputError(f"--min-speed {args.min_speed:g} and --max-speed {args.max_speed:g}"
                         ": need 0 < min < max [m/s]")
    speeds = np.linspace(args.min_speed, args.max_speed, args.num)
    curve = margin_curve(case, speeds, args.model, model_options(args))
    if args.json:
        print_json(curve.to_dict() | {"slip_speed": curve.slip_speed()})
    else:
        units = args.units
        print(f"idler slip check ({curve.model}): line speed [{unit_label('speed', units)}], "
              f"delta_T required and available [{unit_label('tension', units)}], margin")
        for u, r, a, m in zip(curve.speeds, curve.delta_T_required, curve.delta_T_available,
                              curve.slip_margin):
            u, r, a = (convert(u, "speed", units), convert(r, "tension", units),
                       convert(a, "tension", units))
            # SI as it always printed; ft/min and m/min run to 4 digits, pli to 0.0001
            su, st = (3, 3) if units == "si" else (4, 3 if units == "metric" else 4)
            print(f"  {u:8.{su}g} {r:10.{st}f} {a:10.{st}f} {m:9.3g}  "
                  f"{'holds' if m >= 1 else 'SLIPS'}")
        slip = curve.slip_speed()
        print("  the idler holds over the whole range" if slip is None
              else f"  the idler slips above about {display(slip, 'speed', units, 3)}")
    if folder is not None:
        from ..io.idler_chart import idler_chart
        path = idler_chart(curve, folder / f"{Path(args.case).stem}_idler.png",
                           title=f"{Path(args.case).stem}: will the idler slip?",
                           units=args.units)
        print(f"wrote {path}", file=sys.stderr)
    return 0
