"""Case description: one web on one roller, in SI units, validated on creation.

A :class:`Case` groups six frozen sections that mirror the TOML tables ``[roller]``,
``[web]``, ``[wrap]``, ``[air]``, ``[friction]`` and ``[model]``. Defaults are the paper's
newsprint on its base rig (Hashimoto, Tables 1 and 2; base case of Figs. 10-13 at 20 m/s).
The sections are defined in :mod:`webfem.sections` and importable from here; sweeps
(``Sweep``, ``load_sweep``) are in :mod:`webfem.sweepspec` and importable from
:mod:`webfem`. Case files are read strictly: a file that is missing, a directory, not UTF-8
or not TOML, an unknown key or a value out of range is an :class:`InputError` naming it.
Numbers are in SI units; any numeric key also takes text with a unit (``speed = "1200
m/min"``, ``tension = "0.5 pli"``, read by :mod:`webfem.units`), and ``roller.diameter``
may stand for ``roller.radius``.

Examples
--------
>>> from webfem.case import Case
>>> case = Case().updated({"roller.speed": 10.0, "wrap.angle_deg": 40})
>>> round(case.beta, 1)
29.3
>>> Case().updated({"web.width": -1})
Traceback (most recent call last):
...
webfem.errors.InputError: web.width = -1.0 is out of range: must be >= 0.001 and <= 10 [m]
"""

from __future__ import annotations

import dataclasses
import math
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from .errors import CaseError, InputError, show  # CaseError: InputError's old name, for users
from .keys import flatten, is_key, unknown_key, valid_keys
from .physics.validity import THICK_WEB_LIMIT
from .sections import ALIASES, SECTIONS, Air, Friction, Model, Roller, Web, Wrap, resolve_aliases

__all__ = [
    "Air",
    "Case",
    "CaseError",
    "InputError",
    "Friction",
    "Model",
    "Roller",
    "Web",
    "Wrap",
    "case_from_tables",
    "load_case",
    "parse_assignment",
    "read_toml",
    "valid_keys",
]

_MOVED = ("Sweep", "load_sweep", "MAX_VALUES", "MAX_SERIES", "MAX_POINTS")


