"""Command line: ``webfem solve``, ``webfem sweep``, ``webfem keys``.

Run ``webfem --help`` or ``webfem COMMAND --help``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from .api import MODELS, solve, sweep
from .errors import ConvergenceError
from .case import CaseError, load_case, load_sweep, parse_assignment, Case

__all__ = ["main"]


def _overrides(pairs) -> dict:
    return dict(parse_assignment(p) for p in pairs or [])


def _options(pairs) -> dict:
    """``--opt level=2 --opt method=picard`` -> model options (values in TOML syntax)."""
    import tomllib

    out = {}
    for text in pairs or []:
        if "=" not in text:
            raise CaseError(f"--opt {text!r}: expected key=value, e.g. --opt level=2")
        key, raw = (t.strip() for t in text.split("=", 1))
        try:
            out[key] = tomllib.loads(f"v = {raw}")["v"]
        except tomllib.TOMLDecodeError:
            out[key] = raw
    return out


class _Progress:
    """Progress on stderr with the time left: a live line on a terminal, else every 10 %."""

    def __init__(self):
        self.t0 = time.perf_counter()
        self.last = -1

    def __call__(self, done: int, total: int) -> None:
        tty = sys.stderr.isatty()
        decile = 10 * done // total
        if not tty and decile == self.last and done != total:
            return
        self.last = decile
        elapsed = time.perf_counter() - self.t0
        left = elapsed / done * (total - done)
        end = "\n" if (done == total or not tty) else "\r"
        print(f"  {done}/{total} points, {elapsed:.1f} s elapsed, about {left:.1f} s left",
              end=end, file=sys.stderr, flush=True)


def _cmd_solve(args) -> int:
    case = load_case(args.case, _overrides(args.set))
    try:
        result = solve(case, model=args.model, **_options(args.opt))
    except ConvergenceError as err:
        print(f"webfem: error: {err}", file=sys.stderr)
        if args.json and err.result is not None:
            print(json.dumps(err.result.to_json(), indent=2))
        return 3
    if args.json:
        print(json.dumps(result.to_json(), indent=2))
    else:
        print(result.describe())
    return 0 if result["converged"] else 3


def _cmd_sweep(args) -> int:
    from .io.charts import sweep_chart
    from .io.tables import sweep_rows, write_csv

    spec = load_sweep(args.case, _overrides(args.set))
    out = Path(args.out)
    print(f"webfem sweep: {args.case}, model {args.model}, {spec.parameter} over "
          f"{len(spec.values)} values x {len(spec.series)} series", file=sys.stderr)
    points = list(sweep(spec, model=args.model, progress=None if args.quiet else _Progress(),
                        **_options(args.opt)))
    rows = sweep_rows(points, spec.parameter)
    stem = Path(args.case).stem
    csv_path = write_csv(rows, out / f"{stem}_{args.model}.csv")
    reference = None
    if args.model != "closed-form":  # the paper's model beside the field solution
        reference = sweep_rows(sweep(spec, model="closed-form"), spec.parameter)
    png_path = sweep_chart(rows, out / f"{stem}_{args.model}.png",
                           title=f"{stem}: {args.model}"
                           + (" (thin: closed form, Eq. 21)" if reference else ""),
                           reference=reference)
    print(f"wrote {csv_path}\nwrote {png_path}")
    failed = [r for r in rows if not r["converged"]]
    if failed:
        print(f"webfem: {len(failed)} of {len(rows)} points did not converge (see the CSV)",
              file=sys.stderr)
        return 3
    return 0


def _cmd_keys(args) -> int:
    import dataclasses
    from .case import _SECTIONS

    default = Case()
    for name, cls in _SECTIONS.items():
        print(f"[{name}]")
        for f in dataclasses.fields(cls):
            meta = f.metadata
            unit = meta.get("unit", "")
            extra = (" one of " + ", ".join(meta["choices"])) if "choices" in meta else \
                f" [{unit}]"
            print(f"  {f.name:<18} = {getattr(getattr(default, name), f.name)!r:<12}"
                  f"{extra}  {meta.get('doc', '')}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="webfem",
        description="Air film and traction between a moving web and a roller "
                    "(Hashimoto's model: closed form and finite elements).")
    sub = parser.add_subparsers(dest="command", required=True)

    def common(p):
        p.add_argument("case", help="case TOML file (see cases/ and `webfem keys`)")
        p.add_argument("--set", action="append", metavar="SECTION.KEY=VALUE",
                       help="override a case value, e.g. --set roller.speed=30 (repeatable)")
        p.add_argument("--model", default="closed-form", choices=sorted(MODELS),
                       help="model to use (default: closed-form, the paper's Eq. 21)")
        p.add_argument("--opt", action="append", metavar="KEY=VALUE",
                       help="model option, e.g. --opt method=picard --opt level=2 (fe1d: "
                            "entry, level, order, compressible, contact, method, tol, max_iter, "
                            "omega, aitken, adapt; see webfem.models.fe1d.solve)")

    p = sub.add_parser("solve", help="solve one operating point and print a summary")
    common(p)
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (keys: model, h_center, h_inlet, h_outlet, h_min, "
                        "mu, delta_T, regime, lambda, beta, eq21_valid, converged, iterations, "
                        "n_dofs, solve_time_s, ...)")
    p.set_defaults(func=_cmd_solve)

    p = sub.add_parser("sweep", help="sweep a parameter ([sweep] table): CSV and chart")
    common(p)
    p.add_argument("--out", required=True, help="output folder for CASE_MODEL.csv and .png")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    p.set_defaults(func=_cmd_sweep)

    p = sub.add_parser("keys", help="list the case TOML keys with units and defaults")
    p.set_defaults(func=_cmd_keys)
    return parser


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except CaseError as err:
        print(f"webfem: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
