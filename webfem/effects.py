"""What each effect does: the case solved with each effect it includes switched off in turn.

"Model no more than a scene needs": the table says which effects move the answer for a
case and by how much, so a user sees which the scene needs (:mod:`webfem.physics.effects`
names the effects and the keys that switch them off).

Examples
--------
>>> from webfem import Case
>>> table = effects_table(Case().updated({"roller.speed": 40.0}), "closed-form")
>>> [row.effect for row in table.rows]
['all included', 'bending', 'slip', 'isothermal-permeation', 'load-friction', 'roughness-flow', 'spans']
>>> table.not_carried                  # the closed form cannot carry these
('bending', 'slip', 'isothermal-permeation', 'spans')

With ``model="auto"`` the full case is solved with auto, and every variant with the model
auto chose for it (and that model's options): a variant answered by another model would
mix a model change into the effect's change, and the closed form, which cannot carry
bending, would show bending as changing nothing.
"""

from __future__ import annotations

import math

from dataclasses import dataclass

from .api import solve
from .case import Case
from .models.options import fe_options
from .models.registry import make_options, model_spec
from .physics.effects import SWITCH_OFF, included
from .units import ROLES, convert, unit_label

__all__ = ["EffectRow", "EffectsTable", "effects_table", "answered_by"]


def answered_by(result, model: str, options):
    """``(name, options)`` of the model that answered ``result`` when ``model`` was asked
    with ``options``: the model itself, or the one auto chose, with the options it solved
    with (the result's own, else the FE options the auto options carry).

    >>> import webfem
    >>> r = webfem.solve(webfem.Case().updated({"roller.speed": 2.0}), model="auto")
    >>> answered_by(r, "auto", None)[0] == r.summary.model_used
    True
    """
    used = result.summary.model_used or result.summary.model
    if used == model:
        return model, make_options(model, options)
    kind = model_spec(used).options
    own = getattr(result.diagnostics, "options", None)
    if isinstance(own, kind):
        return used, own
    if used == "closed-form":
        return used, kind()
    return used, fe_options(make_options(model, options), kind)


@dataclass(frozen=True)
class EffectRow:
    """One solve: the ``effect`` switched off (or "all included"), the keys changed, the
    gaps [m] and mu, and their relative changes against the solve with every effect (for a
    mu below 1e-3, as on an idler where nothing slides, the change of mu is absolute), and
    an idler's slip margin."""

    effect: str
    switched: dict
    h_center: float
    h_min: float
    mu: float
    d_h_center: float
    d_h_min: float
    d_mu: float
    slip_margin: float | None = None

    def to_dict(self) -> dict:
        return dict(self.__dict__)


