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
converged    True when the solver met its tolerance (or, balanced stopping, bounded its
             algebraic error and added the bound to the stated errors) and the answer is
             admissible (the closed form: False where it has no answer, the reason in
             ``solver_message``)
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
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .case import Case
from .summary import SUMMARY_KEYS, ReadOnlyMapping, Summary

__all__ = ["Result", "Summary", "Fields", "Film", "Diagnostics", "State", "SUMMARY_KEYS",
           "refused"]


@dataclass(frozen=True, repr=False)
class Fields(ReadOnlyMapping):
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
class Film(ReadOnlyMapping):
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


class Rebuild:
    """A solver object kept as the recipe that builds it again (:meth:`Result.state`)."""

    def __init__(self, build, *args, **kwargs):
        self.build, self.args, self.kwargs = build, args, kwargs

    def __call__(self):
        return self.build(*self.args, **self.kwargs)


@dataclass(frozen=True, repr=False)
class Diagnostics(ReadOnlyMapping):
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
    same state restarts a solve in the process that made it and in a worker.

    For the 2-D film also ``key``: the options it was solved with (a restart with others
    starts from its 1-D state only), and ``prior``: the case and DOF vector of the point
    before it on a path, on this answer's mesh (solved on the same mesh, or carried over to
    it where the continued start changed the mesh; a secant predictor's second point,
    :mod:`webfem.models.continued`), ``prior2``: the one before that, solved on the same
    mesh too (a quadratic predictor's third point), ``refined``: whether the answer's mesh
    is one its error estimate refined (or one kept from a restart whose was), and ``coarse``: the
    nodes and solved DOF vector ``(X, Z, u)`` on the answer's coarser mesh (its error
    estimate's), from which the next point's coarse solve starts (two-grid start)."""

    case: Case
    model: str
    X: np.ndarray
    u: np.ndarray
    Z: np.ndarray | None = None
    line: "State | None" = None
    key: dict | None = None
    prior: tuple | None = None
    coarse: tuple | None = None
    prior2: tuple | None = None
    refined: bool = False

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
        after :meth:`slim` (continuation reads :attr:`restart`). A 2-D problem is built
        again on each call from its nodes (a result holding its bases and assembly maps
        kept hundreds of MB alive per result)."""
        value = (self.diagnostics.solver or {}).get(name)
        return value() if isinstance(value, Rebuild) else value

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


def refused(case: Case, model: str, message: str) -> Result:
    """The result kept for a point ``model`` refuses to answer (outside its domain, no
    admissible solution): ``converged`` False, the reason in ``solver_message`` and
    ``warnings``, every computed number NaN (null in JSON), only the case's own groups
    (lambda, beta, ...) filled. Many-point calls (:func:`webfem.api.solve_many`, sweeps) keep
    it in place so one refused point does not lose the others' answers.

    >>> r = refused(Case(), "fitted", "outside the domain")
    >>> r["converged"], r["solver_message"], r.to_dict()["mu"]
    (False, 'outside the domain', None)
    """
    nan = float("nan")
    message = " ".join(str(message).split())
    summary = Summary(
        model=model, h_center=nan, h_inlet=nan, h_outlet=nan, h_min=nan, mu=nan, delta_T=nan,
        regime="none", lambda_=case.lam, beta=case.beta,
        eq21_valid=bool(case.beta > 6 and case.lam > 7), converged=False, iterations=0,
        n_dofs=0, solve_time_s=0.0, h_c=nan, sigma=case.sigma, share_boundary=nan,
        share_mixed=nan, share_fluid=nan, eps=case.eps, kappa=case.kappa, U=case.U,
        U_slide=case.U_slide, residual=nan, warnings=(message,), T_eff=case.tension_eff,
        solver_message=message)
    empty = np.empty(0)
    return Result(case, summary, Fields(x=empty, h=empty), Diagnostics(reason=message))
