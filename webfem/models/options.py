"""Solver options as types: one frozen dataclass per model, validated on creation.

Every option is a named, documented field with its valid range in the field's metadata;
:class:`Options` (a :class:`webfem.validated.Validated`, the base the case sections share)
checks them all in one place, builds an options object from keywords
(:meth:`Options.from_mapping`: unknown names are errors that suggest the closest valid one)
or from the command line's strings (:meth:`Options.from_strings`), and describes itself for
``--help``. The registry (:mod:`webfem.models.registry`) ties each model to its type.

Examples
--------
>>> FE1DOptions().level, FE1DOptions(level=2).level
(0, 2)
>>> FE1DOptions.from_mapping({"levle": 2})
Traceback (most recent call last):
...
webfem.errors.InputError: unknown fe1d option 'levle'; did you mean 'level'?
>>> FE2DOptions.from_strings(["level=1", "method=picard"]).method
'picard'
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar, Mapping

import numpy as np

from ..errors import InputError
from ..validated import Validated, spec

__all__ = ["Options", "ClosedFormOptions", "FittedOptions", "FE1DOptions", "FE2DOptions", "AutoOptions",
           "option"]

_TRUE = {"true", "yes", "on", "1"}
_FALSE = {"false", "no", "off", "0"}


def option(default, doc: str, kind: str, *, lo=None, hi=None, lo_open=False, hi_open=False,
           choices: tuple = (), none: bool = False, cli: bool = True):
    """A field with its documentation and valid range (:func:`webfem.validated.spec`).

    ``kind``: "int", "float", "bool", "choice", "path" or "nodes" (an array, API only);
    ``lo``/``hi``: bounds (open or closed); ``none``: None is allowed (meaning stated in
    ``doc``); ``cli``: settable with ``--opt``.
    """
    return field(default=default, metadata=spec(doc, kind, lo=lo, hi=hi, lo_open=lo_open,
                                                 hi_open=hi_open, choices=choices,
                                                 none=none, cli=cli))


@dataclass(frozen=True, repr=False)
class Options(Validated):
    """Shared validation and construction of the per-model option types."""

    #: The model these options belong to (for messages).
    model: ClassVar[str] = ""

    @classmethod
    def label(cls, name: str) -> str:
        return f"{cls.model} option {name}" if cls.model else name

    @classmethod
    def noun(cls) -> str:
        return f"{cls.model} option"

    @classmethod
    def what_is_valid(cls, meta: Mapping[str, Any]) -> str:
        if meta["kind"] in ("path", "nodes"):
            text = "a mesh file" if meta["kind"] == "path" else "an array of node positions"
            return text + (" (or none)" if meta["none"] else "")
        return super().what_is_valid(meta)

    @classmethod
    def check(cls, name: str, value: Any, meta: Mapping[str, Any]) -> Any:
        """The kinds only options have: a mesh file and an array of nodes."""
        kind = meta["kind"]
        if kind not in ("path", "nodes") or (value is None and meta["none"]):
            return super().check(name, value, meta)
        if kind == "path":
            if not isinstance(value, (str, Path)):
                raise cls.invalid(name, value, "is not valid", meta)
            if not Path(value).is_file():
                raise InputError(f"{cls.label(name)}: mesh file '{value}' does not exist")
            return str(value)
        try:
            arr = np.asarray(value, float).ravel()
        except (TypeError, ValueError):
            raise cls.invalid(name, value, "is not valid", meta) from None
        if arr.size < 3 or not np.all(np.isfinite(arr)):
            raise cls.invalid(name, value, "has fewer than 3 finite nodes", meta)
        # a tuple, not the array: options are frozen and hashed (fe2d keys its kept 1-D
        # starts on them) and compared
        return tuple(arr.tolist())

    # -- construction ---------------------------------------------------------------------
    @classmethod
    def unknown(cls, name: Any, valid, where: str = "") -> InputError:
        """The error for a name that is not an option of this model: an option of another
        model says whose it is (``symmetry`` is fe2d's, not fe1d's), instead of a near
        name of this model's that means something else; a misspelling gets the closest
        of this model's names."""
        owners = [t.model for t in _option_types() if t is not cls and name in t.names()
                  and (not where or dataclasses.fields(t)[t.names().index(name)]
                       .metadata["cli"])]
        if owners and cls.model:
            whose = " and ".join(owners) if len(owners) < 3 else \
                ", ".join(owners[:-1]) + " and " + owners[-1]
            takes = ", ".join(valid) if valid else "none"
            use = f"--model {owners[0]}" if where else f"model='{owners[0]}'"
            return InputError(f"unknown {cls.model} option '{name}'{where}: it is an "
                              f"option of {whose}, not of {cls.model}: give it with that "
                              f"model ({use}) or leave it out; {cls.model} options: {takes}")
        return super().unknown(name, valid, where)

    @classmethod
    def parse(cls, name: str, text: str) -> Any:
        """The typed value of option ``name`` from command-line ``text``."""
        fields = {f.name: f for f in dataclasses.fields(cls)}
        valid = [n for n, f in fields.items() if f.metadata["cli"]]
        if name in fields and not fields[name].metadata["cli"]:
            raise InputError(f"{cls.model} option '{name}' (--opt) is set from Python only "
                             f"({fields[name].metadata['doc']})")
        if name not in fields:
            raise cls.unknown(name, valid, " (--opt)")
        meta = fields[name].metadata
        raw = text.strip().strip('"').strip("'")
        kind = meta["kind"]
        bad = InputError(f"--opt {name}={text}: {name} must be {cls.what_is_valid(meta)}")
        if meta["none"] and raw.lower() in ("none", "null", ""):
            return None
        if kind == "bool":
            if raw.lower() in _TRUE:
                return True
            if raw.lower() in _FALSE:
                return False
            raise bad
        if kind in ("choice", "path"):
            return raw
        try:
            number = float(raw)
        except ValueError:
            raise bad from None
        if kind == "int":
            if not math.isfinite(number) or number != int(number):
                raise bad
            return int(number)
        return number

    @classmethod
    def from_strings(cls, pairs) -> "Options":
        """Options from ``["level=2", "method=picard"]`` (the CLI's ``--opt``)."""
        values = {}
        for text in pairs or []:
            if "=" not in text:
                raise InputError(f"--opt {text!r}: expected name=value, e.g. --opt level=2")
            key, raw = (t.strip() for t in text.split("=", 1))
            values[key] = cls.parse(key, raw)
        return cls.from_mapping(values)

    def changed(self) -> dict[str, Any]:
        """The options that differ from their defaults (for sweep signatures and repr)."""
        out = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if isinstance(value, np.ndarray) or not _same(value, f.default):
                out[f.name] = value.tolist() if isinstance(value, np.ndarray) else value
        return out

    def __repr__(self) -> str:
        changed = ", ".join(f"{k}={v!r}" for k, v in self.changed().items()
                            if not isinstance(v, list))
        return f"{type(self).__name__}({changed})"

    def to_dict(self) -> dict[str, Any]:
        """All options, JSON-friendly (arrays as lists)."""
        return {f.name: (v.tolist() if isinstance(v, np.ndarray) else v)
                for f in dataclasses.fields(self) for v in [getattr(self, f.name)]}

    @classmethod
    def describe(cls) -> str:
        """One line per option: name, default, valid range, meaning (for ``--help``)."""
        lines = []
        for f in dataclasses.fields(cls):
            if not f.metadata["cli"]:
                continue
            default = "none" if f.default is None else repr(f.default)
            lines.append(f"{f.name} = {default}: {f.metadata['doc']} "
                         f"({cls.what_is_valid(f.metadata)})")
        return "\n".join(lines) if lines else "(no options)"


