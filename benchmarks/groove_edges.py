"""The periodic groove cell against the full width (issue 38): does the edges' estimate
(:func:`webfem.fem.grooves.edge_effect`) bound what the web's edges change, per quantity?

Each case is solved by fe2d twice, ``grooves = "cell"`` and ``"full"`` (error_tol 2.5e-3,
auto's at tol 1 %); the change is measured as webfem's errors are
(:func:`webfem.models.readout.error_scale` of the cell's value) and divided by the estimate
read from the cell's state. A ratio above 1 is a change the estimate misses; the stated
error (twice the estimate plus the mesh error) must still bound it.

Run (on demand, serial, minutes per case: the full width is the cost)::

    .venv/bin/python benchmarks/groove_edges.py /tmp/groove_edges.jsonl [first last]
"""

from __future__ import annotations

import json
import sys
import time

from webfem import api
from webfem.bundled import load_case
from webfem.fem.grooves import edge_effect
from webfem.models.groove_domain import venting
from webfem.models.readout import error_scale

QUANTITIES = ("h_center", "h_min", "mu", "contact_share")
CASES = [
    ("base_grooved", {}),
    ("base_grooved", {"roller.groove_depth": 1e-6}),
    ("base_grooved", {"roller.groove_depth": 5e-6}),
    ("base_grooved", {"roller.groove_depth": 25e-6}),
    ("base_grooved", {"roller.groove_depth": 100e-6}),
    ("base_grooved", {"roller.speed": 40.0}),
    ("base_grooved", {"roller.speed": 5.0}),
    ("base_grooved", {"roller.groove_pitch": 2.54e-3}),
    ("base_grooved", {"roller.groove_width": 0.5e-3}),
    ("base_grooved", {"web.width": 0.06}),
    ("pet_idler_grooved", {"web.width": 0.05}),
    ("pet_idler_grooved", {"web.width": 0.05, "roller.groove_depth": 10e-6}),
    ("base_grooved", {"roller.groove_depth": 1e-6, "roller.speed": 40.0}),
    ("base_grooved", {"roller.groove_depth": 10e-6, "roller.speed": 10.0}),
    ("base_grooved", {"roller.groove_pitch": 0.635e-3, "roller.groove_width": 0.125e-3}),
    ("base_grooved", {"roller.groove_depth": 5e-6, "web.width": 0.1}),
    ("pet_idler_grooved", {"web.width": 0.05, "roller.groove_depth": 1e-6}),
]


def measure(name: str, over: dict) -> dict:
    """One case's cell, full width, estimate and changes (a JSON-ready row)."""
    case = load_case(name, over)
    t0 = time.perf_counter()
    cell = api.solve(case, "fe2d", grooves="cell", error_tol=2.5e-3)
    t1 = time.perf_counter()
    full = api.solve(case, "fe2d", grooves="full", error_tol=2.5e-3)
    vent, film = venting(case, cell), 1.0 - cell["contact_share"]
    est = edge_effect(case.lam, case.roller.groove_pitch / case.x_scale, vent, film)
    true = {q: abs(cell[q] - full[q]) / error_scale(case, q, cell[q]) for q in QUANTITIES}
    return {"case": name, "over": over, "vent": vent, "film": film, "estimate": est,
            "pitches": case.web.width / case.roller.groove_pitch,
            "cell": {q: cell[q] for q in QUANTITIES},
            "full": {q: full[q] for q in QUANTITIES},
            "stated": {q: cell[f"error_{q}"] for q in QUANTITIES},
            "true": true, "ratio": {q: v / est for q, v in true.items()},
            "cell_s": t1 - t0, "full_s": time.perf_counter() - t1}


def main(argv: list[str]) -> None:
    first, last = (int(argv[2]), int(argv[3])) if len(argv) > 3 else (0, len(CASES))
    with open(argv[1], "a") as out:
        for name, over in CASES[first:last]:
            row = measure(name, over)
            print(json.dumps(row), file=out, flush=True)
            print(name, over, f"estimate {row['estimate']:.3g}",
                  {q: round(v, 2) for q, v in row["ratio"].items()}, flush=True)


if __name__ == "__main__":
    main(sys.argv)
