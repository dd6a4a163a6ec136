"""The fitted model's interpolant, evaluated with numpy alone: a Gaussian-process mean with
anisotropic (ARD) Matern-5/2 kernel over a linear trend, many outputs sharing one kernel.

y(x) = [1, x] b + sum_i k(x, x_i) a_i with k(x, x') = (1 + r sqrt5 + 5 r^2 / 3)
exp(-r sqrt5), r = |(x - x') / l|; x are the fit's coordinates mapped to the unit box.
The coefficients (``centres``, ``scales`` l, ``trend`` b, ``weights`` a, the outputs' mean
and spread) are fitted by :mod:`webfem.studies.fit_build` and stored in an ``.npz`` file.

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

import numpy as np

__all__ = ["Kernel", "matern52", "thin_plate", "KINDS"]

_SQRT5 = np.sqrt(5.0)


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

    def __call__(self, x: np.ndarray, chunk: int = 4096) -> np.ndarray:
        x = np.atleast_2d(np.asarray(x, float))
        out = np.empty((len(x), self.weights.shape[1]))
        for i in range(0, len(x), chunk):     # bounded memory: chunk x centres at a time
            xi = x[i:i + chunk]
            base = np.hstack([np.ones((len(xi), 1)), xi]) @ self.trend
            phi = KINDS[self.kind](xi, self.centres, self.scales)
            out[i:i + chunk] = base + phi @ self.weights
        return out * self.y_std + self.y_mean

    def arrays(self, prefix: str) -> dict[str, np.ndarray]:
        """The coefficients as named arrays (for ``np.savez``)."""
        return {f"{prefix}_{k}": np.asarray(getattr(self, k)) for k in
                ("centres", "scales", "trend", "weights", "y_mean", "y_std", "kind")}

    @classmethod
    def from_arrays(cls, data, prefix: str) -> "Kernel":
        return cls(**{k: np.asarray(data[f"{prefix}_{k}"], float) for k in
                      ("centres", "scales", "trend", "weights", "y_mean", "y_std")},
                   kind=str(data[f"{prefix}_kind"]))
