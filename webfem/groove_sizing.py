"""Groove sizing: traction against groove pitch and land fraction at the case's speed(s), and
the traction-loss speed of each groove geometry.

The question users bring (issue 15): which groove keeps mu above ``mu_min`` at a given line
speed, and how much land (contact area, heat transfer, marking) does it cost? For each
design (pitch p_g, land fraction a/p_g, depth delta) at each speed :func:`groove_map` solves
the grooved 2-D film (fe2d) and marks the designs with mu >= mu_min as feasible, unless the
answer's own warning says its film is not what fe2d computes (the web sagging into wide
grooves: ``flag``); the recommended one is the feasible design with the largest land fraction
(ties: the larger mu). Each design keeps its h_min, stated errors and warnings.
:func:`loss_speed_map` finds, per geometry, the roller speed at which mu falls to ``mu_min``
(:func:`webfem.traction.traction_loss_speed` with fe2d), beside the smooth roller's.

Both are resumable when given a ``store`` (a CSV path): each design's row is saved as it
finishes and a re-run with the same arguments solves only what is missing
(:mod:`webfem.sweeps.keyed`). Designs without an answer are kept as they are: each design is
solved from cold, so solving it again would repeat the failure (and a design with no
admissible solution can cost minutes: the driver confirms it on finer meshes).

Examples
--------
>>> DEFAULT_PITCHES[1], DEFAULT_LAND_FRACTIONS[-1]
(0.00127, 0.9)
"""

from __future__ import annotations

import json
import warnings
from dataclasses import asdict, dataclass
from functools import partial
from typing import Callable, Sequence

from .api import solve
from .case import Case
from .errors import ConvergenceError, InputError, NoAdmissibleSolution, ValidityWarning
from .line_speed import at_speed, ratio_text, speed_ratio
from .models.groove_domain import sag_warning
from .models.registry import make_options
from .sweeps.keyed import run_points
from .sweeps.workers import Processes, check_workers
from .traction import traction_loss_speed

__all__ = ["GrooveDesign", "LossSpeed", "groove_map", "best_designs", "loss_speed_map",
           "check_arguments",
           "DEFAULT_PITCHES", "DEFAULT_LAND_FRACTIONS", "DEFAULT_DEPTH", "DEFAULT_SPEED_FACTORS",
           "LOSS_PITCHES", "LOSS_LAND_FRACTIONS", "LOSS_SPEED_RANGE", "LOSS_SCAN"]

#: Pitches [m] of the map: fine to coarse around Walker's 1.27 mm.
DEFAULT_PITCHES = (0.8e-3, 1.27e-3, 2.5e-3, 5e-3)
#: Land fractions a/p_g of the map.
DEFAULT_LAND_FRACTIONS = (0.5, 0.65, 0.8, 0.9)
#: Groove depth [m] of the map (Walker's 0.25 mm).
DEFAULT_DEPTH = 0.25e-3
#: Map speeds unless told, as multiples of the case's roller speed: the case's, and twice it
#: for the margin of a faster line (20 and 40 m/s on the base case); the web follows at the
#: case's ratio U_w/U_r (:func:`webfem.line_speed.at_speed`).
DEFAULT_SPEED_FACTORS = (1.0, 2.0)
#: The traction-loss grid (each geometry is a root find of about 14 fe2d solves: a smaller
#: grid than the map's).
LOSS_PITCHES = (1.27e-3, 2.5e-3, 5e-3)
LOSS_LAND_FRACTIONS = (0.8, 0.9, 0.95)
#: Roller speeds [m/s] the traction-loss search scans, and its points (logarithmic).
LOSS_SPEED_RANGE = (1.0, 100.0)
LOSS_SCAN = 8

MAP_COLUMNS = ("speed", "pitch", "width", "depth", "land_fraction", "mu", "h_center",
               "contact_share", "converged", "solver_message", "h_min", "error_h_center",
               "error_h_min", "error_mu", "error_contact_share", "warnings", "flag")

#: A design's ``flag`` where the web sags into its grooves by more than the model holds
#: (:func:`webfem.models.groove_domain.sag_warning`): its film over the land edges is not
#: what fe2d computes, so its mu does not make it feasible.
SAG_FLAG = "web sags into the grooves: the film over the land edges is not what fe2d computes"
LOSS_COLUMNS = ("pitch", "width", "depth", "land_fraction", "loss_speed", "mu_peak",
                "speed_peak", "evaluations", "converged", "message", "scan_limit",
                "scanned_to")


