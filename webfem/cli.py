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
    stem = f"{Path(args.case).stem}_{args.model}"
    try:
        result = solve(case, model=args.model, **_options(args.opt))
    except ConvergenceError as err:
        print(f"webfem: error: {err}", file=sys.stderr)
        if err.result is not None:
            if args.json:
                print(json.dumps(err.result.to_json(), indent=2))
            if args.vtu:   # the last iterate, for inspection, marked in its file names
                for path in err.result.save_vtu(args.vtu, stem):
                    print(f"wrote {path} (NOT converged)", file=sys.stderr)
        return 3
    if args.json:
        print(json.dumps(result.to_json(), indent=2))
    else:
        print(result.describe())
    written = []
    if args.vtu:
        written += result.save_vtu(args.vtu, stem)
    if args.plot:
        from .io.pictures import film_pictures
        written += film_pictures(result, args.vtu or ".", stem)
    for path in written:
        print(f"wrote {path}", file=sys.stderr)
    return 0


def _cmd_sweep(args) -> int:
    from .io.charts import sweep_chart
    from .io.tables import sweep_rows
    from .sweeps import run

    spec = load_sweep(args.case, _overrides(args.set))
    if args.num:
        import dataclasses

        import numpy as np
        if args.num < 1:
            raise CaseError(f"--num {args.num} is out of range: must be >= 1")
        spacing = np.geomspace if min(spec.values) > 0 and args.log else np.linspace
        spec = dataclasses.replace(spec, values=tuple(
            spacing(min(spec.values), max(spec.values), args.num).tolist()))
    out = Path(args.out)
    stem = Path(args.case).stem
    where = ("Dask " + args.dask) if args.dask else (
        f"{args.workers} processes" if args.workers > 1 else "serial, with continuation")
    print(f"webfem sweep: {args.case}, model {args.model}, {spec.parameter} over "
          f"{len(spec.values)} values x {len(spec.series)} series ({where})", file=sys.stderr)
    csv_path = out / f"{stem}_{args.model}.csv"
    rows = run(spec, args.model, csv_path, options=_options(args.opt), workers=args.workers,
               dask=args.dask, vtu_dir=args.vtu, vtu_stem=f"{stem}_{args.model}",
               progress=None if args.quiet else _Progress())
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


def _cmd_mesh(args) -> int:
    """Export the graded meshes a model starts from (before refinement where the film is thin)."""
    import meshio
    import numpy as np

    from .fem.mesh import graded_nodes
    from .fem.transfer import width_nodes

    case = load_case(args.case, _overrides(args.set))
    opts = _options(args.opt)
    X = graded_nodes(case.beta, float(opts.get("entry", 40.0)), level=int(opts.get("level", 0)))
    Z = width_nodes(case.lam, int(opts.get("level", 0)), half=bool(opts.get("symmetry", True)),
                    fine=float(opts.get("width_fine", 0.25)))
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    stem = Path(args.case).stem
    x = X * case.x_scale
    line = meshio.Mesh(np.column_stack([x, 0 * x, 0 * x]),
                       [("line", np.column_stack([np.arange(x.size - 1), np.arange(1, x.size)]))])
    xx, zz = np.meshgrid(X, Z, indexing="ij")
    idx = np.arange(X.size * Z.size).reshape(X.size, Z.size)
    quads = np.column_stack([idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(),
                             idx[:-1, 1:].ravel()])
    pts = np.column_stack([xx.ravel(), zz.ravel(), 0 * xx.ravel()]) * case.x_scale
    film = meshio.Mesh(pts, [("quad", quads)])
    for mesh, name in ((line, f"{stem}_web.vtu"), (film, f"{stem}_film.vtu")):
        meshio.write(out / name, mesh)
        print(f"wrote {out / name}")
    return 0


