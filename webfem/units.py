"""Units at the edges: text with units in, SI floats inside, the trade's units out.

A case key holds an SI float. At the edge (TOML, ``--set``, ``Case.updated``) it may also
be given as text with a unit, ``"1200 m/min"``, ``"0.5 pli"``, ``"4 um"``, ``"2.5 in"``,
``"60 deg"``, ``"1.27e-4 N*m"``, which :func:`to_si` reads with pint and converts to the
key's SI unit. Plain numbers never reach this module, so pint is imported only when a
string is read. :func:`display` formats SI values in one of :data:`SYSTEMS` for printing,
with fixed factors (no pint); :func:`convert` and :func:`unit_label` serve charts, and
:func:`table_in_units` turns a table of SI numbers into one in metric or US units whose
column names end in their unit (``h_center_mil``): the one place where webfem converts what
it writes. :data:`ROLES` says what each quantity webfem writes measures.

Besides pint's units: ``pli`` (pound-force per linear inch, the US unit of web tension),
``fpm`` (feet per minute), and ``mil`` is a thousandth of an inch (pint's ``mil`` is an
angle).

Examples
--------
>>> to_si("roller.speed", "1200 m/min", "m/s")
20.0
>>> round(to_si("web.tension", "0.5 pli", "N/m"), 3)
87.563
>>> to_si("web.tension", "3 m", "N/m")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
webfem.errors.InputError: web.tension = '3 m' has dimension length; expected force/length, ...
>>> display(20.0, "speed", "us")
'3937 ft/min'
"""

from __future__ import annotations

import functools
import math
import re

from .errors import InputError, show

__all__ = ["SYSTEMS", "KINDS", "ROLES", "to_si", "examples", "kind_of", "display", "convert",
           "unit_label", "column_name", "table_in_units"]

#: The display systems of ``--units``.
SYSTEMS = ("si", "metric", "us")

#: What each SI unit of a case key measures, as named in messages.
KINDS = {
    "m": "length", "m/s": "speed", "N/m": "force/length", "Pa": "pressure",
    "Pa s": "viscosity", "m^2": "area", "N m": "torque", "kg m^2": "moment of inertia",
    "kg/m^3": "density", "m/s^2": "acceleration", "deg": "angle", "-": "no unit",
}
# further names for what a user may give by mistake (messages only)
_OTHER_KINDS = {"N": "force", "kg": "mass", "s": "time", "J/s": "power", "m^3": "volume",
                "1/s": "frequency", "kg/m^2": "mass/area", "m^2/s": "area/time"}

_EXAMPLES_BY_UNIT = {
    "m": ("4 um", "2.5 in"), "m/s": ("1200 m/min", "3900 ft/min"),
    "N/m": ("80 N/m", "0.45 pli"), "Pa": ("175 kPa", "25 psi"),
    "Pa s": ("1.81e-5 Pa*s", "0.0181 cP"), "m^2": ("5e-15 m^2", "5e-9 mm^2"),
    "N m": ("1.27e-4 N*m", "0.0011 lbf*in"), "kg m^2": ("0.002 kg*m^2", "6.8 lb*in^2"),
    "kg/m^3": ("650 kg/m^3", "40 lb/ft^3"), "m/s^2": ("0.5 m/s^2", "1.6 ft/s^2"),
    "deg": ("60 deg", "1.05 rad"), "-": ("0.3", "30 %"),
}
#: Examples per key where the unit's own would mislead (a radius is not microns).
_EXAMPLES_BY_KEY = {
    "roller.radius": ("55 mm", "2.17 in"), "roller.diameter": ("110 mm", "4.33 in"),
    "roller.roughness": ("0.6 um", "24 uin"), "web.width": ("35 mm", "1.38 in"),
    "web.thickness": ("70 um", "2.76 mil"), "web.roughness": ("4 um", "0.16 mil"),
    "web.modulus_md": ("4.46 GPa", "647 ksi"), "air.ambient_pressure": ("101.325 kPa",
                                                                          "14.7 psi"),
    "air.mean_free_path": ("65 nm", "2.56 uin"),
    "roller.drag_torque": ("0.05 N*m", "0.44 lbf*in"),
    "friction.speed_constant": ("0.4 m/s", "79 ft/min"),
    "roller.groove_pitch": ("1.27 mm", "0.05 in"), "roller.groove_width": ("0.6 mm", "0.024 in"),
    "roller.groove_depth": ("0.25 mm", "0.01 in"), "wrap.span": ("1 m", "40 in"),
}
_NUMBER_FIRST = re.compile(r"\s*[-+]?(\d|\.\d)")
_MIL = re.compile(r"(?<![A-Za-z_])mils?(?![A-Za-z_])")
#: Digits on both sides of a comma or a space: pint reads '1,5 m/s' as 15 m/s (the comma a
#: thousands separator) and '1 500 m/min' as 1 x 500 m/min, so a decimal comma or a grouped
#: number would be taken silently at another value.
_SPLIT_NUMBER = re.compile(r"\d\s*,\s*\d|\d\s+\d")


