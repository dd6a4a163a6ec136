"""``webfem study KIND CASE --out DIR``: run one study of :mod:`webfem.studies` and write its
CSV, chart and markdown through :mod:`webfem.io.studies`.

Kinds: ``convergence``, ``pareto``, ``stability``, ``lambda-table``, ``variants`` and
``report`` (the first three and docs/studies.md). The markdown goes to stdout, progress
lines and the files written to stderr.
"""

from __future__ import annotations

import sys

from ..models.registry import MODELS
from ..studies import convergence, lambda_table, pareto, report, stability, variants
from .common import add_case_arguments, case_from, output_folder, positive_int

#: kind -> its help line
KINDS = {
    "convergence": "mesh refinement of the FE models (observed orders, Richardson values) and "
                   "Eq. 21 against the 2-D model over lambda and beta",
    "pareto": "time per solve against error for every method, and the Pareto front",
    "stability": "where each coupling scheme converges, stalls or diverges",
    "lambda-table": "Eq. 21 against the 2-D central gap over lambda = 7 ... 100",
    "variants": "mu against roller speed for the friction model's options, closed form and "
                "an FE model",
    "report": "convergence, pareto and stability, then studies.md from their numbers "
              "(15-25 minutes on 2 cores; --quick about 2)",
}


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("study", help="run a study of a case (convergence, pareto, "
                                            "stability, lambda-table, variants, report): CSV, "
                                            "chart and markdown",
                              description="Run one study of a case and write its CSV, "
                                          "chart (PNG) and markdown into --out; the markdown "
                                          "is also printed. --quick runs the reduced study.")
    kinds = p.add_subparsers(dest="kind", required=True, metavar="KIND")
    for kind, text in KINDS.items():
        k = kinds.add_parser(kind, help=text, description=text)
        add_case_arguments(k, model=False)
        k.add_argument("--out", required=True, help="output folder")
        k.add_argument("--quick", action="store_true", help="the reduced study the tests run")
        k.add_argument("--quiet", action="store_true", help="no progress lines")
        if kind == "pareto":
            k.add_argument("--repeats", type=positive_int, default=3,
                           help="solves per method; the time is their median (default 3)")
        elif kind == "lambda-table":
            k.add_argument("--speed", type=float, default=40.0,
                           help="roller speed of every point, m/s (default 40: the web flies)")
        elif kind == "variants":
            fe = [m for m in MODELS if m != "closed-form"]
            k.add_argument("--model", default="fe2d", choices=fe,
                           help="the model beside the closed form (default fe2d)")
            k.add_argument("--num", type=positive_int,
                           help="number of roller speeds from 0.5 to 40 m/s (default 24, "
                                "--quick 6)")
            k.add_argument("--workers", type=positive_int, default=1,
                           help="solve the eight curves in this many local processes "
                                "(default 1; the same values, to rounding)")


def _progress(message: str) -> None:
    print(f"  {message}", file=sys.stderr, flush=True)


def _compute(args, case, progress):
    kind, quick = args.kind, args.quick
    if kind == "convergence":
        return convergence.run(case, quick, progress)
    if kind == "pareto":
        return pareto.run(case, quick, args.repeats, progress)
    if kind == "stability":
        return stability.run(case, quick, progress)
    if kind == "lambda-table":
        return lambda_table.run(case, args.speed, quick=quick, progress=progress)
    if kind == "variants":
        return variants.run(case, args.model, args.num, quick, progress, args.workers)
    return report.run(case, quick, progress)


def run(args) -> int:
    from ..io.studies import markdown, write

    case = case_from(args)
    if case.grooved:
        # every study sets the FE models beside the closed form on the smooth-roller film
        from ..errors import InputError
        from ..physics.validity import groove_keys_text
        raise InputError(
            f"webfem study {args.kind} studies smooth rollers (it compares the closed form, "
            f"fe1d and fe2d); {args.case} is grooved ({groove_keys_text(case)}): --set "
            "roller.groove_width=0 for its smooth roller, or `webfem grooves` / `webfem "
            "sweep` for the grooved one")
    out = output_folder(args.out, "--out")
    if not args.quiet:
        print(f"webfem study {args.kind}: {args.case}{' (quick)' if args.quick else ''}",
              file=sys.stderr, flush=True)
    study = _compute(args, case, None if args.quiet else _progress)
    paths = write(study, out, source=args.case)
    print(markdown(study, source=args.case), end="")
    for path in paths:
        print(f"wrote {path}", file=sys.stderr)
    failed = getattr(study, "failed", 0)
    if failed:
        print(f"webfem: {failed} points did not converge (NaN in the table)", file=sys.stderr)
        return 3
    return 0
