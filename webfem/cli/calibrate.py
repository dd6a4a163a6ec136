"""``webfem calibrate``: fit mu_cc and C (and sigma) to measured traction."""

from __future__ import annotations

import sys
from pathlib import Path

from ..calibrate import calibrate, read_measurements
from .common import (HELP_FORMATTER, add_case_arguments, case_from, model_options,
                     options_epilog, output_folder, print_json)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("calibrate",
                              help="fit mu_cc and C (and sigma) to measured traction",
                              formatter_class=HELP_FORMATTER, epilog=options_epilog())
    p.add_argument("data", help="CSV (UTF-8): roller_speed, tension, wrap_deg (or any case "
                                "key) and delta_T [N/m] or mu per row")
    add_case_arguments(p, positional=False, default_model="closed-form")
    p.add_argument("--fit-sigma", action="store_true", help="also fit the web roughness sigma")
    p.add_argument("--json", action="store_true",
                   help="estimates, errors, residuals and notes as JSON")
    p.add_argument("--out", metavar="DIR", help="write the measured-against-predicted chart")


def _pm(fit, name: str) -> str:
    value, half, se = fit.estimates[name], fit.ci95[name], fit.stderr[name]
    if half is None:
        return f"{value:.6g} (not identified by these data; see the note)"
    return f"{value:.6g} +- {half:.3g} (95 %), std. error {se:.3g}"


def run(args) -> int:
    case = case_from(args)
    options = model_options(args)
    rows = read_measurements(args.data)
    chart_dir = output_folder(args.out, "--out") if args.out else None
    fit = calibrate(rows, case, model=args.model, fit_sigma=args.fit_sigma, options=options)
    if args.json:
        print_json(fit.to_dict())
    else:
        print(f"webfem calibrate ({fit.model}, {len(rows)} rows of {fit.measured}):")
        for name in fit.estimates:
            print(f"  {name:15s} = {_pm(fit, name)}")
        print(f"  residual rms {fit.rms:.4g}, {fit.dof} degrees of freedom")
        for note in fit.notes:
            print(f"  note: {note}")
    if chart_dir:
        from ..io.charts import calibration_chart
        path = calibration_chart(fit, chart_dir / f"{Path(args.data).stem}_calibration.png")
        print(f"wrote {path}", file=sys.stderr)
    return 0 if fit.converged else 3
