"""``webfem grooves``: which circumferential grooves keep mu >= mu_min, and at what cost in
land (contact area): a map of traction against groove pitch and land fraction."""

from __future__ import annotations

import csv
import sys
from pathlib import Path

from ..groove_sizing import (DEFAULT_DEPTH, DEFAULT_LAND_FRACTIONS, DEFAULT_PITCHES,
                             best_designs, groove_map)
from ..units import convert, display, unit_label
from .common import (HELP_FORMATTER, Progress, add_case_arguments, add_quiet_argument,
                     add_units_argument, case_from, model_options, output_folder, print_json,
                     speed_value)


def _floats(text: str) -> list[float]:
    from ..errors import InputError
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise InputError(f"'{text}' is not a comma-separated list of numbers") from None
    if not values:
        raise InputError(f"'{text}': give at least one number")
    return values


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "grooves", help="groove sizing: traction against groove pitch and land fraction",
        formatter_class=HELP_FORMATTER,
        description="Solve the grooved 2-D film (fe2d) for each groove design at the case's "
                    "speed (or --speed) and mark the designs that keep mu >= --mu-min; the "
                    "recommended one has the largest land fraction (contact area).")
    add_case_arguments(p, model=False)
    p.add_argument("--opt", action="append", metavar="NAME=VALUE",
                   help="fe2d option, e.g. --opt level=1")
    p.add_argument("--mu-min", type=float, required=True, help="friction needed, e.g. 0.2")
    p.add_argument("--speed", type=speed_value, action="append",
                   help="roller speed (m/s or with a unit, e.g. '1000 m/min'); repeat for "
                        "several (default: the case's)")
    p.add_argument("--pitches", default=",".join(f"{v:g}" for v in DEFAULT_PITCHES),
                   help="groove pitches [m], comma-separated (default "
                        + ",".join(f"{v:g}" for v in DEFAULT_PITCHES) + ")")
    p.add_argument("--lands", default=",".join(f"{v:g}" for v in DEFAULT_LAND_FRACTIONS),
                   help="land fractions a/pitch, comma-separated (default "
                        + ",".join(f"{v:g}" for v in DEFAULT_LAND_FRACTIONS) + ")")
    p.add_argument("--depths", default=f"{DEFAULT_DEPTH:g}",
                   help=f"groove depths [m], comma-separated (default {DEFAULT_DEPTH:g})")
    p.add_argument("--json", action="store_true", help="the designs as JSON (SI units)")
    p.add_argument("--out", metavar="DIR", help="also write the map as CSV (SI; with --units "
                                                "metric or us also a converted copy) and a "
                                                "chart (PNG) into DIR")
    add_units_argument(p)
    add_quiet_argument(p)


def run(args) -> int:
    case = case_from(args)
    args.model = "fe2d"
    options = model_options(args)
    folder = output_folder(args.out, "--out") if args.out else None
    designs = groove_map(case, args.mu_min, speeds=args.speed, pitches=_floats(args.pitches),
                         land_fractions=_floats(args.lands), depths=_floats(args.depths),
                         options=options,
                         progress=Progress(args.quiet, "designs"))
    best = best_designs(designs)
    if folder:
        path = folder / f"{Path(args.case).stem}_grooves.csv"
        with path.open("w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(designs[0].to_dict()))
            w.writeheader()
            for d in designs:
                w.writerow(d.to_dict())
        print(f"wrote {path}", file=sys.stderr)
        from ..io.charts import groove_chart
        from ..io.tables import write_in_units

        copy = write_in_units([d.to_dict() for d in designs], path, args.units)
        if copy is not None:
            print(f"wrote {copy}", file=sys.stderr)
        chart = groove_chart(designs, args.mu_min, folder / f"{Path(args.case).stem}_grooves.png",
                             best, units=args.units)
        print(f"wrote {chart}", file=sys.stderr)
    if args.json:
        print_json({"mu_min": args.mu_min, "designs": [d.to_dict() for d in designs],
                    "best": {f"{s:g}": (b.to_dict() if b else None) for s, b in best.items()}})
        return 0 if all(best.values()) else 4
    units = args.units
    size, thin = unit_label("position", units), unit_label("thin", units)

    def mm(value):   # a groove size in the display unit (mm, or in for us)
        return convert(value, "position", units)

    for speed, b in best.items():
        print(f"roller speed {display(speed, 'speed', units)}, mu_min {args.mu_min:g} "
              "(* feasible):")
        print(f"  pitch {size:2}  groove {size:2}  depth {size:2}  land %      mu   "
              f"h_center {thin:2}  contact share")
        for d in designs:
            if d.speed != speed:
                continue
            mu = f"{d.mu:7.4f}" if d.converged else "  no answer"
            hc = f"{convert(d.h_center, 'thin', units):11.3g}" if d.converged else ""
            cs = f"{d.contact_share:14.3f}" if d.converged else ""
            mark = "*" if d.feasible else " "
            print(f"{mark} {mm(d.pitch):8.3g}  {mm(d.width):9.3g}  {mm(d.depth):8.3g}  "
                  f"{100 * d.land_fraction:6.1f}  {mu}  {hc}{cs}")
        if b is None:
            print("  no design keeps mu >= mu_min: finer pitches or narrower lands")
        else:
            print(f"  best: pitch {mm(b.pitch):.3g} {size}, groove {mm(b.width):.3g} {size} "
                  f"wide and {mm(b.depth):.3g} {size} deep: land {100 * b.land_fraction:.0f} "
                  f"%, mu {b.mu:.3f}")
    return 0 if all(best.values()) else 4
