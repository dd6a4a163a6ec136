"""The fitted model's variants compared on the campaign's hold-out rows (docs/fit.md, last
section): every variant is fitted on the training rows only and measured on the same
hold-out rows, errors 50 / 90 / 95 % in webfem's measures.

    python benchmarks/fit_variants.py [--store benchmarks/fit_campaign/campaign.csv]
                                      [--previous OLD.npz] [--mlp] [--curve]

``--previous``: a coefficients file to measure as well (e.g. the previous shipped fit:
``git show 09bd3ee:webfem/models/fitted_coefficients.npz > old.npz``). ``--mlp``: the small
neural network (scipy L-BFGS); ``--curve``: the learning curve. One core: set
OMP_NUM_THREADS=1.
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

from webfem.models import fit_groups as fg
from webfem.models import fitted
from webfem.models.readout import error_scale
from webfem.physics.friction import mu_boundary
from webfem.studies import fit_build as fb
from webfem.studies.fit_campaign import case_of_groups
from webfem.sweeps.table import read_table, typed

N = len(fg.NODES)
Q = ("h_center", "h_min", "mu", "contact_share")
HYPER = fb.HYPER_POINTS


def groups(rows):
    return np.array([[r[f"g_{g}"] for g in fg.GROUPS] for r in rows], float)


def box():
    lo, hi = fg.box()
    lo = lo.copy()
    lo[fg.GROUPS.index("Kb")] -= 0.3
    return lo, hi


class Check:
    """The hold-out rows: their cases, fe2d's answers and the error scales."""

    def __init__(self, rows):
        self.rows = rows
        self.G = groups(rows)
        self.cases = [case_of_groups(dict(zip(fg.GROUPS, g))) for g in self.G]
        self.v = fg.case_columns(self.cases)
        self.true = {q: np.array([r[q] for r in rows]) for q in Q}
        self.scale = {q: np.array([error_scale(c, q, t) for c, t in
                                   zip(self.cases, self.true[q])]) for q in Q}
        ratio = self.true["h_min"] / np.array([c.sigma for c in self.cases])
        self.region = np.searchsorted(fb.REGION_EDGES, ratio)

    def errors(self, pr, own=None):
        """Errors of a profile prediction ``pr``; ``own``: quantities predicted directly."""
        r = fitted.read_profiles(self.v, pr["H"], pr["P"], pr["H_min"], pr["s_min"])
        own = own or {}
        return {q: np.abs(own.get(q, r[q]) - self.true[q]) / self.scale[q] for q in Q}


def show(name, e):
    cells = [" / ".join(f"{np.percentile(e[q], p):.2g}" for p in (50, 90, 95)) if q in e
             else "" for q in Q]
    print(f"| {name} | " + " | ".join(cells) + " |", flush=True)


# -- the profile in a chosen gap variable ---------------------------------------------------

VARIABLES = {"log": (fg.gap_to_fit, fg.fit_to_gap), "asinh": (fg.gap_to_asinh, fg.asinh_to_gap)}


def profile_targets(rows, to):
    G = groups(rows)
    base, base_min = fg.baseline(G)
    S = G[:, 7][:, None]
    Hc = S * np.log(G[:, 6])[:, None]
    H = np.array([[r[f"H{j}"] for j in range(N)] for r in rows])
    P = np.array([[r[f"P{j}"] for j in range(N)] for r in rows])
    Hmin = np.array([r["h_min"] / r["h_scale"] for r in rows])
    smin = np.array([r["x_min"] / (r["x_scale"] * r["g_beta"]) for r in rows])
    return np.column_stack([to(H, S, Hc) - to(base, S, Hc), P,
                            to(Hmin, S[:, 0], Hc[:, 0]) - to(base_min, S[:, 0], Hc[:, 0]),
                            smin])


