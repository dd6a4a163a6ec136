"""The envelope benchmark's operating points and how it reads an outcome (issue 22, item 5).

The sample is fixed: point ``i`` is drawn by its own generator,
``numpy.random.default_rng([SEED, i])`` (PCG64 seeded by the sequence (22, i)), so the first
N points are the same for any ``--points`` and a point can be redrawn alone. Per point, in
this order:

* material: newsprint (``cases/base.toml``), PET film (``cases/pet_idler.toml``), aluminium
  foil (``cases/foil_roller.toml``) or board (``cases/board.toml``), one in four each: the
  case's ``[web]`` (thickness, moduli, roughness, permeability, density), ``[friction]``,
  ``[model]`` and its roller roughness (a film runs on a polished roller); drag torque,
  inertia and acceleration are left out (they only feed the idler check);
* motion, one in three each: held (U_w = 0, U_r = speed), idler (U_r = U_w = speed), driven
  (U_w = speed, U_r = r x speed with r log-uniform in 0.5-2, |r - 1| >= 2 %, U_r in range);
* roller radius 0.02-0.3 m, tension 20-400 N/m, wrap 10-180 deg, web width 0.01-3 m,
  speed 0.5-60 m/s: all log-uniform (each range spans more than a decade);
* grooves on every fourth point (i % 4 == 3: exactly a quarter of each four): pitch
  log-uniform 0.5-6 mm, land fraction uniform 50-95 %, groove width = pitch x (1 - land
  fraction), redrawn until it is within 0.1-1 mm; depth log-uniform 25 um-1 mm.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

SEED = 22
ROOT = Path(__file__).resolve().parents[1]
MATERIALS = {"newsprint": "base", "PET": "pet_idler", "foil": "foil_roller", "board": "board"}
MODES = ("held", "idler", "driven")
#: The parameters of a point, in the CSV's order.
PARAMS = ("index", "material", "mode", "grooved", "radius", "tension", "wrap_deg", "width",
          "U_r", "U_w", "groove_pitch", "groove_width", "groove_depth")


def _logu(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def draw(i: int) -> dict:
    """Operating point ``i`` of the fixed sample (see the module's docstring)."""
    rng = np.random.default_rng([SEED, i])
    material = list(MATERIALS)[int(rng.integers(len(MATERIALS)))]
    mode = MODES[int(rng.integers(len(MODES)))]
    p = {"index": i, "material": material, "mode": mode, "grooved": i % 4 == 3,
         "radius": _logu(rng, 0.02, 0.3), "tension": _logu(rng, 20.0, 400.0),
         "wrap_deg": _logu(rng, 10.0, 180.0), "width": _logu(rng, 0.01, 3.0)}
    speed = _logu(rng, 0.5, 60.0)
    if mode == "held":
        p["U_r"], p["U_w"] = speed, 0.0
    elif mode == "idler":
        p["U_r"] = p["U_w"] = speed
    else:
        while True:
            r = _logu(rng, 0.5, 2.0)
            if abs(r - 1.0) >= 0.02 and 0.5 <= r * speed <= 60.0:
                break
        p["U_r"], p["U_w"] = r * speed, speed
    p["groove_pitch"] = p["groove_width"] = p["groove_depth"] = 0.0
    if p["grooved"]:
        while True:
            pitch = _logu(rng, 0.5e-3, 6e-3)
            width = pitch * (1.0 - rng.uniform(0.5, 0.95))
            if 0.1e-3 <= width <= 1e-3:
                break
        p["groove_pitch"], p["groove_width"] = pitch, width
        p["groove_depth"] = _logu(rng, 25e-6, 1e-3)
    return p


def case_of(p: dict):
    """The :class:`webfem.Case` of point ``p`` (raises InputError for T_eff <= 0)."""
    import webfem
    base = webfem.load_case(ROOT / "cases" / f"{MATERIALS[p['material']]}.toml")
    return base.updated({
        "roller.radius": p["radius"], "roller.speed": p["U_r"], "roller.drag_torque": 0.0,
        "roller.inertia": 0.0, "roller.groove_pitch": p["groove_pitch"],
        "roller.groove_width": p["groove_width"], "roller.groove_depth": p["groove_depth"],
        "web.width": p["width"], "web.tension": p["tension"], "web.speed": p["U_w"],
        "web.acceleration": 0.0, "wrap.angle_deg": p["wrap_deg"]})


def smooth_possible(points: int):
    """The cases of the first ``points`` points on smooth rollers that are physically
    possible (T_eff > 0 and a thin film: :data:`IMPOSSIBLE`'s two kinds left out)."""
    from webfem.errors import InputError
    for i in range(points):
        p = draw(i)
        if p["grooved"]:
            continue
        try:
            case = case_of(p)
        except InputError:          # T_eff <= 0: no tension holds the web
            continue
        if case.h_scale < case.roller.radius / 100:     # a thin film
            yield case


# -- reading an outcome --------------------------------------------------------------------

#: Refusals no model could answer: the point is not physically possible (not counted).
IMPOSSIBLE = {
    "T_eff <= 0": "the web is too fast for its tension: turning it takes rho_w t U_w^2, at "
                  "least T, so no tension holds it on the roller (an input error)",
    "film thicker than R/100": "the air lifts the web to more than R/100: not a thin film, "
                               "the web is no longer guided by the roller (outside any "
                               "lubrication model)",
}
#: (pattern in the message, category), the first match wins.
CATEGORIES = (
    ("cannot be held on the roller", "T_eff <= 0"),
    ("the thin-film (Reynolds) model does not hold", "film thicker than R/100"),
    ("the web lands", "the web lands: contact cannot carry T/R"),
    ("the film's suction", "suction pulls the web through its asperities"),
    ("the web is pressed", "the web is pressed through its asperities"),
    ("entry lengths long", "wrap beyond the FE models, no closed-form answer"),
)


def category(status: str, message: str) -> str:
    """The group of a refusal or failure: a known cause, else the message's first words
    with numbers blanked."""
    for pattern, name in CATEGORIES:
        if pattern in message:
            return name
    if status == "timeout":
        return "timeout"
    words = re.sub(r"(?<![\w.])[-+]?\d[\d.eE+-]*", "#", message).split()
    return " ".join(words[:10])
