"""Case description: one web on one roller, in SI units, validated on creation.

A :class:`Case` groups five frozen sections that mirror the TOML tables
``[roller]``, ``[web]``, ``[wrap]``, ``[air]`` and ``[friction]``. Defaults are
the paper's newsprint on its base rig (Hashimoto, Tables 1 and 2; base case of
Figs. 10-13 at 20 m/s).

Examples
--------
>>> from webfem.case import Case
>>> case = Case().updated({"roller.speed": 10.0, "wrap.angle_deg": 40})
>>> round(case.beta, 1)
29.3
>>> Case().updated({"web.width": -1})
Traceback (most recent call last):
...
webfem.case.CaseError: web.width = -1.0 is out of range: must be > 0 [m]
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

__all__ = [
    "Air",
    "Case",
    "CaseError",
    "Friction",
    "Roller",
    "Sweep",
    "Web",
    "Wrap",
    "load_case",
    "load_sweep",
    "parse_assignment",
]


class CaseError(ValueError):
    """An input that webfem rejects; the message names the key, its value and the valid range."""


def _num(unit: str, lo: float | None = None, hi: float | None = None,
         lo_open: bool = True, hi_open: bool = True, doc: str = ""):
    """Field metadata: unit and valid interval (None = unbounded)."""
    return {"unit": unit, "lo": lo, "hi": hi, "lo_open": lo_open, "hi_open": hi_open, "doc": doc}


def _choice(*options: str, doc: str = ""):
    return {"choices": options, "doc": doc}


def _range_text(meta: Mapping[str, Any]) -> str:
    lo, hi = meta["lo"], meta["hi"]
    parts = []
    if lo is not None:
        parts.append(f"{'>' if meta['lo_open'] else '>='} {lo:g}")
    if hi is not None:
        parts.append(f"{'<' if meta['hi_open'] else '<='} {hi:g}")
    return "must be " + " and ".join(parts) if parts else "must be finite"


class _Section:
    """Shared validation for the frozen section dataclasses."""

    _name = ""

    def __post_init__(self):
        for f in dataclasses.fields(self):
            meta = f.metadata
            key = f"{self._name}.{f.name}"
            value = getattr(self, f.name)
            if "choices" in meta:
                if value not in meta["choices"]:
                    raise CaseError(f"{key} = {value!r} is not valid: must be one of "
                                    + ", ".join(repr(c) for c in meta["choices"]))
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise CaseError(f"{key} = {value!r} is not a number: expected a value in "
                                f"{meta['unit']} ({_range_text(meta)})")
            value = float(value)
            object.__setattr__(self, f.name, value)
            lo, hi = meta["lo"], meta["hi"]
            bad = not math.isfinite(value)
            if lo is not None:
                bad |= value <= lo if meta["lo_open"] else value < lo
            if hi is not None:
                bad |= value >= hi if meta["hi_open"] else value > hi
            if bad:
                raise CaseError(f"{key} = {value!r} is out of range: {_range_text(meta)} "
                                f"[{meta['unit']}]")


@dataclass(frozen=True)
class Roller(_Section):
    """The roller. ``radius`` R [m], surface ``speed`` U_r [m/s], RMS ``roughness`` sigma_r [m]."""

    _name = "roller"
    radius: float = field(default=0.055, metadata=_num("m", 0.0, doc="roller radius R"))
    speed: float = field(default=20.0, metadata=_num("m/s", 0.0, lo_open=False,
                                                      doc="roller surface speed U_r"))
    roughness: float = field(default=0.6e-6, metadata=_num("m", 0.0, lo_open=False,
                                                            doc="RMS roughness sigma_r"))


@dataclass(frozen=True)
class Web(_Section):
    """The web (defaults: newsprint of the paper's Table 1).

    ``width`` L [m], ``tension`` T [N/m], ``speed`` U_w [m/s], ``thickness`` t [m],
    ``modulus_thickness`` E_b [Pa], ``modulus_md`` E_m [Pa], RMS ``roughness`` sigma_w [m],
    ``permeability`` k [m^2], ``bending_stiffness`` D [N m] (0 = membrane, the paper's model).
    """

    _name = "web"
    width: float = field(default=0.035, metadata=_num("m", 0.0, doc="web width L"))
    tension: float = field(default=80.0, metadata=_num("N/m", 0.0, doc="web tension T"))
    speed: float = field(default=0.0, metadata=_num("m/s", 0.0, lo_open=False,
                                                     doc="web speed U_w"))
    thickness: float = field(default=70e-6, metadata=_num("m", 0.0, doc="web thickness t"))
    modulus_thickness: float = field(default=175e3, metadata=_num(
        "Pa", 0.0, doc="thickness-direction modulus E_b"))
    modulus_md: float = field(default=4.46e9, metadata=_num("Pa", 0.0, doc="MD modulus E_m"))
    roughness: float = field(default=4.0e-6, metadata=_num("m", 0.0, doc="RMS roughness sigma_w"))
    permeability: float = field(default=5e-15, metadata=_num("m^2", 0.0, lo_open=False,
                                                             doc="Darcy permeability k"))
    bending_stiffness: float = field(default=0.0, metadata=_num(
        "N m", 0.0, lo_open=False, doc="bending stiffness D (0 = membrane)"))


@dataclass(frozen=True)
class Wrap(_Section):
    """Wrap ``angle_deg`` B in degrees, 0 < B < 360."""

    _name = "wrap"
    angle_deg: float = field(default=60.0, metadata=_num("deg", 0.0, 360.0,
                                                          doc="wrap angle B"))


@dataclass(frozen=True)
class Air(_Section):
    """Air ``viscosity`` eta [Pa s] and ``ambient_pressure`` p_a [Pa]."""

    _name = "air"
    viscosity: float = field(default=1.81e-5, metadata=_num("Pa s", 0.0, doc="viscosity eta"))
    ambient_pressure: float = field(default=101325.0, metadata=_num(
        "Pa", 0.0, doc="ambient pressure p_a"))


@dataclass(frozen=True)
class Friction(_Section):
    """Friction constants and model variants.

    ``mu_cc`` [-] and ``speed_constant`` C [m/s] are the paper's Eq. 29 constants.
    ``variant``: ``"paper"`` reproduces Eqs. 13 and 29 as printed (with their jumps at
    h = h_c and h = 3 sigma); ``"continuous"`` removes the jumps (see
    :mod:`webfem.physics.friction`). ``roughness``: ``"web"`` uses sigma = sigma_w as
    the paper does, ``"composite"`` uses sqrt(sigma_r^2 + sigma_w^2). ``distribution``:
    asperity heights ``"exponential"`` (Eq. 2, the paper's) or ``"gaussian"`` (Eq. 1).
    """

    _name = "friction"
    mu_cc: float = field(default=0.3, metadata=_num("-", 0.0, lo_open=False,
                                                     doc="asperity friction constant mu_cc"))
    speed_constant: float = field(default=0.4, metadata=_num("m/s", 0.0,
                                                             doc="speed constant C"))
    variant: str = field(default="paper", metadata=_choice(
        "paper", "continuous", doc="Eqs. 13, 29 as printed, or without their jumps"))
    roughness: str = field(default="web", metadata=_choice(
        "web", "composite", doc="sigma = sigma_w (paper) or sqrt(sigma_r^2 + sigma_w^2)"))
    distribution: str = field(default="exponential", metadata=_choice(
        "exponential", "gaussian", doc="asperity heights: Eq. 2 (paper) or Eq. 1"))


_SECTIONS: dict[str, type[_Section]] = {
    "roller": Roller, "web": Web, "wrap": Wrap, "air": Air, "friction": Friction,
}


def valid_keys() -> list[str]:
    """All dotted case keys, e.g. ``'roller.speed'``."""
    return [f"{s}.{f.name}" for s, cls in _SECTIONS.items() for f in dataclasses.fields(cls)]


def _unknown(key: str, where: str = "") -> CaseError:
    close = difflib.get_close_matches(key, valid_keys() + list(_SECTIONS), n=1, cutoff=0.5)
    hint = f"; did you mean '{close[0]}'?" if close else "; valid keys: " + ", ".join(valid_keys())
    return CaseError(f"unknown key '{key}'{where}{hint}")


def _flatten(data: Mapping[str, Any], where: str = "") -> dict[str, Any]:
    """``{"roller": {"speed": 1}}`` -> ``{"roller.speed": 1}``, rejecting unknown keys."""
    flat = {}
    for section, table in data.items():
        if section not in _SECTIONS:
            if isinstance(table, Mapping):
                raise _unknown(section, where)
            flat[section] = table  # dotted key already, checked below
            continue
        if not isinstance(table, Mapping):
            raise CaseError(f"'{section}'{where} must be a table of keys, got {table!r}")
        for key, value in table.items():
            flat[f"{section}.{key}"] = value
    for key in flat:
        if key not in valid_keys():
            raise _unknown(key, where)
    return flat


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

    def __post_init__(self):
        for name, cls in _SECTIONS.items():
            if not isinstance(getattr(self, name), cls):
                raise CaseError(f"Case.{name} must be a webfem.case.{cls.__name__}")
        if self.roller.speed + self.web.speed <= 0.0:
            raise CaseError("roller.speed = 0 and web.speed = 0: at least one speed must be > 0 "
                            "[m/s] (no air is entrained otherwise)")

    # -- construction -------------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: Mapping[str, Any], where: str = "") -> "Case":
        """Build from nested tables (as in TOML) or dotted keys; unknown keys are errors."""
        return cls().updated(_flatten(data, where))

    def updated(self, values: Mapping[str, Any]) -> "Case":
        """A copy with dotted keys replaced, e.g. ``{"roller.speed": 5.0}``."""
        sections = {name: dataclasses.asdict(getattr(self, name)) for name in _SECTIONS}
        for key, value in values.items():
            if key not in valid_keys():
                raise _unknown(key)
            section, name = key.split(".", 1)
            sections[section][name] = value
        return Case(**{name: _SECTIONS[name](**kw) for name, kw in sections.items()})

    def get(self, key: str) -> Any:
        """Value of a dotted key, e.g. ``case.get("web.tension")``."""
        if key not in valid_keys():
            raise _unknown(key)
        section, name = key.split(".", 1)
        return getattr(getattr(self, section), name)

    def to_dict(self) -> dict[str, dict[str, Any]]:
        """Nested tables, the TOML layout."""
        return {name: dataclasses.asdict(getattr(self, name)) for name in _SECTIONS}

    def to_toml(self) -> str:
        """TOML text that :func:`load_case` reads back to an equal case."""
        lines = []
        for name, table in self.to_dict().items():
            lines.append(f"[{name}]")
            for key, value in table.items():
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

    @property
    def eps(self) -> float:
        """Web speed parameter eps = 6 eta U / T (Eq. 22)."""
        return 6.0 * self.air.viscosity * self.U / self.web.tension

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
        """Permeability parameter kappa = k T B / (eta t R U) (Eq. 22)."""
        w = self.web
        return w.permeability * w.tension * self.B / (
            self.air.viscosity * w.thickness * self.roller.radius * self.U)

    @property
    def p_bar(self) -> float:
        """Wrap pressure T/R [Pa]."""
        return self.web.tension / self.roller.radius

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


@dataclass(frozen=True)
class Sweep:
    """A parameter sweep: one swept dotted key and one or more curve families (series).

    TOML::

        [sweep]
        parameter = "roller.speed"
        start = 0.5
        stop = 40.0
        num = 60            # or: values = [1, 2, 5]; spacing = "linear" | "log"

        [[series]]
        label = "B = 20 deg"
        wrap = { angle_deg = 20 }
    """

    parameter: str
    values: tuple[float, ...]
    series: tuple[tuple[str, Case], ...]

    def points(self):
        """Yield ``(series_label, value, case)`` for every point of every series."""
        for label, base in self.series:
            for value in self.values:
                yield label, value, base.updated({self.parameter: value})


def _sweep_from_dict(case: Case, data: Mapping[str, Any], where: str) -> Sweep:
    import numpy as np

    spec = dict(data.get("sweep", {}))
    allowed = {"parameter", "values", "start", "stop", "num", "spacing"}
    for key in spec:
        if key not in allowed:
            close = difflib.get_close_matches(key, sorted(allowed), n=1)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            raise CaseError(f"unknown key 'sweep.{key}'{where}{hint}")
    parameter = spec.get("parameter", "roller.speed")
    if parameter not in valid_keys():
        raise _unknown(parameter, where + " (sweep.parameter)")
    if "values" in spec:
        values = tuple(float(v) for v in spec["values"])
    elif {"start", "stop"} <= spec.keys():
        num = int(spec.get("num", 40))
        if num < 1:
            raise CaseError(f"sweep.num = {num}{where} is out of range: must be >= 1")
        spacing = spec.get("spacing", "linear")
        if spacing == "log":
            values = tuple(np.geomspace(spec["start"], spec["stop"], num).tolist())
        elif spacing == "linear":
            values = tuple(np.linspace(spec["start"], spec["stop"], num).tolist())
        else:
            raise CaseError(f"sweep.spacing = {spacing!r}{where} is not valid: "
                            "must be 'linear' or 'log'")
    elif "sweep" in data:
        raise CaseError(f"[sweep]{where} needs 'values' or 'start' and 'stop'")
    else:  # default: the paper's speed range
        values = tuple(np.linspace(0.5, 40.0, 60).tolist())
    if not values:
        raise CaseError(f"sweep.values{where} is empty")
    series = []
    for i, entry in enumerate(data.get("series", [])):
        entry = dict(entry)
        label = str(entry.pop("label", f"series {i + 1}"))
        series.append((label, case.updated(_flatten(entry, f"{where} (series '{label}')"))))
    if not series:
        series = [("base", case)]
    # validate every point now so a long sweep does not fail half way
    for label, base in series:
        for value in values:
            try:
                base.updated({parameter: value})
            except CaseError as err:
                raise CaseError(f"{err}{where} (series '{label}', {parameter} = {value:g})") \
                    from None
    return Sweep(parameter, values, tuple(series))


def _read_toml(path: str | Path) -> tuple[dict[str, Any], str]:
    path = Path(path)
    if not path.is_file():
        raise CaseError(f"case file '{path}' does not exist")
    try:
        with path.open("rb") as fh:
            return tomllib.load(fh), f" in {path}"
    except tomllib.TOMLDecodeError as err:
        raise CaseError(f"{path}: malformed TOML: {err}") from None


def load_case(path: str | Path, overrides: Mapping[str, Any] | None = None) -> Case:
    """Read a case TOML file (``[sweep]`` and ``[[series]]`` tables are ignored here)."""
    data, where = _read_toml(path)
    tables = {k: v for k, v in data.items() if k not in ("sweep", "series")}
    case = Case.from_dict(tables, where)
    return case.updated(overrides) if overrides else case


def load_sweep(path: str | Path, overrides: Mapping[str, Any] | None = None) -> Sweep:
    """Read a case TOML file with its ``[sweep]`` and ``[[series]]`` tables."""
    data, where = _read_toml(path)
    case = load_case(path, overrides)
    return _sweep_from_dict(case, data, where)


def parse_assignment(text: str) -> tuple[str, Any]:
    """Parse a CLI ``--set section.key=value`` (value in TOML syntax; bare words are strings).

    >>> parse_assignment("roller.speed=12.5")
    ('roller.speed', 12.5)
    """
    if "=" not in text:
        raise CaseError(f"--set {text!r}: expected section.key=value")
    key, raw = (s.strip() for s in text.split("=", 1))
    if key not in valid_keys():
        raise _unknown(key, " (--set)")
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        value = raw
    return key, value
