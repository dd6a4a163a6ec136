"""The dimensionless groups the fitted model is a function of, its domain and its profile nodes.

The scaled film problem fe2d solves on a smooth roller (:class:`webfem.fem.scaling.
FoilParameters`) depends on a case only through eight groups, so one fit serves every
material, roller and speed:

``beta``   wrap length B / eps^(1/3);
``lam``    width L / (2 R eps^(1/3));
``Kb``     permeation over the whole wrap, K beta (K = 12 k / (R t eps^(4/3)): the uniform
           gap falls by K per unit of X, so K beta is the fall from entry to exit);
``d``      compressibility T_eff / (R p_a);
``slip``   first-order slip 6 a lambda_a / (R eps^(2/3));
``Dn``     bending D / (T_eff (R eps^(1/3))^2);
``c``      contact stiffness over wrap pressure E_b sigma R / (2 t T_eff);
``S``      roughness over the film scale sigma / (R eps^(2/3)).

Inertia folds into T_eff. The fit is made in the coordinates :func:`coordinates` (log10 of
each group; ``Kb`` as log10(Kb + KB_FLOOR), so an impermeable web sits at the bottom of its
axis). :data:`DOMAIN` is the box the campaign sampled; :func:`outside` names a group outside
it. The gap and pressure are fitted at the fixed scaled positions :data:`NODES` along the
wrap (Chebyshev-Lobatto, dense at the wrap's edges where the entry and exit zones are).

Examples
--------
>>> from webfem import Case
>>> g = groups_of(Case())
>>> sorted(g) == sorted(GROUPS)
True
>>> outside(Case()) is None
True
"""

from __future__ import annotations

import math

import numpy as np

from ..case import Case
from ..sections import Wrap
from ..fem.scaling import FoilParameters
from ..physics.friction import SLIP_COEFFICIENT

__all__ = ["GROUPS", "DOMAIN", "KB_FLOOR", "NODES", "WEIGHTS", "groups_of", "coordinates",
           "baseline", "baseline_sigmas", "baseline_factors", "softplus", "gap_to_fit",
           "fit_to_gap", "gap_to_asinh", "asinh_to_gap", "share_to_fit", "fit_to_share",
           "outside", "physics_refusal", "group_array", "case_columns", "groups_of_columns",
           "COLUMNS"]

#: The groups, in the order of the fit's coordinates.
GROUPS = ("beta", "lam", "Kb", "d", "slip", "Dn", "c", "S")
#: The box the campaign sampled, per group (lo, hi); Kb's lower end is an impermeable web.
#: Chosen to hold >= 90 % of the envelope benchmark's smooth points (docs/fit.md).
DOMAIN = {"beta": (3.5, 350.0), "lam": (1.2, 4000.0), "Kb": (0.0, 300.0),
          "d": (7e-4, 0.22), "slip": (7e-4, 0.45), "Dn": (2e-3, 1e4), "c": (0.25, 5e4),
          "S": (2e-4, 3.0)}
#: Kb's offset in its log coordinate: below it permeation moves the gap by < 0.1 % of H0.
KB_FLOOR = 1e-3
#: The fitted profile's positions along the wrap, as a fraction of it (-1/2 entry, 1/2 exit).
N_NODES = 33
NODES = -0.5 * np.cos(np.pi * np.arange(N_NODES) / (N_NODES - 1))


