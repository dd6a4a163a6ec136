"""The fitted model's stated error per point, from the hold-out points nearest it.

Each answer states, per quantity, ``factor x (the mean error of its K nearest hold-out
points + floor)``: the local spread of the hold-out's errors, scaled by one factor per
quantity chosen so that the statement holds for 95 % of the hold-out points when each is
left out of its own neighbours (a normalised split-conformal statement; docs/fit.md,
"Stated errors per point"). The errors are measured against the smaller of the fe2d
answer's and the fitted answer's scales (:func:`webfem.models.readout.error_scale`), so
the statement bounds the error either way it is read. The floor (half the quantity's
hold-out median) keeps a patch whose neighbours happen to be exact from stating about
nothing. Nearness is measured in the contact share's kernel's length scales (for all four
quantities: one search; each quantity's own kernel's measured within noise of it) over the
unit box of the groups, with two more coordinates the fit predicts: log10 of the smallest
gap over sigma (floored at 0.1) and arcsin(sqrt(share)), which place a point on the step
from flying to resting.

Against the table per (gap region, Dn band) it replaces, on the 635 hold-out points split
in two (each half stating the other's errors; ``benchmarks/fit_stated_check.py holdout``):
it held for 92.5-97.5 % of the other half's points in every quantity, the table for 79-95 %
(mu's 79-82 %; errors against the smaller of the two scales). docs/fit.md has the
checks on the bundled cases' families and on fresh design points.

The arrays (``local_*`` in a coefficients file; a file without them states the table's
errors, :func:`webfem.models.fitted.region_of`):

``local_x``
    (m, 10) the hold-out points' coordinates (unit box, then the two predicted ones).
``local_scales``
    (metrics, 10) the length scales of each metric.
``local_metric``
    (4,) the metric of each quantity (a row of ``local_scales``).
``local_errors``
    (m, 4) the hold-out points' errors (webfem's measures, against the smaller scale).
``local_floor``, ``local_factor``
    (4,) per quantity.
``local_k``
    () the neighbours.
"""

from __future__ import annotations

import contextlib

import numpy as np

from . import fit_groups as fg
from .fit_kernel import ONE_THREAD_FROM, blas_one_thread

__all__ = ["KEYS", "coordinates", "spread", "stated", "calibrate", "K", "FLOOR", "QUANTILE"]

#: The arrays of a coefficients file that state errors per point.
KEYS = ("local_x", "local_scales", "local_metric", "local_errors", "local_floor",
        "local_factor", "local_k")
#: Neighbours per point. Chosen on the hold-out set split in two (10, 15 and 20 tried:
#: within noise of each other; 15 the middle).
K = 15
#: The floor of the local spread, as a fraction of the quantity's hold-out median error
#: (0, 0.5 and 1 tried; 0 lets a patch of exact neighbours state nearly 0).
FLOOR = 0.5
#: The statement is this percentile of the hold-out's leave-one-out ratios error / spread.
QUANTILE = 95.0
#: Rows processed at once (the distance matrix of a block stays small).
BLOCK = 2048


def coordinates(x: np.ndarray, H_min_over_S: np.ndarray, share: np.ndarray) -> np.ndarray:
    """The neighbour search's coordinates: unit-box groups ``x`` (n, 8), then log10 of the
    predicted smallest gap over sigma (floored at 0.1) and arcsin(sqrt(predicted share))."""
    return np.column_stack([x, np.log10(np.maximum(H_min_over_S, 0.1)),
                            np.arcsin(np.sqrt(np.clip(share, 0.0, 1.0)))])


def _pools(local: dict) -> list:
    """Per metric: the hold-out points' coordinates over its length scales, stacked for
    one product giving the squared distances (``[-2 p, |p|^2, 1]``), and the errors of the
    quantities it serves (made once per file: cached in ``local``)."""
    pools = local.get("_pools")
    if pools is None:
        metric = np.asarray(local["local_metric"], int)
        pools = []
        for m in np.unique(metric):
            s = local["local_scales"][m]
            P = local["local_x"] / s
            B = np.column_stack([-2.0 * P, np.einsum("ij,ij->i", P, P), np.ones(len(P))])
            cols = np.flatnonzero(metric == m)
            pools.append((s, np.ascontiguousarray(B.T), cols,
                          np.ascontiguousarray(local["local_errors"][:, cols])))
        local["_pools"] = pools
    return pools


