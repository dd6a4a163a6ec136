"""``webfem fit build``: the fitted model's training campaign (fe2d over a Sobol design in the
dimensionless groups, resumable) and the fit, written as the coefficients file."""

from __future__ import annotations

import sys
import textwrap
import time
from pathlib import Path

from ..errors import InputError
from .common import (HELP_FORMATTER, Progress, add_dask_argument, add_quiet_argument,
                     output_folder, positive_int, print_json)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "fit", help="build the fitted model: fe2d over a design in the dimensionless "
                    "groups (resumable), then the fit and its hold-out errors",
        formatter_class=HELP_FORMATTER,
        description=textwrap.fill(
            "fit build: solve the first --points points of the scrambled Sobol design over "
            "the fitted model's domain with fe2d into --store/campaign.csv (each row saved as "
            "it finishes: a run interrupted continues where it stopped when run again, and "
            "a run with more --points extends the same table), fit "
            "the training points (every fifth point is held out and states the errors) and "
            "write the coefficients to --out. --fit-only fits what the store holds. The points "
            "are solved in --workers local processes or on a Dask cluster (--dask), each "
            "with its own --timeout; the rows are a serial run's.", 88))
    p.add_argument("action", choices=("build",), help="what to do (build)")
    p.add_argument("--points", type=int, default=128,
                   help="design points to solve (default 128: every fifth is held out, and "
                        "the fit states its errors from at least 20 converged hold-out "
                        "points; the shipped fit: README)")
    p.add_argument("--store", default="fit_campaign",
                   help="folder of the resumable campaign table (default fit_campaign)")
    p.add_argument("--out", default=None,
                   help="coefficients file to write (default STORE/fitted_coefficients.npz)")
    p.add_argument("--timeout", type=float, default=12.0,
                   help="seconds one fe2d solve may take before it is recorded as failed")
    p.add_argument("--fit-only", action="store_true",
                   help="fit the rows the store holds, solve nothing")
    p.add_argument("--retry-failed", action="store_true",
                   help="solve the points recorded as failed again (default: kept as they "
                        "are; e.g. with a longer --timeout, or after a solver change that keeps the "
                        "campaign's signature)")
    p.add_argument("--workers", type=positive_int, default=1,
                   help="local worker processes (default 1: serial; > 1: the design points "
                        "in parallel, each a cold solve as in a serial run)")
    add_dask_argument(p)
    p.add_argument("--recheck", action="store_true",
                   help="solve the hold-out points among the first --points again with the "
                        "current physics into STORE/holdout.csv (resumable); whenever that "
                        "table exists its rows state the errors (for a fit trained on an "
                        "earlier physics: the shipped one); with --fit-only it solves "
                        "these alone")
    p.add_argument("--extra-holdout", type=positive_int, default=None, metavar="N",
                   help="solve the first N points of a design of another seed (every one "
                        "held out) into STORE/extra_holdout.csv (resumable); whenever that "
                        "table exists its rows join the hold-out rows in stating the errors "
                        "(the shipped fit: docs/fit.md); with --fit-only it solves these "
                        "alone")
    p.add_argument("--json", action="store_true", help="print the report as JSON")
    add_quiet_argument(p)


def run(args) -> int:
    from ..studies import fit_build, fit_campaign
    if not 0.0 < args.timeout <= 3600.0:
        raise InputError(f"--timeout = {args.timeout:g} is out of range: must be > 0 and "
                         "<= 3600 s")
    folder = output_folder(args.store, "--store")
    csv = folder / "campaign.csv"
    out = Path(args.out) if args.out else folder / "fitted_coefficients.npz"
    t0 = time.perf_counter()
    if args.fit_only and args.retry_failed:
        raise InputError("--fit-only solves nothing: --retry-failed is for the campaign")
    if args.fit_only and not (args.recheck or args.extra_holdout) and \
            (args.workers > 1 or args.dask):
        raise InputError("--fit-only solves nothing: --workers and --dask are for the "
                         "campaign (or --recheck, --extra-holdout)")
    if not args.fit_only:
        fit_campaign.run(csv, args.points, timeout=args.timeout,
                         progress=Progress(args.quiet, "design points"),
                         workers=args.workers, dask=args.dask,
                         retry_failed=args.retry_failed)
    elif not csv.is_file():
        raise InputError(f"--fit-only: no campaign table {csv}: run without --fit-only first")
    recheck = folder / "holdout.csv"
    if args.recheck:
        fit_campaign.recheck(recheck, args.points, timeout=args.timeout,
                             progress=Progress(args.quiet, "hold-out points"),
                             workers=args.workers, dask=args.dask)
    extra = folder / "extra_holdout.csv"
    if args.extra_holdout:
        fit_campaign.extra_holdout(extra, args.extra_holdout, timeout=args.timeout,
                                   progress=Progress(args.quiet, "extra hold-out points"),
                                   workers=args.workers, dask=args.dask)
    solved = time.perf_counter() - t0
    report = fit_build.build(csv, out, holdout_csv=recheck if recheck.is_file() else None,
                             extra_csv=extra if extra.is_file() else None)
    report.update(campaign_seconds=solved, total_seconds=time.perf_counter() - t0,
                  coefficients=str(out))
    from ..models.fitted import MIN_HOLDOUT
    report["errors_stated"] = report["holdout"] >= MIN_HOLDOUT
    if not report["errors_stated"]:
        print(f"webfem fit build: warning: {report['holdout']} hold-out points, fewer than "
              f"the {MIN_HOLDOUT} the fitted model states its errors from: its answers with "
              f"these coefficients state none (NaN) and auto does not take them; the "
              f"percentiles below are {report['holdout']} errors' luck", file=sys.stderr)
    if args.json:
        print_json(report, units=False)
        return 0
    print(f"{report['train']} training and {report['holdout']} hold-out fe2d solutions "
          f"({report['failed']} failed) in {solved:.0f} s; coefficients: {out}"
          + ("; the hold-out points solved again with the current physics (holdout.csv) "
             "state the errors" if report["holdout_rechecked"] else "")
          + (f"; {report['holdout_extra']} of them from another design (extra_holdout.csv)"
             if report["holdout_extra"] else ""))
    print("hold-out error percentiles 50/90/95/max:")
    full = report["full_fit_percentiles_50_90_95_max"]
    print(f"  (centres kept: {', '.join(str(m) for m in report['centres'])} of "
          f"{report['train']}; the fit with every one, in brackets)")
    for q, v in report["percentiles_50_90_95_max"].items():
        print(f"  {q:<14} " + " ".join(f"{x:.3g}" for x in v)
              + "  (" + " ".join(f"{x:.3g}" for x in full[q]) + ")")
    return 0
