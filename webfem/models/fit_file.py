"""Reading a coefficients file of the fitted model: a NumPy .npz archive written by `webfem
fit build`, checked whole, so a file that holds no fit is an input error naming the option,
the file and what is wrong (not a traceback from deep inside a solve).

It sits apart from :mod:`webfem.models.fitted` so that
:class:`~webfem.models.options.FittedOptions` can read the file when the option is set (every
command then refuses it before solving) without the options importing the model.
"""

from __future__ import annotations

import zipfile
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import InputError
from .fit_kernel import Kernel

__all__ = ["read_fit", "REQUIRED"]

#: The arrays a coefficients file must hold: the profile kernel's (``k_*``) and the box, the
#: stated-error table and what the fit was trained on.
REQUIRED = (*(f"k_{k}" for k in ("centres", "scales", "trend", "weights", "y_mean", "y_std",
                                 "kind")),
            "lo", "hi", "region_edges", "region_errors", "physics", "info")


def _not_a_fit(path, what: str) -> InputError:
    return InputError(f"fitted option coefficients = '{path}' {what}: it must be a "
                      "coefficients file of the fit, a NumPy .npz archive written by "
                      "`webfem fit build` (or leave the option out for the shipped fit)")


@lru_cache(maxsize=4)
def read_fit(path: str) -> dict:
    """The arrays of the coefficients file at ``path`` and the kernels they make.

    Returns
    -------
    dict
        ``arrays`` (name -> array), ``kernel`` (the profile's :class:`Kernel`), ``scalars``
        (the scalars' kernels, in order) and ``scalar_names``.

    Raises
    ------
    webfem.errors.InputError
        ``path`` is no file, not an .npz archive, lacks arrays of :data:`REQUIRED` (named)
        or holds arrays that make no kernel.
    """
    p = Path(path)
    if not p.is_file():
        raise _not_a_fit(path, "is no file")
    try:
        data = np.load(p, allow_pickle=False)
    except (OSError, ValueError, EOFError, zipfile.BadZipFile) as err:
        # numpy's first sentence says what it found ("This file contains pickled data")
        raise _not_a_fit(path, f"is not a NumPy .npz archive ({str(err).split('. ')[0]})") \
            from None
    if not isinstance(data, np.lib.npyio.NpzFile):
        raise _not_a_fit(path, "is a single NumPy array (.npy), not an .npz archive of the "
                               "fit's arrays")
    with data:
        try:
            arrays = {k: data[k] for k in data.files}
        except (OSError, ValueError, EOFError, zipfile.BadZipFile) as err:
            raise _not_a_fit(path, f"has an unreadable array ({err})") from None
    missing = [k for k in REQUIRED if k not in arrays]
    if missing:
        raise _not_a_fit(path, "lacks the arrays " + ", ".join(missing))
    try:
        scalars, j = [], 0
        while f"s{j}_centres" in arrays:
            scalars.append(Kernel.from_arrays(arrays, f"s{j}"))
            j += 1
        kernel = Kernel.from_arrays(arrays, "k")
        names = tuple(str(n) for n in arrays.get("scalar_names", ()))
    except (KeyError, ValueError, TypeError, IndexError) as err:
        raise _not_a_fit(path, f"holds arrays that make no fit ({type(err).__name__}: "
                               f"{err})") from None
    return {"arrays": arrays, "kernel": kernel, "scalars": scalars, "scalar_names": names}