def __getattr__(name: str):
    # Sweeps are built on cases (webfem.sweepspec imports this module): loading them from
    # here would make the two modules import each other, so the error says where they are.
    if name in _MOVED:
        also = f"; webfem.{name} works too" if name in ("Sweep", "load_sweep") else ""
        raise AttributeError(f"webfem.case.{name} is webfem.sweepspec.{name}{also}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


class AcrossKeys(InputError):
    """A case refused by a check across its keys (the mean free path against the roughness
    flow, the web's thickness against the roller's radius, the tension against the web's
    inertia), which another key may mend: a ``--set`` or a sweep's series."""


@dataclass(frozen=True)
class Case:
    """A complete operating point: roller, web, wrap, air and friction constants.

    Derived quantities follow the paper's Eq. 22 with U = U_r + U_w (entrainment) and
    U_s = |U_r - U_w| (sliding); see ``docs`` in the README.

    Examples
    --------
    >>> c = Case()
    >>> f"{c.eps:.3e}", f"{c.lam:.2f}"
    ('2.715e-05', '10.59')
    """

    roller: Roller = field(default_factory=Roller)
    web: Web = field(default_factory=Web)
    wrap: Wrap = field(default_factory=Wrap)
    air: Air = field(default_factory=Air)
    friction: Friction = field(default_factory=Friction)
    model: Model = field(default_factory=Model)

    def __post_init__(self):
        for name, cls in SECTIONS.items():
            if not isinstance(getattr(self, name), cls):
                got = type(getattr(self, name)).__name__
                raise InputError(
                    f"Case.{name} must be a webfem.case.{cls.__name__}, not a {got}: build a "
                    f"case from tables with Case.from_dict({{'{name}': {{...}}}}) or change "
                    f"keys with Case().updated({{'{name}.KEY': value}})")
        if self.roller.speed + self.web.speed <= 0.0:
            raise InputError("roller.speed = 0 and web.speed = 0: at least one speed must be > 0 "
                            "[m/s] (no air is entrained otherwise)")
        t, R = self.web.thickness, self.roller.radius
        if t / (2.0 * R) > THICK_WEB_LIMIT:
            raise AcrossKeys(
                f"web.thickness = {t:g} m on roller.radius = {R:g} m: t/(2R) = {t / (2 * R):.3g}"
                f", the web would bend to an outer-fibre strain of {100 * t / (2 * R):.3g} % "
                "and the thin-web model (its tension at the film's surface, wrap pressure "
                f"T/R) is off by as much; valid: t/(2R) <= {THICK_WEB_LIMIT:g}, "
                f"web.thickness <= {2 * THICK_WEB_LIMIT * R:.3g} m on this roller or "
                f"roller.radius >= {t / (2 * THICK_WEB_LIMIT):.3g} m for this web")
        if self.air.mean_free_path == 0.0 and self.roughness_flow_model == "mean-gap":
            # the air sheared between the asperities is cut off at contact only at the
            # molecular scale 2 a lambda: without it the mean Couette shear diverges
            raise AcrossKeys(
                "air.mean_free_path = 0 m with air.roughness_flow = mean-gap: the air "
                "sheared between the asperities then has no molecular cut-off and its shear "
                "(so mu) is infinite; valid: air.mean_free_path > 0 m (6.5e-08 m at 1 atm, "
                "at most 0.0001 m), or air.roughness_flow = none (the film gap h with a "
                "numerical floor) or model.physics = paper")
        if self.tension_eff <= 0.0:
            w = self.web
            raise AcrossKeys(
                f"web.speed = {w.speed:g} m/s: the web cannot be held on the roller at that "
                f"speed: turning it takes rho_w t U_w^2 = {self.web_inertia:.4g} N/m, at least "
                f"its tension web.tension = {w.tension:g} N/m (raise the tension above "
                f"{self.web_inertia:.4g} N/m or lower web.speed below "
                f"{math.sqrt(w.tension / (w.density * w.thickness)):.4g} m/s)")

    # -- construction -------------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: Mapping[str, Any], where: str = "") -> "Case":
        """Build from nested tables (as in TOML) or dotted keys; unknown keys are errors."""
        try:
            return cls().updated(flatten(data, where))
        except InputError as err:
            if where and where not in str(err):
                raise type(err)(f"{err}{where}") from None
            raise

    def updated(self, values: Mapping[str, Any]) -> "Case":
        """A copy with dotted keys replaced, e.g. ``{"roller.speed": 5.0}``; values may be
        text with units (``"1200 m/min"``) and ``roller.diameter`` may stand for
        ``roller.radius``."""
        changed: dict[str, dict[str, Any]] = {}
        for key, value in resolve_aliases(values).items():
            if not is_key(key):
                raise unknown_key(key)
            section, name = key.split(".", 1)
            if section not in changed:
                changed[section] = dataclasses.asdict(getattr(self, section))
            changed[section][name] = value
        # untouched sections are frozen and valid: share them (sweeps build many cases)
        return dataclasses.replace(self, **{section: SECTIONS[section](**kw)
                                            for section, kw in changed.items()})

    def get(self, key: str) -> Any:
        """Value of a dotted key, e.g. ``case.get("web.tension")``."""
        if not is_key(key):
            raise unknown_key(key)
        section, name = key.split(".", 1)
        return getattr(getattr(self, section), name)

    def to_dict(self) -> dict[str, dict[str, Any]]:
        """Nested tables, the TOML layout."""
        return {name: dataclasses.asdict(getattr(self, name)) for name in SECTIONS}

    def to_toml(self) -> str:
        """TOML text that :func:`load_case` reads back to an equal case."""
        lines = []
        for name, table in self.to_dict().items():
            lines.append(f"[{name}]")
            for key, value in table.items():
                if value is not None:   # an absent key (e.g. D from the material)
                    lines.append(f"{key} = {_toml_value(value)}")
            lines.append("")
        return "\n".join(lines)

    # -- derived quantities (SI) ---------------------------------------------------------
    @property
    def U(self) -> float:
        """Entrainment speed U = U_r + U_w [m/s]; drives the air film."""
        return self.roller.speed + self.web.speed

    @property
    def U_slide(self) -> float:
        """Sliding speed U_s = |U_r - U_w| [m/s]; drives shear and asperity friction."""
        return abs(self.roller.speed - self.web.speed)

    @property
    def B(self) -> float:
        """Wrap angle [rad]."""
        return math.radians(self.wrap.angle_deg)

    # -- which physics ---------------------------------------------------------------------
    @property
    def paper_physics(self) -> bool:
        """True when ``model.physics = "paper"``: Hashimoto's model exactly."""
        return self.model.physics == "paper"

    @property
    def span_used(self) -> float | None:
        """The span [m] through which the models hold the web beyond their entry and exit
        zones (``wrap.span``), or None where they hold it at the zones' ends (the paper's
        Eq. 20): ``wrap.ends = "held"``, a span left out, or the paper's physics."""
        if self.paper_physics or self.wrap.ends == "held":
            return None
        return self.wrap.span

    @property
    def web_inertia(self) -> float:
        """Tension the moving web spends turning around the roller, rho_w t U_w^2 [N/m]
        (0 with the paper's physics)."""
        if self.paper_physics:
            return 0.0
        return self.web.density * self.web.thickness * self.web.speed**2

    @property
    def tension_eff(self) -> float:
        """Effective tension T_eff = T - rho_w t U_w^2 [N/m]: what the wrap pressure, the
        web equation, the scaling and the belt formula see."""
        return self.web.tension - self.web_inertia

    @property
    def bending_used(self) -> float:
        """Bending stiffness D the models use [N m]: ``web.bending_stiffness`` when given,
        else 0 with the paper's physics, else E_m t^3 / 12 from the material."""
        if self.web.bending_stiffness is not None:
            return self.web.bending_stiffness
        if self.paper_physics:
            return 0.0
        return self.web.modulus_md * self.web.thickness**3 / 12.0

    @property
    def slip_model(self) -> str:
        """Slip flow used: ``air.slip``, or "none" with the paper's physics."""
        return "none" if self.paper_physics else self.air.slip

    @property
    def roughness_flow_model(self) -> str:
        """Air through the roughness: ``air.roughness_flow``, or "none" with the paper's
        physics."""
        return "none" if self.paper_physics else self.air.roughness_flow

    @property
    def permeation_model(self) -> str:
        """Darcy sink used: ``web.permeation``, or "paper" with the paper's physics."""
        return "paper" if self.paper_physics else self.web.permeation

    @property
    def friction_variant(self) -> str:
        """Friction model used: ``friction.variant``; "loads" becomes "paper" with the
        paper's physics."""
        v = self.friction.variant
        return "paper" if (v == "loads" and self.paper_physics) else v

    @property
    def grooved(self) -> bool:
        """True when the roller has circumferential grooves (width and depth > 0)."""
        return self.roller.grooved

    @property
    def land_fraction(self) -> float:
        """Share of the roller surface that is land, 1 - groove_width/groove_pitch (1 for a
        smooth roller)."""
        r = self.roller
        return 1.0 - r.groove_width / r.groove_pitch if r.groove_width > 0.0 else 1.0

    @property
    def eps(self) -> float:
        """Web speed parameter eps = 6 eta U / T_eff (Eq. 22, with the effective tension)."""
        return 6.0 * self.air.viscosity * self.U / self.tension_eff

    @property
    def lam(self) -> float:
        """Width parameter lambda = L / (2 R eps^(1/3)) (Eq. 22)."""
        return self.web.width / (2.0 * self.roller.radius * self.eps ** (1 / 3))

    @property
    def beta(self) -> float:
        """Wrap parameter beta = B / eps^(1/3) (Eq. 22)."""
        return self.B / self.eps ** (1 / 3)

    @property
    def kappa(self) -> float:
        """Permeability parameter kappa = k T_eff B / (eta t R U) (Eq. 22)."""
        w = self.web
        return w.permeability * self.tension_eff * self.B / (
            self.air.viscosity * w.thickness * self.roller.radius * self.U)

    @property
    def p_bar(self) -> float:
        """Wrap pressure T_eff/R [Pa]."""
        return self.tension_eff / self.roller.radius

    @property
    def sigma(self) -> float:
        """Roughness used by the contact model [m] (see ``friction.roughness``)."""
        if self.friction.roughness == "composite":
            return math.hypot(self.roller.roughness, self.web.roughness)
        return self.web.roughness

    @property
    def h_scale(self) -> float:
        """Film thickness scale R eps^(2/3) [m]."""
        return self.roller.radius * self.eps ** (2 / 3)

    @property
    def x_scale(self) -> float:
        """Entry-zone length scale R eps^(1/3) [m]."""
        return self.roller.radius * self.eps ** (1 / 3)


def _toml_value(value: Any) -> str:
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)  # shortest round-trip form
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return str(value)


