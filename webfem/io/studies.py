"""The studies' files: CSV tables, charts (:mod:`webfem.io.study_charts`) and markdown.

:func:`write` takes any study of :mod:`webfem.studies` (its dataclass, told apart by its
``kind``) and an output folder; :func:`markdown` gives the text of its ``.md`` file. Each
file is written whole (temporary file, the user's umask, rename). Nothing here solves.
"""

from __future__ import annotations

from pathlib import Path

from ..files import write_text
from . import study_charts as charts
from .tables import write_csv

__all__ = ["write", "markdown", "convergence_markdown", "pareto_markdown",
           "stability_markdown", "lambda_table_markdown", "variants_markdown",
           "report_markdown", "STATUS"]

#: Status columns of the stability table (other statuses count under "other").
STATUS = ("converged", "stalled", "diverged")


def _range(rows, key) -> str:
    if not rows:
        return "no points"
    return f"{min(r[key] for r in rows):+.0f} % to {max(r[key] for r in rows):+.0f} %"


def convergence_markdown(study) -> str:
    """The observed orders table and one line on Eq. 21 inside and outside its range."""
    case = study.case
    lines = [f"Case: U_r = {case.roller.speed:g} m/s, lambda = {case.lam:.3g}, "
             f"beta = {case.beta:.3g}. Uniform refinement (adaptivity off).", "",
             "| model | element | quantity | observed order | Richardson value | "
             "error of finest | error of coarsest |", "|---|---|---|---|---|---|---|"]
    for s in study.summary:
        el = ("P" if s["model"] == "fe1d" else "Q") + str(s["order"])
        lines.append(f"| {s['model']} | {el} | {s['quantity']} | {s['observed_order']:.2f} | "
                     f"{s['richardson']:.6g} | {s['relative_error_finest']:.1e} | "
                     f"{s['relative_error_coarsest']:.1e} |")
    inside = [g for g in study.eq21 if g["eq21_valid"]]
    outside = [g for g in study.eq21 if not g["eq21_valid"]]
    lines += ["", f"Eq. 21 against the 2-D central gap: inside its range "
              f"{_range(inside, 'gap_error_pct')}, outside {_range(outside, 'gap_error_pct')}; "
              f"its wrap-averaged mu: inside {_range(inside, 'mu_error_pct')}, outside "
              f"{_range(outside, 'mu_error_pct')}."]
    return "\n".join(lines) + "\n"


def pareto_markdown(study) -> str:
    """Time, iterations and errors per method, and which are on the mu front."""
    case = study.case
    lines = [f"Reference: fe2d Q2 level {study.reference_level} ({study.reference_dofs} "
             f"unknowns); case U_r = {case.roller.speed:g} m/s, lambda = {case.lam:.3g}, "
             f"beta = {case.beta:.3g}. Time: median of {study.repeats} solves.", "",
             "| method | time [ms] | iterations | error h_center | error h_min | error mu | "
             "Pareto (mu) |", "|---|---|---|---|---|---|---|"]
    for r in study.rows:
        lines.append(f"| {r['method']} | {r['time_s'] * 1e3:.2f} | {r['iterations']} | "
                     f"{r['error_h_center']:.1e} | {r['error_h_min']:.1e} | "
                     f"{r['error_mu']:.1e} | {'yes' if r['pareto_mu'] else ''} |")
    if any(not r.get("same_case", True) for r in study.rows):
        lines += ["", "fitted (default physics): the fitted model was trained on the default "
                  "physics only and refuses this case's; its row is the same case with the "
                  "default physics, against fe2d Q2 level "
                  f"{study.reference_level} of that case, and is left off the front."]
    return "\n".join(lines) + "\n"


def stability_markdown(study) -> str:
    """Points per status for each (study, method)."""
    rows = study.rows
    lines = ["| study | method | points | converged | stalled | diverged | other |",
             "|---|---|---|---|---|---|---|"]
    for (part, method) in dict.fromkeys((r["study"], r["method"]) for r in rows):
        sel = [r for r in rows if r["study"] == part and r["method"] == method]
        n = {s: sum(r["status"] == s for r in sel) for s in STATUS}
        other = len(sel) - sum(n.values())
        lines.append(f"| {part} | {method} | {len(sel)} | {n['converged']} | {n['stalled']} | "
                     f"{n['diverged']} | {other} |")
    return "\n".join(lines) + "\n"


