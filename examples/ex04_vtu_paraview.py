"""VTU files for ParaView: the 2-D film and the web of the base case at 40 m/s.

The 2-D model solves the film pressure over the wrap and the web's deflection along it.
``webfem.io.vtu.write_result`` writes ``base_fe2d_film.vtu`` (quadrilaterals; point data p,
"p-p_a [Pa]", "h [m]", "p_contact [Pa]", "chi_c [-]", "mu [-]", "regime", "in_wrap") and
``base_fe2d_web.vtu`` (a polyline; "w [m]", "h [m]", the width-averaged "p-p_a [Pa]",
"p_contact [Pa]", ...). Open both in ParaView and colour by "p-p_a [Pa]" or "h [m]".

In the uniform middle of the wrap the web is straight, so film and asperities together carry
the wrap pressure T/R there. The script reads the web file back (meshio) and prints, on its
last line, (p - p_a + p_contact) / (T/R) at the wrap centre: close to 1.

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
load = web.point_data["p-p_a [Pa]"][centre] + web.point_data["p_contact [Pa]"][centre]
print(f"film nodes: {len(result.film['points'])}, web nodes: {len(web.points)}")
print("load at the wrap centre / (T/R):", load / (case.web.tension / case.roller.radius))