def _clenshaw_curtis(n: int) -> np.ndarray:
    """Clenshaw-Curtis weights on the n Chebyshev-Lobatto nodes of [-1/2, 1/2], summing
    to 1 (the wrap average)."""
    N = n - 1
    theta = np.pi * np.arange(n) / N
    w = np.zeros(n)
    for j in range(n):
        s = sum((1.0 if 2 * k == N else 2.0) / (4 * k * k - 1) * math.cos(2 * k * theta[j])
                for k in range(1, N // 2 + 1))
        w[j] = (1.0 - s) / N * (1.0 if j in (0, N) else 2.0)
    return w / w.sum()


#: Quadrature weights of the wrap average on :data:`NODES`.
WEIGHTS = _clenshaw_curtis(N_NODES)


#: Eshel-Elrod's uniform gap and exit constriction (physics.md).
H0, EXIT = 0.643, 0.716


def softplus(z):
    """log(1 + e^z), as max(z, 0) + log1p(e^-|z|): ``np.logaddexp(0, z)`` to rounding, on
    numpy's vectorised exp and log1p (logaddexp's loop is scalar: 0.42 against 0.06 us a
    point on the 33 nodes)."""
    z = np.asarray(z, float)
    t = np.copysign(z, -1.0)                  # -|z| in one pass
    np.exp(t, out=t)
    np.log1p(t, out=t)
    t += np.maximum(z, 0.0)
    return t


#: The nodes from the wrap's entry, and a row of ones: the right factor of the products that
#: give the baseline's linear parts (:func:`baseline_factors`).
_U1 = np.vstack([NODES + 0.5, np.ones(N_NODES)])


def baseline_factors(G: np.ndarray) -> tuple[np.ndarray, ...]:
    """:func:`baseline_sigmas` as :func:`webfem.models.fitted.predict` reads it, in fewer
    passes over the (n, nodes) arrays: the gap at the nodes is H = F e^Y + K for the fit's
    remainder Y (:func:`fit_to_gap` of Y plus the baseline's :func:`gap_to_fit`), so this
    gives F = S (E + FLOOR_SIGMAS) (n, nodes), K = H_c - FLOOR_SIGMAS S (n,), and E at the
    centre node and of the smallest gap (n,), E the baseline's height over the contact
    gap in sigmas. The same as from :func:`baseline_sigmas` to rounding (F within 1e-13
    relative, E within 1e-12 sigma where the web lands and the film's terms cancel:
    tests/test_fitted.py): with the gap's own two (times F, plus K), 14 passes over the
    (n, nodes) arrays where that function and the gap's algebra took 19 (docs/fit.md,
    "Speed")."""
    G = np.asarray(G, float)
    g = {k: G[:, i] for i, k in enumerate(GROUPS)}
    S = g["S"]
    H_c = S * np.log(g["c"])
    # 1 + 6 H0^2 (beta / lam^2) u and (Kb u + H_c) / S, u the nodes from the entry, each as
    # one product (a pass where the outer product and the sum took two)
    t = np.column_stack([(6.0 * H0**2) * g["beta"] / g["lam"] ** 2, np.ones(len(G))]) @ _U1
    np.sqrt(t, out=t)
    np.divide((H0 / S)[:, None], t, out=t)          # the edge-drained film over S
    q = np.column_stack([g["Kb"] / S, H_c / S]) @ _U1
    t -= q                                           # z = (fluid - H_c) / S
    # softplus(z) (above) with its work array reused
    np.copysign(t, -1.0, out=q)
    np.exp(q, out=q)
    np.log1p(q, out=q)
    np.maximum(t, 0.0, out=t)
    t += q                                           # E
    E_center = t[:, N_NODES // 2].copy()
    t += FLOOR_SIGMAS
    t *= S[:, None]
    low = (H0 / np.sqrt(1.0 + (6.0 * H0**2) * g["beta"] / g["lam"] ** 2) - g["Kb"]) * EXIT
    return t, H_c - FLOOR_SIGMAS * S, E_center, softplus((low - H_c) / S)


def baseline_sigmas(G: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The :func:`baseline`'s height over the contact gap H_c = S ln c in sigmas, (baseline
    - H_c) / S, at :data:`NODES` (n, nodes) and of the smallest gap (n,): the fit's gap
    variables are functions of it (:func:`gap_to_fit`, :func:`gap_to_asinh`)."""
    G = np.asarray(G, float)
    g = {k: G[:, i:i + 1] for i, k in enumerate(GROUPS)}
    u = NODES[None, :] + 0.5                  # from the entry, as a fraction of the wrap
    fluid = np.sqrt(1.0 + (6.0 * H0**2) * (g["beta"] / g["lam"] ** 2) * u)
    np.divide(H0, fluid, out=fluid)
    fluid -= g["Kb"] * u
    H_c = g["S"] * np.log(g["c"])
    low = fluid[:, -1] * EXIT
    fluid -= H_c
    fluid /= g["S"]
    return softplus(fluid), softplus((low - H_c[:, 0]) / g["S"][:, 0])


def baseline(G: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The physical baseline of the scaled gap at :data:`NODES` and of the smallest gap, per
    row of groups ``G``: Eshel-Elrod's uniform gap H0 at the wrap's entry, drained along the
    wrap by the edges and by permeation, the exit constriction EXIT at the exit, and the web
    resting at H_c = S ln c where that is below (a smooth maximum over a width S:
    H_c + S log(1 + e^((H - H_c)/S)), :func:`baseline_sigmas`). The fit is made to the
    remainder.

    The edges: the width-averaged film carries T/R with a parabolic pressure across the
    width, whose side flow drains the Couette flux, dH/dX = -3 H^3 / lam^2, so H = H0 /
    sqrt(1 + 6 H0^2 X / lam^2) (X from the wrap's entry; at the base case's centre this is
    the 1.48/lambda edge loss of docs/model.md within 1 %). Permeation: -K X (K beta = Kb
    over the wrap).
    """
    G = np.asarray(G, float)
    E, E_min = baseline_sigmas(G)
    S = G[:, GROUPS.index("S")]
    H_c = S * np.log(G[:, GROUPS.index("c")])
    return H_c[:, None] + S[:, None] * E, H_c + S * E_min


#: The fitted gap never falls more than this many sigma below the contact gap H_c (where
#: the asperities alone would carry e^2 = 7.4 times the wrap pressure).
FLOOR_SIGMAS = 2.0


def gap_to_fit(H, S, H_c):
    """The fit's variable of scaled gaps H: log((H - H_c) / S + FLOOR_SIGMAS), the log of the
    gap's height over its floor in sigmas (relative where the web flies far above its
    roughness, absolute in sigma where it rests); gaps at or below the floor are taken
    1e-3 sigma above it."""
    return np.log(np.maximum((H - H_c) / S + FLOOR_SIGMAS, 1e-3))


def fit_to_gap(y, S, H_c):
    """The scaled gap of the fit's variable ``y`` (inverse of :func:`gap_to_fit`)."""
    return H_c + S * (np.exp(y) - FLOOR_SIGMAS)


def gap_to_asinh(H, S, H_c):
    """The variable the centre and smallest gaps are fitted in on their own: asinh((H -
    H_c) / S). Like :func:`gap_to_fit` it is the gap's relative change far above the
    roughness and its change in sigmas near the contact gap, but it has no floor: a stiff
    web (large Dn) rests several sigma below H_c, up to 100 sigma in the campaign, where
    the floor of :func:`gap_to_fit` cut the answer off (docs/fit.md)."""
    return np.arcsinh((H - H_c) / S)


def asinh_to_gap(y, S, H_c):
    """The scaled gap of the variable ``y`` (inverse of :func:`gap_to_asinh`)."""
    return H_c + S * np.sinh(y)


def share_to_fit(share):
    """The variable the contact share is fitted in: arcsin(sqrt(s)), the arcsine transform
    of a proportion (``s`` clipped to [0, 1]). The share moves from 0 to 1 across a narrow
    band of the groups (the web landing); fitted as it is, the kernel smoothed that step,
    too high by 0.13 on average where it predicted 0.1-0.5 and too low by 0.09 where it
    predicted 0.5-0.9 (the 635 hold-out points), and too high by 0.07-0.31 on the base
    case at 10-30 m/s. The transform stretches the ends of [0, 1], so the step is less
    steep in it, and unlike a logit it reaches 0 and 1 exactly (a plainly flying web's
    share is 0, not a floor); measured against the share itself and a logit with floors
    1e-3 and 0.02 in docs/fit.md."""
    return np.arcsin(np.sqrt(np.clip(np.asarray(share, float), 0.0, 1.0)))


def fit_to_share(y, out=None):
    """The contact share of the variable ``y`` (inverse of :func:`share_to_fit`, ``y``
    clipped to [0, pi/2]: sin(y)^2, in [0, 1]), into ``out`` where given."""
    out = np.clip(y, 0.0, 0.5 * np.pi, out=out)
    np.sin(out, out=out)
    return np.square(out, out=out)


#: The physics switches the campaign solved with (the defaults); any other is refused.
FIT_PHYSICS = {"model.physics": "full", "air.slip": "first-order",
               "air.roughness_flow": "mean-gap", "web.permeation": "isothermal",
               "friction.distribution": "exponential", "friction.variant": "loads"}


def physics_refusal(case: Case) -> str | None:
    """Why the fit does not apply to ``case``'s physics switches, or None. The campaign
    solved smooth rollers with the default full physics only."""
    if case.grooved:
        return ("grooved roller: the fit covers smooth rollers only (the periodic cell adds "
                "pitch, land fraction and depth groups); use fe2d")
    default = Wrap().span
    if case.wrap.ends != "span" or case.wrap.span != default:
        said = (f"wrap.ends = {case.wrap.ends!r}" if case.wrap.ends != "span"
                else f"wrap.span = {case.wrap.span:g} m")
        return (f"{said}: the fit's errors were measured with the web held through "
                f"{default:g} m spans (wrap.ends = 'span', wrap.span = {default:g} m, the "
                "defaults) only; use fe1d or fe2d")
    wanted = {key: (value, FIT_PHYSICS[key]) for key, value in (
        ("model.physics", case.model.physics), ("air.slip", case.air.slip),
        ("air.roughness_flow", case.air.roughness_flow), ("web.permeation", case.web.permeation),
        ("friction.distribution", case.friction.distribution),
        ("friction.variant", case.friction.variant))}
    for key, (value, need) in wanted.items():
        if value != need:
            return (f"{key} = {value!r}: the fit was trained with {key} = {need!r} only; "
                    "use fe1d or fe2d")
    return None


def groups_of(case: Case) -> dict[str, float]:
    """The eight groups of ``case`` (a smooth roller; see the module text)."""
    prm = FoilParameters.from_case(case)
    return {"beta": prm.beta, "lam": case.lam, "Kb": prm.K * prm.beta, "d": prm.d,
            "slip": prm.slip, "Dn": prm.Dn, "c": prm.c, "S": prm.S}


#: The numbers of a case the fitted model reads (:func:`case_columns`), each the Case's own
#: attribute or property.
COLUMNS = ("R", "T_eff", "eps", "U", "U_slide", "B", "L", "sigma", "h_scale", "x_scale", "D",
           "p_bar", "k", "t", "E_b", "eta", "mfp", "p_a", "mu_cc", "C", "lam", "beta", "kappa",
           "inertia")


def case_columns(cases) -> dict[str, np.ndarray]:
    """The :data:`COLUMNS` of many cases as arrays, one value per case (a few microseconds a
    case: the model's vectorised read-out starts from these)."""
    rows = [(c.roller.radius, c.tension_eff, c.eps, c.U, c.U_slide, c.B, c.web.width, c.sigma,
             c.h_scale, c.x_scale, c.bending_used, c.p_bar, c.web.permeability,
             c.web.thickness, c.web.modulus_thickness, c.air.viscosity, c.air.mean_free_path,
             c.air.ambient_pressure, c.friction.mu_cc, c.friction.speed_constant, c.lam,
             c.beta, c.kappa, c.web_inertia) for c in cases]
    A = np.array(rows, float).reshape(-1, len(COLUMNS))
    return {name: A[:, j] for j, name in enumerate(COLUMNS)}


def groups_of_columns(v: dict[str, np.ndarray]) -> np.ndarray:
    """:func:`groups_of` of many cases at once ((n, 8), :data:`GROUPS` order) from their
    :func:`case_columns`: FoilParameters.from_case's formulas for a smooth roller with the
    fit's physics (exponential heights, first-order slip), on arrays; equal to
    :func:`groups_of` to rounding (tests/test_fitted.py)."""
    R, T, eps, t = v["R"], v["T_eff"], v["eps"], v["t"]
    beta = v["beta"]
    K = 12.0 * v["k"] / (R * t * eps ** (4 / 3))
    return np.column_stack([
        beta, v["lam"], K * beta, v["p_bar"] / v["p_a"],
        6.0 * SLIP_COEFFICIENT * v["mfp"] / v["h_scale"], v["D"] / (T * v["x_scale"] ** 2),
        v["E_b"] * v["sigma"] * R / (2.0 * t * T), v["sigma"] / v["h_scale"]])


def group_array(groups: dict[str, np.ndarray]) -> np.ndarray:
    """Groups (a dict of equal-length arrays or floats) as an (n, 8) array."""
    return np.column_stack([np.atleast_1d(np.asarray(groups[g], float)) for g in GROUPS])


def coordinates(G: np.ndarray) -> np.ndarray:
    """The fit's coordinates of groups ``G`` ((n, 8), :data:`GROUPS` order): log10 of
    each, Kb as log10(Kb + KB_FLOOR)."""
    G = np.asarray(G, float)
    out = np.log10(np.maximum(G, 1e-300))
    kb = GROUPS.index("Kb")
    out[:, kb] = np.log10(G[:, kb] + KB_FLOOR)
    return out


def box() -> tuple[np.ndarray, np.ndarray]:
    """The domain in the fit's coordinates: (lower, upper) arrays."""
    lo = np.array([[DOMAIN[g][0] for g in GROUPS]])
    hi = np.array([[DOMAIN[g][1] for g in GROUPS]])
    return coordinates(lo)[0], coordinates(hi)[0]


def outside_rows(G: np.ndarray) -> np.ndarray:
    """Per row of groups ``G``, the index of the first group outside :data:`DOMAIN`, or
    -1 inside."""
    G = np.asarray(G, float)
    lo = np.array([DOMAIN[g][0] for g in GROUPS])
    hi = np.array([DOMAIN[g][1] for g in GROUPS])
    bad = ~((G >= lo) & (G <= hi))
    return np.where(bad.any(axis=1), np.argmax(bad, axis=1), -1)


def outside(case: Case, g: dict[str, float] | None = None) -> str | None:
    """Why ``case`` is outside the fit's domain (the group, its value and its range), or
    None inside; ``g``: its groups, if already known."""
    why = physics_refusal(case)
    if why:
        return why
    g = groups_of(case) if g is None else g
    i = int(outside_rows(group_array(g))[0])
    return None if i < 0 else outside_text(i, g[GROUPS[i]])


def outside_text(i: int, value: float) -> str:
    """The message for group number ``i`` (:data:`GROUPS`) at ``value``, outside its range."""
    name = GROUPS[i]
    lo, hi = DOMAIN[name]
    return (f"{name} = {value:.4g} is outside the fitted model's domain {lo:g} <= {name} "
            f"<= {hi:g} (docs/fit.md lists the groups); use fe1d or fe2d")
