"""``webfem calibrate``: fit mu_cc and C (and sigma) to measured traction."""

from __future__ import annotations

import math
import sys
from pathlib import Path

from ..units import ROLES, convert, display, unit_label
from .common import (HELP_FORMATTER, add_case_arguments, add_units_argument, case_from,
                     model_options, options_epilog, output_folder, print_json)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("calibrate",
                              help="fit mu_cc and C (and sigma) to measured traction",
                              formatter_class=HELP_FORMATTER, epilog=options_epilog())
    p.add_argument("data", help="CSV (UTF-8): roller_speed, tension, wrap_deg (or any case "
                                "key) and delta_T [N/m] or mu per row")
    add_case_arguments(p, positional=False)
    p.add_argument("--fit-sigma", action="store_true", help="also fit the web roughness sigma")
    p.add_argument("--json", action="store_true",
                   help="estimates, errors (stderr; ci95: the 95 %% half widths; "
                        "interval95: the 95 %% intervals in log space, positive as the "
                        "constants are), residuals and notes as JSON")
    p.add_argument("--out", metavar="DIR", help="write the measured-against-predicted chart")
    add_units_argument(p)


def rounded(value: float, spread: float | None) -> str:
    """``value`` to the digits its ``spread`` (a standard error) leaves meaningful: two
    significant digits of the spread (0.194082 with 0.49 -> ``0.19``; 0.239491 with
    0.0247 -> ``0.239``); six significant digits without a spread.

    >>> rounded(0.194082, 0.49), rounded(0.239491, 0.0247), rounded(0.3, None)
    ('0.19', '0.239', '0.3')
    """
    if spread is None or not spread > 0.0 or value == 0.0 or not math.isfinite(value):
        return f"{value:.6g}"
    digits = math.floor(math.log10(abs(value))) - math.floor(math.log10(spread)) + 2
    return f"{value:.{min(max(digits, 1), 6)}g}"


def _pm(fit, name: str, units: str = "si") -> str:
    """An estimate rounded to its standard error, with its 95 % interval and standard
    error, in ``units`` when it has a unit (speed_constant, sigma). The interval is the
    linear one (estimate +- half width) where it stays above 0 and the log-space one where
    it would not (then the constant is not determined by the data: a note says so)."""
    role = ROLES.get(name)
    unit = f" {unit_label(role, units)}" if role else ""

    def shown(v):
        return v if role is None or v is None else convert(v, role, units)

    value, half, se = (shown(d[name]) for d in (fit.estimates, fit.ci95, fit.stderr))
    if half is None:
        # the least-squares leaves such a constant wherever it stopped (often its bound,
        # 1e-9 of the start): a number there would read as a measurement
        return "not determined by these data: no value (not identified; see the note)"
    if fit.determined(name):
        return (f"{rounded(value, se)} +- {half:.2g}{unit} (95 %), std. error "
                f"{se:.2g}{unit}")
    low, high = (shown(v) for v in fit.interval95[name])
    return (f"{rounded(value, se)}{unit}, not determined: 95 % interval {low:.2g} to "
            f"{high:.2g}{unit} (log space; std. error {se:.2g}{unit}; see the note)")


def run(args) -> int:
    # imported here: the calibration's statistics (scipy.stats) took 0.3-0.5 s of every
    # command's start, as each builds the parser of all of them
    from ..calibrate import calibrate, read_measurements

    case = case_from(args)
    options = model_options(args)
    rows = read_measurements(args.data)
    chart_dir = output_folder(args.out, "--out") if args.out else None
    fit = calibrate(rows, case, model=args.model, fit_sigma=args.fit_sigma, options=options)
    if args.json:
        print_json(fit.to_dict())
    else:
        used = list(dict.fromkeys(fit.models_used))
        answered = (fit.model if used in ([], [fit.model]) else f"{fit.model}: " + ", ".join(
            f"{m} for {n} row{'s' if n > 1 else ''}" for m in used
            for n in [fit.models_used.count(m)]))
        print(f"webfem calibrate ({answered}, {len(rows)} rows of {fit.measured}):")
        for name in fit.estimates:
            print(f"  {name:15s} = {_pm(fit, name, args.units)}")
        if fit.measured == "delta_T":   # the residuals are tension differences
            rms = display(fit.rms, "tension", args.units)
        else:
            rms = f"{fit.rms:.4g}"
        print(f"  residual rms {rms}, {fit.dof} degrees of freedom")
        for note in fit.notes:
            print(f"  note: {note}")
    if chart_dir:
        from ..io.charts import calibration_chart
        path = calibration_chart(fit, chart_dir / f"{Path(args.data).stem}_calibration.png",
                                 units=args.units)
        print(f"wrote {path}", file=sys.stderr)
    return 0 if fit.converged else 3
