"""The six sections of a case, validated on creation.

Each section is a frozen dataclass (a :class:`Section`, on the base the model options share,
:class:`webfem.validated.Validated`) whose fields carry their unit and valid interval (or
their valid words) as metadata; :class:`webfem.case.Case` groups one of each. The dotted
keys that name the fields (``roller.speed``) are :mod:`webfem.keys`'. Import the sections
from :mod:`webfem.case`, which re-exports them.

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
import math
import numbers
from dataclasses import dataclass, field
from typing import Any, Mapping

from .errors import InputError, show, unknown_name
from .units import examples, to_si
from .validated import Validated, interval_text, outside, spec

__all__ = ["ALIASES", "SECTIONS", "Air", "Friction", "Model", "Roller", "Section", "Web",
           "Wrap", "physical_ranges", "range_text", "resolve_aliases", "valid_keys"]


def _num(unit: str, lo: float | None = None, hi: float | None = None,
         lo_open: bool = True, hi_open: bool = True, doc: str = "", absent: str = "",
         real: tuple[float | None, float | None] = (None, None)):
    """Field metadata of a number: unit and valid interval; ``absent``, when given, says
    what the key means when it is left out (its value is then None).

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
    return spec(doc, "float", lo=lo, hi=hi, lo_open=lo_open, hi_open=hi_open, unit=unit,
                absent=absent, sign=sign)


def _choice(*options: str, doc: str = ""):
    return spec(doc, "choice", choices=options)


#: False inside :func:`physical_ranges` (False): only the equations' own bounds are checked.
_PHYSICAL: contextvars.ContextVar[bool] = contextvars.ContextVar("webfem_physical_ranges",
                                                                 default=True)


@contextlib.contextmanager
def physical_ranges(on: bool = True):
    """``with physical_ranges(False):`` cases are checked against the equations' bounds only
    (signs, finiteness, a wrap below 360 deg), not the physical ranges of
    :func:`webfem.keys.key_range`. For dimensional-analysis checks, which rescale every key
    as if the case were given in other units (a modulus times 1e12 is no real web, but the
    same physics); never for a user's input.

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


def range_text(meta: Mapping[str, Any]) -> str:
    """The valid range of a numeric case key's metadata as messages state it, e.g.
    ``'must be >= 0.001 and <= 10'`` (in the key's SI unit, ``meta["unit"]``)."""
    return "must be " + (interval_text(meta) or "finite")


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
    try:
        example = examples(key, meta["unit"])[0]
    except Exception:   # noqa: BLE001 - a hint must never replace the error it adds to
        return ""
    return f" (numbers are SI; text with a unit is read too, e.g. '{example}')"


class Section(Validated):
    """A section of a case: its fields are the keys ``SECTION.NAME``, numbers in SI units
    (text with a unit is read too) or words."""

    _name = ""

    @classmethod
    def label(cls, name: str) -> str:
        return f"{cls._name}.{name}"

    @classmethod
    def unknown(cls, name: Any, valid, where: str = "") -> InputError:
        return unknown_name("key", cls.label(str(name)), [cls.label(v) for v in valid], where)

    @classmethod
    def valid_text(cls, meta: Mapping[str, Any]) -> str:
        if meta["kind"] == "choice":
            return super().valid_text(meta)
        return f"{range_text(meta)} [{meta['unit']}]"

    @classmethod
    def invalid(cls, name: str, value: Any, why: str, meta: Mapping[str, Any]) -> InputError:
        key = cls.label(name)
        if meta["kind"] == "choice" or why == "is out of range":
            hint = _si_hint(key, value, meta) if isinstance(value, float) else ""
            return InputError(f"{key} = {show(value)} {why}: {cls.valid_text(meta)}{hint}")
        return InputError(f"{key} = {show(value)} is not a number: expected a value in "
                          f"{meta['unit']} ({range_text(meta)}) or text with a unit")

    @classmethod
    def check(cls, name: str, value: Any, meta: Mapping[str, Any]) -> Any:
        if meta["kind"] == "float":
            if not _PHYSICAL.get() and "sign" in meta:   # the equations' own bounds
                meta = {**meta, **meta["sign"]}
            if type(value) is float:   # the common case: nothing to read
                pass
            elif isinstance(value, str):   # pint is imported only when text is read
                text, value = value, to_si(cls.label(name), value, meta["unit"])
                if outside(value, meta):   # the message shows what the user typed
                    raise InputError(f"{cls.label(name)} = {show(text)} = {value:.6g} "
                                     f"{meta['unit']} is out of range: "
                                     f"{cls.valid_text(meta)}")
            elif isinstance(value, numbers.Real) and not isinstance(value, bool):
                try:   # a key is a float: messages show it as one (-1.0, not -1)
                    value = float(value)
                except OverflowError:   # 10**400: the range check names it
                    pass
        return super().check(name, value, meta)


@dataclass(frozen=True)
class Roller(Section):
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
            raise InputError(f"roller.groove_pitch = {p!r} with roller.groove_width = {g!r}: "
                            "grooves need a pitch: must be > 0 [m] (and > the groove width)")
        if g > 0.0 and g >= p:
            raise InputError(f"roller.groove_width = {g!r} is out of range: must be < "
                            f"roller.groove_pitch = {p!r} [m] (a land must remain)")
        if g > 0.0 and d <= 0.0:
            raise InputError(f"roller.groove_depth = {d!r} with roller.groove_width = {g!r}: "
                            "must be > 0 [m] when the grooves have a width")

    @property
    def grooved(self) -> bool:
        """True when the roller has grooves of some width and depth."""
        return self.groove_width > 0.0 and self.groove_depth > 0.0


@dataclass(frozen=True)
class Web(Section):
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
        "m/s^2", doc="line acceleration a (idler slip check: the web supplies |M_d + J a / "
        "R| of torque; < 0 when the line slows down, the roller's inertia then helping the "
        "drag)", real=(-1e3, 1e3)))


