"""1-D finite elements: the infinitely wide foil bearing with permeation and asperity contact.

This module is the model on the shared driver (start, state transfer, mesh, summary extras);
the discrete problem and its solvers are :class:`webfem.models.line.FoilBearing1D`.

Solves the compressible Reynolds equation with the Darcy sink coupled to the web (membrane, or
beam when ``web.bending_stiffness`` > 0) on a graded line over the wrap plus entry and exit
zones (:mod:`webfem.fem.forms` states the equations). Elements: P2 Lagrange for the film
pressure (P1 on request) and cubic Hermite for the web deflection, so the beam's second
derivatives are conforming; one composite scikit-fem basis holds both and is built once per
mesh. Coupling: Newton on the whole system with the exact Jacobian (default), with
continuation in the permeability when a cold start fails; or Picard (film, then web, with
fixed or Aitken under-relaxation) as asked by the user.

The web lands on the roller at low speed or with a permeable web (Eq. 21 clamps h <= 0 to 0).
Here the asperity contact pressure of Eq. 10 joins the web equilibrium (``contact=True``, the
default; the paper does not do this), so the gap stays positive; the summary reports the share
of the wrap load carried by contact (``contact_share``). Friction is the paper's Eqs. 10-13,
28-31 on the solved gap, averaged over the wrap.

Examples
--------
>>> from webfem import Case
>>> r = solve(Case().updated({"roller.speed": 40.0}))
>>> r["converged"], r["model"]
(True, 'fe1d')
>>> bool(15e-6 < r["h_min"] < r["h_center"] < 50e-6)
True
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..case import Case
from ..errors import ConvergenceError, InputError
from ..fem import ends, forms
from ..fem.mesh import graded_nodes, refine_nodes
from ..fem.meshfile import read_x_nodes
from ..fem.scaling import FoilParameters
from ..result import Result, State
from .driver import Discretisation, Start, solve_fe, solve_state
from .line import FoilBearing1D
from .model_error import fe1d_basis, fe1d_errors
from .options import FE1DOptions
from .outcome import Facts

__all__ = ["FoilParameters", "FoilBearing1D", "ProblemCache", "LINE", "solve", "solve_case",
           "LineStart", "solve_start",
           "NAME", "spans", "ends_warnings", "short_span_warning", "held_ends_warning",
           "HELD_ENDS_SHARE"]

NAME = "fe1d"
#: The defaults of :class:`~webfem.models.options.FE1DOptions`, by name (read-only view).
DEFAULTS = FE1DOptions().to_dict()
def _nodes(beta, entry, level, nodes=None) -> np.ndarray:
    """The starting X nodes: webfem's graded mesh, or the user's (``nodes``, scaled), with the
    wrap edges added as nodes (the wrap pressure T/R starts and stops there)."""
    if nodes is None:
        return graded_nodes(beta, entry, level=level)
    X = np.unique(np.asarray(nodes, float))
    e = 0.5 * beta
    if X.size < 3 or not (X[0] < -e and X[-1] > e):
        raise InputError(f"mesh spans X = {X[0]:.4g} .. {X[-1]:.4g} (scaled), which does not "
                        f"cover the wrap |X| <= {e:.4g} with entry and exit zones; valid: a "
                        "line mesh over the wrap plus both zones")
    tol = 1e-9 * (X[-1] - X[0])
    X = X[(np.abs(X + e) > tol) & (np.abs(X - e) > tol)]       # snap onto the exact edges
    X = np.unique(np.concatenate([X, [-e, e]]))
    X = X[np.concatenate([[True], np.diff(X) > tol])]          # drop near-duplicates
    return refine_nodes(X, level)


class ProblemCache:
    """Discrete problems by their nodes and element order, built once: the starting meshes
    and the refined ones (a repeated solve, and often a sweep's next point, refine to the
    same nodes). The least recently used makes room for a new one beyond ``size``, so a
    sweep keeps its starting mesh while its refined ones come and go. A problem holds no
    state of a solve that could change the next one's answer (tests/test_trust.py)."""

    def __init__(self, size: int = 12):
        self.size = size
        self._problems: dict = {}

    def __call__(self, X, order, spans: bool = False) -> FoilBearing1D:
        X = np.asarray(X, float)
        key = (X.size, float(X[0]), float(X[-1]), order, bool(spans), X.tobytes())
        problem = self._problems.pop(key, None)
        if problem is None:
            problem = FoilBearing1D(X, order=order, spans=spans)
            while len(self._problems) >= self.size:
                self._problems.pop(next(iter(self._problems)))
        self._problems[key] = problem                # the most recently used last
        return problem

    def clear(self) -> None:
        self._problems.clear()