def spread(coords: np.ndarray, local: dict, exclude_self: bool = False) -> np.ndarray:
    """The local spread (n, 4): per quantity, the mean error of the ``local_k`` hold-out
    points nearest each of ``coords`` (:func:`coordinates`) in its metric, plus the
    floor. ``exclude_self``: ``coords`` are the hold-out points themselves, each left out
    of its own neighbours.

    The squared distances come out of one product (``[a, 1, |a|^2] . [-2 p, |p|^2, 1]``),
    the neighbours are those not farther than the k-th nearest (a partition of each row,
    then one product with the errors: cheaper than an index partition and a gather); a tie
    at the k-th (repeated hold-out points) takes every tied one. On one BLAS thread from
    :data:`~webfem.models.fit_kernel.ONE_THREAD_FROM` points, as the kernels are evaluated
    (the products are small; below it, setting the thread count costs more than it saves)."""
    k = int(local["local_k"])
    out = np.empty((len(coords), local["local_errors"].shape[1]))
    with blas_one_thread() if len(coords) >= ONE_THREAD_FROM else contextlib.nullcontext():
        for s, B, cols, E in _pools(local):
            for i in range(0, len(coords), BLOCK):
                a = coords[i:i + BLOCK] / s
                A = np.column_stack([a, np.ones(len(a)), np.einsum("ij,ij->i", a, a)])
                # float64: a rounding that moved a neighbour across the k-th would make a
                # point's statement depend on its batch
                D = A @ B
                if exclude_self:
                    D[np.arange(len(a)), np.arange(i, i + len(a))] = np.inf
                kth = np.partition(D, k - 1, axis=1)[:, k - 1:k]
                near = (D <= kth).astype(float)
                out[i:i + BLOCK, cols] = (near @ E) / near.sum(axis=1)[:, None]
    return out + local["local_floor"]


def stated(coords: np.ndarray, local: dict) -> np.ndarray:
    """The stated errors (n, 4) at points of ``coords`` (:func:`coordinates`)."""
    return spread(coords, local) * local["local_factor"]


def calibrate(coords: np.ndarray, errors: np.ndarray, scales: np.ndarray,
              metric, *, k: int = K, floor: float = FLOOR,
              quantile: float = QUANTILE) -> dict:
    """The ``local_*`` arrays from hold-out points at ``coords`` with ``errors`` (m, 4):
    the floor (``floor`` x each quantity's median error) and the factor (the ``quantile``
    of error / spread, each point left out of its own neighbours).

    >>> rng = np.random.default_rng(0)
    >>> c = rng.random((200, 10)); e = rng.random((200, 4)) * (1 + 9 * c[:, :1])
    >>> loc = calibrate(c, e, np.ones((1, 10)), [0, 0, 0, 0])
    >>> float(np.mean(e <= stated(c, loc))) >= 0.9
    True
    """
    k = min(k, len(coords) - 1)      # a small campaign's hold-out set
    local = {"local_x": np.asarray(coords, float), "local_errors": np.asarray(errors, float),
             "local_scales": np.atleast_2d(np.asarray(scales, float)),
             "local_metric": np.asarray(metric, np.int64), "local_k": np.array(k),
             "local_floor": floor * np.median(errors, axis=0),
             "local_factor": np.ones(errors.shape[1])}
    ratio = errors / spread(coords, local, exclude_self=True)
    local["local_factor"] = np.percentile(ratio, quantile, axis=0)
    local.pop("_pools")              # the search's cache, not an array of the file
    return local


def unit_of_groups(G: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Groups ``G`` as unit-box coordinates of the fit's box."""
    return (fg.coordinates(G) - lo) / (hi - lo)
