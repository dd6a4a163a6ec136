"""Charts in the style of the paper's Figs. 10-13 (matplotlib, off screen).

Every chart takes ``units`` (:data:`webfem.units.SYSTEMS`, default ``"si"``): the data stay
SI and are converted only as they are drawn, with the axis labels naming the unit
(:func:`webfem.units.convert`, :func:`webfem.units.unit_label`).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from ..files import replacing
from ..units import ROLES, convert, unit_label

__all__ = ["sweep_chart", "traction_loss_chart", "calibration_chart", "needs_markers",
           "PARAMETER_LABELS", "parameter_label", "display_values", "answered", "log_spaced",
           "level_text", "save_figure"]

_GAP_STYLES = (("h_inlet", "inlet", (0, (6, 2))), ("h_center", "centre", (0, (3, 2))),
               ("h_outlet", "exit", (0, (1, 1.5))))


def _f(row: dict, key: str) -> float:
    """A row's number, NaN where it is missing (a failed point, a null in JSON or CSV)."""
    value = row.get(key)
    try:
        return float(value)
    except (TypeError, ValueError):
        return np.nan


#: What the parameters a sweep usually runs over are called on an axis (the unit follows).
_PARAMETER_NAMES = {"roller.speed": "roller speed U_r", "web.speed": "web speed U_w",
                    "line.speed": "line speed U_r (web at the case's U_w/U_r)",
                    "web.tension": "web tension T", "wrap.angle_deg": "wrap angle B",
                    "web.width": "web width L", "roller.radius": "roller radius R",
                    "web.roughness": "web roughness sigma_w",
                    "roller.roughness": "roller roughness sigma_r"}


def display_values(values, role: str | None, units: str) -> np.ndarray:
    """SI ``values`` (None: NaN) as drawn in ``units``: in the display unit of ``role``
    (:data:`webfem.units.ROLES`), or as they are without a role."""
    a = np.array([np.nan if v is None else v for v in np.atleast_1d(values)], float)
    return a if role is None else convert(a, role, units)


def parameter_label(key: str, units: str = "si") -> str:
    """An axis label for case key ``key`` in ``units``, e.g. ``roller speed U_r [ft/min]``
    (the key itself, with its unit when it has one, for keys without a name here)."""
    name = _PARAMETER_NAMES.get(key, key)
    role = ROLES.get(key)
    return f"{name} [{unit_label(role, units)}]" if role else name


#: Axis labels of the parameters a sweep usually runs over (SI units).
PARAMETER_LABELS = {key: parameter_label(key) for key in _PARAMETER_NAMES}


def level_text(value: float) -> str:
    """A regime level as labelled: two decimals (um), three significant digits below 1
    (mil), so close levels stay apart in every unit."""
    decimals = max(2, 2 - int(np.floor(np.log10(abs(value))))) if value else 2
    return f"{value:.{decimals}f}"


def answered(rows: list[dict], asked: str) -> str:
    """Which model answered sweep ``rows`` asked of model ``asked``, from their
    ``model_used`` column: ``fe1d``; for auto ``auto: fe2d at every point`` or ``auto: fe1d
    at 12, fe2d at 28 points``.

    >>> answered([{"model_used": "fe1d"}, {"model_used": "fe2d"}], "auto")
    'auto: fe1d at 1, fe2d at 1 points'
    """
    used = [r["model_used"] for r in rows if r.get("model_used")]
    if not used or set(used) == {asked}:
        return asked
    counts = {m: used.count(m) for m in dict.fromkeys(used)}
    if len(counts) == 1:
        return f"{asked}: {used[0]} at every point"
    return f"{asked}: " + ", ".join(f"{m} at {n}" for m, n in counts.items()) + " points"


def log_spaced(values) -> bool:
    """True for at least 3 positive values evenly spaced in their logarithm (and not
    evenly in themselves): a sweep made with ``--log`` or ``spacing = "log"``."""
    v = np.unique(np.asarray([x for x in values if x is not None and np.isfinite(x)], float))
    if v.size < 3 or v.min() <= 0:
        return False
    steps, logs = np.diff(v), np.diff(np.log(v))
    return bool(np.allclose(logs, logs.mean(), rtol=0.05)
                and not np.allclose(steps, steps.mean(), rtol=0.05))


