"""VTU files for ParaView: the 2-D film and the web of the base case at 40 m/s.

The 2-D model solves the film pressure over the wrap and the web's deflection along it.
``webfem.io.vtu.write_result`` writes ``base_fe2d_film.vtu`` (quadrilaterals; point data p,
p_rel = p - p_a, h, p_contact, chi_c, mu, regime) and ``base_fe2d_web.vtu`` (a polyline; w,
h, the width-averaged p_rel, p_contact, ...). Open both in ParaView and colour by p_rel or h.

In the uniform middle of the wrap the web is straight, so film and asperities together carry
the wrap pressure T/R there. The script reads the web file back (meshio) and prints, on its
last line, (p_rel + p_contact) / (T/R) at the wrap centre: close to 1.

Run from the repository root: ``python examples/ex04_vtu_paraview.py [FOLDER]``
(default: a new temporary folder).
"""

import sys
import tempfile

import meshio
import numpy as np

import webfem
from webfem.io.vtu import write_result

folder = sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="webfem_vtu_")
case = webfem.load_case("cases/base.toml").updated({"roller.speed": 40.0})
result = webfem.solve(case, model="fe2d")
for path in write_result(result, folder, "base_fe2d"):
    print("wrote", path)

web = meshio.read(f"{folder}/base_fe2d_web.vtu")
centre = np.argmin(np.abs(web.points[:, 0]))            # x = 0: the middle of the wrap
load = web.point_data["p_rel"][centre] + web.point_data["p_contact"][centre]
print(f"film nodes: {len(result.film['points'])}, web nodes: {len(web.points)}")
print("load at the wrap centre / (T/R):", load / (case.web.tension / case.roller.radius))