def examples(key: str, unit: str) -> tuple[str, str]:
    """Two accepted spellings for ``key`` (SI unit ``unit``), metric first, then US."""
    return _EXAMPLES_BY_KEY.get(key) or _EXAMPLES_BY_UNIT.get(unit, (f"1 {unit}",) * 2)


def kind_of(unit: str) -> str:
    """What ``unit`` (a case key's SI unit) measures, e.g. ``"force/length"``."""
    return KINDS.get(unit, unit)


@functools.lru_cache(maxsize=1)
def _registry():
    import pint   # here, not at the top: only text with units pays for it

    ureg = pint.UnitRegistry()
    ureg.define("pli = pound_force / inch = PLI = Pli")
    ureg.define("fpm = foot / minute = FPM")
    return ureg


@functools.lru_cache(maxsize=None)
def _dims(unit: str):
    ureg = _registry()
    return ureg.Unit("dimensionless" if unit == "-" else unit).dimensionality


def _dimension_name(q) -> str:
    for table in (KINDS, _OTHER_KINDS):
        for unit, name in table.items():
            if unit not in ("deg", "-") and q.dimensionality == _dims(unit):
                return name
    text = "*".join(f"{d.strip('[]')}^{p:g}".replace("^1", "") if p > 0 else ""
                    for d, p in q.dimensionality.items()).strip("*")
    per = "*".join(f"{d.strip('[]')}^{-p:g}".replace("^1", "") for d, p in
                   q.dimensionality.items() if p < 0)
    return (text or "1") + (f"/{per}" if per else "")


def _is_angle(q) -> bool:
    return q.dimensionless and "radian" in str(q.to_base_units().units)