def needs_markers(values) -> bool:
    """Markers on a sweep of fewer than 30 points or log-spaced values: a smooth line would
    suggest points that were never solved."""
    v = np.unique(np.asarray([x for x in values if np.isfinite(x)], float))
    if v.size < 30:
        return True
    steps = np.diff(v)
    return bool(v.min() > 0 and not np.allclose(steps, steps.mean(), rtol=0.05)
                and np.allclose(np.diff(np.log(v)), np.log(v[-1] / v[0]) / (v.size - 1),
                                rtol=0.05))


def _crowding(ax, boxes, left: bool) -> int:
    """How many samples of the lines drawn on ``ax``'s figure fall inside the label
    ``boxes`` (``(width, bottom, top)`` in pixels) set against ``ax``'s left or right edge:
    how much of the data labels there would cover."""
    edge = ax.get_window_extent()
    count = 0
    for axes in ax.figure.axes:
        for line in axes.get_lines():
            xy = line.get_xydata()
            if not line.get_visible() or len(xy) == 0:
                continue
            px = line.get_transform().transform(xy)
            px = px[np.isfinite(px).all(axis=1)]
            if len(px) >= 2:    # the segments between points cover the data too
                t = np.linspace(0.0, 1.0, 24)[:, None]
                px = np.concatenate([a + t * (b - a) for a, b in zip(px[:-1], px[1:])])
            for width, bottom, top in boxes:
                x0, x1 = (edge.x0, edge.x0 + width) if left else (edge.x1 - width, edge.x1)
                count += int(np.sum((px[:, 0] >= x0) & (px[:, 0] <= x1)
                                    & (px[:, 1] > bottom) & (px[:, 1] < top)))
    return count


def _level_labels(ax, levels: dict, unit: str = "um") -> None:
    """Draw the regime levels on the gap axis ``ax``: ``levels`` maps a gap [``unit``] to
    ``(name, series labels)``. Each distinct value gets one label, naming the series when
    not all share it; labels closer than a text line are pushed apart (with a thin leader)
    so none prints on top of another; they sit at the axis's right end, or at its left
    where they would cover less than half as much of the drawn lines."""
    everyone = set().union(*(who for _, who in levels.values())) if levels else set()
    fig = ax.figure
    fig.canvas.draw()   # the axis limits and pixel scale are final only after a draw
    to_px = ax.transData.transform
    step = 9.0 * fig.dpi / 72.0   # one 7-point line with a little air, in pixels
    placed = []
    for level, (name, who) in sorted(levels.items()):
        ax.axhline(level, color="0.55", lw=0.8, ls="-", zorder=0)
        y = to_px((0.0, level))[1]
        at = max(y, placed[-1][2] + step) if placed else y
        whose = "" if who == everyone else f" ({', '.join(sorted(who))})"
        placed.append((level, f"{name} = {level_text(level)} {unit}{whose}", at, y))
    if not placed:
        return
    # each label's box: about 0.55 em a character wide, from just above its level line
    # (the line itself is not covered) to the next line of text
    em = 7.0 * fig.dpi / 72.0
    boxes = [(0.55 * em * len(text) + 6, at + 2, at + step) for _, text, at, _ in placed]
    # the right end unless the left is clearly clearer: a label does not jump sides
    # between two charts alike for a line or two
    left = 2 * _crowding(ax, boxes, left=True) < _crowding(ax, boxes, left=False)
    for level, text, at, y in placed:
        ax.annotate(text, (0.0 if left else 1.0, level), xycoords=("axes fraction", "data"),
                    xytext=(3 if left else -3, 1.5 + (at - y) * 72.0 / fig.dpi),
                    textcoords="offset points", ha="left" if left else "right", va="bottom",
                    fontsize=7, color="0.25",
                    bbox=dict(fc="white", ec="none", alpha=0.8, pad=0.3),
                    arrowprops=dict(arrowstyle="-", color="0.6", lw=0.5) if at > y else None)