@dataclass(frozen=True)
class GrooveDesign:
    """One design at one roller speed and what fe2d answers for it (SI units)."""

    speed: float
    pitch: float
    width: float
    depth: float
    land_fraction: float
    mu: float | None
    h_center: float | None
    contact_share: float | None
    converged: bool
    feasible: bool
    message: str = ""       # why there is no answer (the solver's or the model's message)
    #: the smallest gap [m], the stated errors (relative, as the summary's), the answer's
    #: warnings, and why a design whose mu meets mu_min is not feasible ("" none:
    #: :data:`SAG_FLAG`)
    h_min: float | None = None
    error_h_center: float | None = None
    error_h_min: float | None = None
    error_mu: float | None = None
    error_contact_share: float | None = None
    warnings: tuple[str, ...] = ()
    flag: str = ""

    def to_dict(self) -> dict:
        return {**asdict(self), "warnings": list(self.warnings)}

    def csv_row(self) -> dict:
        """The row as the map's CSV holds it (:data:`MAP_COLUMNS`: ``solver_message``, the
        warnings joined by " | "), for its copies in other units; then ``feasible`` and
        ``message`` (the copies' columns before they followed the CSV's)."""
        d = asdict(self)
        return {k: d[k] for k in MAP_COLUMNS if k in d} | {
            "solver_message": self.message, "warnings": " | ".join(self.warnings),
            "feasible": self.feasible, "message": self.message}


@dataclass(frozen=True)
class LossSpeed:
    """The traction-loss speed of one groove geometry (pitch 0: the smooth roller), SI units.

    ``speed`` is None when mu does not fall to mu_min in the scanned range (``message`` says
    which way); ``converged`` is False when a solve of the search failed. ``scanned_to``
    [m/s] is the highest speed the scan answered, ``scan_limit`` why it ended there below
    the range asked (as :class:`webfem.traction.TractionLoss`'s: fe2d refused the next
    speed, or the line cannot run faster); None where the scan covered the range or stopped
    at its crossing. A row without a speed and with a ``scan_limit`` was refused partway:
    mu stays on its side of mu_min up to ``scanned_to``, above it nothing is known
    (:meth:`refused_partway`).
    """

    pitch: float
    width: float
    depth: float
    land_fraction: float
    speed: float | None
    mu_peak: float | None
    speed_peak: float | None
    evaluations: int
    converged: bool
    message: str
    scan_limit: str | None = None
    scanned_to: float | None = None

    def to_dict(self) -> dict:
        return asdict(self)

    def csv_row(self) -> dict:
        """The row as the loss-speed CSV holds it (:data:`LOSS_COLUMNS`: ``loss_speed``),
        for its copies in other units; then ``speed`` (the copies' column before)."""
        d = asdict(self)
        return {k: d[k] for k in LOSS_COLUMNS if k in d} | {"loss_speed": self.speed,
                                                              "speed": self.speed}

    def refused_partway(self) -> bool:
        """Whether the scan ended below the range asked without finding a speed: its
        answer holds only up to ``scanned_to`` (``scan_limit`` says why)."""
        return self.converged and self.speed is None and bool(self.scan_limit)


def check_arguments(mu_min, *, speeds=(), pitches=(), land_fractions=(), depths=()) -> float:
    """Raise :class:`~webfem.errors.InputError` naming the first value out of range (a
    command checks before it creates its output folder); returns ``mu_min`` as a float."""
    if isinstance(mu_min, bool) or not isinstance(mu_min, (int, float)) \
            or not 0.0 < mu_min < 10.0:
        raise InputError(f"mu_min = {mu_min!r} is out of range: must be > 0 and < 10")
    for v in land_fractions:
        if not 0.0 < v < 1.0:
            raise InputError(f"land fraction = {v!r} is out of range: must be > 0 and < 1")
    for name, values, unit in (("groove pitch", pitches, "m"), ("groove depth", depths, "m"),
                               ("roller speed", speeds, "m/s")):
        for v in values:
            if not 0.0 < v < float("inf"):
                raise InputError(f"{name} = {v!r} is out of range: must be > 0 [{unit}]")
    return float(mu_min)


