"""The cores this process may run on (what a thread pool or a set of worker processes can
use; on Linux the affinity mask, which a container or ``taskset`` narrows).

>>> usable_cores() >= 1
True
"""

from __future__ import annotations

import os

__all__ = ["usable_cores"]


def usable_cores() -> int:
    """The number of cores this process may run on (at least 1)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:       # not on Linux
        return os.cpu_count() or 1