def _transfer(coarse: FoilBearing1D, u, prm, fine: FoilBearing1D) -> np.ndarray:
    """A state on another mesh (exact on a nested finer one for the P1/P2 and Hermite
    spaces, up to the interpolation of P2 midpoints)."""
    v = np.zeros(fine.n_dofs)
    xn = fine.X
    # slope of W: derivative of the Hermite interpolant through probes at +- a small offset
    d = 1e-7 * max(1.0, float(np.ptp(xn)))
    xa, xb = np.clip(xn - d, xn[0], xn[-1]), np.clip(xn + d, xn[0], xn[-1])
    # one probe of the three point sets (point by point the same numbers as three)
    n = xn.size
    pts = np.concatenate([xn, xb, xa])
    W = coarse.gap(u, prm, pts) - forms.departure(pts, prm.beta)
    v[fine.iW] = W[:n]
    v[fine.iWx] = (W[n:2 * n] - W[2 * n:]) / (xb - xa)
    xP = fine.basis.doflocs[0][fine.iP]
    v[fine.iP] = coarse.pressure(u, xP)
    v[fine.fixed] = 0.0
    return v


class _Line(Discretisation):
    """The 1-D model's part of the shared driver (:mod:`webfem.models.driver`)."""

    name = NAME

    def __init__(self):
        #: the discrete problems of recent solves, kept for the next (bounded)
        self.problems = ProblemCache()

    def _start_problem(self, prm, options, case) -> FoilBearing1D:
        nodes = options.nodes
        if options.mesh is not None:
            nodes = read_x_nodes(options.mesh) / case.x_scale
        X = _nodes(prm.beta, options.entry, options.level, nodes)
        return self.problems(X, options.order, spans(case, X))

    def start(self, case: Case, prm: FoilParameters, options: FE1DOptions,
              restart: State | None) -> Start:
        problem = self._start_problem(prm, options, case)
        return Start(problem, self._restarted(problem, prm, options, restart))

    def _restarted(self, problem, prm, options, restart) -> np.ndarray:
        """The start vector: a 1-D state of a nearby case mapped through the scaled gap
        (positions relative to the nearer wrap edge, so the entry and exit zones line up),
        else the cold start."""
        if restart is None or restart.model != NAME:
            return problem.initial_guess(prm)
        old = self.problems(restart.X, options.order, problem.spans)
        if old.n_dofs != restart.u.size:
            return problem.initial_guess(prm)
        prev = FoilParameters.from_case(restart.case, options.compressible, options.contact,
                                        options.floor)
        Xprev = old.X
        inner = np.clip(Xprev, Xprev[0] + 1e-6, Xprev[-1] - 1e-6)
        e_prev, e = 0.5 * prev.beta, 0.5 * prm.beta
        X = problem.X
        Xmap = np.where(X < 0, X + e - e_prev, X - e + e_prev)
        H = np.interp(Xmap, Xprev, old.gap(restart.u, prev, Xprev))
        P = np.interp(Xmap, Xprev, old.pressure(restart.u, inner))
        u = problem.initial_guess(prm)
        W = H - forms.departure(X, prm.beta)
        if not problem.spans:
            W[0] = W[-1] = 0.0
        u[problem.iW] = W
        u[problem.iWx] = np.gradient(W, X)
        xP = problem.basis.doflocs[0][problem.iP]
        u[problem.iP] = np.interp(xP, X, P)
        u[problem.fixed] = 0.0
        return u

    def safe_start(self, case: Case, prm: FoilParameters, options: FE1DOptions) -> Start | None:
        """The starting mesh solved along the Eshel-Elrod continuation from cold (Newton
        only): the driver's second try when the direct start failed or converged to an
        inadmissible branch (at 15-20 m/s on the base case the direct cold start ends with
        the web through the roller at the exit, the continuation on the physical branch on
        the same mesh). None when it does not converge."""
        if options.method != "newton" or not options.continuation:
            return None
        problem = self._start_problem(prm, options, case)
        u, info = problem.solve_continued(prm, options)
        if not info.converged:
            return None
        return Start(problem, u, info=info)

    def remeshed(self, problem, u, prm, X, Z, options):
        """The problem on the nodes X (coarser or finer) and ``u`` carried over to it."""
        other = self.problems(np.asarray(X, float), options.order, problem.spans)
        return other, _transfer(problem, u, prm, other)

    def mesh_text(self, problem, options) -> str:
        return f"{line_mesh_text(problem.X, options)}, P{options.order}/Hermite"

    def facts(self, case: Case, problem, u, prm, options, readout) -> Facts:
        warnings = ((f"lambda = {case.lam:.3g}: a narrow web leaks air at its edges, which "
                     "the 1-D (infinitely wide) model ignores; its gap is too large",)
                    if case.lam < 7.0 else ()) + ends_warnings(case, prm, problem.X)
        return Facts(n_cells=len(problem.X) - 1, warnings=warnings)