def lambda_table_markdown(study) -> str:
    """Eq. 21 against the 2-D central gap per web and lambda."""
    rows = study.rows
    lines = [f"Base case at U_r = {study.speed:g} m/s (beta = {rows[0]['beta']:.1f}), web width "
             "set to give lambda; 2-D central gap at mesh level 1 (its difference from level 0 "
             "in the mesh column), Eq. 21's central gap, and Eq. 21's error against the 2-D "
             "solution.", "",
             "| web | lambda | L [mm] | fe2d h_center [um] | mesh [%] | Eq. 21 [um] | "
             "Eq. 21 error [%] | fe1d (infinite width) [um] |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        web = f"newsprint k = {r['permeability']:g}" if r["permeability"] else "impermeable"
        lines.append(f"| {web} | {r['lambda']:.0f} | {r['width_m'] * 1e3:.1f} | "
                     f"{r['h_center_fe2d_um']:.3f} | {r['fe2d_mesh_error_pct']:.1e} | "
                     f"{r['h_center_eq21_um']:.3f} | {r['eq21_error_pct']:+.1f} | "
                     f"{r['h_center_fe1d_um']:.3f} |")
    return "\n".join(lines) + "\n"


def variants_markdown(study) -> str:
    """mu at about six speeds per model and friction option."""
    pick = study.picks()
    lines = ["mu of the base case for the friction model's options (`webfem study variants`).",
             "", "| model | variant | heights | "
             + " | ".join(f"{study.speeds[i]:.1f} m/s" for i in pick) + " |",
             "|---|---|---|" + "---|" * len(pick)]
    for (variant, dist, m), mu in study.mu.items():
        lines.append(f"| {m} | {variant} | {dist} | "
                     + " | ".join(f"{mu[i]:.4f}" for i in pick) + " |")
    return "\n".join(lines) + "\n"


def _variants_rows(study) -> list[dict]:
    return [{"speed": u, **{f"mu {m} {v} {d}": mu[i] for (v, d, m), mu in study.mu.items()}}
            for i, u in enumerate(study.speeds)]


def _stability_keys(rows) -> list[str]:
    """Every column of any row, the first row's order first (failed points lack h_min)."""
    first = list(rows[0])
    return sorted({k for r in rows for k in r}, key=lambda k: first.index(k)
                  if k in first else 99)


def report_markdown(report, source: str = "the case") -> str:
    """docs/studies.md: each study's chart, the numbers that matter in sentences, and the
    stability table. ``source``: how the case is named (its file)."""
    conv, par, st = report.convergence, report.pareto, report.stability
    q2 = conv.order("fe2d", 2, "h_center")
    p2 = conv.order("fe1d", 2, "h_center")
    cf = next(r for r in par.rows if r["model"] == "closed-form")
    front = [r["method"] for r in par.rows if r["pareto_mu"]]
    q2_default = min(r["error_mu"] for r in par.rows if r["method"] == "fe2d Q2 level 0")
    fit = next((r for r in par.rows if r["model"] == "fitted"), None)
    fitted_text = "" if fit is None else (
        f" The fitted model (`{fit['method']}`) costs {fit['time_s'] * 1e6:.0f} us and misses "
        f"mu by {fit['error_mu'] * 100:.0f} %"
        + ("" if fit.get("same_case", True) else
           " (the same case with the default physics, against its own finest 2-D solution: "
           "the fit was trained on that physics only)") + ".")
    count = st.count
    command = (f"webfem study report {source} --quick" if report.quick else "make studies")
    return f"""# Studies: convergence, speed against accuracy, stability

Generated by `{command}` on
`{source}` in {report.seconds / 60:.1f} minutes; every number below comes from that run (the CSV
files beside the charts hold all of them).

## Convergence ([convergence.md](convergence.md))

![convergence](convergence.png)

Uniform refinement of the graded meshes: the 2-D model's central gap converges at order
{q2['observed_order']:.2f} with Q2 elements (Richardson value {q2['richardson'] * 1e6:.4f} um,
default mesh within {q2['relative_error_coarsest']:.1e}), the 1-D model's at order
{p2['observed_order']:.2f} with P2 pressure. The right panels compare Eq. 21 with the
converged 2-D central gap and mu over lambda and beta at the case's speed; the black lines
mark Eq. 21's stated range (lambda > 7, beta > 6). {convergence_markdown(conv).splitlines()[-1]}

## Speed against accuracy ([pareto.md](pareto.md))

![pareto](pareto.png)

The closed form costs {cf['time_s'] * 1e6:.0f} us and misses mu by {cf['error_mu'] * 100:.0f} %
against the finest 2-D solution; the Pareto front for mu is: {', '.join(front)}.{fitted_text} What the
extra time buys is in the table: the 1-D model is fast but carries the edge-leakage error
(about 1.5/lambda in the gap), the 2-D model's default mesh is already within
{q2_default:.0e} in mu.

## Stability ([stability.md](stability.md))

![stability](stability.png)

Over roller speed, wrap angle and mesh level on the 1-D model: Newton converged at
{count('Newton', 'converged')} of {count('Newton')} points
(without its continuation fallback {count('Newton, no continuation', 'converged')});
Picard with fixed relaxation 1: {count('Picard omega 1', 'converged')} converged,
{count('Picard omega 1', 'diverged')} diverged, {count('Picard omega 1', 'stalled')} stalled;
fixed 0.2: {count('Picard omega 0.2', 'converged')} / {count('Picard omega 0.2', 'diverged')}
/ {count('Picard omega 0.2', 'stalled')}; Picard with Anderson acceleration (the default):
{count('Picard Anderson (default)', 'converged')} converged; the staggered Picard (film, then
web): {count('Picard staggered', 'converged')} converged. Without asperity contact in the web
equilibrium, Newton converged at {count('Newton, contact off', 'converged')} of
{count('Newton, contact off')} speeds (with it:
{count('Newton, contact on', 'converged')}). The 2-D model converged at
{count('fe2d Newton', 'converged')} of {count('fe2d Newton')}
(speed, width) points. The closed form was inside its range at
{count('Eq. 21', 'converged')} of {count('Eq. 21')} points.

{stability_markdown(st)}
"""


_MARKDOWN = {"convergence": convergence_markdown, "pareto": pareto_markdown,
             "stability": stability_markdown, "lambda-table": lambda_table_markdown,
             "variants": variants_markdown}


def markdown(study, source: str = "the case") -> str:
    """The markdown of any study (for a report: docs/studies.md)."""
    if study.kind == "report":
        return report_markdown(study, source)
    return _MARKDOWN[study.kind](study)


def write(study, out, source: str = "the case") -> list[Path]:
    """Write a study's files into folder ``out`` (created if needed); returns their paths.

    ==============  ==========================================================================
    kind            files
    ==============  ==========================================================================
    convergence     convergence_refinement.csv, convergence_eq21.csv, convergence.png, .md
    pareto          pareto.csv, pareto.png, pareto.md
    stability       stability.csv, stability.png, stability.md
    lambda-table    lambda_table.csv, lambda_table.png, lambda_table.md
    variants        variants.csv, variants.png, variants.md
    report          the convergence, pareto and stability files, then studies.md
    ==============  ==========================================================================
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    kind = study.kind
    if kind == "report":
        paths = [p for part in (study.convergence, study.pareto, study.stability)
                 for p in write(part, out)]
        return paths + [write_text(out / "studies.md", report_markdown(study, source))]
    stem = kind.replace("-", "_")
    if kind == "convergence":
        paths = [write_csv(list(study.refinement), out / "convergence_refinement.csv"),
                 write_csv(list(study.eq21), out / "convergence_eq21.csv")]
    elif kind == "stability":
        rows = list(study.rows)
        paths = [write_csv(rows, out / "stability.csv", _stability_keys(rows))]
    elif kind == "variants":
        paths = [write_csv(_variants_rows(study), out / "variants.csv")]
    else:
        paths = [write_csv(list(study.rows), out / f"{stem}.csv")]
    chart = getattr(charts, f"{stem}_chart")
    paths.append(chart(study, out / f"{stem}.png"))
    paths.append(write_text(out / f"{stem}.md", markdown(study)))
    return paths