def sweep_chart(rows: list[dict], path: str | Path, title: str = "",
                beside: list[dict] | None = None, units: str = "si",
                log_x: bool | None = None) -> Path:
    """mu against the swept parameter per series, with the gaps (dashed) on a second axis.

    ``beside``: rows of another model (the closed form beside an FE sweep), drawn thin in
    the series' colours: mu solid, its gaps dashed like the main ones. Points that did not
    converge are marked x on the axis and left out of the lines. Sweeps of fewer than 30
    points or log-spaced ones get markers (:func:`needs_markers`).

    The regime boundaries h = h_c and h = 3 sigma are grey lines on the gap axis, labelled
    there, one label per distinct value (close values share one); gaps below 0 (a web
    resting compressed) extend the gap axis below 0, where h = 0 is drawn and named. The
    legend sits below the axes, clear of the title. ``units``: the swept parameter and the gaps are drawn in that
    system's units. ``log_x``: a logarithmic parameter axis (None: when the values are
    log-spaced, :func:`log_spaced`). A row's ``model_used`` (auto's choice) is named in the
    legend.
    """
    series = list(dict.fromkeys(r["series"] for r in rows))
    parameter = rows[0]["parameter"]
    role = ROLES.get(parameter)

    def xs(sel):
        return display_values([r["value"] for r in sel], role, units)

    def gaps(sel, key, ok=None):
        h = display_values([_f(r, key) for r in sel], "thin", units)
        return h if ok is None else np.where(ok, h, np.nan)

    fig, ax = plt.subplots(figsize=(9.0, 5.0), layout="constrained")
    ax2 = ax.twinx()
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    marker = "o" if needs_markers(xs(rows)) else None
    levels, varying = {}, set()
    for i, label in enumerate(series):
        sel = [r for r in rows if r["series"] == label]
        ok = [r.get("converged") is True for r in sel]
        U = xs(sel)
        colour = colours[i % len(colours)]
        model = answered(sel, sel[0]["model"])
        ax.plot(U, [_f(r, "mu") if k else np.nan for r, k in zip(sel, ok)], "-", color=colour,
                lw=1.8, marker=marker, ms=3.5,
                label=f"{label}: mu ({model})" if len(series) > 1 else f"mu ({model})")
        bad = [r for r, k in zip(sel, ok) if not k]
        if bad:
            ax.plot(xs(bad), [0.0] * len(bad), "x", color=colour,
                    label="not converged", clip_on=False)
        for key, name, dash in _GAP_STYLES:
            ax2.plot(U, gaps(sel, key, ok), linestyle=dash, color=colour, lw=1.1, marker=marker,
                     ms=2.0)
        ref = [r for r in beside or [] if r["series"] == label]
        if ref:
            rmodel = ref[0]["model"]
            rU = xs(ref)
            ax.plot(rU, [_f(r, "mu") for r in ref], "-", color=colour, lw=0.8, alpha=0.7,
                    label=f"{label}: mu ({rmodel})" if len(series) > 1 else f"mu ({rmodel})")
            for key, name, dash in _GAP_STYLES:
                ax2.plot(rU, gaps(ref, key), linestyle=dash, color=colour, lw=0.6, alpha=0.7)
        for key, factor, name in (("h_c", 1.0, "h_c"), ("sigma", 3.0, "3 sigma")):
            here = [(x, float(level_text(factor * float(gaps([r], key)[0]))))
                    for x, r, k in zip(U, sel, ok) if k and np.isfinite(_f(r, key))]
            if len({v for _, v in here}) > 1:
                # a level that moves with the swept parameter (h_c with the tension) is a
                # curve: a flat line per point's value across the whole axis would claim
                # levels that hold at one point only
                ax2.plot([x for x, _ in here], [v for _, v in here], color="0.45", lw=0.9,
                         ls="-.", zorder=1)
                varying.add(name)
                continue
            for _, value in here:
                levels.setdefault(value, (name, set()))[1].add(str(label))
    if log_x is None:
        log_x = log_spaced([r["value"] for r in rows])
    if log_x:
        ax.set_xscale("log")
    ax.set_xlabel(parameter_label(parameter, units) + (" (log scale)" if log_x else ""))
    ax.set_ylabel("friction coefficient mu [-] (solid)")
    thin = unit_label("thin", units)
    ax2.set_ylabel(f"web spacing h [{thin}] (dashed; grey: regime levels)")
    mu = [_f(r, "mu") for r in rows if r.get("converged") is True]
    ax.set_ylim(0.0, max([0.4] + [1.1 * m for m in mu if np.isfinite(m)]))
    ax2.set_ylim(0.0, None)
    # where the wrap edges' gaps dwarf the centre's (a stiff board at low tension leaves the
    # roller at the wrap's edges: 3 mm against a film of microns), the gap axis is scaled
    # to the centre gap and the regime levels, what the chart is about, and the legend says
    # how far the edge gaps run off it (as the film picture's do)
    drawn = [r for r in rows if r.get("converged") is True] + list(beside or [])
    edges = [h for r in drawn for h in (_f(r, "h_inlet"), _f(r, "h_outlet")) if np.isfinite(h)]
    core = [h for r in drawn for h in (_f(r, "h_center"), _f(r, "h_c"), 3.0 * _f(r, "sigma"))
            if np.isfinite(h)]
    clipped = bool(edges) and bool(core) and max(core) > 0.0 and max(edges) > 3.0 * max(core)
    if clipped:
        ax2.set_ylim(0.0, float(display_values([1.5 * max(core)], "thin", units)[0]))
    # a web resting compressed on its asperities has gaps below 0 (wide grooves, a slow
    # roller): the axis reaches down to them, with the roller's crest drawn, rather than
    # cutting the curves off at 0 without a word
    drawn_gaps = [h for r in drawn for h in (_f(r, k) for k, _, _ in _GAP_STYLES)
                  if np.isfinite(h)]
    lowest = min(drawn_gaps, default=0.0)
    if lowest < 0.0:
        ax2.set_ylim(bottom=float(display_values([1.1 * lowest], "thin", units)[0]))
        ax2.axhline(0.0, color="k", lw=0.8, zorder=1)
    ax.grid(True, alpha=0.3)
    h1, l1 = ax.get_legend_handles_labels()
    # the gap styles once, in black: the colours already name the series
    models = [rows[0]["model"]] + ([beside[0]["model"]] if beside else [])
    styles = [(Line2D([], [], color="k", lw=1.1 if m == models[0] else 0.6, linestyle=dash),
               f"gap h {name} ({m}{'' if m == models[0] else ', thin'})")
              for m in models for _, name, dash in _GAP_STYLES]
    meaning = {"h_c": "h_c (contact gap)", "3 sigma": "3 sigma (fluid above)"}
    styles += [(Line2D([], [], color="0.45", lw=0.9, ls="-."),
                f"{meaning[name]}: moves with the parameter")
               for name in ("h_c", "3 sigma") if name in varying]
    if clipped:
        styles.append((Line2D([], [], color="none"),
                       f"(edge gaps up to {display_values([max(edges)], 'thin', units)[0]:.4g}"
                       f" {thin}: off the top of the gap axis)"))
    if lowest < 0.0:
        styles.append((Line2D([], [], color="k", lw=0.8),
                       f"h = 0 (below: the web rests compressed on its asperities; "
                       f"lowest {display_values([lowest], 'thin', units)[0]:.4g} {thin})"))
    # below the axes, in two columns: on the right, the long entries (a series' model,
    # the edge gaps, h = 0) took half the canvas's width and ran into the title
    fig.legend(h1 + [h for h, _ in styles], l1 + [t for _, t in styles], fontsize=7,
               loc="outside lower center", ncol=2)
    _level_labels(ax2, levels, thin)
    stated = stated_errors_text(rows)
    if title or stated:
        ax.set_title("\n".join(t for t in (title, stated) if t), fontsize=10)
    return _save(fig, path)