def _same(a, b) -> bool:
    try:
        return bool(a == b)
    except (TypeError, ValueError):
        return False


@dataclass(frozen=True, repr=False)
class ClosedFormOptions(Options):
    """The paper's closed form (Eq. 21 with Eqs. 10-13, 28-31)."""

    model: ClassVar[str] = "closed-form"
    n_points: int = option(201, "points along the wrap in the fields (charts, VTU)", "int",
                           lo=2, hi=100_000)


@dataclass(frozen=True, repr=False)
class FittedOptions(Options):
    """The fitted model (a fit of fe2d solutions in the dimensionless groups)."""

    model: ClassVar[str] = "fitted"
    coefficients: str | None = option(None, "coefficients file of the fit (none: the one "
                                      "shipped in the package)", "path", none=True)

    @classmethod
    def what_is_valid(cls, meta: Mapping[str, Any]) -> str:
        if meta["kind"] == "path":
            return ("a coefficients file of the fit (a NumPy .npz archive written by `webfem "
                    "fit build`), or none")
        return super().what_is_valid(meta)

    @classmethod
    def check(cls, name: str, value: Any, meta: Mapping[str, Any]) -> Any:
        """The coefficients file is loaded here, once (cached for the solves), so a file
        holding no fit is refused before any command solves or writes."""
        if meta["kind"] != "path" or value is None:
            return super().check(name, value, meta)
        if not isinstance(value, (str, Path)):
            raise cls.invalid(name, value, "is not valid", meta)
        from .fit_file import read_fit   # numpy's zip reader only when the option is set
        read_fit(str(value))
        return str(value)