def _cmd_traction_loss(args) -> int:
    from .traction import traction_loss_speed

    case = load_case(args.case, _overrides(args.set))
    out = traction_loss_speed(case, args.mu_min, model=args.model,
                              speed_range=(args.min_speed, args.max_speed), **_options(args.opt))
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        print(f"webfem traction-loss ({out['model']}): {out['message']}; peak mu "
              f"{out['mu_peak']:.4f} at {out['speed_peak']:.3g} m/s; {out['evaluations']} solves")
    if args.chart:
        import numpy as np

        from .io.charts import traction_loss_chart
        from .traction import traction_loss_table

        models = ["closed-form"] + ([args.model] if args.model != "closed-form" else [])
        rows = traction_loss_table(case, args.mu_min, models, n=args.points,
                                   progress=None if args.quiet else _Progress(),
                                   **_options(args.opt))
        curves = {}
        for model in models:
            speeds = np.geomspace(args.min_speed, args.max_speed, 40)
            res, prev = [], None
            for u in speeds:
                kw = {"initial": prev} if prev is not None and model != "closed-form" else {}
                prev = solve(case.updated({"roller.speed": float(u)}), model=model, **kw,
                             **(_options(args.opt) if model != "closed-form" else {}))
                res.append(prev["mu"])
            curves[model] = (speeds, res)
        path = traction_loss_chart(rows, curves, args.mu_min,
                                   Path(args.chart) / f"{Path(args.case).stem}_traction_loss.png")
        print(f"wrote {path}", file=sys.stderr)
    return 0 if out["speed"] is not None else 4


def _cmd_calibrate(args) -> int:
    from .calibrate import calibrate, read_measurements

    case = load_case(args.case, _overrides(args.set))
    rows = read_measurements(args.data)
    fit = calibrate(rows, case, model=args.model, fit_sigma=args.fit_sigma,
                    **_options(args.opt))
    if args.json:
        keep = ("model", "measured", "estimates", "stderr", "ci95", "rms", "dof", "converged")
        out = {k: fit[k] for k in keep}
        out["residuals"] = fit["residuals"].tolist()
        print(json.dumps(out, indent=2))
    else:
        print(f"webfem calibrate ({fit['model']}, {len(rows)} rows of {fit['measured']}):")
        for k, v in fit["estimates"].items():
            print(f"  {k:15s} = {v:.6g} +- {fit['ci95'][k]:.3g} (95 %), std. error "
                  f"{fit['stderr'][k]:.3g}")
        print(f"  residual rms {fit['rms']:.4g}, {fit['dof']} degrees of freedom")
    if args.out:
        from .io.charts import calibration_chart
        path = calibration_chart(fit, Path(args.out) / f"{Path(args.data).stem}_calibration.png")
        print(f"wrote {path}", file=sys.stderr)
    return 0 if fit["converged"] else 3