def read_toml(path: str | Path) -> tuple[dict[str, Any], str]:
    """The tables of a TOML case file and the ``" in FILE"`` suffix for messages.

    Raises
    ------
    InputError
        Naming the file: missing, a directory, unreadable, not UTF-8 or not TOML.
    """
    path = Path(path)
    if path.is_dir():
        raise InputError(f"case file '{path}' is a directory: give a .toml file")
    if not path.exists():
        raise InputError(f"case file '{path}' does not exist")
    if not path.is_file():
        raise InputError(f"case file '{path}' is not a regular file: give a .toml file")
    try:
        raw = path.read_bytes()
    except OSError as err:
        raise InputError(f"case file '{path}' cannot be read: {err.strerror or err}") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        line = raw[:err.start].count(b"\n") + 1
        raise InputError(f"case file '{path}' is not UTF-8 text (byte 0x{raw[err.start]:02x} "
                        f"on line {line}): save it as UTF-8") from None
    try:
        # a byte-order mark (some Windows editors write one) is not TOML but harmless
        return tomllib.loads(text.removeprefix("\ufeff")), f" in {path}"
    except tomllib.TOMLDecodeError as err:
        raise InputError(f"{path}: malformed TOML: {err}") from None
    except ValueError:  # an integer literal beyond Python's digit limit (4300 digits)
        raise InputError(f"{path}: a number is out of range (an integer of more than "
                        f"{sys.get_int_max_str_digits()} digits)") from None


