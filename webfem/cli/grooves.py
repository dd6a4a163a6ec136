"""``webfem grooves``: which circumferential grooves keep mu >= mu_min, and at what cost in
land (contact area): a map of traction against groove pitch and land fraction, and with
``--loss-speed`` the traction-loss speed of each groove geometry; resumable."""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

from ..errors import InputError
from ..keys import key_meta
from ..groove_sizing import (DEFAULT_DEPTH, DEFAULT_LAND_FRACTIONS, DEFAULT_PITCHES,
                             DEFAULT_SPEED_FACTORS, LOSS_LAND_FRACTIONS, LOSS_PITCHES,
                             LOSS_SCAN, LOSS_SPEED_RANGE, best_designs, check_arguments,
                             LOSS_COLUMNS, MAP_COLUMNS, groove_map, loss_speed_map)
from ..units import convert, display, to_si, unit_label
from .common import (HELP_FORMATTER, Progress, add_case_arguments, add_quiet_argument,
                     add_units_argument, case_from, local_workers, model_options,
                     output_folder, positive_int, print_json, saved_if_interrupted,
                     speed_value)

#: Worker processes of a map unless told (at most the machine's cores): its designs are
#: independent cold solves, so two cores halve its time.
DEFAULT_WORKERS = 2


def _workers(asked: int | None) -> int:
    return local_workers(asked, DEFAULT_WORKERS)


#: The case key whose unit a list of lengths is read in (None: plain fractions).
_LIST_KEYS = {"pitches": "roller.groove_pitch", "loss_pitches": "roller.groove_pitch",
              "depths": "roller.groove_depth", "lands": None, "loss_lands": None}


def _floats(name: str, text: str) -> list[float]:
    """The values of list option ``--NAME``: lengths in metres or with a unit ("1.27 mm"),
    > 0; land fractions as numbers > 0 and < 1, or in percent ("50 %"). A bad item is an
    error naming the flag, the text, the item, the unit and the valid range."""
    flag, key = "--" + name.replace("_", "-"), _LIST_KEYS[name]
    hi = key_meta(key)["hi"] if key else 1.0
    what = (f"lengths > 0 and <= {hi:g} m (the case key {key}'s range), in m or with a unit, "
            "comma-separated (e.g. 0.00127,2.5 mm)" if key else
            "land fractions a/pitch > 0 and < 1, or in percent, comma-separated (e.g. 0.5,0.8 "
            "or 50 %,80 %)")
    values = []
    for item in (t.strip() for t in text.split(",")):
        if not item:
            continue
        value = _item_value(flag, key, text, item, what)
        if not (0.0 < value < 1.0 if key is None else 0.0 < value <= hi):
            unit = "" if key is None else " m"
            shown = item if value == _number(item) else f"{item} = {value:g}{unit}"
            # a bare number read in metres that would fit in millimetres: a unit forgotten
            meant = (f" (a bare number is metres: '{item} mm'?)" if key is not None
                     and value == _number(item) and 0.0 < value * 1e-3 <= hi else "")
            raise InputError(f"{flag} = {text!r}: {shown} is out of range{meant}; give {what}")
        values.append(value)
    if not values:
        raise InputError(f"{flag} = {text!r}: give at least one value: {what}")
    return values


def _item_value(flag: str, key: str | None, text: str, item: str, what: str) -> float:
    """One item of a list option: a plain number, a length with a unit (``key`` names the
    case key whose unit it is read in), or a land fraction in percent (``key`` None)."""
    value = _number(item)
    if value is not None:
        return value
    if key is None:
        percent = _number(item[:-1]) if item.endswith("%") else None
        if percent is None:
            raise InputError(f"{flag} = {text!r}: {item!r} is not a number; give {what}")
        return percent / 100.0
    try:
        return to_si(key, item, "m")
    except InputError as err:
        why = str(err).split(" = ", 1)[-1]
        raise InputError(f"{flag} = {text!r}: {why}; give {what}") from None


def _number(text: str) -> float | None:
    try:
        return float(text)
    except ValueError:
        return None