def _grooved(case: Case, pitch: float, land: float, depth: float) -> Case:
    return case.updated({"roller.groove_pitch": pitch,
                         "roller.groove_width": pitch * (1.0 - land),
                         "roller.groove_depth": depth})


def _signature(kind: str, case: Case, opts, points: int, **grid) -> dict:
    """What makes two runs the same table (JSON-ready; also the lock's description)."""
    from . import __version__
    # a moving web follows the roller since the line speed module: a store made with the
    # web speed fixed must not be resumed (a web at rest, ratio 0, answers as before)
    moved = {"web": "at the case's ratio to the roller"} if speed_ratio(case) else {}
    return {**moved, "table": kind, "parameter": kind, "model": "fe2d", "points": points,
            "case": case.to_dict(), "webfem": __version__,
            "options": json.loads(json.dumps(opts.changed(), sort_keys=True, default=str)),
            **{k: [float(v) for v in vs] if isinstance(vs, (list, tuple)) else vs
               for k, vs in grid.items()}}


def _run(rows_of, n: int, store, sig, columns, keys, points, progress,
         workers: int = 1, what: str = "designs", notice=None) -> list[dict]:
    """Every row, through the resumable store when there is one, else in memory; in
    ``workers`` processes when more than one (each row is solved from cold, so the rows do
    not depend on which process solved them). A design without an answer is kept too: a
    re-run would only repeat its failure (delete the CSV to solve everything again)."""
    if store is not None:
        return run_points(store, sig, columns, keys, points, rows_of, progress=progress,
                          keep_failures=True, workers=workers, what=what, notice=notice)
    out: list = [None] * n
    finished = 0

    def record(i: int, row: dict) -> None:
        nonlocal finished
        out[i] = row
        finished += 1
        if progress:
            progress(finished, n)

    if workers > 1 and n > 1:
        pool = Processes(min(workers, n))
        try:
            pool.run([(i, (i,)) for i in range(n)], record, task=rows_of)
        finally:
            pool.close()
    else:
        for i in range(n):
            record(i, rows_of(i))
    return out


def groove_map(case: Case, mu_min: float, *, speeds: Sequence[float] | None = None,
               pitches: Sequence[float] = DEFAULT_PITCHES,
               land_fractions: Sequence[float] = DEFAULT_LAND_FRACTIONS,
               depths: Sequence[float] = (DEFAULT_DEPTH,), options=None,
               progress: Callable[[int, int], None] | None = None,
               store=None, workers: int = 1,
               notice: Callable[[str], None] | None = None) -> list[GrooveDesign]:
    """Every design (pitch x land fraction x depth) at every roller speed, solved with fe2d.

    Parameters
    ----------
    case : Case
        The line; its groove keys are replaced by each design's.
    mu_min : float
        Traction needed, > 0 and < 10: marks the feasible designs.
    speeds : sequence of float, optional
        Roller speeds [m/s]; default :data:`DEFAULT_SPEED_FACTORS` times the case's. The web
        follows at the case's ratio U_w/U_r (:func:`webfem.line_speed.at_speed`).
    pitches, land_fractions, depths : sequences of float
        The grid: pitches and depths [m] > 0, land fractions a/pitch in (0, 1).
    options : FE2DOptions or dict, optional
        fe2d's options.
    progress : callable, optional
        ``progress(finished, total)`` after each design.
    store : path, optional
        A CSV: each design's row is saved as it finishes and a re-run of the same map
        (case, grid, options; ``mu_min`` may differ: it only marks) solves only the
        missing designs. None: in memory.
    workers : int
        Designs solved at once, each in a process of its own (1: in this process). Each
        design is solved from cold, so the answers do not depend on it; each process holds
        one design's matrices (about 1.2 GB at the default grid's largest).
    notice : callable, optional
        ``notice(text)``: told in one line when a ``store`` is resumed (how many designs are
        there, how many left) or an old table there is started afresh.

    Returns
    -------
    list of GrooveDesign
        Speed by speed, then pitch, land fraction and depth. A design that does not
        converge, or has no admissible solution (the web pressed through its asperities),
        has ``converged = False``, ``mu = None`` and the reason in ``message``.

    Raises
    ------
    InputError
        A value out of range (before anything is solved), an output that cannot be written
        or a store locked by a running map.
    SweepInterrupted
        Ctrl-C with a ``store``: says how many designs are saved.
    """
    speeds = ([f * case.roller.speed for f in DEFAULT_SPEED_FACTORS] if speeds is None
              else [float(s) for s in speeds])
    mu_min = check_arguments(mu_min, speeds=speeds, pitches=pitches,
                             land_fractions=land_fractions, depths=depths)
    opts = make_options("fe2d", options)
    workers = check_workers(workers)
    for s in speeds:   # refused before anything is solved, naming the speed
        try:
            at_speed(case, s)
        except InputError as err:
            raise InputError(f"roller speed {s:g} m/s ({ratio_text(case)}): {err}") from None
    designs = [(s, p, p * (1.0 - f), d, f) for s in speeds for p in pitches
               for f in land_fractions for d in depths]

    row = partial(_design_row, case, opts, designs)
    sig = _signature("groove map", case, opts, len(designs), speeds=speeds, pitches=pitches,
                     land_fractions=land_fractions, depths=depths)
    rows = _run(row, len(designs), store, sig, MAP_COLUMNS,
                ("speed", "pitch", "width", "depth"), [d[:4] for d in designs], progress,
                workers, "designs", notice)
    return [GrooveDesign(r["speed"], r["pitch"], r["width"], r["depth"], r["land_fraction"],
                         r.get("mu"), r.get("h_center"), r.get("contact_share"),
                         bool(r["converged"]),
                         bool(r["converged"] and r["mu"] >= mu_min and not r.get("flag")),
                         r.get("solver_message") or "", h_min=r.get("h_min"),
                         error_h_center=r.get("error_h_center"),
                         error_h_min=r.get("error_h_min"), error_mu=r.get("error_mu"),
                         error_contact_share=r.get("error_contact_share"),
                         warnings=tuple(w for w in (r.get("warnings") or "").split(" | ")
                                        if w),
                         flag=r.get("flag") or "") for r in rows]