def _cmd_study(args) -> int:
    import warnings

    from .errors import ValidityWarning
    from .studies import convergence, pareto, stability

    warnings.simplefilter("ignore", ValidityWarning)   # studies cross validity ranges
    case = load_case(args.case, _overrides(args.set))
    module = {"convergence": convergence, "pareto": pareto, "stability": stability}[args.kind]
    out = module.run(case, args.out, quick=args.quick,
                     progress=None if args.quiet else
                     (lambda msg: print(f"  {msg}", file=sys.stderr, flush=True)))
    print(out["report"])
    print(f"wrote {args.kind} CSV, PNG and markdown into {args.out}", file=sys.stderr)
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
    p.add_argument("--vtu", metavar="DIR",
                   help="write VTU files of the web (and film, fe2d) into DIR for ParaView")
    p.add_argument("--plot", action="store_true",
                   help="render PNG pictures of p and h of the film (fe2d) with pyvista, into "
                        "the --vtu DIR (or the current folder)")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (keys: model, h_center, h_inlet, h_outlet, h_min, "
                        "mu, delta_T, regime, lambda, beta, eq21_valid, converged, iterations, "
                        "n_dofs, solve_time_s, ...)")
    p.set_defaults(func=_cmd_solve)

    p = sub.add_parser("sweep", help="sweep a parameter ([sweep] table): CSV and chart; "
                                     "each point is saved as it finishes and a re-run of the "
                                     "same sweep resumes where it stopped")
    common(p)
    p.add_argument("--out", required=True, help="output folder for CASE_MODEL.csv and .png")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    p.add_argument("--vtu", metavar="DIR",
                   help="also write VTU files per point and a .pvd collection per series")
    p.add_argument("--num", type=int, help="override the number of swept values (same range)")
    p.add_argument("--log", action="store_true", help="with --num: logarithmic spacing")
    p.add_argument("--workers", type=int, default=1,
                   help="local worker processes (default 1: serial with continuation from "
                        "point to point; > 1: independent points in parallel)")
    p.add_argument("--dask", metavar="local|tcp://HOST:PORT",
                   help="run the points on Dask: 'local' starts a LocalCluster (with --workers "
                        "workers), an address joins an existing scheduler")
    p.set_defaults(func=_cmd_sweep)

    p = sub.add_parser("mesh", help="write the graded web and film meshes of a case (VTU, "
                                    "metres) as the FE models start from them")
    common(p)
    p.add_argument("--out", required=True, help="output folder")
    p.set_defaults(func=_cmd_mesh)

    p = sub.add_parser("traction-loss", help="roller speed at which mu falls below a threshold")
    common(p)
    p.add_argument("--mu-min", type=float, required=True, help="friction threshold, e.g. 0.1")
    p.add_argument("--min-speed", type=float, default=0.5, help="scan from (m/s, default 0.5)")
    p.add_argument("--max-speed", type=float, default=100.0, help="scan to (m/s, default 100)")
    p.add_argument("--json", action="store_true",
                   help="one JSON object: speed (m/s, null if none), model, mu_min, mu_peak, "
                        "speed_peak, bracket, evaluations, message")
    p.add_argument("--chart", metavar="DIR",
                   help="also chart the traction-loss speed against T, B, L and R (closed "
                        "form and --model) into DIR")
    p.add_argument("--points", type=int, default=5, help="points per parameter in the chart")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    p.set_defaults(func=_cmd_traction_loss)

    p = sub.add_parser("calibrate", help="fit mu_cc and C (and sigma) to measured traction")
    p.add_argument("data", help="CSV: roller_speed, tension, wrap_deg (or any case key) and "
                                "delta_T [N/m] or mu per row")
    p.add_argument("--case", required=True, help="case TOML for everything the rows leave out")
    p.add_argument("--set", action="append", metavar="SECTION.KEY=VALUE")
    p.add_argument("--model", default="closed-form", choices=sorted(MODELS))
    p.add_argument("--opt", action="append", metavar="KEY=VALUE")
    p.add_argument("--fit-sigma", action="store_true", help="also fit the web roughness sigma")
    p.add_argument("--json", action="store_true", help="estimates, errors and residuals as JSON")
    p.add_argument("--out", metavar="DIR", help="write the measured-against-predicted chart")
    p.set_defaults(func=_cmd_calibrate)

    p = sub.add_parser("study", help="convergence, speed-against-accuracy (pareto) or "
                                     "stability study of a case: CSV, PNG and markdown")
    p.add_argument("kind", choices=("convergence", "pareto", "stability"))
    p.add_argument("case", help="case TOML file")
    p.add_argument("--set", action="append", metavar="SECTION.KEY=VALUE")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--quick", action="store_true", help="the reduced study the tests run")
    p.add_argument("--quiet", action="store_true", help="no progress lines")
    p.set_defaults(func=_cmd_study)

    p = sub.add_parser("keys", help="list the case TOML keys with units and defaults")
    p.set_defaults(func=_cmd_keys)
    return parser


def main(argv=None) -> int:
    import warnings

    from .errors import ValidityWarning

    args = build_parser().parse_args(argv)
    # the summary (or the JSON "warnings" key) already carries each validity warning
    warnings.simplefilter("ignore", ValidityWarning)
    try:
        return args.func(args)
    except CaseError as err:
        print(f"webfem: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