def _listed(values) -> str:
    return ",".join(f"{v:g}" for v in values)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "grooves", help="groove sizing: traction against groove pitch and land fraction, "
                        "and the traction-loss speed of each groove (resumable)",
        formatter_class=HELP_FORMATTER,
        description=textwrap.fill(
                    "Solve the grooved 2-D film (fe2d) for each groove design (pitch x land "
                    "fraction x depth) at each roller speed and mark the designs that keep "
                    "mu >= --mu-min; the recommended one has the largest land fraction "
                    "(contact area). A speed moves the line: the web follows the roller at "
                    "the case's ratio U_w/U_r (at rest in the paper's rig, at U_r on an "
                    "idler; the web speed used to stay fixed). Writes CASE_grooves.csv and "
                    ".png into --out; each design is saved as it finishes, so a run that is interrupted (Ctrl-C, kill) "
                    "continues where it stopped when run again with the same arguments.", 88),
        epilog=textwrap.fill("With --loss-speed it also finds, for each pitch in --loss-pitches and land "
               "fraction in --loss-lands (at the first --depths), the roller speed at which "
               "mu falls to --mu-min (a scan of "
               f"{LOSS_SCAN} speeds over {LOSS_SPEED_RANGE[0]:g}-{LOSS_SPEED_RANGE[1]:g} m/s "
               "refined by Brent's method to 1 %, about 14 fe2d solves per geometry), and the "
               "smooth roller's: CASE_grooves_loss.csv and .png (loss speed against land "
               "fraction, a line per pitch). On the base case the defaults take about a "
               "minute for the map (its 32 designs all answer; 0.5-1.2 minutes on a 2-core "
               "machine shared with other work) and minutes more for --loss-speed; a "
               "design without an answer is kept, not solved again.", 88))
    add_case_arguments(p, model=False)
    p.add_argument("--opt", action="append", metavar="NAME=VALUE",
                   help="fe2d option, e.g. --opt level=1")
    p.add_argument("--mu-min", type=float, required=True, help="friction needed, e.g. 0.2")
    p.add_argument("--speed", type=speed_value, action="append",
                   help="roller speed (m/s or with a unit, e.g. '1000 m/min'), the web at the "
                        "case's ratio U_w/U_r; repeat for "
                        "several (default: the case's speed times "
                        + " and ".join(f"{f:g}" for f in DEFAULT_SPEED_FACTORS)
                        + ", for the margin of a faster line: "
                        + " and ".join(f"{20 * f:g}" for f in DEFAULT_SPEED_FACTORS)
                        + " m/s on the base case)")
    p.add_argument("--pitches", default=_listed(DEFAULT_PITCHES),
                   help=f"groove pitches [m, or with a unit: '1.27 mm'], comma-separated "
                        f"(default "
                        f"{_listed(DEFAULT_PITCHES)})")
    p.add_argument("--lands", default=_listed(DEFAULT_LAND_FRACTIONS),
                   help=f"land fractions a/pitch, or in percent (\"50 %%\"), comma-separated "
                        f"(default "
                        f"{_listed(DEFAULT_LAND_FRACTIONS)})")
    p.add_argument("--depths", default=f"{DEFAULT_DEPTH:g}",
                   help=f"groove depths [m, or with a unit], comma-separated (default "
                        f"{DEFAULT_DEPTH:g})")
    p.add_argument("--loss-speed", action="store_true",
                   help="also chart the traction-loss speed against groove geometry")
    p.add_argument("--loss-pitches", default=_listed(LOSS_PITCHES),
                   help=f"pitches [m] of --loss-speed (default {_listed(LOSS_PITCHES)})")
    p.add_argument("--loss-lands", default=_listed(LOSS_LAND_FRACTIONS),
                   help=f"land fractions of --loss-speed (default "
                        f"{_listed(LOSS_LAND_FRACTIONS)})")
    p.add_argument("--workers", type=positive_int, default=None,
                   help="designs (with --loss-speed, geometries) solved at once, each in a "
                        "process of its own: each is solved from cold, so the answers do "
                        f"not depend on it (default: {DEFAULT_WORKERS} where the machine has "
                        f"{DEFAULT_WORKERS} cores or more, else 1; each process holds up to "
                        "about 1.2 GB)")
    p.add_argument("--json", action="store_true", help="the designs as JSON (SI units)")
    add_units_argument(p)
    p.add_argument("--out", metavar="DIR", default=".",
                   help="folder for CASE_grooves.csv and .png, their sidecars "
                        "(.sweep.json: what was run, for resuming) and with --loss-speed "
                        "CASE_grooves_loss.csv and .png (default: the current folder)")
    add_quiet_argument(p)


