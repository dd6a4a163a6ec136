"""A report to share: one self-contained HTML page of a solved case.

Where the case states an idler load the page opens with the idler's verdict (``id="idler"``:
holds, unsure, slips or not judged, with the traction needed and available: the sentence
``webfem solve`` prints, :func:`webfem.describe.idler_verdict`), repeated among the warnings
unless it holds. Then it holds, in this order, sections with these ``id`` attributes: ``inputs`` (every case
key with its value, unit and meaning), ``model`` (which model answered, why, the effects
included and the options), ``summary`` (the numbers with units), ``pictures`` (the film
picture of :mod:`webfem.io.pictures` and any charts given, embedded as base64 PNG),
``warnings`` and ``computed`` (mesh, iterations, residual, time, webfem and Python versions).
Nothing is fetched: no scripts, no style sheets or images from elsewhere, so a colleague
opens the file in any browser without webfem.

``units`` (si, metric or us; :data:`webfem.units.SYSTEMS`) sets the units of the inputs, the
summary and the pictures; the quantities :data:`webfem.units.ROLES` does not list (viscosity,
moduli, ...) stay SI and say so.

Examples
--------
>>> import tempfile, webfem
>>> result = webfem.solve(webfem.Case(), model="closed-form")
>>> with tempfile.TemporaryDirectory() as d:
...     page = write_report(result, d, title="demo")
...     text = page.read_text()
>>> page.name, 'id="summary"' in text, "<script" in text
('report.html', True, False)
"""

from __future__ import annotations

import base64
import dataclasses
import datetime
import math
import platform
import re
import tempfile
from html import escape
from pathlib import Path

from ..describe import contact_gap_text, error_text, idler_verdict, judged_text, resting_text
from ..files import write_text
from ..models.model_error import SAFETY
from ..units import ROLES, convert, unit_label

__all__ = ["write_report", "report_html", "page_warnings", "SECTIONS", "SUMMARY_UNITS"]

#: The sections of the page: id -> heading.
SECTIONS = {"inputs": "Inputs", "model": "Model", "summary": "Summary",
            "pictures": "Pictures", "warnings": "Warnings", "computed": "How it was computed"}

#: Summary key -> (unit, meaning) for the summary table in SI (gaps in um, x_min in mm); in
#: other units a key of :data:`webfem.units.ROLES` shows its display unit.
SUMMARY_UNITS = {
    "mu": ("-", "wrap-averaged friction coefficient"),
    "delta_T": ("N/m", "tension increase the roller carries before slip (Eq. 31)"),
    "mu_film": ("-", "nothing sliding: the film's own drag at these speeds"),
    "delta_T_film": ("N/m", "nothing sliding: the belt formula's delta_T for mu_film"),
    "regime": ("", "lubrication regime over most of the wrap, by the gap against h_c and "
                   "3 sigma (the paper's classification; the load the asperities carry is "
                   "contact_share)"),
    "h_center": ("um", "gap at the wrap centre"), "h_inlet": ("um", "gap at the inlet edge"),
    "h_outlet": ("um", "gap at the outlet edge"), "h_min": ("um", "smallest gap"),
    "x_min": ("mm", "position of the smallest gap"),
    "h_c": ("um", "contact gap: the asperities alone carry T/R; boundary lubrication below"),
    "sigma": ("um", "combined RMS roughness (fluid above 3 sigma)"),
    "share_boundary": ("-", "share of the wrap in boundary lubrication"),
    "share_mixed": ("-", "share of the wrap in mixed lubrication"),
    "share_fluid": ("-", "share of the wrap in fluid lubrication"),
    "contact_share": ("-", "share of the wrap load carried by the asperities (the contact "
                           "model: its heights have no cut-off at 3 sigma)"),
    "lambda": ("-", "width parameter L / (2 R eps^(1/3))"),
    "beta": ("-", "wrap parameter B / eps^(1/3)"),
    "eq21_valid": ("", "inside Eq. 21's range (beta > 6, lambda > 7)"),
    "T_eff": ("N/m", "effective tension T - rho_w t U_w^2"),
    "bending_stiffness_used": ("N m", "bending stiffness used"),
    "slip_margin": ("-", "idler: available / required tension difference"),
    "delta_T_required": ("N/m", "idler: tension difference needed"),
    "delta_T_available": ("N/m", "idler: tension difference available"),
    "mu_onset": ("-", "traction at the onset of slip: mu_cc x contact share"),
    "idler_basis": ("", "idler: the web slides here, so the idler keys come from this solve "
                        "of the idler's own film (U_r = U_w)"),
}