def to_si(key: str, text: str, unit: str) -> float:
    """The value of ``text`` (a number and a unit) in ``unit``, the SI unit of ``key``.

    Raises
    ------
    InputError
        Naming the key, the text and what it expects: not a number with a unit, an unknown
        unit, or the wrong dimension (``'3 m'`` for a tension).
    """
    e1, e2 = examples(key, unit)
    expect = f"expected {kind_of(unit)}, e.g. '{e1}' or '{e2}'"
    shown = show(text)
    if not _NUMBER_FIRST.match(text):
        raise InputError(f"{key} = {shown} is not a number: give a number and a unit; "
                         f"{expect}")
    if _SPLIT_NUMBER.search(text):
        raise InputError(f"{key} = {shown} has a comma or a space between digits, which "
                         "could be a decimal comma or a thousands separator: write one "
                         f"number with a decimal point and no separators; {expect}")
    ureg = _registry()
    try:
        q = ureg.Quantity(_MIL.sub("thou", text.strip()))
    except Exception as err:   # pint raises many kinds (undefined unit, syntax, ValueError)
        names = getattr(err, "unit_names", None)
        why = (f"unknown unit {', '.join(map(repr, names))}" if names
               else "cannot be read")
        raise InputError(f"{key} = {shown} is not a number with a unit ({why}); {expect}") \
            from None
    if not isinstance(q, ureg.Quantity) or not isinstance(q.magnitude, (int, float)):
        raise InputError(f"{key} = {shown} is not a number with a unit; {expect}")
    if not q._units:   # a bare number in quotes: likely a slip, and which unit is unclear
        bare = "" if unit == "-" else f", in {unit}"
        raise InputError(f"{key} = {shown} is not a number: quoted text needs a unit, "
                         f"e.g. '{e2 if unit == '-' else e1}' (or give the number unquoted{bare})")
    if unit == "deg":
        fits = _is_angle(q)
    elif unit == "-":
        fits = q.dimensionless and not _is_angle(q)
    else:
        fits = q.dimensionality == _dims(unit)
    if not fits:
        got = "angle" if _is_angle(q) else ("no unit" if q.dimensionless
                                             else _dimension_name(q))
        raise InputError(f"{key} = {shown} has dimension {got}; {expect}")
    target = {"-": "dimensionless", "deg": "degree"}.get(unit, unit)
    magnitude = q.to(target).magnitude
    try:
        return float(magnitude)
    except OverflowError:   # the key's range check then names it
        return math.copysign(math.inf, magnitude)


# -- display --------------------------------------------------------------------------------
# role -> system -> (unit label, SI value per displayed unit); fixed factors, checked
# against pint in tests/test_units.py
_INCH = 0.0254
_LBF = 4.4482216152605
_DISPLAY = {
    "length": {"si": ("m", 1.0), "metric": ("mm", 1e-3), "us": ("in", _INCH)},
    "thin": {"si": ("um", 1e-6), "metric": ("um", 1e-6), "us": ("mil", 1e-3 * _INCH)},
    "speed": {"si": ("m/s", 1.0), "metric": ("m/min", 1 / 60), "us": ("ft/min", 0.3048 / 60)},
    "tension": {"si": ("N/m", 1.0), "metric": ("N/m", 1.0), "us": ("pli", _LBF / _INCH)},
    # coordinates on the film and small lengths (grooves): mm even in SI, as drawn
    "position": {"si": ("mm", 1e-3), "metric": ("mm", 1e-3), "us": ("in", _INCH)},
    "pressure": {"si": ("Pa", 1.0), "metric": ("kPa", 1e3), "us": ("psi", _LBF / _INCH**2)},
    "torque": {"si": ("N m", 1.0), "metric": ("N m", 1.0), "us": ("lbf in", _LBF * _INCH)},
    "angle": {s: ("deg", 1.0) for s in SYSTEMS},
}


def _check_system(system: str) -> None:
    if system not in SYSTEMS:
        raise InputError(f"units = {system!r} is not valid: must be one of "
                         + ", ".join(SYSTEMS))


def unit_label(role: str, system: str) -> str:
    """The unit ``display`` prints for ``role`` in ``system``, e.g. ``"ft/min"``."""
    _check_system(system)
    return _DISPLAY[role][system][0]


def convert(value: float, role: str, system: str) -> float:
    """An SI value of ``role`` (length, thin, speed, tension, pressure, torque, angle) in
    ``system``'s display unit."""
    _check_system(system)
    return value / _DISPLAY[role][system][1]


def display(value: float, role: str, system: str, digits: int = 4) -> str:
    """``value`` (SI) as text in ``system``'s unit for ``role``, ``digits`` significant
    (more for a large whole number, never ``1.24e+03``).

    >>> display(0.055, "length", "metric"), display(80.0, "tension", "us")
    ('55 mm', '0.4568 pli')
    >>> display(6.3, "speed", "us", 3)
    '1240 ft/min'
    """
    label = unit_label(role, system)
    shown = convert(value, role, system)
    if math.isfinite(shown) and 1.0 <= abs(shown) < 1e15:
        digits = max(digits, math.floor(math.log10(abs(shown))) + 1)
    return f"{shown:.{digits}g} {label}"