def _short(message: str, width: int = 64) -> str:
    """A long message cut to ``width`` characters (the CSV and --json hold all of it)."""
    message = message or "no message"
    return message if len(message) <= width else message[:width - 3] + "..."


def _print_map(designs, best, mu_min: float, units: str = "si") -> None:
    size, thin = unit_label("position", units), unit_label("thin", units)

    def g(value):   # a groove size in the display unit (mm, or in for us)
        return convert(value, "position", units)

    for speed, b in best.items():
        here = [d for d in designs if d.speed == speed]
        flagged = [d for d in here if d.flag and d.converged and d.mu >= mu_min]
        print(f"roller speed {display(speed, 'speed', units)}"
              + (f" ({60 * speed:.0f} m/min)" if units == "si" else "")
              + f", mu_min {mu_min:g} (* feasible"
              + (", ! mu >= mu_min but flagged" if flagged else "") + "):")
        print(f"  pitch {size:2}  groove {size:2}  depth {size:2}  land %      mu   "
              f"h_center {thin:2}  h_min {thin:2}  contact share")
        for d in here:
            mu = f"{d.mu:7.4f}" if d.converged else f"  no answer: {_short(d.message)}"
            hc = f"{convert(d.h_center, 'thin', units):11.3g}" if d.converged else ""
            hm = f"{convert(d.h_min, 'thin', units):9.3g}" if d.h_min is not None else ""
            cs = f"{d.contact_share:15.3f}" if d.converged else ""
            mark = "*" if d.feasible else "!" if d in flagged else " "
            print(f"{mark} {g(d.pitch):8.3g}  {g(d.width):9.3g}  {g(d.depth):8.3g}  "
                  f"{100 * d.land_fraction:6.1f}  {mu}  {hc}{hm}{cs}")
        for d in flagged:
            print(f"  ! {g(d.pitch):.3g} {size} / {g(d.width):.3g} {size} groove: {d.flag} "
                  f"(its warning in the CSV and --json): not counted as feasible")
        if b is None:
            print("  no design keeps mu >= mu_min: finer pitches or narrower lands")
        else:
            print(f"  best: pitch {g(b.pitch):.3g} {size}, groove {g(b.width):.3g} {size} "
                  f"wide and {g(b.depth):.3g} {size} deep: land {100 * b.land_fraction:.0f} "
                  f"%, mu {b.mu:.3f}")
            if b.land_fraction >= max(d.land_fraction for d in designs) * (1 - 1e-9):
                print("  (the largest land fraction tried: larger --lands may keep mu >= "
                      "mu_min too)")


def _print_losses(losses, mu_min: float, units: str = "si") -> None:
    size = unit_label("position", units)
    fast = "m/min" if units != "us" else "ft/min"
    other = "metric" if units != "us" else "us"

    def g(value):
        return convert(value, "position", units)

    print(f"traction-loss speed (mu falls to {mu_min:g}):")
    print(f"  pitch {size:2}  groove {size:2}  depth {size:2}  land %  loss speed m/s  "
          f"{fast:6}  solves")
    for x in losses:
        shape = ("  smooth roller            " if x.pitch == 0.0 else
                 f"  {g(x.pitch):8.3g}  {g(x.width):9.3g}  {g(x.depth):8.3g}")
        if not x.converged:
            found = f"  no answer: {_short(x.message)}"
        elif x.refused_partway():
            found = f"  {_refused_text(x, mu_min, units)}"
        elif x.speed is None:
            found = f"  {x.message}"
        else:
            found = (f"{x.speed:16.3g}  {convert(x.speed, 'speed', other):6.0f}   "
                     f"{x.evaluations:6d}")
        print(f"{shape}  {100 * x.land_fraction:6.1f}{found}")