_STYLE = """
body{font-family:system-ui,-apple-system,'Segoe UI',Helvetica,Arial,sans-serif;margin:0 auto;
max-width:62rem;padding:1rem 1.5rem;color:#222;line-height:1.4}
h1{font-size:1.5rem;margin-bottom:.2rem}h2{font-size:1.15rem;border-bottom:1px solid #ccc;
padding-bottom:.2rem;margin-top:1.8rem}.sub{color:#555;margin-top:0}
table{border-collapse:collapse;font-size:.9rem;margin:.5rem 0}
table.wide{width:100%}td,th{border-bottom:1px solid #e4e4e4;padding:.2rem .7rem;text-align:left;vertical-align:top}
td.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
th{background:#f4f4f4}figure{margin:1rem 0}img{max-width:100%;height:auto;border:1px solid #ddd}
figcaption{font-size:.85rem;color:#555}.warn{background:#fff4e0;border-left:4px solid #e8a33d;
padding:.4rem .7rem;margin:.3rem 0}.ok{color:#2a7a2a}.key{font-family:monospace}
nav a{margin-right:1rem}
"""


def _num(value) -> str:
    if isinstance(value, bool) or value is None:
        return "-" if value is None else ("yes" if value else "no")
    if isinstance(value, (int, float)):
        return f"{value:.5g}" if math.isfinite(value) else "n/a"
    if isinstance(value, (list, tuple)):
        return ", ".join(map(str, value)) or "-"
    return str(value)


def _numeric(text) -> bool:
    try:
        float(str(text))
    except ValueError:
        return False
    return True