def _design_row(case: Case, opts, designs, n: int) -> dict:
    """The map's row of design ``n`` (a module function: the workers' task)."""
    speed, pitch, width, depth, land = designs[n]
    # the line moves: the web keeps the case's ratio to the roller (webfem.line_speed)
    c = at_speed(_grooved(case, pitch, land, depth), speed)
    out = {"speed": speed, "pitch": pitch, "width": width, "depth": depth,
           "land_fraction": c.land_fraction, "converged": False}
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            r = solve(c, model="fe2d", options=opts)
    except (ConvergenceError, NoAdmissibleSolution) as err:   # kept, as in a sweep
        return {**out, "solver_message": " ".join(str(err).split())}
    said = tuple(r.get("warnings") or ())
    h_min = r.get("h_min")
    # the sag warning is the solve's own (same case, same h_min): a design whose film the
    # model does not compute is flagged, whatever its mu
    sag = sag_warning(c, h_min) if h_min is not None else ""
    return {**out, "mu": r["mu"], "h_center": r["h_center"],
            "contact_share": r["contact_share"], "converged": True, "h_min": h_min,
            **{k: r.get(k) for k in ("error_h_center", "error_h_min", "error_mu",
                                     "error_contact_share")},
            # " | " between warnings: they hold "; " themselves
            "warnings": " | ".join(" ".join(w.split()) for w in said),
            "flag": SAG_FLAG if sag and sag in said else ""}


def best_designs(designs: Sequence[GrooveDesign]) -> dict[float, GrooveDesign | None]:
    """Per speed: the feasible design with the largest land fraction (ties: larger mu), or
    None when no design keeps mu >= mu_min."""
    best: dict[float, GrooveDesign | None] = {}
    for d in designs:
        best.setdefault(d.speed, None)
        if d.feasible:
            b = best[d.speed]
            if b is None or (d.land_fraction, d.mu) > (b.land_fraction, b.mu):
                best[d.speed] = d
    return best


