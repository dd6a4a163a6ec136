"""The fitted model's interpolant, evaluated with numpy alone: a Gaussian-process mean with
anisotropic (ARD) Matern-5/2 kernel over a linear trend, many outputs sharing one kernel.

y(x) = [1, x] b + sum_i k(x, x_i) a_i with k(x, x') = (1 + r sqrt5 + 5 r^2 / 3)
exp(-r sqrt5), r = |(x - x') / l|; x are the fit's coordinates mapped to the unit box.
The coefficients (``centres``, ``scales`` l, ``trend`` b, ``weights`` a, the outputs' mean
and spread) are fitted by :mod:`webfem.studies.fit_build` and stored in an ``.npz`` file;
the centres x_i are the training points or, in a compressed fit, a subset of them with
weights fitted to all (subset of regressors). :class:`Stack` evaluates several kernels, each
its own centres and length scales, in one pass.

Examples
--------
>>> import numpy as np
>>> k = Kernel(centres=np.zeros((1, 2)), scales=np.ones(2), trend=np.zeros((3, 1)),
...            weights=np.ones((1, 1)), y_mean=np.zeros(1), y_std=np.ones(1))
>>> float(k(np.zeros((1, 2)))[0, 0])
1.0
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

__all__ = ["Kernel", "Stack", "matern52", "thin_plate", "KINDS", "blas_one_thread"]

_SQRT5 = np.sqrt(5.0)
#: From this many points the kernel runs its matrix products on one BLAS thread: blocks of a
#: few hundred points are too small to share, and on a loaded machine the threads' waiting
#: cost several times the work (measured: 4e4 against 2e5 points/s; docs/fit.md, "Speed").
ONE_THREAD_FROM = 64


@lru_cache(maxsize=1)
def _controller():
    from threadpoolctl import ThreadpoolController
    return ThreadpoolController()


def blas_one_thread():
    """A context in which BLAS uses one thread (threadpoolctl, a dependency)."""
    return _controller().limit(limits=1, user_api="blas")


def matern52(A: np.ndarray, B: np.ndarray, scales: np.ndarray) -> np.ndarray:
    """The Matern-5/2 kernel matrix between rows of A and B with length scales ``scales``."""
    a, b = A / scales, B / scales
    d2 = (np.sum(a * a, 1)[:, None] + np.sum(b * b, 1)[None, :] - 2.0 * a @ b.T)
    r = np.sqrt(np.maximum(d2, 0.0)) * _SQRT5
    return (1.0 + r + r * r / 3.0) * np.exp(-r)


def thin_plate(A: np.ndarray, B: np.ndarray, scales: np.ndarray) -> np.ndarray:
    """The thin-plate spline r^2 log r between rows of A and B, r scaled by ``scales``."""
    a, b = A / scales, B / scales
    d2 = np.maximum(np.sum(a * a, 1)[:, None] + np.sum(b * b, 1)[None, :] - 2.0 * a @ b.T,
                    1e-300)
    return 0.5 * d2 * np.log(d2)


#: The radial functions a :class:`Kernel` may use, by the name its file stores.
KINDS = {"matern52": matern52, "thin-plate": thin_plate}


@dataclass(frozen=True)
class Kernel:
    """A fitted interpolant (see the module text); call it on unit-box coordinates (n, m)
    to get the outputs (n, k)."""

    centres: np.ndarray
    scales: np.ndarray
    trend: np.ndarray
    weights: np.ndarray
    y_mean: np.ndarray
    y_std: np.ndarray
    kind: str = "matern52"

    def __call__(self, x: np.ndarray, chunk: int = 512) -> np.ndarray:
        x = np.atleast_2d(np.asarray(x, float))
        if self.kind == "matern52":
            if len(x) < ONE_THREAD_FROM:
                return self._matern52(x, chunk)
            with blas_one_thread():
                return self._matern52(x, chunk)
        out = np.empty((len(x), self.weights.shape[1]))
        for i in range(0, len(x), chunk):     # bounded memory: chunk x centres at a time
            xi = x[i:i + chunk]
            base = np.hstack([np.ones((len(xi), 1)), xi]) @ self.trend
            phi = KINDS[self.kind](xi, self.centres, self.scales)
            out[i:i + chunk] = base + phi @ self.weights
        return out * self.y_std + self.y_mean

    @cached_property
    def _prepared(self) -> tuple[np.ndarray, ...]:
        """The constant parts of an evaluation: the scaled centres as -2 b^T and |b|^2, and
        the weights and trend with the outputs' spread and mean folded in."""
        b = self.centres / self.scales
        trend = self.trend * self.y_std
        trend[0] += self.y_mean
        return (np.ascontiguousarray(-2.0 * b.T), np.sum(b * b, axis=1),
                np.ascontiguousarray(self.weights * self.y_std), trend[0], trend[1:])

    def _matern52(self, x: np.ndarray, chunk: int) -> np.ndarray:
        """:func:`matern52` times the weights, in place on blocks of ``chunk`` points (the
        block's kernel matrix stays in cache): the same sum as the generic path to rounding,
        about three times faster."""
        b2, bb, w, t0, t1 = self._prepared
        out = np.empty((len(x), w.shape[1]))
        for i in range(0, len(x), chunk):
            a = x[i:i + chunk] / self.scales
            r = a @ b2                                   # |a - b|^2 = |a|^2 - 2 a.b + |b|^2
            r += np.einsum("ij,ij->i", a, a)[:, None]
            r += bb
            np.maximum(r, 0.0, out=r)
            np.sqrt(r, out=r)
            r *= _SQRT5
            e = np.negative(r)
            np.exp(e, out=e)
            phi = r * (1.0 / 3.0)                        # (1 + r (1 + r/3)) e^-r
            phi += 1.0
            phi *= r
            phi += 1.0
            phi *= e
            o = out[i:i + chunk]
            np.matmul(phi, w, out=o)
            o += t0
            o += x[i:i + chunk] @ t1
        return out

    def arrays(self, prefix: str) -> dict[str, np.ndarray]:
        """The coefficients as named arrays (for ``np.savez``)."""
        return {f"{prefix}_{k}": np.asarray(getattr(self, k)) for k in
                ("centres", "scales", "trend", "weights", "y_mean", "y_std", "kind")}

    @classmethod
    def from_arrays(cls, data, prefix: str) -> "Kernel":
        return cls(**{k: np.asarray(data[f"{prefix}_{k}"], float) for k in
                      ("centres", "scales", "trend", "weights", "y_mean", "y_std")},
                   kind=str(data[f"{prefix}_kind"]))


