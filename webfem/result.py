"""Result of one solve: the summary (the JSON keys), fields along x, the film, diagnostics.

Every model (closed form, 1-D, 2-D, auto) answers through the same summary keys, the fields
of :class:`Summary` (``lambda`` is ``lambda_`` in Python, ``"lambda"`` in JSON):

============ ==========================================================================
key          meaning
============ ==========================================================================
model        model that produced the numbers ("closed-form", "fe1d", ...)
h_center     gap at the wrap centre x = 0 [m]
h_inlet      gap at the inlet edge x = -RB/2 [m]
h_outlet     gap at the outlet edge x = +RB/2 [m]
h_min        smallest gap anywhere in the solved domain [m]
mu           wrap-averaged friction coefficient [-]; where nothing slides (U_s = 0, an
             idler) the traction available at the onset of slip, mu_onset
delta_T      tension increase the roller carries before slip, Eq. 31 [N/m]; where nothing
             slides delta_T_available = T_eff (exp(mu_onset B) - 1)
regime       lubrication regime covering most of the wrap: boundary, mixed or fluid
lambda       width parameter L/(2 R eps^(1/3))
beta         wrap parameter B/eps^(1/3)
eq21_valid   True inside Eq. 21's stated range (beta > 6 and lambda > 7)
converged    True when the solver met its tolerance and the answer is admissible (the
             closed form: False where it has no answer, the reason in ``solver_message``)
iterations   nonlinear iterations (0 for the closed form)
n_dofs       unknowns of the discrete problem (0 for the closed form)
solve_time_s wall time of the solve [s]
============ ==========================================================================

Examples
--------
>>> import webfem
>>> r = webfem.solve(webfem.Case(), model="closed-form")
>>> r["model"], r.summary.model, r["lambda"] == r.summary.lambda_
('closed-form', 'closed-form', True)
>>> len(repr(r)) < 1000
True
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .case import Case

__all__ = ["Result", "Summary", "Fields", "Film", "Diagnostics", "State", "SUMMARY_KEYS"]

#: The contract: keys every model's summary carries (others may be added, none removed).
SUMMARY_KEYS = ("model", "h_center", "h_inlet", "h_outlet", "h_min", "mu", "delta_T", "regime",
                "lambda", "beta", "eq21_valid", "converged", "iterations", "n_dofs",
                "solve_time_s")


def _plain(value: Any) -> Any:
    """JSON-safe value: numpy to Python, non-finite floats to None, tuples to lists."""
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, (np.floating, float)):
        value = float(value)
        return value if math.isfinite(value) else None
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def _attr(key: str) -> str:
    return "lambda_" if key == "lambda" else key


class _ReadOnlyMapping:
    """``obj["name"]``, ``"name" in obj``, ``keys()``, ``get()`` over a frozen dataclass's
    fields: those that are set (not None), or all of them when ``_all_keys`` (a summary
    answers every key, None where a model does not compute it)."""

    _aliases: dict = {}
    _all_keys = False

    def _key_names(self):
        return [self._aliases.get(f.name, f.name) for f in dataclasses.fields(self)
                if self._all_keys or getattr(self, f.name) is not None]

    def __getitem__(self, key: str) -> Any:
        name = _attr(key) if self._aliases else key
        if not isinstance(key, str) or name not in {f.name for f in dataclasses.fields(self)}:
            raise KeyError(key)
        value = getattr(self, name)
        if value is None and not self._all_keys:
            raise KeyError(key)
        return value

    def __contains__(self, key) -> bool:
        return key in self._key_names()

    def __iter__(self):
        return iter(self._key_names())

    def keys(self):
        return self._key_names()

    def items(self):
        return [(k, self[k]) for k in self._key_names()]

    def get(self, key: str, default: Any = None) -> Any:
        """The value, or ``default`` when the key is unknown or its value None."""
        try:
            value = self[key]
        except KeyError:
            return default
        return default if value is None else value


@dataclass(frozen=True, repr=False)
class Summary(_ReadOnlyMapping):
    """The numbers of one solve: every JSON key is a field (SI units).

    Optional fields are None where a model does not compute them (the closed form has no
    mesh). ``summary["mu"]`` reads a field by its JSON key.
    """

    _aliases = {"lambda_": "lambda"}
    _all_keys = True

    model: str
    h_center: float
    h_inlet: float
    h_outlet: float
    h_min: float
    mu: float
    delta_T: float
    regime: str
    lambda_: float
    beta: float
    eq21_valid: bool
    converged: bool
    iterations: int
    n_dofs: int
    solve_time_s: float
    h_c: float
    sigma: float
    share_boundary: float
    share_mixed: float
    share_fluid: float
    eps: float
    kappa: float
    U: float
    U_slide: float
    residual: float
    warnings: tuple[str, ...] = ()
    #: The physics: effective tension T_eff = T - rho_w t U_w^2 [N/m], the bending stiffness
    #: used [N m] and the effects included (:mod:`webfem.physics.effects`).
    T_eff: float | None = None
    bending_stiffness_used: float | None = None
    effects: tuple[str, ...] = ()
    #: Idler slip check (when the case states a drag torque or a line acceleration):
    #: tension difference needed and available [N/m], their ratio, and the friction
    #: coefficient assumed at the onset of slip.
    #: Where nothing slides (U_s = 0) ``mu_onset`` and ``delta_T_available`` are given even
    #: without an idler load: they are then ``mu`` and ``delta_T``.
    delta_T_required: float | None = None
    delta_T_available: float | None = None
    slip_margin: float | None = None
    mu_onset: float | None = None
    #: Where nothing slides (U_s = 0): the film's own traction at the stated speeds, its
    #: pressure-driven drag -(h/2) dp/dx averaged over the wrap (tiny, of either sign) and
    #: the belt formula's delta_T for it [N/m]; None where something slides (then ``mu`` and
    #: ``delta_T`` are that traction).
    mu_film: float | None = None
    delta_T_film: float | None = None
    #: FE models: position of the minimum gap [m], share of the wrap load carried by
    #: asperity contact, coupling method, mesh description, cells, refinement rounds and
    #: the solver's closing message.
    x_min: float | None = None
    contact_share: float | None = None
    method: str | None = None
    mesh: str | None = None
    n_cells: int | None = None
    width_cells: int | None = None
    adapt_rounds: int | None = None
    solver_message: str | None = None
    #: Grooved roller (fe2d): land fraction a/p_g (1 smooth), the share of the lands'
    #: load carried by asperity contact, and the domain solved across the width.
    land_fraction: float | None = None
    contact_share_lands: float | None = None
    groove_domain: str | None = None
    #: The error of what the result states, estimated per quantity: relative for the gaps,
    #: relative to max(|mu|, 0.1 mu_cc) for mu, absolute for the contact share (FE models:
    #: the mesh error from two meshes, :mod:`webfem.models.mesh_error`; the closed form and
    #: fe1d also their model error against fe2d), and how the estimate was obtained.
    error_h_center: float | None = None
    error_h_min: float | None = None
    error_mu: float | None = None
    error_contact_share: float | None = None
    error_basis: str | None = None
    #: auto: the model that answered, its estimated relative error in ``quantity`` against
    #: ``tolerance``, and why it was chosen.
    model_used: str | None = None
    estimated_error: float | None = None
    quantity: str | None = None
    tolerance: float | None = None
    why: str | None = None

    def __post_init__(self):
        object.__setattr__(self, "warnings", tuple(self.warnings))
        object.__setattr__(self, "effects", tuple(self.effects))

    @classmethod
    def from_mapping(cls, values: dict) -> "Summary":
        """A summary from JSON keys (``"lambda"``); unknown keys are an error."""
        names = {f.name for f in dataclasses.fields(cls)}
        kw = {_attr(k): v for k, v in values.items()}
        extra = set(kw) - names
        if extra:
            raise TypeError(f"not summary keys: {sorted(extra)}")
        return cls(**kw)

    def replace(self, **changes) -> "Summary":
        """A copy with fields changed (JSON key ``lambda`` as ``lambda_``)."""
        return dataclasses.replace(self, **{_attr(k): v for k, v in changes.items()})

    def to_dict(self) -> dict[str, Any]:
        """Every key, JSON-safe (non-finite numbers become None), the contract keys first."""
        out = {}
        for f in dataclasses.fields(self):
            out[self._aliases.get(f.name, f.name)] = _plain(getattr(self, f.name))
        return {k: out[k] for k in SUMMARY_KEYS} | {k: v for k, v in out.items()
                                                     if k not in SUMMARY_KEYS}

    def to_json(self, **kwargs) -> str:
        """The summary as strict JSON text (no NaN or Infinity)."""
        return json.dumps(self.to_dict(), allow_nan=False, **kwargs)

    def __repr__(self) -> str:
        return (f"Summary(model={self.model!r}, h_center={self.h_center:.4g}, "
                f"h_min={self.h_min:.4g}, mu={self.mu:.4g}, converged={self.converged})")


@dataclass(frozen=True, repr=False)
class Fields(_ReadOnlyMapping):
    """Fields along the web at the nodes (closed form: along the wrap), SI units.

    ``x`` [m] arc position, ``h`` [m] gap; FE models add ``w`` web deflection [m], ``p`` and
    ``p_rel`` film pressure absolute and relative to ambient [Pa] (2-D: width-averaged),
    ``p_contact`` asperity contact pressure [Pa], ``in_wrap`` (1 in the wrap); all models
    the local ``chi_c`` contact load share, ``mu_c``, ``mu_f``, ``mu`` friction and
    ``regime`` codes (0 boundary, 1 mixed, 2 fluid).
    """

    x: np.ndarray
    h: np.ndarray
    w: np.ndarray | None = None
    p_rel: np.ndarray | None = None
    p: np.ndarray | None = None
    p_contact: np.ndarray | None = None
    in_wrap: np.ndarray | None = None
    chi_c: np.ndarray | None = None
    mu_c: np.ndarray | None = None
    mu_f: np.ndarray | None = None
    mu: np.ndarray | None = None
    regime: np.ndarray | None = None

    def __repr__(self) -> str:
        return f"Fields({len(self.x)} points: {', '.join(self.keys())})"


@dataclass(frozen=True, repr=False)
class Film(_ReadOnlyMapping):
    """The 2-D film at its mesh vertices: ``points`` [m] (x, z, 0), ``quads`` (vertex
    indices), ``p``, ``p_rel``, ``p_contact`` [Pa], ``h`` [m], ``chi_c``, ``mu``, ``regime``."""

    points: np.ndarray
    quads: np.ndarray
    p: np.ndarray
    p_rel: np.ndarray
    h: np.ndarray
    p_contact: np.ndarray
    chi_c: np.ndarray
    mu: np.ndarray
    regime: np.ndarray

    def __repr__(self) -> str:
        return f"Film({len(self.points)} vertices, {len(self.quads)} quadrilaterals)"


@dataclass(frozen=True, repr=False)
class Diagnostics(_ReadOnlyMapping):
    """How a solve went: residual ``history`` per iteration, closing ``reason``,
    ``continuation`` steps, the ``options`` used, the wrap quadrature (``wrap_h`` [m] gaps,
    ``wrap_w`` weights summing to 1, ``wrap_p`` [Pa] absolute pressure and ``wrap_dpdx``
    [Pa/m] its gradient, to re-evaluate friction), Picard's ``omegas`` and
    ``block_iterations``. ``solver`` holds the discrete problem and state vector (for
    inspection in the solving process; dropped by :meth:`Result.slim`)."""

    method: str = ""
    history: tuple = ()
    reason: str = ""
    continuation: tuple = ()
    options: Any = None
    wrap_h: np.ndarray | None = None
    wrap_w: np.ndarray | None = None
    wrap_p: np.ndarray | None = None
    wrap_dpdx: np.ndarray | None = None
    omegas: tuple | None = None
    block_iterations: Any = None
    solver: dict | None = field(default=None, compare=False)

    def __repr__(self) -> str:
        return (f"Diagnostics(method={self.method!r}, {len(self.history)} residuals, "
                f"reason={self.reason!r})")


@dataclass(frozen=True, repr=False)
class State:
    """What a later solve restarts from, small and picklable: the ``case`` solved, the
    ``model``, its mesh (scaled nodes ``X``, and ``Z`` across the width for the 2-D film)
    and DOF vector ``u``, and for the 2-D film the 1-D state it started from (``line``). The
    same state restarts a solve in the process that made it and in a worker."""

    case: Case
    model: str
    X: np.ndarray
    u: np.ndarray
    Z: np.ndarray | None = None
    line: "State | None" = None

    def __repr__(self) -> str:
        z = f" x {len(self.Z)} Z" if self.Z is not None else ""
        return f"State({self.model}: {len(self.X)} X{z} nodes, {self.u.size} unknowns)"


@dataclass(frozen=True, repr=False)
class Result:
    """What a model returns: the case, its :class:`Summary`, :class:`Fields` along the web,
    the 2-D :class:`Film` (2-D models) and :class:`Diagnostics`.

    ``result["mu"]`` reads a summary key; ``result.to_dict()`` is the JSON object of
    ``webfem solve --json``.
    """

    case: Case
    summary: Summary
    fields: Fields
    diagnostics: Diagnostics = field(default_factory=Diagnostics)
    film: Film | None = None
    #: What a continued solve starts from (FE models; None for the closed form).
    restart: State | None = None

    def __post_init__(self):
        if not isinstance(self.summary, Summary):
            object.__setattr__(self, "summary", Summary.from_mapping(dict(self.summary)))
        if not isinstance(self.fields, Fields):
            object.__setattr__(self, "fields", Fields(**dict(self.fields)))
        if self.film is not None and not isinstance(self.film, Film):
            object.__setattr__(self, "film", Film(**dict(self.film)))

    def slim(self) -> "Result":
        """A copy without the solver's internal objects (mesh bases, discrete problem):
        small and picklable, for worker processes and storage. What a continued solve starts
        from stays (:attr:`restart`)."""
        return dataclasses.replace(self, diagnostics=dataclasses.replace(self.diagnostics,
                                                                         solver=None))

    def __reduce__(self):
        # pickled as its slim copy: scikit-fem's bases hold lambdas, and a result sent to or
        # from a worker process needs only what a continued solve starts from
        s = self.slim()
        return (Result, (s.case, s.summary, s.fields, s.diagnostics, s.film, s.restart))

    def state(self, name: str):
        """The solver's internal object ``name`` ("problem", "state": the discrete problem
        and the DOF vector of the answer), for inspection in the process that solved; None
        after :meth:`slim` (continuation reads :attr:`restart`)."""
        return (self.diagnostics.solver or {}).get(name)

    def __getitem__(self, key: str) -> Any:
        return self.summary[key]

    def get(self, key: str, default: Any = None) -> Any:
        """A summary value, or ``default`` when the model does not report that key."""
        return self.summary.get(key, default)

    def to_dict(self) -> dict[str, Any]:
        """The summary as a JSON-safe dict (non-finite numbers become null)."""
        return self.summary.to_dict()

    #: the name this method had before the summary was typed
    to_json = to_dict

    def __repr__(self) -> str:
        s, c = self.summary, self.case
        um = 1e6
        return (f"<Result {s.model}{' -> ' + s.model_used if s.model_used else ''}: "
                f"U_r = {c.roller.speed:g} m/s, T = {c.web.tension:g} N/m, "
                f"B = {c.wrap.angle_deg:g} deg, L = {c.web.width:g} m, "
                f"R = {c.roller.radius:g} m; h_center = {s.h_center * um:.4g} um, "
                f"h_min = {s.h_min * um:.4g} um, mu = {s.mu:.4g}, regime {s.regime}, "
                f"converged = {s.converged}>")

    def _repr_html_(self) -> str:
        from html import escape

        rows = "".join(f"<tr><td>{escape(str(k))}</td><td>{escape(_cell(v))}</td></tr>"
                       for k, v in self.to_dict().items() if v is not None)
        return (f"<table><caption>webfem result ({escape(self.summary.model)})</caption>"
                f"{rows}</table>")

    def describe(self) -> str:
        """A readable multi-line summary for the terminal."""
        from .describe import describe
        return describe(self)


def _cell(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, list):
        return "; ".join(map(str, value)) or "-"
    return str(value)