def case_from_tables(data: Mapping[str, Any], where: str,
                     overrides: Mapping[str, Any] | None = None) -> Case:
    """The case of a case file's tables (as :func:`read_toml` gives them; ``[sweep]`` and
    ``[[series]]`` are left to :func:`webfem.sweepspec.load_sweep`), with ``overrides``
    (dotted keys) applied; ``where`` (" in FILE") ends the messages."""
    tables = {k: v for k, v in data.items() if k not in ("sweep", "series")}
    if overrides:
        # the checks across keys (e.g. the mean free path against the roughness flow) must
        # see the overrides, or a --set that mends the file's case could never be applied
        try:
            # both resolved: the file's roller.diameter and an override's roller.radius
            # are one key
            return Case.from_dict({**resolve_aliases(flatten(tables, where)),
                                   **resolve_aliases(overrides)})
        except InputError as err:
            final = err
        try:
            case = Case.from_dict(tables, where)
        except InputError as err:
            if str(err).startswith(str(final)):   # the file's own fault: name the file
                raise
            raise final from None
        return case.updated(overrides)
    return Case.from_dict(tables, where)


def load_case(path: str | Path, overrides: Mapping[str, Any] | None = None) -> Case:
    """Read a case TOML file (``[sweep]`` and ``[[series]]`` tables are ignored here)."""
    return case_from_tables(*read_toml(path), overrides)


def parse_assignment(text: str) -> tuple[str, Any]:
    """Parse a CLI ``--set section.key=value`` (value in TOML syntax; anything else, such as
    a number with a unit, is kept as text for the case to read).

    >>> parse_assignment("roller.speed=12.5")
    ('roller.speed', 12.5)
    >>> parse_assignment("roller.speed=1200 m/min")
    ('roller.speed', '1200 m/min')
    """
    if "=" not in text:
        raise InputError(f"--set {show(text)}: expected section.key=value")
    key, raw = (s.strip() for s in text.split("=", 1))
    if not is_key(key) and key not in ALIASES:
        raise unknown_key(key, " (--set)")
    if "\n" in raw or "\r" in raw:  # TOML would read the next line as more keys
        raise InputError(f"--set {key} = {show(raw)}: the value must be on one line")
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except ValueError:  # not TOML (a bare word), or an integer past the digit limit
        value = raw
    return key, value