@dataclass(frozen=True)
class Wrap(Section):
    """Wrap ``angle_deg`` B in degrees, 0.1 <= B < 360, and where the web is held beyond
    it: ``ends`` "span" (default: at the neighbouring rollers, a free ``span`` [m] from each
    wrap edge) or "held" (at the ends of the FE models' entry and exit zones, the paper's
    Eq. 20)."""

    _name = "wrap"
    angle_deg: float = field(default=60.0, metadata=_num("deg", 0.0, 360.0,
                                                          doc="wrap angle B",
                                                          real=(0.1, None)))
    span: float | None = field(default=1.0, metadata=_num(
        "m", 0.0, doc="free span from each wrap edge to the neighbouring roller, where the "
        "web is held on its nominal line (the FE models: a straight, unloaded web from the "
        "end of their entry or exit zone to there); used with ends = \"span\"",
        absent="the web held at the ends of the entry and exit zones (as ends = \"held\")",
        real=(1e-3, 100.0)))
    ends: str = field(default="span", metadata=_choice(
        "span", "held", doc="where the web is held: at the neighbouring rollers, span "
        "beyond each wrap edge (span), or at the ends of the entry and exit zones, "
        "w = 0 there (held: the paper's Eq. 20, an artefact of the domain's length for "
        "stiff webs)"))


@dataclass(frozen=True)
class Air(Section):
    """Air ``viscosity`` eta [Pa s] and ``ambient_pressure`` p_a [Pa], its ``mean_free_path``
    [m], ``slip`` flow and ``roughness_flow`` (how the air passes the roughness)."""

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
    roughness_flow: str = field(default="mean-gap", metadata=_choice(
        "mean-gap", "none", doc="air through the roughness: the flow gap E[(h - z)+] and the "
        "mean Couette shear over the wetted area (mean-gap), or h with a numerical floor and "
        "eta U_s / (h + 2 a lambda) (none)"))


@dataclass(frozen=True)
class Friction(Section):
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
class Model(Section):
    """Which physics: ``physics = "full"`` (every effect webfem models, each switchable by
    its own key) or ``"paper"`` (Hashimoto's model exactly: no web inertia, a membrane unless
    web.bending_stiffness is given, no slip flow, the paper's permeation and friction)."""

    _name = "model"
    physics: str = field(default="full", metadata=_choice(
        "full", "paper", doc="every effect webfem models, or the paper's model exactly"))


#: The sections of a case by their TOML table's name.
SECTIONS: dict[str, type[Section]] = {
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
                raise InputError(f"{key} = {show(out[key])} and {alias} = "
                                 f"{show(out[alias])}: give one of them, not both")
            section, name = alias.split(".", 1)
            out[key] = factor * SECTIONS[section].check(name, out.pop(alias), meta)
    return out


def valid_keys() -> list[str]:
    """All dotted case keys, e.g. ``'roller.speed'``."""
    return [f"{s}.{f.name}" for s, cls in SECTIONS.items() for f in dataclasses.fields(cls)]