#: The bending length sqrt(D/T_eff), as a share of the entry and exit zones, above which a
#: result warns that where the web is held moves its answer. On the envelope benchmark's
#: smooth points (zones 40 R eps^(1/3)), freeing the web's ends instead of holding them moved
#: the largest of h_center, h_min and mu by at most 0.77 % where the bending length was under
#: 5 % of the zones (Dn < 4, median 0.03 %), by up to 1.3 % at 5-14 % and by 7-106 % above
#: 28 % (Dn > 100; docs/model.md).
HELD_ENDS_SHARE = 0.05


def spans(case: Case, X) -> bool:
    """Whether the web is held through spans beyond the domain on the (scaled) nodes ``X``
    (:mod:`webfem.fem.ends`) rather than at its ends: where the case asks for it
    (``wrap.ends = "span"``, :attr:`Case.span_used`) and its span reaches past the entry
    and exit zones (else :func:`short_span_warning` says it is held at the zones' ends)."""
    span = case.span_used
    return span is not None and span / case.x_scale > ends.shortest_span(X, case.beta)


def ends_warnings(case: Case, prm: FoilParameters, X) -> tuple[str, ...]:
    """What a result on the (scaled) nodes ``X`` says about where its web is held: a span
    that does not reach past the zones (:func:`short_span_warning`) and a stiff web held at
    the zones' ends (:func:`held_ends_warning`); both models' facts."""
    return held_ends_warning(case, prm, X) + short_span_warning(case, X)


def short_span_warning(case: Case, X) -> tuple[str, ...]:
    """The warning that ``wrap.span`` does not reach past the entry and exit zones on the
    nodes ``X``, so that the web is held at the zones' ends instead (Eq. 20)."""
    span = case.span_used
    if span is None or spans(case, X):
        return ()
    least = ends.shortest_span(X, case.beta)
    return (f"wrap.span = {span:g} m does not reach past the entry and exit zones "
            f"({least * case.x_scale:.4g} m, {least:.4g} R eps^(1/3)): the web is held at the "
            "zones' ends instead (w = 0, the paper's Eq. 20); a shorter option entry shortens "
            "the zones",)


def held_ends_warning(case: Case, prm: FoilParameters, X) -> tuple[str, ...]:
    """The warning that the web's ends, held on its nominal line at the ends of the entry
    and exit zones (w = 0, the paper's Eq. 20), move the answer: a web whose bending length
    reaches :data:`HELD_ENDS_SHARE` of the zones does not run parallel to its nominal line
    there, and the ends' position (an artefact of the domain) enters the answer. Nothing
    (an empty tuple) for flexible webs."""
    zone = min(-float(X[0]), float(X[-1])) - 0.5 * prm.beta
    bend = float(np.sqrt(max(prm.Dn, 0.0)))
    if spans(case, X) or zone <= 0.0 or bend <= HELD_ENDS_SHARE * zone:
        return ()
    mm = 1e3 * case.x_scale
    return (f"bending: the web's bending length sqrt(D/T_eff) = {bend * mm:.3g} mm is "
            f"{bend / zone:.2g} x the entry and exit zones ({zone * mm:.3g} mm), at whose "
            "ends the web is held on its nominal line (w = 0, Eq. 20): where it is held "
            "moves the answer, and the stated errors do not include that. On the envelope "
            "benchmark's board points with Dn > 100 freeing the ends instead moved h_center, "
            "h_min or mu by 7-106 % (docs/model.md, 'Where the web is held'); wrap.ends = \"span\" "
            "(the default) holds it at the neighbouring rollers instead, wrap.span (m) from "
            "the wrap edges",)