def loss_speed_map(case: Case, mu_min: float, *, pitches: Sequence[float] = LOSS_PITCHES,
                   land_fractions: Sequence[float] = LOSS_LAND_FRACTIONS,
                   depth: float = DEFAULT_DEPTH, speed_range=LOSS_SPEED_RANGE,
                   n_scan: int = LOSS_SCAN, xtol: float = 1e-2, options=None,
                   progress: Callable[[int, int], None] | None = None,
                   store=None, workers: int = 1,
                   notice: Callable[[str], None] | None = None) -> list[LossSpeed]:
    """The traction-loss speed (mu falls to ``mu_min`` after its peak) of the smooth roller
    and of every groove geometry, with fe2d.

    Each is :func:`webfem.traction.traction_loss_speed`: a logarithmic scan of ``n_scan``
    speeds walked with continuation, then Brent's method to ``xtol`` of the bracket's low
    end (1 % by default: the chart's resolution).

    Parameters
    ----------
    case : Case
        The line; its roller speed is scanned (the web at the case's ratio U_w/U_r), its
        groove keys replaced.
    mu_min : float
        The traction threshold, > 0 and < 10.
    pitches, land_fractions : sequences of float
        The geometries: pitches [m] > 0 x land fractions in (0, 1).
    depth : float
        Groove depth [m] of every geometry.
    speed_range : (float, float)
        Roller speeds [m/s] scanned.
    n_scan, xtol
        Scan points and Brent's relative tolerance.
    options : FE2DOptions or dict, optional
        fe2d's options.
    progress : callable, optional
        ``progress(finished, total)`` after each geometry.
    store : path, optional
        A CSV: each geometry is saved as it finishes and a re-run of the same table
        (case, grid, ``mu_min``, scan, options) solves only what is missing.
    workers : int
        Geometries searched at once, each in a process of its own (1: in this process).
    notice : callable, optional
        As :func:`groove_map`'s (geometries).

    Returns
    -------
    list of LossSpeed
        The smooth roller first (pitch 0), then pitch by pitch, land fraction by land
        fraction. A search whose solve failed has ``converged = False`` and the reason; one
        whose scan fe2d refused partway, before a crossing, ``scan_limit`` and
        ``scanned_to``.

    Raises
    ------
    InputError, SweepInterrupted
        As :func:`groove_map`.
    """
    mu_min = check_arguments(mu_min, pitches=pitches, land_fractions=land_fractions,
                             depths=[depth])
    opts = make_options("fe2d", options)
    workers = check_workers(workers)
    shapes = [(0.0, 0.0, 0.0, 1.0)] + [(p, p * (1.0 - f), depth, f) for p in pitches
                                       for f in land_fractions]

    row = partial(_loss_row, case, mu_min, opts, shapes,
                  dict(speed_range=speed_range, n_scan=n_scan, xtol=xtol))
    # the scan stops at its first crossing (since the loss_scan module): a store made by a
    # full scan must not be resumed by it
    sig = _signature("traction-loss speed", case, opts, len(shapes), scan="first crossing",
                     mu_min=mu_min,
                     pitches=pitches, land_fractions=land_fractions, depth=float(depth),
                     speed_range=list(speed_range), n_scan=n_scan, xtol=xtol)
    rows = _run(row, len(shapes), store, sig, LOSS_COLUMNS, ("pitch", "width", "depth"),
                [s[:3] for s in shapes], progress, workers, "geometries", notice)
    return [LossSpeed(r["pitch"], r["width"], r["depth"], r["land_fraction"],
                      r.get("loss_speed"), r.get("mu_peak"), r.get("speed_peak"),
                      int(r.get("evaluations") or 0), bool(r["converged"]),
                      r.get("message") or "", r.get("scan_limit") or None,
                      r.get("scanned_to")) for r in rows]


def _loss_row(case: Case, mu_min: float, opts, shapes, search: dict, n: int) -> dict:
    """The traction-loss row of geometry ``n`` (a module function: the workers' task)."""
    pitch, width, d, land = shapes[n]
    c = _grooved(case, pitch, land, d) if pitch else case.updated(
        {"roller.groove_width": 0.0})
    out = {"pitch": pitch, "width": width, "depth": d, "land_fraction": c.land_fraction,
           "evaluations": 0}
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)
            t = traction_loss_speed(c, mu_min, "fe2d", options=opts, **search)
    except (ConvergenceError, NoAdmissibleSolution) as err:   # kept, as in a sweep
        return {**out, "converged": False, "message": " ".join(str(err).split())}
    return {**out, "loss_speed": t.speed, "mu_peak": t.mu_peak, "speed_peak": t.speed_peak,
            "evaluations": t.evaluations, "converged": True, "message": t.message,
            "scan_limit": t.scan_limit, "scanned_to": t.scanned[1] if t.scanned else None}