_METHODS_1D = ("newton", "picard", "picard-staggered")


@dataclass(frozen=True, repr=False)
class FE1DOptions(Options):
    """The 1-D (infinitely wide) finite-element model: discretisation and solver."""

    model: ClassVar[str] = "fe1d"
    entry: float = option(40.0, "length of the entry and exit zones, units of R eps^(1/3)",
                          "float", lo=0.0, lo_open=True, hi=200.0)
    level: int = option(0, "uniform refinement level (each bisects every cell; the error "
                        "estimate refines further where it must)", "int", lo=0, hi=3)
    order: int = option(2, "Lagrange order of the film pressure (2: P2/Q2, 1: P1/Q1)", "int",
                        lo=1, hi=2)
    compressible: bool = option(True, "compressible (isothermal ideal gas) film", "bool")
    contact: bool = option(True, "asperity contact pressure in the web equilibrium", "bool")
    method: str = option("newton", "coupling scheme", "choice", choices=_METHODS_1D)
    tol: float = option(1e-9, "residual tolerance, 2-norm in scaled units", "float",
                        lo=0.0, lo_open=True, hi=1e-2)
    max_iter: int = option(60, "Newton iteration limit", "int", lo=1, hi=1000)
    omega: float = option(1.0, "Picard relaxation factor", "float", lo=0.0, lo_open=True,
                          hi=2.0)
    aitken: bool = option(True, "Picard: Aitken's dynamic relaxation as the fallback", "bool")
    anderson: int = option(10, "Picard: Anderson acceleration depth (0: off)", "int", lo=0,
                           hi=50)
    picard_max_iter: int = option(500, "Picard iteration limit", "int", lo=1, hi=20000)
    floor: float = option(0.1, "film thickness floor in Reynolds, fraction of sigma", "float",
                          lo=0.0, hi=1.0)
    adapt: int = option(6, "rounds of refinement where the film is thin", "int", lo=0, hi=20)
    adapt_ratio: float = option(1.0, "refine cells longer than this times the film's "
                                "reaction length", "float", lo=0.0, lo_open=True, hi=100.0)
    min_cell: float = option(2e-3, "smallest cell the refinement makes, scaled units",
                             "float", lo=0.0, lo_open=True, hi=10.0)
    adapt_settle: bool = option(True, "stop the rounds of refinement where the film is thin "
                                "once one changes no quantity read (h_center, h_min, mu, "
                                "contact share) by more than error_tol/10 (false: every "
                                "round the length rule asks for)", "bool")
    continuation: bool = option(True, "Newton: continuation from the Eshel-Elrod problem on "
                                "failure", "bool")
    backtrack: float = option(1.5, "Picard: undo a step that raises the residual by more "
                              "than this factor (0: off)", "float", lo=0.0, hi=1e6)
    estimate: bool = option(True, "estimate the mesh error of h_center, h_min, mu and the "
                            "contact share from a second mesh with cells twice as long, and "
                            "refine until each meets error_tol (false: no estimate, the "
                            "error_* keys null)", "bool")
    error_tol: float = option(1e-3, "target of the mesh error estimates (gaps against the "
                              "larger of the gap and sigma; mu "
                              "against max(|mu|, 0.1 mu_cc), the contact share absolute): "
                              "every cell is bisected until each estimate meets it", "float",
                              lo=1e-8, hi=1.0)
    mesh: str | None = option(None, "mesh file whose x nodes [m] replace the graded mesh "
                              "(e.g. one of meshes/)", "path", none=True)
    nodes: Any = option(None, "starting nodes in scaled X (API only; mesh= reads them from a "
                        "file)", "nodes", none=True, cli=False)

    def __post_init__(self):
        super().__post_init__()
        if self.mesh is not None and self.nodes is not None:
            raise InputError(f"{self.model} options mesh and nodes both given: use one")


