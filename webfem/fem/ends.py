"""Where the web is held: at the ends of the domain (the paper's Eq. 20, w = 0 there) or at
the neighbouring rollers, a free span from each wrap edge (``wrap.span``).

Beyond the domain's ends (the entry and exit zones) the gap is millimetres, the film at
ambient pressure, so the web there is a straight, unloaded membrane from the domain's end to
the roller where it is held on its nominal line: w' = -w / s at the exit end and w' = w / s
at the entry end, s the rest of the span (in X). In the web's weak form (membrane term
int W' V', scaled T = 1) the boundary term -[W' V] becomes + W V / s at each end: a spring
of stiffness 1/s on the end's deflection. s -> infinity leaves the ends free (the far-field
limit, spans parallel to their nominal lines); s -> 0 holds them (Eq. 20). The bending
term's natural conditions (W'' = 0, no moment) stay: the span's end is a support, not a
clamp.

Examples
--------
>>> import numpy as np
>>> from webfem import Case
>>> from webfem.fem.scaling import FoilParameters
>>> prm = FoilParameters.from_case(Case().updated({"wrap.span": 1.0}))
>>> X = np.array([-57.4, 0.0, 57.4])          # zones of 40 beyond the wrap's 34.8
>>> k = end_springs(X, prm)
>>> bool(k[0] == k[1] > 0)
True
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["end_springs", "springs", "shortest_span", "with_springs", "jacobian_with_springs",
           "uniform_lift"]


def shortest_span(X, beta: float) -> float:
    """The longer of the two zones beyond the wrap edges (in X): the least span that
    reaches past the domain on both sides."""
    return max(-float(X[0]), float(X[-1])) - 0.5 * beta


def end_springs(X, prm) -> tuple[float, float]:
    """The stiffness (scaled, T = 1) of the spans beyond the domain's ends at X[0] and
    X[-1]: 1 / (span - zone) each, the zone the end's distance from its wrap edge; (0, 0)
    where the web is held at the domain's ends (``prm.span`` 0). The span must reach past
    both ends (the models check it: :func:`shortest_span`)."""
    if not prm.span > 0.0:
        return 0.0, 0.0
    e = 0.5 * prm.beta
    rest = (prm.span - (-float(X[0]) - e), prm.span - (float(X[-1]) - e))
    if min(rest) <= 0.0:
        raise ValueError(f"span = {prm.span:g} does not reach past the domain's ends "
                         f"(zones {-float(X[0]) - e:g} and {float(X[-1]) - e:g})")
    return 1.0 / rest[0], 1.0 / rest[1]


def springs(problem, prm) -> tuple[float, float]:
    """The springs of ``problem`` (a 1-D or 2-D problem with ``X`` and ``spans``): none
    where it holds the web at the domain's ends (its end deflections are fixed at 0)."""
    return end_springs(problem.X, prm) if problem.spans else (0.0, 0.0)


def with_springs(r: np.ndarray, u, ends, springs) -> np.ndarray:
    """The residual ``r`` with the spans' springs on the end deflections ``u[ends]``."""
    if not any(springs):
        return r
    r = np.array(r, copy=True)
    r[ends] += np.asarray(springs) * u[ends]
    return r


def jacobian_with_springs(J, ends, springs):
    """The Jacobian ``J`` (CSR, a fresh assembly) with the spans' springs added to the end
    deflections' diagonal entries in place: the sparsity pattern, which the factorisations'
    plans are kept by, stays the assembly's own arrays."""
    if not any(springs):
        return J
    J = J if isinstance(J, sp.csr_matrix) else sp.csr_matrix(J)
    for i, k in zip(ends, springs):
        row = slice(J.indptr[i], J.indptr[i + 1])
        at = np.flatnonzero(J.indices[row] == i)
        if at.size != 1:
            raise ValueError(f"row {i} has no single diagonal entry")
        J.data[J.indptr[i] + at[0]] += k
    return J


def uniform_lift(n: int, values) -> np.ndarray:
    """The DOF vector of the web lifted by 1 everywhere (its deflection ``values`` 1, slopes
    and pressures 0): the mode only the spans' springs and the film's gap sensitivity hold
    where the ends are unknowns (:func:`webfem.fem.picard.lift_correction`)."""
    z = np.zeros(n)
    z[np.asarray(values)] = 1.0
    return z
