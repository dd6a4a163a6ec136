"""How much the span, a group the fitted model does not see, moves fe2d's answers at the
campaign's hold-out points: each of about N points spread over the bending group Dn is
solved at wrap.span 0.3 m and 3 m beside its 1 m row; one JSON line per point, the changes
in webfem's error measures (docs/fit.md, "Errors").

    python benchmarks/fit_span_sensitivity.py benchmarks/fit_campaign/campaign.csv 30

(about 10 minutes on the 2-core VM).

    python benchmarks/fit_span_sensitivity.py --envelope [2000]

how far real rollers are from the campaign's span for their groups: over the envelope
benchmark's smooth points inside the fitted domain, the span in film lengths Ls = span /
(R eps^(1/3)) of the case against that of ``case_of_groups`` of its groups (the campaign's
case), by Dn band (a few seconds)."""
import csv
import json
import sys
import warnings

import webfem
from webfem.models import fit_groups as fg
from webfem.models.readout import error_scale
from webfem.studies import fit_campaign as fc
from webfem.studies.time_limit import time_limit


def envelope(points: int) -> None:
    import os

    import numpy as np
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import envelope_sample as es
    rows = []
    for case in es.smooth_possible(points):
        if fg.outside(case) is not None:
            continue
        g = fg.groups_of(case)
        ref = fc.case_of_groups(g)
        rows.append((g["Dn"], case.span_used / case.x_scale, ref.span_used / ref.x_scale))
    A = np.array(rows)
    r = np.abs(np.log10(A[:, 1] / A[:, 2]))
    for lo, hi in ((0, 1), (1, 100), (100, 1e3), (1e3, np.inf)):
        m = (A[:, 0] >= lo) & (A[:, 0] < hi)
        print(f"Dn {lo:g}-{hi:g}: {m.sum()} points, |log10 Ls / Ls_campaign| 50 / 90 % / max "
              f"{np.percentile(r[m], 50):.2f} / {np.percentile(r[m], 90):.2f} / "
              f"{r[m].max():.2f}; Ls {A[m, 1].min():.0f}-{A[m, 1].max():.0f}")


def main() -> None:
    warnings.simplefilter("ignore")
    if sys.argv[1] == "--envelope":
        envelope(int(sys.argv[2]) if len(sys.argv) > 2 else 2000)
        return
    with open(sys.argv[1], newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["holdout"] == "1" and r["converged"] == "True"]
    rows.sort(key=lambda r: float(r["g_Dn"]))
    pick = rows[::max(1, len(rows) // int(sys.argv[2]))]
    Q = ("h_center", "h_min", "mu", "contact_share")
    for r in pick:
        g = {k: float(r[f"g_{k}"]) for k in fg.GROUPS}
        case = fc.case_of_groups(g)
        ls = 1.0 / case.x_scale
        rec = {"n": int(r["n"]), "Dn": g["Dn"], "Ls": ls}
        for span in (0.3, 3.0):
            try:
                with time_limit(40.0):
                    a = webfem.solve(case.updated({"wrap.span": span}), model="fe2d",
                                     **fc.FE2D_OPTIONS)
                rec[span] = {q: abs(a[q] - float(r[q])) / error_scale(case, q, float(r[q]))
                             for q in Q}
            except Exception as e:
                rec[span] = str(e)[:60]
        print(json.dumps(rec), flush=True)


if __name__ == "__main__":
    main()