def _table(head, rows) -> str:
    """An HTML table; numbers in the value column are right-aligned and kept on one line,
    text wraps."""
    out = ["<table>", "<tr>" + "".join(f"<th>{escape(h)}</th>" for h in head) + "</tr>"]
    for row in rows:
        out.append("<tr>" + "".join(
            f'<td class="n">{escape(c)}</td>' if i == 1 and _numeric(c)
            else f"<td>{escape(c)}</td>" for i, c in enumerate(row)) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def _shown(key: str, value, unit: str, units: str):
    """``(value, unit)`` of a key as the page shows it in ``units``."""
    role = ROLES.get(key)
    if role is None or not isinstance(value, (int, float)) or isinstance(value, bool):
        return value, unit
    return convert(float(value), role, units), unit_label(role, units)


def _inputs(case, units: str = "si") -> str:
    rows = []
    for section in dataclasses.fields(case):
        part = getattr(case, section.name)
        if not dataclasses.is_dataclass(part):
            continue
        for f in dataclasses.fields(part):
            meta, value = f.metadata, getattr(part, f.name)
            unit, doc = meta.get("unit", ""), meta.get("doc", "")
            key = f"{section.name}.{f.name}"
            if value is None:   # not set: the key says what is used instead ("left out"
                # read as "not modelled" to a user whose bending stiffness was computed)
                shown, doc = "not set", f"{doc}; not set, so: {meta.get('absent', '')}"
            elif units == "si":   # the keys' own units, as a case file holds them
                shown = _num(value)
            else:
                value, unit = _shown(key, value, unit, units)
                shown = _num(value)
            rows.append((key, shown, unit, doc))
    return _table(("key", "value", "unit (SI)" if units == "si" else "unit", "meaning"), rows)


def _model(result, asked: str | None = None) -> str:
    s, d = result.summary, result.diagnostics
    used = s.model_used or s.model
    lines = [f"<p>Asked for <b>{escape(s.model)}</b>"
             + (f" ({escape(asked)})" if asked else "")
             + f"; answered by <b>{escape(used)}</b>.</p>"]
    if not s.why:
        how = (escape(asked) if asked else
               f"{escape(s.model)} was named (<span class=key>model = '{escape(s.model)}'"
               "</span>)")
        lines.append(f"<p>Why: {how}; <span class=key>--model auto</span> picks the "
                     "simplest model within its tolerance.</p>")
    else:
        lines.append(f"<p>Why: {escape(s.why)} ({escape(judged_text(s))}).</p>")
    errors = error_text(s)
    lines.append(f"<p>Stated error: {escape(errors)}; {escape(s.error_basis or '')}.</p>"
                 if errors else "<p>Stated error: none (no estimate was made).</p>")
    if s.groove_domain is not None:
        lines.append(f"<p>Across the width: {escape(domain_headline(s))}. "
                     f"{escape(_sentence(s.groove_domain))}.</p>")
    effects = ", ".join(s.effects) or "none beyond the paper's model"
    lines.append(f"<p>Effects included: {escape(effects)}. Physics: "
                 f"<span class=key>{escape(result.case.model.physics)}</span>.</p>")
    options = d.options
    if options is not None and hasattr(options, "to_dict"):
        changed = options.changed()
        if changed:
            lines.append(_table(("option", "value"), [(k, _num(v)) for k, v in
                                                      changed.items()]))
        lines.append(f"<p>{'Every other' if changed else 'Every'} option of "
                     f"{escape(s.model)} at its default.</p>")
    return "\n".join(lines)


def domain_headline(s) -> str:
    """The domain a grooved answer solved across the width, in a few words: a periodic cell
    with what its left-out edges are estimated to change (``error_edges`` is twice it)."""
    if not s.periodic_cell:
        return s.groove_domain.split(":")[0]
    if s.error_edges is None:
        return "periodic cell, the web's edges left out"
    return (f"periodic cell, edges estimated to change it by {s.error_edges / SAFETY:.3g} "
            f"(left out; twice that, {s.error_edges:.3g}, is in each stated error)")


def film_caption(s) -> str:
    """The film picture's caption start: what its width shows."""
    if s.periodic_cell:
        return ("Film pressure over one groove pitch (the periodic cell, land centre to "
                "groove centre, mirrored; the web's edges left out), ")
    return "Film pressure over the full width, "


def _summary(result, units: str = "si") -> str:
    data = result.summary
    rows = []
    for key, (unit, meaning) in SUMMARY_UNITS.items():
        value = data.get(key)
        if value is None:
            continue
        if key == "mu":
            meaning = f"{meaning} {_mu_when(data, units)}"
        elif key == "h_min" and resting_text(data):
            meaning = f"{meaning}; {_in_units(resting_text(data), units)}"
        elif key == "h_c":
            meaning += _in_units(contact_gap_text(data), units)
        value, unit = _shown(key, value, unit, units)
        rows.append((key, _num(value), unit, meaning))
    return _table(("quantity", "value", "unit", "meaning"), rows)


def _mu_when(s, units: str) -> str:
    """When the case's mu applies: at the onset of slip where nothing slides (U_s = 0), else
    at the stated speeds, the web sliding U_s over the roller."""
    if not s.get("U_slide"):
        return "(nothing sliding: at the onset of slip)"
    speed = f"{convert(abs(s.U_slide), 'speed', units):.4g} {unit_label('speed', units)}"
    return f"(at the stated speeds: the web slides {speed} over the roller, U_s = |U_r - U_w|)"


def _in_units(text: str, units: str) -> str:
    """``text``'s thin lengths (``2.25 um``) in ``units``."""
    if units == "si" or not text:
        return text
    return re.sub(r"([-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?) um",
                  lambda m: f"{convert(float(m.group(1)) * 1e-6, 'thin', units):.3g} "
                            f"{unit_label('thin', units)}", text)


def _picture(path: Path, caption: str) -> str:
    data = base64.b64encode(Path(path).read_bytes()).decode("ascii")
    return (f'<figure><img alt="{escape(caption)}" src="data:image/png;base64,{data}">'
            f"<figcaption>{escape(caption)}</figcaption></figure>")


def _computed(result, version: str) -> str:
    s, d = result.summary, result.diagnostics
    rows = [("model", s.model_used or s.model, "", ""),
            ("method", s.method or d.method or "closed form", "", ""),
            ("mesh", s.mesh or "none (closed form)", "", ""),
            ("unknowns", _num(s.n_dofs), "", ""), ("cells", _num(s.n_cells), "", ""),
            ("refinement rounds", _num(s.adapt_rounds), "", ""),
            ("iterations", _num(s.iterations), "", ""),
            ("final residual", _num(s.residual), "", "scaled"),
            ("solver", s.solver_message or d.reason or "-", "", ""),
            ("converged", _num(s.converged), "", ""),
            ("solve time", _num(s.solve_time_s), "s", ""),
            ("webfem", version, "", ""),
            ("Python", platform.python_version(), "", platform.platform(terse=True)),
            ("written", datetime.datetime.now().isoformat(timespec="seconds"), "", "")]
    return _table(("", "value", "unit", "note"), rows)


def _sentence(text: str) -> str:
    """``text`` with its first letter a capital, as a sentence of the page."""
    return text[:1].upper() + text[1:]


def page_warnings(result) -> list[str]:
    """The warnings the page lists: the solve's, and the idler's verdict where it slips, is
    unsure or cannot be judged (:func:`webfem.describe.idler_verdict`, the sentence
    ``webfem solve`` prints)."""
    said = idler_verdict(result.summary, result.case)
    idler = [_sentence(said[1])] if said and said[0] != "holds" else []
    return idler + list(result.summary.warnings)


def _idler_headline(result) -> str:
    """The idler's verdict as the page's first line ("" without an idler load): green where
    it holds, a warning box otherwise."""
    said = idler_verdict(result.summary, result.case)
    if said is None:
        return ""
    word, text = said
    shown = (f"<b>Idler slip check: {escape(word.upper())}.</b> "
             f"{escape(_sentence(text))}.")
    return (f'<p class="ok" id="idler">{shown}</p>' if word == "holds" else
            f'<div class="warn" id="idler">{shown}</div>')


def report_html(result, *, title: str = "", pictures=(), version: str = "",
                units: str = "si", asked: str | None = None) -> str:
    """The page as text. ``pictures``: ``(png path, caption)`` pairs, embedded in order;
    ``units``: of the inputs and the summary; ``asked``: how the model was asked for (e.g.
    "the default of webfem report (--model auto)"), shown beside it."""
    s = result.summary
    used = s.model_used or s.model
    title = title or "webfem report"
    rests = _in_units(resting_text(s) or "", units)
    # a negative gap is an answer, not a warning, but the page must say why it is negative
    # wherever a reader meets it: the heading, the summary table and this section
    note = f"<p>Note: {escape(_sentence(rests))}.</p>" if rests else ""
    warn = note + ("".join(f'<div class="warn">{escape(w)}</div>'
                           for w in page_warnings(result))
                   or '<p class="ok">No warnings.</p>')
    figures = "\n".join(_picture(p, c) for p, c in pictures) or "<p>No pictures.</p>"
    body = {"inputs": _inputs(result.case, units), "model": _model(result, asked),
            "summary": _summary(result, units), "pictures": figures, "warnings": warn,
            "computed": _computed(result, version)}
    share = s.get("contact_share")
    carried = (f"contact carries {100 * share:.1f} % of the load, "
               if share is not None and math.isfinite(share) else "")
    head = (f"<p class=sub>mu = {s.mu:.4g}, regime {escape(s.regime)} (by the gap), "
            f"{carried}smallest gap "
            f"{convert(s.h_min, 'thin', units):.3g} {unit_label('thin', units)}"
            f"{f' ({escape(rests)})' if rests else ''}; model "
            f"{escape(used)}"
            f"{'' if s.converged else ' (NOT converged)'}</p>")
    nav = "<nav>" + "".join(f'<a href="#{k}">{v}</a>' for k, v in SECTIONS.items()) + "</nav>"
    sections = "\n".join(f'<section id="{k}"><h2>{SECTIONS[k]}</h2>\n{body[k]}\n</section>'
                         for k in SECTIONS)
    return (f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
            f'<meta name="viewport" content="width=device-width, initial-scale=1">'
            f"<title>{escape(title)}</title><style>{_STYLE}</style></head>\n<body>"
            f"<h1>{escape(title)}</h1>{_idler_headline(result)}{head}{nav}\n{sections}\n"
            "</body></html>\n")


def write_report(result, folder, *, title: str = "", charts=(), name: str = "report.html",
                 units: str = "si", asked: str | None = None) -> Path:
    """Write the page into ``folder`` (created if missing) and return its path.

    The film picture (:func:`webfem.io.pictures.film_figure`) is drawn for every result;
    ``charts`` adds ``(png path, caption)`` pairs after it. The page appears whole or not at
    all. ``units``: of the tables and the film picture (charts given are drawn already);
    ``asked``: how the model was asked for, as the page states it (:func:`report_html`).
    """
    from .. import __version__
    from .pictures import film_figure

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    used = result.summary.model_used or result.summary.model
    with tempfile.TemporaryDirectory(prefix=".webfem-report-", dir=folder) as tmp:
        film = film_figure(result, Path(tmp) / "film.png", units=units)
        caption = ((film_caption(result.summary) if result.film is not None else "")
                   + f"gap along the centre line and local friction in the wrap ({used}).")
        html = report_html(result, title=title, version=__version__,
                           pictures=[(film, caption), *charts], units=units, asked=asked)
    return write_text(folder / name, html)
