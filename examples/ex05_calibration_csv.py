"""Calibration from a CSV: recover the friction constants mu_cc and C from measurements.

The paper's boundary friction mu_c = (2/pi) mu_cc atan(U_s/C) has two constants to be
measured on a rig. Here the "rig" is the closed form itself with known constants
(mu_cc = 0.35, C = 0.6 m/s): it predicts the tension increase before slip, delta_T, at six
roller speeds and two tensions, 1 % of noise (fixed seed) is added, and the rows are written
as a CSV in the format ``webfem calibrate`` reads. ``webfem.calibrate`` then fits mu_cc and C
back by least squares through the model and Euler's belt formula (Eq. 31).

Prints the CSV's path, the fitted constants with their 95 % intervals and the residual rms;
the last line is the fitted mu_cc (true value 0.35).

Run from the repository root: ``python examples/ex05_calibration_csv.py``
(the same fit from the shell: ``webfem calibrate FILE.csv --case cases/base.toml
--model closed-form``; the command's default model is auto).
"""

import csv
import tempfile
import warnings
from pathlib import Path

import numpy as np

import webfem
from webfem.calibrate import calibrate, read_measurements

case = webfem.load_case("cases/base.toml")
true = {"friction.mu_cc": 0.35, "friction.speed_constant": 0.6}
noise = np.random.default_rng(2024)

rows = []
with warnings.catch_warnings():
    warnings.simplefilter("ignore", webfem.errors.ValidityWarning)   # landed webs
    for tension in (60.0, 100.0):
        for speed in (0.5, 1.0, 2.0, 4.0, 8.0, 15.0):
            point = case.updated({"roller.speed": speed, "web.tension": tension, **true})
            delta_T = webfem.solve(point, model="closed-form")["delta_T"] * (1 + 0.01 * noise.standard_normal())
            rows.append([speed, tension, 60.0, round(delta_T, 4)])

path = Path(tempfile.mkdtemp(prefix="webfem_rig_")) / "rig.csv"
with path.open("w", newline="") as fh:
    fh.write("# synthetic rig: closed form with mu_cc = 0.35, C = 0.6 m/s, 1 % noise\n")
    writer = csv.writer(fh)
    writer.writerow(["roller_speed", "tension", "wrap_deg", "delta_T"])
    writer.writerows(rows)
print("measurements:", path)

fit = calibrate(read_measurements(path), case, model="closed-form")
for name, value in fit.estimates.items():
    print(f"{name} = {value:.4f} +- {fit.ci95[name]:.4f} (95 %)")
print(f"residual rms {fit.rms:.3f} N/m over {len(rows)} rows")
print("fitted mu_cc:", fit.estimates["mu_cc"])
