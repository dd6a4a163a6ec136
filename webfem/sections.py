"""The six sections of a case, validated on creation, and the dotted keys that name them.

Each section is a frozen dataclass whose fields carry their unit and valid interval (or
their valid words) as metadata; :class:`webfem.case.Case` groups one of each. Import these
names from :mod:`webfem.case`, which re-exports them.

Examples
--------
>>> from webfem.sections import Wrap
>>> Wrap(angle_deg=400)
Traceback (most recent call last):
...
webfem.errors.InputError: wrap.angle_deg = 400.0 is out of range: must be >= 0.1 and < 360 [deg]
"""

from __future__ import annotations

import contextlib
import contextvars
import dataclasses
import difflib
import math
import numbers
import reprlib
from dataclasses import dataclass, field
from typing import Any, Mapping

from .errors import CaseError

__all__ = ["ALIASES", "Air", "Friction", "Model", "Roller", "Web", "Wrap", "resolve_aliases",
           "valid_keys"]

_repr = reprlib.Repr()
_repr.maxlist = _repr.maxtuple = _repr.maxdict = 6
_repr.maxstring = _repr.maxother = 60


def _show(value: Any) -> str:
    """``repr`` for messages: long lists and strings cut, huge integers as ``1.00e+400``."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**20:
        exp = int(math.log10(abs(value)))
        lead = abs(value) // 10 ** (exp - 2)
        if lead >= 1000:  # log10 rounded down across a power of ten
            exp, lead = exp + 1, lead // 10
        return f"{'-' if value < 0 else ''}{lead / 100:.2f}e+{exp}"
    try:
        return _repr.repr(value)
    except ValueError:  # an integer beyond Python's digit limit inside a container
        return f"<{type(value).__name__} holding a number too large to print>"


def _num(unit: str, lo: float | None = None, hi: float | None = None,
         lo_open: bool = True, hi_open: bool = True, doc: str = "", absent: str = "",
         real: tuple[float | None, float | None] = (None, None)):
    """Field metadata: unit and valid interval; ``absent``, when given, says what the key
    means when it is left out (its value is then None).

    ``lo``/``hi`` (None = unbounded) are what the equations need (a positive radius, a
    wrap below 360 deg); ``real`` are closed limits inside them that no real line comes
    near (a radius from 1 mm to 10 m), so that a slip of the keyboard (a roughness of 1 m,
    1e30 anywhere) is refused by name instead of reaching a solver. The stored ``lo``,
    ``hi``, ``lo_open``, ``hi_open`` are the interval checked; ``sign`` keeps the
    equations' own for :func:`physical_ranges` (False).
    """
    sign = {"lo": lo, "hi": hi, "lo_open": lo_open, "hi_open": hi_open}
    rlo, rhi = real
    if rlo is not None and (lo is None or rlo > lo):
        lo, lo_open = rlo, False
    if rhi is not None and (hi is None or rhi < hi):
        hi, hi_open = rhi, False
    return {"unit": unit, "lo": lo, "hi": hi, "lo_open": lo_open, "hi_open": hi_open,
            "doc": doc, "absent": absent, "sign": sign}


#: False inside :func:`physical_ranges` (False): only the equations' own bounds are checked.
_PHYSICAL: contextvars.ContextVar[bool] = contextvars.ContextVar("webfem_physical_ranges",
                                                                 default=True)


@contextlib.contextmanager
def physical_ranges(on: bool = True):
    """``with physical_ranges(False):`` cases are checked against the equations' bounds only
    (signs, finiteness, a wrap below 360 deg), not the physical ranges of
    :func:`key_range`. For dimensional-analysis checks, which rescale every key as if the
    case were given in other units (a modulus times 1e12 is no real web, but the same
    physics); never for a user's input.

    >>> from webfem.sections import Web
    >>> with physical_ranges(False):
    ...     Web(roughness=1.0).roughness
    1.0
    """
    token = _PHYSICAL.set(bool(on))
    try:
        yield
    finally:
        _PHYSICAL.reset(token)


def _checked_meta(meta: Mapping[str, Any]) -> Mapping[str, Any]:
    """The interval checked now: the physical one, or the equations' own inside
    ``physical_ranges(False)``."""
    if _PHYSICAL.get() or "sign" not in meta:
        return meta
    return {**meta, **meta["sign"]}


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


def key_range(key: str) -> str:
    """The valid range of numeric case key ``key`` (an alias too) as the messages state it,
    e.g. ``'must be >= 0.001 and <= 10'``; its unit is :func:`key_unit`'s.

    >>> key_range("web.roughness")
    'must be >= 1e-09 and <= 0.001'
    """
    return _range_text(_meta(key))


def key_unit(key: str) -> str:
    """The SI unit of numeric case key ``key`` (``"m"``, ``"-"`` ...)."""
    return _meta(key)["unit"]


def _meta(key: str) -> Mapping[str, Any]:
    if key in ALIASES:
        return ALIASES[key][2]
    if not _is_key(key):
        raise _unknown(key)
    section, name = key.split(".", 1)
    meta = _SECTIONS[section].__dataclass_fields__[name].metadata
    if "unit" not in meta:
        raise CaseError(f"{key} takes a word ({', '.join(meta['choices'])}), not a number")
    return meta


def _number(key: str, value: Any, meta: Mapping[str, Any]) -> float:
    """``value`` of numeric ``key`` as a float in range: a number in the key's SI unit, or
    text with a unit (``"1200 m/min"``, read by :mod:`webfem.units`)."""
    meta = _checked_meta(meta)
    if isinstance(value, str):
        from .units import to_si   # pint only when text is given: numbers never pay for it
        value = to_si(key, value, meta["unit"])
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise CaseError(f"{key} = {_show(value)} is not a number: expected a value "
                        f"in {meta['unit']} ({_range_text(meta)}) or text with a unit")
    try:
        value = float(value)
    except OverflowError:  # an integer beyond float range (TOML allows 10**400)
        raise CaseError(f"{key} = {_show(value)} is out of range: "
                        f"{_range_text(meta)} [{meta['unit']}]") from None
    lo, hi = meta["lo"], meta["hi"]
    bad = not math.isfinite(value)
    if lo is not None:
        bad |= value <= lo if meta["lo_open"] else value < lo
    if hi is not None:
        bad |= value >= hi if meta["hi_open"] else value > hi
    if bad:
        raise CaseError(f"{key} = {value!r} is out of range: {_range_text(meta)} "
                        f"[{meta['unit']}]{_si_hint(key, value, meta)}")
    return value


def _si_hint(key: str, value: float, meta: Mapping[str, Any]) -> str:
    """For a finite value the equations would take but no real line has (a roughness of
    4 m where 4 um was meant): a reminder that bare numbers are SI, with an example of
    text with a unit."""
    sign = meta.get("sign")
    if sign is None or not math.isfinite(value) or meta["unit"] in ("-", "deg"):
        return ""
    lo, hi = sign["lo"], sign["hi"]
    if (lo is not None and (value <= lo if sign["lo_open"] else value < lo)) or (
            hi is not None and (value >= hi if sign["hi_open"] else value > hi)):
        return ""   # wrong in any unit (a negative width): the range says it all
    if (meta["hi"] is not None and value > 1e9 * max(meta["hi"], 0.0)) or (
            meta["lo"] is not None and 0.0 <= value < 1e-9 * meta["lo"]):
        return ""   # further off than any unit prefix (1e30): no unit slip, a typing one
    from .units import examples   # pint only on this error path
    try:
        example = examples(key, meta["unit"])[0]
    except Exception:   # noqa: BLE001 - a hint must never replace the error it adds to
        return ""
    return f" (numbers are SI; text with a unit is read too, e.g. '{example}')"


class _Section:
    """Shared validation for the frozen section dataclasses."""

    _name = ""

    def __post_init__(self):
        for f in dataclasses.fields(self):
            meta = f.metadata
            key = f"{self._name}.{f.name}"
            value = getattr(self, f.name)
            if value is None and meta.get("absent"):
                continue
            if "choices" in meta:
                if not isinstance(value, str) or value not in meta["choices"]:
                    raise CaseError(f"{key} = {_show(value)} is not valid: must be one of "
                                    + ", ".join(repr(c) for c in meta["choices"]))
                continue
            object.__setattr__(self, f.name, _number(key, value, meta))


@dataclass(frozen=True)
class Roller(_Section):
    """The roller. ``radius`` R [m], surface ``speed`` U_r [m/s], RMS ``roughness`` sigma_r [m]."""

    _name = "roller"
    radius: float = field(default=0.055, metadata=_num("m", 0.0, doc="roller radius R",
                                                            real=(1e-3, 10.0)))
    speed: float = field(default=20.0, metadata=_num("m/s", 0.0, lo_open=False,
                                                      doc="roller surface speed U_r",
                                                      real=(None, 300.0)))
    roughness: float = field(default=0.6e-6, metadata=_num("m", 0.0, lo_open=False,
                                                            doc="RMS roughness sigma_r",
                                                            real=(None, 1e-3)))
    drag_torque: float = field(default=0.0, metadata=_num(
        "N m", 0.0, lo_open=False, doc="bearing and seal drag torque M_d of an undriven "
        "(idler) roller; with inertia, turns on the idler slip check", real=(None, 1e4)))
    inertia: float = field(default=0.0, metadata=_num(
        "kg m^2", 0.0, lo_open=False, doc="moment of inertia J of an idler roller",
        real=(None, 1e6)))
    groove_pitch: float = field(default=0.0, metadata=_num(
        "m", 0.0, lo_open=False, doc="pitch p_g of circumferential grooves, land plus groove "
        "(0: smooth roller)", real=(None, 0.1)))
    groove_width: float = field(default=0.0, metadata=_num(
        "m", 0.0, lo_open=False, doc="width g of a circumferential groove (0: smooth roller)",
        real=(None, 0.1)))
    groove_depth: float = field(default=0.0, metadata=_num(
        "m", 0.0, lo_open=False, doc="depth delta of a circumferential groove", real=(None, 0.02)))

    def __post_init__(self):
        super().__post_init__()
        p, g, d = self.groove_pitch, self.groove_width, self.groove_depth
        if g > 0.0 and p <= 0.0:
            raise CaseError(f"roller.groove_pitch = {p!r} with roller.groove_width = {g!r}: "
                            "grooves need a pitch: must be > 0 [m] (and > the groove width)")
        if g > 0.0 and g >= p:
            raise CaseError(f"roller.groove_width = {g!r} is out of range: must be < "
                            f"roller.groove_pitch = {p!r} [m] (a land must remain)")
        if g > 0.0 and d <= 0.0:
            raise CaseError(f"roller.groove_depth = {d!r} with roller.groove_width = {g!r}: "
                            "must be > 0 [m] when the grooves have a width")

    @property
    def grooved(self) -> bool:
        """True when the roller has grooves of some width and depth."""
        return self.groove_width > 0.0 and self.groove_depth > 0.0


@dataclass(frozen=True)
class Web(_Section):
    """The web (defaults: newsprint of the paper's Table 1).

    ``width`` L [m], ``tension`` T [N/m], ``speed`` U_w [m/s], ``thickness`` t [m],
    ``modulus_thickness`` E_b [Pa], ``modulus_md`` E_m [Pa], RMS ``roughness`` sigma_w [m],
    ``permeability`` k [m^2], ``bending_stiffness`` D [N m] (left out: E_m t^3/12 from the
    material; 0 = membrane, the paper's model), ``density`` rho_w [kg/m^3] (the moving web's
    inertia), ``permeation`` (the Darcy sink's density law), line ``acceleration`` [m/s^2]
    (idler slip check).
    """

    _name = "web"
    width: float = field(default=0.035, metadata=_num("m", 0.0, doc="web width L",
                                                          real=(1e-3, 10.0)))
    tension: float = field(default=80.0, metadata=_num("N/m", 0.0, doc="web tension T",
                                                              real=(None, 1e5)))
    speed: float = field(default=0.0, metadata=_num("m/s", 0.0, lo_open=False,
                                                     doc="web speed U_w", real=(None, 300.0)))
    thickness: float = field(default=70e-6, metadata=_num("m", 0.0, doc="web thickness t",
                                                              real=(1e-6, 0.01)))
    modulus_thickness: float = field(default=175e3, metadata=_num(
        "Pa", 0.0, doc="thickness-direction modulus E_b", real=(100.0, 1e12)))
    modulus_md: float = field(default=4.46e9, metadata=_num("Pa", 0.0, doc="MD modulus E_m",
                                                                  real=(1e5, 1e12)))
    roughness: float = field(default=4.0e-6, metadata=_num("m", 0.0, doc="RMS roughness sigma_w",
                                                                real=(1e-9, 1e-3)))
    permeability: float = field(default=5e-15, metadata=_num("m^2", 0.0, lo_open=False,
                                                             doc="Darcy permeability k",
                                                             real=(None, 1e-8)))
    bending_stiffness: float | None = field(default=None, metadata=_num(
        "N m", 0.0, lo_open=False, doc="bending stiffness D (0 = membrane)",
        absent="D = E_m t^3 / 12 from web.modulus_md and web.thickness", real=(None, 1e4)))
    density: float = field(default=650.0, metadata=_num(
        "kg/m^3", 0.0, lo_open=False, doc="density rho_w; the web turns at the cost of "
        "rho_w t U_w^2 of its tension (T_eff = T - rho_w t U_w^2)", real=(None, 3e4)))
    permeation: str = field(default="isothermal", metadata=_choice(
        "isothermal", "paper", doc="Darcy sink (12 k/t) ((p + p_a)/2) (p - p_a), or the "
        "paper's (12 k/t) p (p - p_a)"))
    acceleration: float = field(default=0.0, metadata=_num(
        "m/s^2", doc="line acceleration a (idler slip check: J a / R of torque; < 0 when "
        "the line slows down)", real=(-1e3, 1e3)))


@dataclass(frozen=True)
class Wrap(_Section):
    """Wrap ``angle_deg`` B in degrees, 0.1 <= B < 360."""

    _name = "wrap"
    angle_deg: float = field(default=60.0, metadata=_num("deg", 0.0, 360.0,
                                                          doc="wrap angle B",
                                                          real=(0.1, None)))


@dataclass(frozen=True)
class Air(_Section):
    """Air ``viscosity`` eta [Pa s] and ``ambient_pressure`` p_a [Pa]."""

    _name = "air"
    viscosity: float = field(default=1.81e-5, metadata=_num("Pa s", 0.0, doc="viscosity eta",
                                                                  real=(1e-6, 1e-3)))
    ambient_pressure: float = field(default=101325.0, metadata=_num(
        "Pa", 0.0, doc="ambient pressure p_a", real=(1e3, 1e7)))
    mean_free_path: float = field(default=65e-9, metadata=_num(
        "m", 0.0, lo_open=False, doc="mean free path of air at p_a (65 nm at 1 atm, 23 C)",
        real=(None, 1e-4)))
    slip: str = field(default="first-order", metadata=_choice(
        "first-order", "none", doc="slip flow: Burgdorfer's first order (a = 1) or none"))


@dataclass(frozen=True)
class Friction(_Section):
    """Friction constants and model variants.

    ``mu_cc`` [-] and ``speed_constant`` C [m/s] are the paper's Eq. 29 constants.
    ``variant``: ``"loads"`` (the default) takes the local traction from the solved loads,
    mu_c p_c + film shear, over T_eff/R; ``"paper"`` reproduces Eqs. 13 and 29 as printed
    (with their jumps at h = h_c and h = 3 sigma); ``"continuous"`` removes the jumps (see
    :mod:`webfem.physics.friction`). ``roughness``: ``"web"`` uses sigma = sigma_w as
    the paper does, ``"composite"`` uses sqrt(sigma_r^2 + sigma_w^2). ``distribution``:
    asperity heights ``"exponential"`` (Eq. 2, the paper's) or ``"gaussian"`` (Eq. 1).
    """

    _name = "friction"
    mu_cc: float = field(default=0.3, metadata=_num("-", 0.0, lo_open=False,
                                                     doc="asperity friction constant mu_cc",
                                                     real=(None, 5.0)))
    speed_constant: float = field(default=0.4, metadata=_num("m/s", 0.0,
                                                             doc="speed constant C",
                                                             real=(None, 1e3)))
    variant: str = field(default="loads", metadata=_choice(
        "loads", "paper", "continuous", doc="friction from the solved loads, Eqs. 13, 29 "
        "as printed, or without their jumps"))
    roughness: str = field(default="web", metadata=_choice(
        "web", "composite", doc="sigma = sigma_w (paper) or sqrt(sigma_r^2 + sigma_w^2)"))
    distribution: str = field(default="exponential", metadata=_choice(
        "exponential", "gaussian", doc="asperity heights: Eq. 2 (paper) or Eq. 1"))


@dataclass(frozen=True)
class Model(_Section):
    """Which physics: ``physics = "full"`` (every effect webfem models, each switchable by
    its own key) or ``"paper"`` (Hashimoto's model exactly: no web inertia, a membrane unless
    web.bending_stiffness is given, no slip flow, the paper's permeation and friction)."""

    _name = "model"
    physics: str = field(default="full", metadata=_choice(
        "full", "paper", doc="every effect webfem models, or the paper's model exactly"))


_SECTIONS: dict[str, type[_Section]] = {
    "roller": Roller, "web": Web, "wrap": Wrap, "air": Air, "friction": Friction,
    "model": Model,
}


#: Keys read at the edge only, each stored as another: alias -> (stored key, factor, field
#: metadata of the alias). A diameter is how the trade names a roller.
ALIASES: dict[str, tuple[str, float, dict]] = {
    "roller.diameter": ("roller.radius", 0.5, _num("m", 0.0, doc="roller diameter 2R, "
                                                    "instead of roller.radius",
                                                    real=(2e-3, 20.0))),
}


def resolve_aliases(values: Mapping[str, Any]) -> Mapping[str, Any]:
    """``values`` with each alias replaced by its stored key (``roller.diameter`` by
    ``roller.radius`` = diameter / 2); an alias given together with its key is an error."""
    if not any(k in ALIASES for k in values):
        return values
    out = dict(values)
    for alias, (key, factor, meta) in ALIASES.items():
        if alias in out:
            if key in out:
                raise CaseError(f"{key} = {_show(out[key])} and {alias} = "
                                f"{_show(out[alias])}: give one of them, not both")
            out[key] = factor * _number(alias, out.pop(alias), meta)
    return out


def valid_keys() -> list[str]:
    """All dotted case keys, e.g. ``'roller.speed'``."""
    return [f"{s}.{f.name}" for s, cls in _SECTIONS.items() for f in dataclasses.fields(cls)]


_KEYS = frozenset(valid_keys())


def _is_key(key: Any) -> bool:
    return isinstance(key, str) and key in _KEYS


def _section_keys(section: str) -> list[str]:
    """The key names of ``section`` (its aliases included), e.g. ``width`` for ``web``."""
    names = [f.name for f in dataclasses.fields(_SECTIONS[section])]
    return names + [a.split(".", 1)[1] for a in ALIASES if a.startswith(section + ".")]


def _where_named(name: str) -> list[str]:
    """The dotted keys (aliases included) whose name is ``name``, in any section."""
    return [f"{s}.{name}" for s in _SECTIONS if name in _section_keys(s)]


def _either(keys: list[str]) -> str:
    return " or ".join(f"'{k}'" for k in keys)


def _unknown(key: Any, where: str = "", table: bool = False) -> CaseError:
    """The error for a name that is no case key: a suggestion only where it exists (a
    section's own keys for ``web.tensoin``; the section that has the key for
    ``roller.tension``; the keys of a section given as a key, ``web=80``). ``table``: the
    name heads a TOML table, so a close section name is what to suggest."""
    key = key if isinstance(key, str) else _show(key)
    head = f"unknown key '{key}'{where}"
    if key in _SECTIONS and not table:
        return CaseError(f"'{key}'{where} is a section, not a key: give {key}.KEY=VALUE with "
                         f"one of its keys: {', '.join(_section_keys(key))}")
    if table:
        close = difflib.get_close_matches(key, list(_SECTIONS), n=1, cutoff=0.5)
        hint = (f"; did you mean '{close[0]}'?" if close
                else "; sections: " + ", ".join(_SECTIONS))
        return CaseError(f"unknown section '{key}'{where}{hint}")
    section, dot, name = key.partition(".")
    if not dot:   # a bare name: the key of some section, or a misspelt one
        owners = _where_named(key)
        if owners:
            return CaseError(f"{head}: '{key}' is a key of a section; did you mean "
                             f"{_either(owners)}?")
        names = sorted({n for s in _SECTIONS for n in _section_keys(s)})
        close = difflib.get_close_matches(key, names, n=1, cutoff=0.6)
        if close:
            return CaseError(f"{head}; did you mean {_either(_where_named(close[0]))}?")
        return CaseError(f"{head}; a key is SECTION.NAME, e.g. web.tension (`webfem keys` "
                         "lists them)")
    if section in _SECTIONS:
        own = _section_keys(section)
        owners = _where_named(name)   # an exact name elsewhere beats a near one here
        if owners:
            of = " and ".join(f"[{o.split('.')[0]}]" for o in owners)
            return CaseError(f"{head}: '{name}' is not a key of [{section}] but of {of}; "
                             f"did you mean {_either(owners)}?")
        close = difflib.get_close_matches(name, own, n=1, cutoff=0.5)
        if close:
            return CaseError(f"{head}; did you mean '{section}.{close[0]}'?")
        return CaseError(f"{head}; the keys of [{section}]: {', '.join(own)}")
    owners = _where_named(name)   # a misspelt section: the key's own section
    close = difflib.get_close_matches(section, list(_SECTIONS), n=1, cutoff=0.5)
    if owners:
        return CaseError(f"{head}; did you mean {_either(owners)}?")
    if close:
        near = difflib.get_close_matches(name, _section_keys(close[0]), n=1, cutoff=0.5)
        if near:
            return CaseError(f"{head}; did you mean '{close[0]}.{near[0]}'?")
    return CaseError(f"{head}; sections: {', '.join(_SECTIONS)} (`webfem keys` lists their "
                     "keys)")


def _flatten(data: Mapping[str, Any], where: str = "") -> dict[str, Any]:
    """``{"roller": {"speed": 1}}`` -> ``{"roller.speed": 1}``, rejecting unknown keys."""
    flat = {}
    for section, table in data.items():
        if section not in _SECTIONS:
            if isinstance(table, Mapping):
                raise _unknown(section, where, table=True)
            flat[section] = table  # dotted key already, checked below
            continue
        if not isinstance(table, Mapping):
            raise CaseError(f"'{section}'{where} must be a table of keys, got {_show(table)}")
        for key, value in table.items():
            flat[f"{section}.{key}"] = value
    for key in flat:
        if not _is_key(key) and key not in ALIASES:
            raise _unknown(key, where)
    return flat

