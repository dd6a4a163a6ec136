"""How much the span, a group the fitted model does not see, moves fe2d's answers at the
campaign's hold-out points: each of about N points spread over the bending group Dn is
solved at wrap.span 0.3 m and 3 m beside its 1 m row; one JSON line per point, the changes
in webfem's error measures (docs/fit.md, "Errors").

    python benchmarks/fit_span_sensitivity.py benchmarks/fit_campaign/campaign.csv 30

(about 10 minutes on the 2-core VM)."""
import csv
import json
import sys
import warnings

import webfem
from webfem.models import fit_groups as fg
from webfem.models.readout import error_scale
from webfem.studies import fit_campaign as fc
from webfem.studies.time_limit import time_limit


def main() -> None:
    warnings.simplefilter("ignore")
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
