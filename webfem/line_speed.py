"""A line at another speed: the one place a case is moved to a scanned speed.

A speed scan (the traction-loss search, the groove map and its loss search, the chart's mu
curve, the studies' speed axes) asks how the line behaves faster or slower: the roller and the web move together,
so the scan keeps the case's web-to-roller speed ratio U_w/U_r (the paper's rig, web at
rest, keeps ratio 0: only the roller moves; an idler, ratio 1, keeps U_r = U_w; a draw of
1 % keeps it). The scanned speed is the roller's, U_r; the web follows at ratio x U_r.
Changing only the roller speed would add a sliding speed U_s = |U_r - U_w| the line does not
have, and the asperity friction (2/pi) mu_cc atan(U_s/C) with it. A case whose roller stands
still (U_r = 0, a web dragged over a fixed bar) has no ratio: its web speed is kept.

The idler's margin (:mod:`webfem.idler`) is the check at the onset of slip, U_r = U_w, so it
moves the line with ratio 1 whatever the case's speeds are. A sweep sets the one key it
names (``roller.speed`` moves the roller alone, a draw the line does not have on an idler);
its ``line.speed`` parameter (:data:`LINE_SPEED`, :func:`line_at`) moves the line as a scan
does.

Examples
--------
>>> from webfem import Case
>>> c = Case().updated({"roller.speed": 20.0, "web.speed": 19.8})
>>> moved = at_speed(c, 10.0)
>>> moved.roller.speed, round(moved.web.speed, 6)
(10.0, 9.9)
>>> at_speed(Case(), 5.0).web.speed      # the paper's rig: the web stays at rest
0.0
"""

from __future__ import annotations

from .case import Case
from .errors import InputError
from .physics.effects import states_load
from .physics.validity import thin_film_message

__all__ = ["speed_ratio", "at_speed", "line_at", "top_speed", "ratio_text", "LINE_SPEED",
           "holds_web_speed"]

#: The sweep parameter that moves the line (:func:`line_at`): not a case key, a speed
#: [m/s] as roller.speed is.
LINE_SPEED = "line.speed"


def speed_ratio(case: Case) -> float | None:
    """U_w/U_r of ``case``, or None where the roller stands still (no ratio to keep)."""
    if case.roller.speed <= 0.0:
        return None
    return case.web.speed / case.roller.speed


def at_speed(case: Case, speed: float, ratio: float | None = None) -> Case:
    """``case`` with the roller at ``speed`` [m/s] and the web at ``ratio`` x it.

    ``ratio`` defaults to the case's own (:func:`speed_ratio`); where that is None (the
    roller at rest) the web speed is kept.
    """
    r = speed_ratio(case) if ratio is None else float(ratio)
    if r is None:
        return case.updated({"roller.speed": float(speed)})
    return case.updated({"roller.speed": float(speed), "web.speed": r * float(speed)})


def line_at(case: Case, speed: float) -> Case:
    """``case`` with its line at ``speed`` [m/s], the sweep parameter :data:`LINE_SPEED`:
    the roller at ``speed`` and the web at the case's ratio U_w/U_r x it (:func:`at_speed`);
    where the roller stands still (no ratio) ``speed`` is the web's and the roller stays at
    rest.

    >>> from webfem import Case
    >>> idler = Case().updated({"roller.speed": 10.0, "web.speed": 10.0})
    >>> moved = line_at(idler, 15.0)
    >>> moved.roller.speed, moved.web.speed
    (15.0, 15.0)
    >>> bar = Case().updated({"roller.speed": 0.0, "web.speed": 5.0})
    >>> line_at(bar, 8.0).web.speed, line_at(bar, 8.0).roller.speed
    (8.0, 0.0)
    """
    if speed_ratio(case) is None:
        return case.updated({"web.speed": float(speed)})
    return at_speed(case, speed)


def holds_web_speed(case: Case) -> bool:
    """True where moving ``roller.speed`` alone holds a web speed the user set: an idler
    (the web drives its roller) or any case with a moving web. A sweep of roller.speed then
    sweeps the draw U_r - U_w as well, which :data:`LINE_SPEED` does not."""
    return case.web.speed > 0.0 or states_load(case)


def top_speed(case: Case, up_to: float, ratio: float | None = None) -> tuple[float, str]:
    """The highest roller speed [m/s] up to ``up_to`` at which :func:`at_speed` gives a case
    the models hold, and why not above it (``""`` when ``up_to`` itself holds).

    A web whose speed rises with the roller's spends rho_w t U_w^2 of its tension turning
    and flies off the roller when that reaches the tension (T_eff <= 0); before that its
    film outgrows the thin-film bound R/100
    (:func:`webfem.physics.validity.thin_film_message`), as does any line fast enough. Both
    grow with the speed: found by bisection, to 1e-4 relative. The reason names the
    quantity at the first speed above: the film, and the T_eff left where the web moves.
    """
    def why(u: float) -> str:
        try:
            c = at_speed(case, u, ratio)
        except InputError:
            return ("T_eff = T - rho_w t U_w^2 <= 0 (the moving web spends all its tension "
                    "turning: it cannot be held on the roller)")
        if not thin_film_message(c):
            return ""
        # a film thickening with the speed: on a moving web, mostly as T_eff falls
        left = (f"; T_eff = {c.tension_eff:.3g} N/m of T = {c.web.tension:g} N/m is left "
                "after the moving web's inertia rho_w t U_w^2" if c.web_inertia > 0.0 else "")
        return ("the film R eps^(2/3) is thicker than R/100 (the thin-film model does not "
                f"hold{left})")

    said = why(up_to)
    if not said:
        return float(up_to), ""
    lo, hi = 0.0, float(up_to)
    while hi - lo > 1e-4 * hi:
        mid = 0.5 * (lo + hi)
        if why(mid):
            hi = mid
        else:
            lo = mid
    return lo, why(hi)


def ratio_text(case: Case, ratio: float | None = None) -> str:
    """How a scan moves the web, for messages: ``web at rest``, ``web at 0.9933 x U_r``."""
    r = speed_ratio(case) if ratio is None else ratio
    if r is None:
        return f"web kept at {case.web.speed:.4g} m/s (the roller at rest has no ratio)"
    if r == 0.0:
        return "web at rest"
    if r == 1.0:
        return "web at U_r"
    return f"web at {r:.4g} x U_r"