@dataclass(frozen=True, repr=False)
class FE2DOptions(FE1DOptions):
    """The 2-D film + 1-D web finite-element model."""

    model: ClassVar[str] = "fe2d"
    level: int = option(0, "uniform refinement level (each bisects every cell, both "
                        "directions)", "int", lo=0, hi=3)
    method: str = option("newton", "coupling scheme", "choice", choices=("newton", "picard"))
    max_iter: int = option(40, "Newton iteration limit", "int", lo=1, hi=1000)
    width_fine: float = option(0.25, "cell size at the web edges, scaled units", "float",
                               lo=0.0, lo_open=True, hi=10.0)
    symmetry: bool = option(True, "half width with a symmetry condition (false: full width)",
                            "bool")
    grooves: str = option("auto", "grooved roller: the periodic cell land centre to groove "
                          "centre (the web's edges left out), the full width with its edge "
                          "lands, the edge strip (the edge lands, the interior as its "
                          "periodic cell), or auto (the cell where its stated error, twice the "
                          "edges' estimated effect plus error_tol, is within edge_tol, else "
                          "the strip, the full width on a web too narrow for one)", "choice",
                          choices=("auto", "cell", "full", "strip"))
    edge_tol: float = option(0.01, "grooves = auto: the largest stated error (relative, as "
                             "auto's tol) with which the periodic cell answers: twice the "
                             "web's edges' estimated effect, which its stated errors "
                             "include, plus error_tol", "float", lo=0.0, hi=1.0, lo_open=True)
    strip_width: float | None = option(None, "grooves = strip: the edge strip's width, scaled "
                                       "units (none: 24, what grooves that do not vent "
                                       "need; auto sets it from the periodic cell's "
                                       "groove pressure)", "float", lo=0.0, lo_open=True,
                                       hi=1e6, none=True, cli=False)
    groove_pressure: str = option("solved", "grooved roller: the groove pressure solved with "
                                  "the film, or held at ambient (the deep-groove limit, for "
                                  "checks)", "choice", choices=("solved", "ambient"))
    tol: float = option(1e-9, "residual tolerance, 2-norm in scaled units (at this default "
                        "a smooth roller's fe2d Newton may stop earlier: "
                        "algebraic_share; set to any other value, every solve meets it)",
                        "float", lo=0.0, lo_open=True, hi=1e-2)
    algebraic_share: float = option(1e-3, "smooth roller, Newton, tol at its default: "
                                    "Newton also stops once the bound of its algebraic "
                                    "error in h_center, h_min, mu and the contact share is "
                                    "at most this times error_tol; the bound is added to "
                                    "the stated errors (0: every solve to tol)", "float",
                                    lo=0.0, hi=0.1)

    @classmethod
    def line_options(cls, options: "FE2DOptions") -> FE1DOptions:
        """The 1-D options of the infinitely wide start (same mesh and physics)."""
        keep = ("entry", "level", "compressible", "contact", "floor", "adapt", "adapt_ratio",
                "min_cell", "adapt_settle", "error_tol", "mesh", "nodes")
        # the 1-D solution only starts the 2-D solve: its own mesh error is not stated
        return FE1DOptions(estimate=False, **{k: getattr(options, k) for k in keep})