def line_mesh_text(X, options) -> str:
    """What the x mesh is: webfem's graded one or the user's, its span and cells."""
    cells = f"{len(X) - 1} cells after refinement, level {options.level}"
    if options.nodes is None and options.mesh is None:
        return f"graded line, {cells}, entry/exit {options.entry:g} R eps^(1/3)"
    source = f"user mesh {options.mesh}" if options.mesh else "user nodes"
    return f"{source}, X = {X[0]:.4g} .. {X[-1]:.4g} R eps^(1/3), {cells}"


#: The 1-D model as the driver sees it.
LINE = _Line()


def solve_case(case: Case, options: FE1DOptions, *, initial: Result | None = None,
               raise_on_failure: bool = True) -> Result:
    """The registry's entry: :func:`solve` with a ready options object. A grooved roller is
    refused (the 1-D film has no width)."""
    from ..physics.validity import grooves_refused

    grooves_refused(case, "fe1d")
    try:
        r = solve_fe(LINE, case, options, initial, raise_on_failure)
    except ConvergenceError as err:
        if err.result is not None:
            err.result = with_model_error(err.result)
        raise
    return with_model_error(r)


@dataclasses.dataclass(frozen=True)
class LineStart:
    """A 1-D solution as the start of another solve (:func:`solve_start`): its discrete
    ``problem`` and ``state``, the Newton ``iterations`` it took, whether it ``converged``
    (admissible), and ``restart``: the state a later 1-D solve continues from (a result's
    :attr:`~webfem.result.Result.restart`)."""

    problem: FoilBearing1D
    state: np.ndarray
    iterations: int
    converged: bool
    restart: State


def solve_start(case: Case, options: FE1DOptions, *, initial: Result | State | None = None
                ) -> LineStart:
    """:func:`solve_case` without its result (its read-out, friction, fields and model
    error; ``raise_on_failure`` False: a failed solve is returned, not raised): the solve
    that starts fe2d's, which reads only the state (:func:`webfem.models.driver.
    solve_state`). ``initial``: a 1-D result or state to continue from."""
    from ..physics.validity import grooves_refused

    grooves_refused(case, "fe1d")
    start, problem, u, info = solve_state(LINE, case, options, initial)
    return LineStart(problem, u, int(info.iterations), bool(info.converged),
                     LINE.state(case, problem, u, start, options))


def with_model_error(r: Result) -> Result:
    """``r`` with its stated errors the mesh error plus the edge leakage the infinitely wide
    model leaves out (:func:`webfem.models.model_error.fe1d_errors`); unchanged without a
    mesh error estimate (``estimate = False``)."""
    s = r.summary
    if s.error_h_center is None:
        return r
    model = fe1d_errors(r.case, s, r.diagnostics, r.fields)
    errors = {f"error_{q}": s.get(f"error_{q}", 0.0) + e for q, e in model.items()}
    basis = f"mesh: {s.error_basis}; model: {fe1d_basis(r.case)}"
    return dataclasses.replace(r, summary=s.replace(**errors, error_basis=basis))


def solve(case: Case, options: FE1DOptions | None = None, *, initial: Result | None = None,
          raise_on_failure: bool = True, **values) -> Result:
    """Solve one case with the 1-D FE model.

    ``options`` (or the same names as keywords, see
    :class:`~webfem.models.options.FE1DOptions`): ``entry``, ``level``, ``order``,
    ``compressible``, ``contact``, ``method`` ("newton", "picard", "picard-staggered"),
    ``tol`` ... ``initial``: a previous fe1d result to start from (continuation in a sweep).

    Raises :class:`webfem.errors.ConvergenceError` (carrying the unconverged result and the
    residual history) when no converged, admissible solution is found, unless
    ``raise_on_failure=False``.
    """
    options = options.replace(**values) if options is not None else \
        FE1DOptions.from_mapping(values)
    return solve_case(case, options, initial=initial, raise_on_failure=raise_on_failure)