#: What each dimensional quantity webfem writes measures (a role of :func:`convert`), by
#: name: summary keys, case keys and the columns of the tables it writes. Quantities not
#: listed are written as they are: no unit (mu, shares, lambda), a count, a time in s, a
#: scaled number (residual, eps), or a unit the trade keeps in SI (moduli, viscosity).
ROLES = {
    # summary keys (webfem.result.Summary)
    **dict.fromkeys(("h_center", "h_inlet", "h_outlet", "h_min", "h_c", "sigma"), "thin"),
    "x_min": "position",
    **dict.fromkeys(("delta_T", "T_eff", "delta_T_required", "delta_T_available",
                     "delta_T_film"), "tension"),
    "U": "speed", "U_slide": "speed", "bending_stiffness_used": "torque",
    # case keys
    **dict.fromkeys(("roller.radius", "roller.diameter", "web.width"), "length"),
    **dict.fromkeys(("roller.groove_pitch", "roller.groove_width", "roller.groove_depth"),
                    "position"),
    **dict.fromkeys(("roller.roughness", "web.roughness", "web.thickness",
                     "air.mean_free_path"), "thin"),
    **dict.fromkeys(("roller.speed", "web.speed", "friction.speed_constant"), "speed"),
    # the sweep parameter that moves the line (webfem.line_speed.LINE_SPEED)
    "line.speed": "speed",
    "web.tension": "tension", "wrap.angle_deg": "angle", "air.ambient_pressure": "pressure",
    **dict.fromkeys(("roller.drag_torque", "web.bending_stiffness"), "torque"),
    # groove designs (webfem.groove_sizing.GrooveDesign): speed, groove pitch, width, depth
    "speed": "speed", **dict.fromkeys(("pitch", "width", "depth"), "position"),
    # traction-loss speeds of groove geometries (webfem.groove_sizing.LossSpeed)
    "speed_peak": "speed",
    # calibration estimates (webfem.calibrate.Calibration; sigma as above)
    "speed_constant": "speed",
}


def column_name(name: str, role: str | None, system: str) -> str:
    """A table column's name in ``system``: ``name`` itself in SI or without a role (the
    SI files' names are a contract), else ``name_UNIT`` with ``/`` spelt ``_per_`` and
    spaces ``_``, so every column of a converted table names its unit.

    >>> column_name("h_center", "thin", "us"), column_name("value", "speed", "metric")
    ('h_center_mil', 'value_m_per_min')
    """
    if system == "si" or role is None:
        return name
    unit = unit_label(role, system).replace("/", "_per_").replace(" ", "_")
    return f"{name}_{unit}"


def table_in_units(rows, keys, system: str, roles: dict | None = None
                   ) -> tuple[list[str], list[dict]]:
    """Rows of SI numbers (``{column: value}``) as column names and rows in ``system``.

    ``roles`` adds to or overrides :data:`ROLES` for this table (e.g. ``{"value":
    "speed"}`` for a sweep over roller speed); ``None`` as a role leaves a column as it is.
    In SI the names and rows come back unchanged. Otherwise each column with a role is
    converted (numbers only: empty cells, text and booleans stay) and renamed by
    :func:`column_name`; the others keep their name and values.

    >>> table_in_units([{"mu": 0.2, "h_min": 4.5e-6}], ["mu", "h_min"], "metric")
    (['mu', 'h_min_um'], [{'mu': 0.2, 'h_min_um': 4.5}])
    """
    _check_system(system)
    keys = list(keys)
    if system == "si":
        return keys, [dict(r) for r in rows]
    role_of = {**ROLES, **(roles or {})}
    names = {k: column_name(k, role_of.get(k), system) for k in keys}
    out = []
    for row in rows:
        new = {}
        for k in keys:
            v, role = row.get(k), role_of.get(k)
            if role is not None and isinstance(v, (int, float)) and not isinstance(v, bool):
                v = convert(float(v), role, system)
            new[names[k]] = v
        out.append(new)
    return [names[k] for k in keys], out
