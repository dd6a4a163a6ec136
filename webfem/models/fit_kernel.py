"""The fitted model's interpolant, evaluated with numpy alone: a Gaussian-process mean with
anisotropic (ARD) Matern-5/2 kernel over a linear trend, many outputs sharing one kernel.

y(x) = [1, x] b + sum_i k(x, x_i) a_i with k(x, x') = (1 + r sqrt5 + 5 r^2 / 3)
exp(-r sqrt5), r = |(x - x') / l|; x are the fit's coordinates mapped to the unit box.
The coefficients (``centres``, ``scales`` l, ``trend`` b, ``weights`` a, the outputs' mean
and spread) are fitted by :mod:`webfem.studies.fit_build` and stored in an ``.npz`` file;
the centres x_i are the training points or, in a compressed fit, a subset of them with
weights fitted to all (subset of regressors). :class:`Stack` evaluates several kernels, each
its own centres and length scales, in one pass. Other radial functions (:data:`KINDS`: a
Gaussian and a rational-quadratic, cheaper to evaluate; a thin-plate spline) serve the
build's comparisons (docs/fit.md).

Examples
--------
>>> import numpy as np
>>> k = Kernel(centres=np.zeros((1, 2)), scales=np.ones(2), trend=np.zeros((3, 1)),
...            weights=np.ones((1, 1)), y_mean=np.zeros(1), y_std=np.ones(1))
>>> float(k(np.zeros((1, 2)))[0, 0])
1.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

__all__ = ["Kernel", "Stack", "matern52", "gaussian", "thin_plate", "KINDS", "STACKED",
           "blas_one_thread"]

_SQRT5 = np.sqrt(5.0)
#: From this many points the kernel runs its matrix products on one BLAS thread: blocks of a
#: few hundred points are too small to share, and on a loaded machine the threads' waiting
#: cost several times the work (measured: 4e4 against 2e5 points/s; docs/fit.md, "Speed").
ONE_THREAD_FROM = 64
#: Points per block of :class:`Stack`'s evaluation: its work arrays (100-250 kB each) then
#: stay in the core's cache. In float32 every block's products take this many rows (a lone
#: point's padded to it), so it also sets the smallest evaluation's cost (measured on 2048
#: points, one thread, the shipped fit: 2.2-2.5 us a point at 32, 2.1-2.5 at 48 and 64,
#: 2.8-2.9 at 16 and 128; again with the float64 distances and the views made once per
#: call: 2.2 at 32, 2.4 at 48, 2.5 at 64, and a lone point 41, 53 and 65 us).
CHUNK = 32
#: Where :class:`Stack`'s float32 coordinates start: the unit box's middle (their squares'
#: rounding, which the distances' product carries, 4 times smaller than from its corner).
SHIFT = 0.5


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


def gaussian(A: np.ndarray, B: np.ndarray, scales: np.ndarray) -> np.ndarray:
    """The squared-exponential kernel exp(-r^2 / 2) between rows of A and B, r scaled by
    ``scales``: no square root, so one exponential per centre is its whole radial work."""
    a, b = A / scales, B / scales
    d2 = (np.sum(a * a, 1)[:, None] + np.sum(b * b, 1)[None, :] - 2.0 * a @ b.T)
    return np.exp(-0.5 * np.maximum(d2, 0.0))


def cauchy(A: np.ndarray, B: np.ndarray, scales: np.ndarray) -> np.ndarray:
    """The rational-quadratic kernel of exponent 1, 1 / (1 + r^2 / 2), between rows of A
    and B, r scaled by ``scales``: one division per centre."""
    a, b = A / scales, B / scales
    d2 = (np.sum(a * a, 1)[:, None] + np.sum(b * b, 1)[None, :] - 2.0 * a @ b.T)
    return 1.0 / (1.0 + 0.5 * np.maximum(d2, 0.0))


def thin_plate(A: np.ndarray, B: np.ndarray, scales: np.ndarray) -> np.ndarray:
    """The thin-plate spline r^2 log r between rows of A and B, r scaled by ``scales``."""
    a, b = A / scales, B / scales
    d2 = np.maximum(np.sum(a * a, 1)[:, None] + np.sum(b * b, 1)[None, :] - 2.0 * a @ b.T,
                    1e-300)
    return 0.5 * d2 * np.log(d2)


#: The radial functions a :class:`Kernel` may use, by the name its file stores.
KINDS = {"matern52": matern52, "gaussian": gaussian, "cauchy": cauchy,
         "thin-plate": thin_plate}
#: The kinds :class:`Stack` evaluates in one pass, with the factor its product carries:
#: (sqrt5 r log2(e))^2 for the Matern kernel (its exponential taken in base 2: numpy's
#: float32 exp2 measured 0.18 against exp's 0.32 us a point, and rounds to 1 ulp against
#: exp's 2.4), -r^2 / 2 for the Gaussian.
STACKED = {"matern52": 5.0 / math.log(2.0) ** 2, "gaussian": -0.5, "cauchy": 0.5}
#: The Matern polynomial in q = sqrt5 r log2(e): 1 + sqrt5 r + 5 r^2 / 3 = LN2_3 (q^2 +
#: MATERN_A q + MATERN_B), LN2_3 = ln(2)^2 / 3 going into the weights. Python floats: a
#: numpy float64 would take the float32 passes to float64 (numpy's type promotion).
_LN2 = math.log(2.0)
MATERN_A, MATERN_B, LN2_3 = 3.0 / _LN2, 3.0 / _LN2 ** 2, _LN2 ** 2 / 3.0
#: The same polynomial about -MATERN_A / 2, as :class:`Stack` evaluates it: with w = -(q +
#: MATERN_H), q^2 + MATERN_A q + MATERN_B = w^2 + MATERN_C and 2^-q = 2^MATERN_H 2^w, so
#: one pass gives both the exponential's argument and the polynomial's variable (six passes
#: a centre where the form above took eight: docs/fit.md, "Speed"); MATERN_C > 0, so the
#: sum has no cancellation, and 2^MATERN_H goes into the weights with LN2_3.
MATERN_H, MATERN_C = 0.5 * MATERN_A, MATERN_B - 0.25 * MATERN_A ** 2


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
    """Several :class:`Kernel` s of one of the :data:`STACKED` kinds (each its own centres
    and length scales) evaluated in one pass: one matrix product gives every kernel's
    squared distances (|x/l|^2 - 2 x.c/l^2 + |c/l|^2, with x, each kernel's |x/l|^2 and 1
    side by side), one sweep of the radial function covers all the centres, then each
    kernel's weights on its own columns; the outputs side by side, in the kernels' order.
    The same values as calling each kernel to rounding, with the per-call costs paid once.

    ``radial``: the type the distances' product, the radial function (the Matern kernel's
    sqrt, base-2 exponential and polynomial) and the weight products are evaluated in. In float32 the
    coordinates are taken from the unit box's middle (:data:`SHIFT`): the product's three
    terms, which cancel where a point is near a centre, are then 4 times smaller (up to
    1.3e3 with the profile's shortest length scale, 0.07), and so is their rounding (the
    shipped fit's hold-out answers move by up to 1.3e-4 of webfem's error measures against
    float64 throughout; docs/fit.md, "Speed"). In float32 every block's products take
    ``chunk`` rows, a short last block padded: BLAS then runs the same kernel on every
    block, and a point's answer has the same bits alone, in any batch and at any place in
    it (a float32 product's rounding otherwise follows the block's shape: 1e-5 here)."""

    def __init__(self, kernels, radial=np.float64):
        kernels = list(kernels)
        kinds = {k.kind for k in kernels}
        if len(kinds) != 1 or not kinds <= set(STACKED):
            raise ValueError(f"Stack evaluates kernels of one kind of {sorted(STACKED)}, "
                             f"not {sorted(kinds)}")
        self.kind = kinds.pop()
        # kept to tell whether a fit still holds these kernels (fitted.predict)
        self.kernels = tuple(kernels)
        self.radial = np.dtype(radial)
        # the Matern polynomial's factors go into the weights (_matern52)
        scale = 1.0 / (LN2_3 * 2.0 ** MATERN_H) if self.kind == "matern52" else 1.0
        self._shift = SHIFT if self.radial != np.float64 else 0.0
        cols, self._blocks, self._trends = [], [], []
        # each kernel's |x/l|^2 is one number a point, the same for all its centres: one
        # column of the coordinates' side per kernel (computed there, in float64) and a row
        # of the product's other side that picks it for that kernel's centres, so the
        # product is m + len(kernels) + 1 deep, not 2m + 1 (the float32 products' terms
        # then round once, not once per coordinate)
        self._inv2 = np.array([1.0 / k.scales ** 2 for k in kernels])
        start = out = 0
        for j, k in enumerate(kernels):
            c = k.centres - self._shift
            pick = np.zeros((len(kernels), len(c)))
            pick[j] = 1.0
            cols.append(np.vstack([-2.0 * (c * self._inv2[j]).T, pick,
                                   np.sum(c ** 2 * self._inv2[j], axis=1)[None, :]]))
            _, _, w, t0, t1 = k._prepared
            self._blocks.append((slice(start, start + len(k.centres)),
                                 slice(out, out + w.shape[1]),
                                 np.ascontiguousarray(w / scale, self.radial), t0))
            if t1.any():
                self._trends.append((self._blocks[-1][1], t1))
            start += len(k.centres)
            out += w.shape[1]
        # the product is the radial function's argument as it takes it
        self._A = np.ascontiguousarray(STACKED[self.kind] * np.hstack(cols), self.radial)
        self.n_outputs = out
        # every output's mean, added once per block
        self._means = np.concatenate([b[3] for b in self._blocks])

    def __call__(self, x: np.ndarray, chunk: int = CHUNK) -> np.ndarray:
        x = np.atleast_2d(np.asarray(x, float))
        if len(x) < ONE_THREAD_FROM:
            return self.evaluate(x, chunk)
        with blas_one_thread():
            return self.evaluate(x, chunk)

    def evaluate(self, x: np.ndarray, chunk: int = CHUNK, *,
                 clamp: bool = False) -> np.ndarray:
        """The outputs at unit-box points ``x`` (n, m), BLAS's threads as the caller left
        them (:meth:`__call__` sets one from :data:`ONE_THREAD_FROM` points; threads
        evaluating blocks of points side by side set it once around them all).

        The Matern kernel's square root takes the squared distances as the product gives
        them: where a point is within the product's rounding of a centre a square may come
        out a little below 0, its root NaN, and so the point's outputs. Those points alone
        are evaluated again with the squares clamped (``clamp``: |.|, a pass over every
        centre that the rest skip), so every point's answer is the same function of its own
        row as before, NaN-free for finite ``x``."""
        with np.errstate(invalid="ignore"):     # the NaN roots, taken again below
            out = self._evaluate(x, chunk, clamp)
        if self.kind == "matern52" and not clamp:
            # a NaN output is a NaN root (or a NaN input, which gives NaN again): found by
            # each row's sum, a product (0.008 against isnan's 0.03 us a point; a sum
            # overflowing to inf - inf only takes a point again, to the same bits)
            again = np.flatnonzero(np.isnan(out @ np.ones(self.n_outputs)))
            if again.size:
                out[again] = self._evaluate(x[again], chunk, True)
        return out

    def _evaluate(self, x: np.ndarray, chunk: int, clamp: bool) -> np.ndarray:
        """:meth:`evaluate`'s pass, the Matern squares clamped or not (``clamp``)."""
        n = len(x)
        out = np.empty((n, self.n_outputs))
        f32 = self.radial != np.float64
        # float32: the products on whole blocks of ``chunk`` rows (the class text), the
        # padding's rows 0
        c = chunk if f32 else min(chunk, n)
        m = x.shape[1]
        xx = np.zeros((-(-n // c) * c if f32 else n, self._A.shape[0]), self.radial)
        xs = x - self._shift
        xx[:n, :m] = xs
        xx[:n, m:-1] = np.square(xs) @ self._inv2.T       # |x/l|^2 of each kernel
        xx[:, -1] = 1.0
        # one set of work arrays per call, reused by every block (a call is one thread's:
        # fitted.predict runs blocks of points on several); the squares are the radial
        # function's work array
        d2 = np.empty((c, self._A.shape[1]), self.radial)
        # the radial function's values end in ``phi`` (the Matern kernel's exponential's
        # array: two work arrays, not three, stay in cache: its passes 0.91 against 1.03 us a
        # point); its rows past a short last block keep an earlier block's values (or 0),
        # finite or NaN: the products' rows are each their own, and those rows' are not read
        phi = np.zeros_like(d2)
        o32 = np.empty((c, self.n_outputs), self.radial) if f32 else None
        # a block costs about 12 numpy calls, 0.4 us a point of interpreter time (held under
        # the GIL) against 1.5 of arithmetic: the full blocks' views are made once and
        # every call's out is positional (0.1 us a point less, the same bits)
        full = (d2, phi, clamp)
        products = [(phi[:, cols], w, o32[:, outs]) for cols, outs, w, _ in self._blocks] \
            if f32 else None
        A, means, matmul, radial = self._A, self._means, np.matmul, self._radial
        for i in range(0, n, c):
            k = min(c, n - i)
            # the products take whole blocks in float32; the elementwise passes (the same
            # bits whatever the array's length) only the block's points: a lone point pays
            # the padding's products, not its radial functions
            if f32:
                matmul(xx[i:i + c], A, d2)
                radial(*(full if k == c else (d2[:k], phi[:k], clamp)))
                # the whole block, whatever k: the product's shape is the block's
                for p, w, o in products:
                    matmul(p, w, o)
                np.add(o32 if k == c else o32[:k], means, out[i:i + k])
            else:
                dk, phik = d2[:k], phi[:k]
                matmul(xx[i:i + k], A, dk)
                radial(dk, phik, clamp)
                for cols, outs, w, t0 in self._blocks:
                    o = out[i:i + k, outs]
                    matmul(phik[:, cols], w, o)
                    o += t0
            for outs, t1 in self._trends:    # a fit without a trend (the shipped one) skips it
                out[i:i + k, outs] += x[i:i + k] @ t1
        return out

    def _radial(self, d2, phi, clamp):
        """phi of the squared distances' product ``d2`` (overwritten), into ``phi``;
        ``clamp``: the Matern squares through |.| (:meth:`evaluate`)."""
        if self.kind == "gaussian":
            # e^(-r^2/2), unclamped: a coincident point's rounding above 0 gives 1 + ulp
            np.exp(d2, out=phi, dtype=self.radial, casting="unsafe")
        elif self.kind == "cauchy":
            d2 += 1.0                    # 1 + r^2/2
            np.reciprocal(d2, out=phi)
        else:
            self._matern52(d2, phi, clamp)

    @staticmethod
    def _matern52(d2, phi, clamp=False):
        """phi = (w^2 + MATERN_C) 2^w, w = -(q + MATERN_H), of d2 = q^2 (q = sqrt5 r
        log2(e): the kernel over LN2_3 2^MATERN_H, which is in the weights), in six passes,
        through ``d2`` itself (for q, then w) and ``phi`` (2^w, then phi). A square a little
        below 0 (a point within rounding of a centre) gives NaN unless ``clamp`` (|.| first,
        a seventh pass: :meth:`evaluate` takes those points again)."""
        if clamp:
            np.abs(d2, d2)
        np.sqrt(d2, d2)
        np.subtract(-MATERN_H, d2, d2)
        np.exp2(d2, phi)
        np.square(d2, d2)
        np.add(d2, MATERN_C, d2)
        np.multiply(phi, d2, phi)