@dataclass(frozen=True)
class EffectsTable:
    """The rows of :func:`effects_table`, the model that answered, and the effects of the
    case that this model cannot carry (switching them off changes nothing there).

    ``asked``: the model asked for (``"auto"``, or ``model`` itself); ``why``: auto's reason
    for its choice on the full case (None when a model was named)."""

    model: str
    rows: tuple[EffectRow, ...]
    not_carried: tuple[str, ...] = ()
    asked: str = ""
    why: str | None = None
    #: The full answer's stated errors (``error_h_center``, ``error_h_min``, ``error_mu``):
    #: a change below them is within what the model can tell apart.
    errors: dict | None = None
    #: Why the slip margin column is missing though the case states an idler load (the web
    #: slides: no model judges an idler from a sliding film; None where it is shown or
    #: no load is stated).
    margin_note: str | None = None

    def to_dict(self) -> dict:
        return {"model": self.model, "rows": [r.to_dict() for r in self.rows],
                "not_carried": list(self.not_carried), "asked": self.asked or self.model,
                "why": self.why, "errors": {k: v if v is not None and math.isfinite(v)
                                            else None for k, v in (self.errors or {}).items()}}

    def text(self, units: str = "si") -> str:
        """A fixed-width table: how much switching each effect off moves the answer, the gaps
        in ``units`` ("si" and "metric": um, "us": mil)."""
        gap = unit_label(ROLES["h_center"], units)
        w1, w2 = max(12, len(gap) + 10), max(10, len(gap) + 7)    # um: as before
        idler = self.rows[0].slip_margin is not None
        chosen = (f" (auto's choice for the full case; every row solved with {self.model})"
                  if self.asked and self.asked != self.model else "")
        lines = [f"effects on {self.model}{chosen}: the answer with every effect, then with "
                 "each one switched off (change relative to all included)"]
        if chosen and self.why:
            lines.append(f"  why {self.model}: {self.why}")
        lines.append(f"  {'effect switched off':<24}{'h_center ' + gap:>{w1}}{'h_min ' + gap:>{w2}}"
                     f"{'mu':>9}{'d h_center':>12}{'d h_min':>10}{'d mu':>10}"
                     + (f"{'slip margin':>13}" if idler else ""))
        small_mu = abs(self.rows[0].mu) < 1e-3
        for r in self.rows:
            d_mu = (("-" if r.d_mu == 0 else f"{r.d_mu:+.4f}") if small_mu else _pct(r.d_mu))
            h_c, h_m = (convert(v, ROLES["h_center"], units) for v in (r.h_center, r.h_min))
            lines.append(f"  {r.effect:<24}{h_c:>{w1}.3f}{h_m:>{w2}.3f}"
                         f"{r.mu:>9.4f}{_pct(r.d_h_center):>12}{_pct(r.d_h_min):>10}"
                         f"{d_mu:>10}" + (f"{_margin(r.slip_margin):>13}" if idler else ""))
        if small_mu:
            lines.append("  (mu below 1e-3: its change is absolute, not relative)")
        known = {k: v for k, v in (self.errors or {}).items() if v is not None}
        if known:
            lines.append("  stated errors of the full answer: " + ", ".join(
                f"{k.removeprefix('error_')} {v:.2g}" for k, v in known.items())
                + " (a smaller change is within them)")
        if self.not_carried:
            lines.append(f"  ({', '.join(self.not_carried)}: not carried by {self.model})")
        if self.margin_note:
            lines.append(f"  ({self.margin_note})")
        return "\n".join(lines)


def _pct(x: float) -> str:
    return "-" if x == 0.0 else f"{100 * x:+.2f} %"


def _rel(a: float, b: float) -> float:
    return (a - b) / b if b else 0.0


def effects_table(case: Case, model: str = "fe2d", options=None, progress=None,
                  **values) -> EffectsTable:
    """Solve ``case`` with every effect it includes, then with each switched off in turn.

    ``progress(done, total)`` is called after each solve. Raises what :func:`webfem.solve`
    raises (an effect switched off may leave a case with no admissible solution).
    """
    opts = make_options(model, options, **values)
    effects = included(case)
    total = 1 + len(effects)
    base = solve(case, model, options=opts)
    asked, why = model, base.summary.why
    # the variants go to the model that answered the full case (auto's choice), so that a
    # row's change is the effect's, not a change of model
    model, opts = answered_by(base, model, opts)
    carried = tuple(base.summary.effects)
    rows = [EffectRow("all included", {}, base["h_center"], base["h_min"], base["mu"],
                      0.0, 0.0, 0.0, base["slip_margin"])]
    if progress:
        progress(1, total)
    for i, effect in enumerate(effects, start=2):
        switched = SWITCH_OFF[effect]
        r = solve(case.updated(switched), model, options=opts)
        d_mu = (r["mu"] - base["mu"] if abs(base["mu"]) < 1e-3
                else _rel(r["mu"], base["mu"]))
        rows.append(EffectRow(effect, dict(switched), r["h_center"], r["h_min"], r["mu"],
                              _rel(r["h_center"], base["h_center"]),
                              _rel(r["h_min"], base["h_min"]), d_mu, r["slip_margin"]))
        if progress:
            progress(i, total)
    missing = tuple(e for e in effects if e not in carried)
    errors = {f"error_{q}": base.summary.get(f"error_{q}")
              for q in ("h_center", "h_min", "mu")}
    note = ("slip margin: not judged, the web slides on the roller (an idler turns with it): "
            "`webfem idler`, or `webfem solve` at roller.speed = web.speed, judges it"
            if base.summary.get("delta_T_required") is not None
            and base.summary.get("slip_margin") is None else None)
    return EffectsTable(model, tuple(rows), missing, asked=asked,
                        why=why if asked != model else None, errors=errors, margin_note=note)


def _margin(value) -> str:
    """A slip margin as the table prints it: 3 digits, ``< 0.001`` below (the JSON keeps
    the number), ``-`` where there is none."""
    from .describe import small_text
    return "-" if value is None else small_text(value, ".3g")