def _refused_text(x, mu_min: float, units: str) -> str:
    """A loss-speed row whose scan fe2d refused partway, before a crossing: where it
    answered, which side of mu_min mu stayed on there, and why the scan ended (as
    ``webfem traction-loss`` says it with exit 4 and ``scan_limit``; cut to 100 characters,
    the CSV's and --json's ``scan_limit`` hold all of it)."""
    side = "above" if x.mu_peak is not None and x.mu_peak >= mu_min else "below"
    return (f"refused partway: no loss speed up to {display(x.scanned_to, 'speed', units)}"
            f", the last speed answered (mu stays {side} {mu_min:g} there); the scan ended "
            f"{_short(x.scan_limit, 100)}")


def run(args) -> int:
    case = case_from(args)
    args.model = "fe2d"
    options = model_options(args)
    lists = {name: _floats(name, getattr(args, name)) for name in _LIST_KEYS}
    check_arguments(args.mu_min, speeds=args.speed or (), pitches=lists["pitches"]
                    + lists["loss_pitches"], land_fractions=lists["lands"] + lists["loss_lands"],
                    depths=lists["depths"])
    folder = output_folder(args.out, "--out")
    stem = f"{Path(args.case).stem}_grooves"
    designs = groove_map(case, args.mu_min, speeds=args.speed, pitches=lists["pitches"],
                         land_fractions=lists["lands"], depths=lists["depths"],
                         options=options, progress=Progress(args.quiet, "designs"),
                         store=folder / f"{stem}.csv", workers=_workers(args.workers),
                         notice=_notice)
    with saved_if_interrupted(designs, folder / f"{stem}.csv", "designs"):
        return _after_map(args, case, options, lists, folder, stem, designs)


def _notice(text: str) -> None:
    print(f"webfem: {text}", file=sys.stderr)


def _after_map(args, case, options, lists, folder, stem, designs) -> int:
    """The map's table, chart and printout, then with --loss-speed the loss-speed table."""
    best = best_designs(designs)
    print(f"wrote {folder / f'{stem}.csv'}", file=sys.stderr)
    from ..io.groove_charts import groove_chart, loss_speed_chart
    from ..io.tables import write_in_units

    # the copies hold the SI tables' columns, converted
    copy = write_in_units([d.csv_row() for d in designs], folder / f"{stem}.csv", args.units,
                          MAP_COLUMNS + ("feasible", "message"))
    if copy is not None:
        print(f"wrote {copy}", file=sys.stderr)
    chart = groove_chart(designs, args.mu_min, folder / f"{stem}.png", best, units=args.units)
    print(f"wrote {chart}", file=sys.stderr)
    if not args.json:   # the map now: the loss speeds take minutes more
        _print_map(designs, best, args.mu_min, args.units)
        sys.stdout.flush()
    losses = None
    if args.loss_speed:
        losses = loss_speed_map(case, args.mu_min, pitches=lists["loss_pitches"],
                                land_fractions=lists["loss_lands"], depth=lists["depths"][0],
                                options=options, progress=Progress(args.quiet, "geometries"),
                                store=folder / f"{stem}_loss.csv",
                                workers=_workers(args.workers), notice=_notice)
        with saved_if_interrupted(losses, folder / f"{stem}_loss.csv", "geometries"):
            print(f"wrote {folder / f'{stem}_loss.csv'}", file=sys.stderr)
            copy = write_in_units([x.csv_row() for x in losses],
                                  folder / f"{stem}_loss.csv", args.units,
                                  LOSS_COLUMNS + ("speed",))
            if copy is not None:
                print(f"wrote {copy}", file=sys.stderr)
            chart = loss_speed_chart(losses, args.mu_min, folder / f"{stem}_loss.png",
                                     LOSS_SPEED_RANGE,
                                     title=f"{Path(args.case).stem}: speed at which mu falls "
                                           f"to {args.mu_min:g} (fe2d)", units=args.units)
            print(f"wrote {chart}", file=sys.stderr)
    code = 0 if all(best.values()) else 4
    if args.json:
        out = {"mu_min": args.mu_min, "designs": [d.to_dict() for d in designs],
               "best": {f"{s:g}": (b.to_dict() if b else None) for s, b in best.items()}}
        if losses is not None:
            out["loss_speeds"] = [x.to_dict() for x in losses]
        print_json(out)
        return code
    if losses is not None:
        _print_losses(losses, args.mu_min, args.units)
    return code
