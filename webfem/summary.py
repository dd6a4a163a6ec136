"""The summary of a solve: every JSON key a typed field (:class:`Summary`), and the
read-only mapping the result's parts share.

The keys every model's summary carries (:data:`SUMMARY_KEYS`) are the contract of
``webfem solve --json``; others may be added, none removed.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["Summary", "SUMMARY_KEYS", "ReadOnlyMapping", "plain"]

#: The contract: keys every model's summary carries (others may be added, none removed).
SUMMARY_KEYS = ("model", "h_center", "h_inlet", "h_outlet", "h_min", "mu", "delta_T", "regime",
                "lambda", "beta", "eq21_valid", "converged", "iterations", "n_dofs",
                "solve_time_s")


def plain(value: Any) -> Any:
    """JSON-safe value: numpy to Python, non-finite floats to None, tuples to lists."""
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, (np.floating, float)):
        value = float(value)
        return value if math.isfinite(value) else None
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    return value


def _attr(key: str) -> str:
    return "lambda_" if key == "lambda" else key


class ReadOnlyMapping:
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
class Summary(ReadOnlyMapping):
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
    #: Where the web slides (U_s > 0) this solve's film is not an idler's: the idler keys
    #: above (but ``delta_T_required``) are None unless a second solve at U_r = U_w supplied
    #: them (:func:`webfem.idler.idler_at_web_speed`); then ``idler_basis`` names that solve
    #: and ``error_mu_onset`` is its stated error of mu (as ``error_mu``).
    idler_basis: str | None = None
    error_mu_onset: float | None = None
    #: that second solve's contact share (the verdict's tail rule reads it: an overspeeding
    #: roller entrains more air, so the sliding solve's own share says nothing of the idler's)
    idler_contact_share: float | None = None
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
    #: A web resting on the roller: True where the web's mean surface plane lies below the
    #: roller's crest somewhere (h < 0: its asperities and surface layer compressed), and the
    #: largest compression -h [m] (0 when not resting).
    resting: bool | None = None
    compression: float | None = None
    #: The error of what the result states, estimated per quantity: the gaps' relative to the
    #: larger of the gap and the roughness sigma, mu's relative to max(|mu|, 0.1 mu_cc), absolute for the contact share (FE models:
    #: the mesh error from two meshes, :mod:`webfem.models.mesh_error`; the closed form and
    #: fe1d also their model error against fe2d), and how the estimate was obtained.
    error_h_center: float | None = None
    error_h_min: float | None = None
    error_mu: float | None = None
    error_contact_share: float | None = None
    error_basis: str | None = None
    #: A periodic groove cell (fe2d): the part of each ``error_*`` that is the web's edges it
    #: leaves out (twice their estimated effect, :func:`webfem.models.groove_domain.
    #: edge_error`); None on every other domain and model.
    error_edges: float | None = None
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
            out[self._aliases.get(f.name, f.name)] = plain(getattr(self, f.name))
        return {k: out[k] for k in SUMMARY_KEYS} | {k: v for k, v in out.items()
                                                     if k not in SUMMARY_KEYS}

    def to_json(self, **kwargs) -> str:
        """The summary as strict JSON text (no NaN or Infinity)."""
        return json.dumps(self.to_dict(), allow_nan=False, **kwargs)

    @property
    def periodic_cell(self) -> bool:
        """Whether the answer is a grooved roller's periodic cell (land centre to groove
        centre, the web's edges left out), not the width of the web."""
        return (self.groove_domain or "").startswith("periodic cell")

    def __repr__(self) -> str:
        return (f"Summary(model={self.model!r}, h_center={self.h_center:.4g}, "
                f"h_min={self.h_min:.4g}, mu={self.mu:.4g}, converged={self.converged})")