class Stack:
    """Several Matern-5/2 :class:`Kernel` s (each its own centres and length scales)
    evaluated in one pass: one matrix product gives every kernel's squared distances
    (|x/l|^2 - 2 x.c/l^2 + |c/l|^2, with x^2, x and 1 side by side), one sweep of the
    radial function covers all the centres, then each kernel's weights on its own columns;
    the outputs side by side, in the kernels' order. The same values as calling each kernel
    to rounding, with the per-call costs paid once.

    ``radial``: the type the radial function (sqrt, exp and its polynomial, the bulk of the
    work) is evaluated in; the distances and the weight product stay in float64, so each
    point's answer does not depend on the others in the batch."""

    def __init__(self, kernels, radial=np.float64):
        kernels = list(kernels)
        if any(k.kind != "matern52" for k in kernels):
            raise ValueError("Stack evaluates Matern-5/2 kernels only")
        # kept to tell whether a fit still holds these kernels (fitted.predict)
        self.kernels = tuple(kernels)
        self.radial = np.dtype(radial)
        cols, self._blocks = [], []
        start = out = 0
        for k in kernels:
            inv2 = 1.0 / k.scales ** 2
            cols.append(np.vstack([np.repeat(inv2[:, None], len(k.centres), axis=1),
                                   -2.0 * (k.centres * inv2).T,
                                   np.sum(k.centres ** 2 * inv2, axis=1)[None, :]]))
            _, _, w, t0, t1 = k._prepared
            self._blocks.append((slice(start, start + len(k.centres)),
                                 slice(out, out + w.shape[1]),
                                 np.ascontiguousarray(w / 3.0), t0, t1))
            start += len(k.centres)
            out += w.shape[1]
        # times 5: the product is (sqrt5 r)^2, which the radial function takes as it comes
        self._A = np.ascontiguousarray(5.0 * np.hstack(cols))
        self.n_outputs = out

    def __call__(self, x: np.ndarray, chunk: int = 256) -> np.ndarray:
        x = np.atleast_2d(np.asarray(x, float))
        if len(x) < ONE_THREAD_FROM:
            return self._run(x, chunk)
        with blas_one_thread():
            return self._run(x, chunk)

    def _run(self, x: np.ndarray, chunk: int) -> np.ndarray:
        out = np.empty((len(x), self.n_outputs))
        xx = np.hstack([x * x, x, np.ones((len(x), 1))])
        f32 = self.radial != np.float64
        for i in range(0, len(x), chunk):
            r = xx[i:i + chunk] @ self._A
            np.maximum(r, 0.0, out=r)        # rounding may leave a coincident point below 0
            if f32:
                r = r.astype(self.radial)
            np.sqrt(r, out=r)
            e = np.negative(r)
            np.exp(e, out=e)
            phi = r + 3.0                    # 3 (1 + r + r^2/3) e^-r; the 1/3 is in the weights
            phi *= r
            phi += 3.0
            phi *= e
            if f32:
                phi = phi.astype(np.float64)
            xi = x[i:i + chunk]
            for cols, outs, w, t0, t1 in self._blocks:
                o = out[i:i + chunk, outs]
                np.matmul(phi[:, cols], w, out=o)
                o += t0
                o += xi @ t1
        return out