_FE_NAMES = [f.name for f in dataclasses.fields(FE2DOptions) if f.name != "tol"]


#: Under auto, the FE model's mesh error target (``error_tol``, unless set) is this share of
#: auto's ``tol``: a mesh refined far below the error the user asked for is work no answer
#: needs (auto's 1 % gave fe2d meshes twice as fine as 0.25 % asks on board lines), and the
#: quarter leaves the stated mesh error, the change from the coarser mesh, room within tol.
MESH_SHARE = 0.25


def _auto_fields():
    """Auto takes every fe2d option (passed on to the FE model it uses, default: that
    model's own) besides its own quantity and tolerance."""
    out = []
    for f in dataclasses.fields(FE2DOptions):
        if f.name == "tol":
            continue
        unset = f"{MESH_SHARE:g} x tol" if f.name == "error_tol" else "its default"
        meta = dict(f.metadata, none=True, doc=f.metadata["doc"] + "; passed to the FE model "
                    f"used (none: {unset})")
        out.append((f.name, Any, field(default=None, metadata=meta)))
    return out

@dataclass(frozen=True, repr=False)
class _AutoBase(Options):
    model: ClassVar[str] = "auto"
    quantity: str = option("all", "quantity whose error the choice bounds (all: h_center, "
                           "h_min, mu and the contact share, each)", "choice",
                           choices=("all", "mu", "h_center", "h_min", "contact_share"))
    tol: float = option(0.01, "error the chosen model must meet in each judged quantity "
                        "(gaps against the larger of the gap and sigma, mu against "
                        "max(|mu|, 0.1 mu_cc), the contact share absolute)", "float", lo=0.0, hi=1.0, lo_open=True, hi_open=True)
    fe_tol: float | None = option(None, "residual tolerance of the FE model used (none: its "
                                  "default)", "float", lo=0.0, lo_open=True, hi=1e-2,
                                  none=True)


AutoOptions = dataclasses.make_dataclass(
    "AutoOptions", _auto_fields(), bases=(_AutoBase,), frozen=True, repr=False,
    namespace={"__doc__": "The automatic choice of the cheapest adequate model.",
               "__module__": __name__})


def _option_types() -> tuple[type[Options], ...]:
    """Every model's options type (for the messages that say whose an option is)."""
    return (ClosedFormOptions, FittedOptions, FE1DOptions, FE2DOptions, AutoOptions)


def fe_options(auto, target: type[FE1DOptions]) -> FE1DOptions:
    """The options of ``target`` (FE1DOptions or FE2DOptions) that an auto options object
    sets; unset ones keep ``target``'s defaults, except ``error_tol``: :data:`MESH_SHARE`
    of auto's ``tol``. Options ``target`` lacks are dropped (the fe2d-only width options do
    not reach the 1-D model).

    >>> fe_options(AutoOptions(tol=0.01), FE2DOptions).error_tol
    0.0025
    >>> fe_options(AutoOptions(error_tol=1e-4), FE1DOptions).error_tol
    0.0001
    """
    names = set(target.names())
    values = {k: getattr(auto, k) for k in _FE_NAMES if k in names
              and getattr(auto, k) is not None}
    values.setdefault("error_tol", MESH_SHARE * auto.tol)
    if auto.fe_tol is not None:
        values["tol"] = auto.fe_tol
    return target(**values)