def stated_errors_text(rows: list[dict]) -> str:
    """The largest error the converged rows state, per quantity: ``stated errors up to:
    h_center 3e-04, h_min 4e-05, mu 3e-04`` ("" where no row states one).

    >>> stated_errors_text([{"converged": True, "error_h_center": 2e-4, "error_h_min": 1e-3,
    ...                      "error_mu": None}])
    'stated errors up to: h_center 0.0002, h_min 0.001'
    """
    parts = []
    for q in ("h_center", "h_min", "mu"):
        values = [float(r[f"error_{q}"]) for r in rows if r.get("converged") is True
                  and r.get(f"error_{q}") not in (None, "")]
        if values:
            parts.append(f"{q} {max(values):.1g}")
    return "stated errors up to: " + ", ".join(parts) if parts else ""


def traction_loss_chart(rows: list[dict], mu_curves: dict, mu_min: float, path,
                        parameters, units: str = "si", case_values: dict | None = None,
                        title: str = "base case") -> Path:
    """Panels: mu against roller speed with the threshold (the traction-loss speed is where
    each curve falls through it), then the traction-loss speed against each parameter, one
    line per model.

    ``rows``: ``model``, ``parameter``, ``value``, ``speed`` (None: no loss), and optionally
    ``skipped`` (why a point has no answer: drawn as an x on the panel's floor and counted
    in a note, so a gap is not read as "no loss in range"); ``mu_curves``: model ->
    (speeds, mu); ``parameters``: ``(key, axis label, range)`` per panel, e.g.
    :func:`webfem.traction.chart_parameters` (a key of :data:`webfem.units.ROLES` is drawn
    in ``units``, with :func:`parameter_label`; others as they are, with their label);
    ``case_values``: key -> the case's own value, marked on its panel; ``title``: the first
    panel's (the case the curves are of).
    """
    parameters = list(parameters)
    speed = unit_label("speed", units)
    fig, axes = plt.subplots(1, 1 + len(parameters), figsize=(3.4 * (1 + len(parameters)), 3.8),
                             constrained_layout=True, squeeze=False)
    axes = axes[0]
    ax = axes[0]
    for model, (u, mu) in mu_curves.items():
        ax.plot(display_values(u, "speed", units), mu, label=model)
    ax.axhline(mu_min, color="k", lw=0.8, ls="--", label=f"mu_min = {mu_min:g}")
    ax.set_xlabel(f"roller speed U_r [{speed}]")
    ax.set_ylabel("mu [-]")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="best")
    case_values = case_values or {}
    for ax, (key, label, *_) in zip(axes[1:], parameters):
        role = ROLES.get(key)
        # a point without a speed is marked on the panel's edge, so a gap is never read as
        # one thing when it is another: ^ top (mu stays above mu_min at every speed
        # scanned: the loss is faster), v floor (mu never reaches it: no traction to lose),
        # x floor (no answer at all)
        marks = {"^": [], "v": [], "x": []}
        for model in dict.fromkeys(r["model"] for r in rows):
            sel = [r for r in rows if r["model"] == model and r["parameter"] == key]
            line, = ax.plot(display_values([r["value"] for r in sel], role, units),
                            display_values([r["speed"] for r in sel], "speed", units), "o-",
                            label=model, ms=3)
            for r in sel:
                if r.get("skipped"):
                    marks["x"].append((r["value"], "C3"))
                elif r["speed"] is None:
                    above = _f(r, "mu_peak") >= mu_min
                    marks["^" if above else "v"].append((r["value"], line.get_color()))
        for marker, points in marks.items():
            for value, color in points:
                ax.plot(display_values(value, role, units)[0], 1.0 if marker == "^" else 0.0,
                        marker, color=color, ms=6, mew=1.5, clip_on=False,
                        transform=ax.get_xaxis_transform())
        if key in case_values:
            ax.axvline(display_values(case_values[key], role, units)[0], color="0.5", lw=0.8,
                       ls=":", label="this case")
        ax.set_xlabel(parameter_label(key, units) if key in ROLES else label)
        ax.set_ylabel(f"traction-loss speed [{speed}]")
        notes = []
        if key == "web.width" and any(r["model"] == "fe1d" for r in rows):
            notes.append("fe1d is flat in width: a 1-D film has no\nedge leakage, so "
                         "the width never enters it")
        words = {"^": "^ top: mu above mu_min at every speed scanned",
                 "v": "v floor: mu below mu_min at every speed scanned",
                 "x": "x floor: no answer (see the command's message)"}
        notes += [f"{words[m]} ({len(p)})" for m, p in marks.items() if p]
        if notes:
            # above the panel, where constrained layout makes room: inside it a note hid
            # the points it explains
            ax.set_title("\n".join(notes), fontsize=6.5, color="0.3", loc="left")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"Roller speed at which mu falls below {mu_min:g}", fontsize=10)
    return _save(fig, path)