def fit_profile(rows, variable="log", clip=2.0, hyper=HYPER):
    """A predictor of profiles (like fitted.predict) fitted on ``rows``."""
    to, back = VARIABLES[variable]
    lo, hi = box()
    y = profile_targets(rows, to)
    gaps = np.r_[np.arange(N), 2 * N]
    y[:, gaps] = np.clip(y[:, gaps], -clip, clip)
    k = fb.fit_kernel(fb.unit(groups(rows), lo, hi), y, trend=False, hyper_points=hyper)

    def predict(G):
        Y = k(fb.unit(G, lo, hi))
        base, base_min = fg.baseline(G)
        S = G[:, 7][:, None]
        Hc = S * np.log(G[:, 6])[:, None]
        H = back(Y[:, :N] + to(base, S, Hc), S, Hc)
        Hmin = np.minimum(back(Y[:, 2 * N] + to(base_min, S[:, 0], Hc[:, 0]), S[:, 0],
                               Hc[:, 0]), H.min(1))
        return {"H": H, "P": Y[:, N:2 * N], "H_min": Hmin,
                "s_min": np.clip(Y[:, 2 * N + 1], -0.5, 0.5)}
    return predict


def scalar_values(Y, G, hs, cols=("h_center", "h_min", "contact_share"), variable="asinh"):
    """Gaps [m] and the share from fitted scalar remainders ``Y`` (columns ``cols``)."""
    to, back = VARIABLES[variable]
    base, base_min = fg.baseline(G)
    S, Hc = G[:, 7], G[:, 7] * np.log(G[:, 6])
    out = {}
    for j, q in enumerate(cols):
        if q == "contact_share":
            out[q] = np.clip(Y[:, j], 0.0, 1.0)
        else:
            b = base[:, N // 2] if q == "h_center" else base_min
            out[q] = back(Y[:, j] + to(b, S, Hc), S, Hc) * hs
    return out


def scalar_targets(rows, variable="asinh", clip=4.0):
    to, _ = VARIABLES[variable]
    G = groups(rows)
    base, base_min = fg.baseline(G)
    S, Hc = G[:, 7], G[:, 7] * np.log(G[:, 6])
    hs = np.array([r["h_scale"] for r in rows])
    y = np.column_stack([
        to(np.array([r["h_center"] for r in rows]) / hs, S, Hc) - to(base[:, N // 2], S, Hc),
        to(np.array([r["h_min"] for r in rows]) / hs, S, Hc) - to(base_min, S, Hc),
        [r["contact_share"] for r in rows]])
    if clip:
        y[:, :2] = np.clip(y[:, :2], -clip, clip)
    return y


def mlp(x, Y, xh, hidden=48, decay=1e-3, starts=3):
    """A tanh network x -> hidden -> hidden -> Y, least squares with weight decay, trained
    by scipy's L-BFGS from ``starts`` random starts; evaluated with numpy."""
    from scipy.optimize import minimize
    m, k = x.shape[1], Y.shape[1]
    mu_, sd = Y.mean(0), Y.std(0)
    T = (Y - mu_) / sd
    shapes = [(m, hidden), (hidden,), (hidden, hidden), (hidden,), (hidden, k), (k,)]

    def unpack(w):
        out, i = [], 0
        for s in shapes:
            n = int(np.prod(s))
            out.append(w[i:i + n].reshape(s))
            i += n
        return out

    def forward(w, X):
        W1, b1, W2, b2, W3, b3 = unpack(w)
        a1 = np.tanh(X @ W1 + b1)
        a2 = np.tanh(a1 @ W2 + b2)
        return a1, a2, a2 @ W3 + b3

    def loss(w):
        W1, b1, W2, b2, W3, b3 = unpack(w)
        a1, a2, out = forward(w, x)
        r = out - T
        L = 0.5 * np.mean(np.sum(r * r, 1)) + 0.5 * decay * sum(np.sum(W * W)
                                                                 for W in (W1, W2, W3))
        g3 = r / len(x)
        g2 = (g3 @ W3.T) * (1 - a2 ** 2)
        g1 = (g2 @ W2.T) * (1 - a1 ** 2)
        grads = (x.T @ g1 + decay * W1, g1.sum(0), a1.T @ g2 + decay * W2, g2.sum(0),
                 a2.T @ g3 + decay * W3, g3.sum(0))
        return L, np.concatenate([g.ravel() for g in grads])
    n = sum(int(np.prod(s)) for s in shapes)
    best = None
    for seed in range(starts):
        w0 = np.random.default_rng(seed).normal(0.0, 0.5, n)
        opt = minimize(loss, w0, jac=True, method="L-BFGS-B", options={"maxiter": 3000})
        if best is None or opt.fun < best.fun:
            best = opt
    return forward(best.x, xh)[2] * sd + mu_


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--store", default="benchmarks/fit_campaign/campaign.csv")
    ap.add_argument("--previous", default=None)
    ap.add_argument("--mlp", action="store_true")
    ap.add_argument("--curve", action="store_true")
    a = ap.parse_args()
    warnings.filterwarnings("ignore")
    t0 = time.perf_counter()
    rows = [r for r in typed(read_table(a.store).rows) if r["converged"]]
    train = [r for r in rows if not r["holdout"]]
    check = Check([r for r in rows if r["holdout"]])
    print(f"{len(train)} training rows, {len(check.rows)} hold-out rows (fe2d's regions "
          f"resting / landing / flying: {np.bincount(check.region, minlength=3).tolist()})")
    print("| variant | h_center | h_min | mu | contact share |\n|---|---|---|---|---|")
    if a.previous:
        show(f"coefficients {a.previous}",
             fb.holdout_errors(check.rows, fitted.coefficients(a.previous)))
    own = {"H": np.array([[r[f"H{j}"] for j in range(N)] for r in check.rows]),
           "P": np.array([[r[f"P{j}"] for j in range(N)] for r in check.rows]),
           "H_min": np.array([r["h_min"] / r["h_scale"] for r in check.rows]),
           "s_min": np.array([r["x_min"] / (r["x_scale"] * r["g_beta"]) for r in check.rows])}
    floor = check.errors(own)
    show("fe2d's own 33-node profile through the read-out", floor)
    print("    mu's 95th percentile by fe2d's region: " + ", ".join(
        f"{np.percentile(floor['mu'][check.region == k], 95):.2g}" for k in range(3)))
    base = fit_profile(train)
    pr = base(check.G)
    show("profile (shipped method), log variable, clip 2", check.errors(pr))
    for clip in (4.0, 8.0):
        show(f"profile in asinh((H - H_c)/S), clip {clip:g}",
             check.errors(fit_profile(train, "asinh", clip)(check.G)))
    # the regimes apart: by fe2d's h_min / sigma in training; chosen by a fitted one
    lo, hi = box()
    x, xh = fb.unit(groups(train), lo, hi), fb.unit(check.G, lo, hi)
    ratio = np.array([r["h_min"] / (r["g_S"] * r["h_scale"]) for r in train])
    region = np.searchsorted(fb.REGION_EDGES, ratio)
    kz = fb.fit_kernel(x, np.arcsinh(ratio)[:, None], trend=False, hyper_points=HYPER)
    guess = np.searchsorted(fb.REGION_EDGES, np.sinh(kz(xh)[:, 0]))
    print(f"    regions predicted right: {np.mean(guess == check.region):.0%}")
    for variable, clip in (("log", 2.0), ("asinh", 4.0)):
        parts = [fit_profile([r for r, z in zip(train, region) if z == k], variable, clip)(
            check.G) for k in range(3)]
        for label, z in (("a fitted", guess), ("fe2d's own", check.region)):
            pick = {key: np.choose(z[:, None] if parts[0][key].ndim == 2 else z,
                                   [p[key] for p in parts]) for key in parts[0]}
            show(f"regimes apart ({variable}, clip {clip:g}), chosen by {label} h_min/sigma",
                 check.errors(pick))
    hs = check.v["h_scale"]
    for variable, clip in (("log", 2.0), ("log", None), ("asinh", 4.0)):
        y = scalar_targets(train, variable, clip)[:, :2]
        Y = np.column_stack([fb.fit_kernel(x, y[:, [j]], trend=False, hyper_points=HYPER)(xh)
                             for j in range(2)])
        show(f"h_center, h_min on their own, {variable}, clip {clip}",
             {q: check.errors(pr, scalar_values(Y, check.G, hs, ("h_center", "h_min"),
                                                variable))[q] for q in ("h_center", "h_min")})
    ys = scalar_targets(train)
    own3 = np.column_stack([fb.fit_kernel(x, ys[:, [j]], trend=False, hyper_points=HYPER)(xh)
                            for j in range(3)])
    e = check.errors(pr, scalar_values(own3, check.G, hs))
    show("the three on their own (asinh, clip 4), each its own kernel",
         {q: e[q] for q in ("h_center", "h_min", "contact_share")})
    one = fb.fit_kernel(x, ys, trend=False, hyper_points=HYPER)(xh)
    e = check.errors(pr, scalar_values(one, check.G, hs))
    show("the three on their own, one kernel",
         {q: e[q] for q in ("h_center", "h_min", "contact_share")})
    # mu: a fitted contact load times mu_c plus the profile's film shear (general), and mu
    # fitted directly (the campaign's friction constants only)
    cases = [case_of_groups(dict(zip(fg.GROUPS, g))) for g in groups(train)]
    vt = fg.case_columns(cases)
    Ht = np.array([[r[f"H{j}"] for j in range(N)] for r in train])
    Pt = np.array([[r[f"P{j}"] for j in range(N)] for r in train])
    Hm = np.array([r["h_min"] / r["h_scale"] for r in train])
    sm = np.array([r["x_min"] / (r["x_scale"] * r["g_beta"]) for r in train])
    rt = fitted.read_profiles(vt, Ht, Pt, Hm, sm)
    film_t = np.sum(fg.WEIGHTS * rt["loc"]["mu_f"], axis=1)
    mu_t = np.array([r["mu"] for r in train])
    mu_c = mu_boundary(vt["U_slide"], vt["mu_cc"], vt["C"])
    load = (mu_t - film_t) / mu_c
    kl = fb.fit_kernel(x, np.arcsinh(load / 0.01)[:, None], trend=False, hyper_points=HYPER)
    rh = fitted.read_profiles(check.v, pr["H"], pr["P"], pr["H_min"], pr["s_min"])
    mu = (mu_boundary(check.v["U_slide"], check.v["mu_cc"], check.v["C"])
          * 0.01 * np.sinh(kl(xh)[:, 0]) + np.sum(fg.WEIGHTS * rh["loc"]["mu_f"], axis=1))
    show("mu = mu_c x a fitted contact load + the profile's film shear",
         {"mu": np.abs(mu - check.true["mu"]) / check.scale["mu"]})
    km = fb.fit_kernel(x, np.arcsinh(mu_t / 0.01)[:, None], trend=False, hyper_points=HYPER)
    show("mu fitted directly (the campaign's friction constants only)",
         {"mu": np.abs(0.01 * np.sinh(km(xh)[:, 0]) - check.true["mu"]) / check.scale["mu"]})
    if a.mlp:
        Y = mlp(2 * x - 1, ys, 2 * xh - 1)
        e = check.errors(pr, scalar_values(Y, check.G, hs))
        show("MLP 8-48-48-3 (tanh, weight decay 1e-3), the three scalars",
             {q: e[q] for q in ("h_center", "h_min", "contact_share")})
    # the shipped coefficients, as users get them (webfem fit build's own fit)
    e = fb.holdout_errors(check.rows, fitted.coefficients())
    show("shipped coefficients (profile + the gaps in one kernel + the share in its own)", e)
    if a.curve:
        ordered = sorted(train, key=lambda r: r["n"])
        for n in (300, 600, 900, len(ordered)):
            show(f"learning curve: profile, the design's first {n} training points",
                 check.errors(fit_profile(ordered[:n], hyper=min(HYPER, n))(check.G)))
    print(f"{time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