def save_figure(fig, path, dpi: int = 110) -> Path:
    """Save ``fig`` as PNG under a hidden temporary name, then rename (never a half-written
    chart; the user's umask sets the mode) and close it; returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        with replacing(path) as tmp:
            fig.savefig(tmp, dpi=dpi, format="png")
    finally:
        plt.close(fig)
    return path


_save = save_figure


def _pm(value, half, role=None, units="si", interval=None) -> str:
    """``value +- half`` (in ``units`` with a ``role``); where that would reach below 0 the
    log-space ``interval`` (the constants are positive: ``value (low-high)``); when the
    data cannot bound it, the value alone."""
    unit = f" {unit_label(role, units)}" if role else ""
    if role:
        value, half = (None if v is None else convert(v, role, units) for v in (value, half))
        if interval is not None:
            interval = [convert(v, role, units) for v in interval]
    if half is None:
        return f"{value:.4g}{unit} (not identified)"
    if half >= value and interval is not None:
        return f"{value:.2g}{unit} ({interval[0]:.2g} to {interval[1]:.2g}: not determined)"
    return f"{value:.4g} +- {half:.2g}{unit}"


def calibration_chart(fit: dict, path, units: str = "si") -> Path:
    """Measured against predicted (with the 1:1 line) and the residuals against roller speed.

    ``fit``: a :class:`webfem.calibrate.Calibration` (or a mapping with its keys);
    ``units``: of the tension difference and the speed.
    """
    tension = fit["measured"] == "delta_T"
    role = "tension" if tension else None
    obs = display_values(fit["observed"], role, units)
    pred = display_values(fit["predicted"], role, units)
    speed = display_values([c.roller.speed for c in fit["cases"]], "speed", units)
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    a.plot(obs, pred, "o", ms=4)
    lim = [min(obs.min(), pred.min()), max(obs.max(), pred.max())]
    a.plot(lim, lim, "k-", lw=0.8)
    name = f"delta_T [{unit_label('tension', units)}]" if tension else "mu [-]"
    a.set_xlabel(f"measured {name}")
    try:   # auto: the models that answered the rows (a mapping may not have them)
        used = list(dict.fromkeys(fit["models_used"]))
    except KeyError:
        used = []
    model = fit["model"] + (f": {', '.join(used)}" if used and used != [fit["model"]] else "")
    a.set_ylabel(f"predicted {name} ({model})")
    try:   # a mapping written before the log-space intervals may not have them
        intervals = fit["interval95"] or {}
    except KeyError:
        intervals = {}
    est = ", ".join(f"{k} = {_pm(v, fit['ci95'][k], ROLES.get(k), units, intervals.get(k))}"
                    for k, v in fit["estimates"].items() if v is not None)
    a.set_title(est + " (95 %)", fontsize=8)
    b.plot(speed, display_values(fit["residuals"], role, units), "o", ms=4)
    b.axhline(0.0, color="k", lw=0.8)
    b.set_xlabel(f"roller speed [{unit_label('speed', units)}]")
    b.set_ylabel(f"predicted - measured {name}")
    rms = f"{float(display_values(fit['rms'], role, units)[0]):.3g}" + (
        f" {unit_label(role, units)}" if role else "")
    b.set_title(f"rms {rms}, {fit['dof']} degrees of freedom", fontsize=8)
    for ax in (a, b):
        ax.grid(True, alpha=0.3)
    return _save(fig, path)
