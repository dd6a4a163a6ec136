"""How a solve went, typed: :class:`SolveInfo`, which merges successive solves by itself.

Examples
--------
>>> a = SolveInfo(converged=False, iterations=25, residual=1e-3, history=[1.0, 1e-3],
...               reason="line search failed")
>>> b = SolveInfo(converged=True, iterations=6, residual=1e-11, history=[1e-3, 1e-11],
...               reason="residual below tolerance")
>>> c = b.after(a, "from the safe start")
>>> c.converged, c.iterations, len(c.history), c.reason
(True, 31, 4, 'residual below tolerance (from the safe start)')

The notes stay apart from a reason that has parentheses of its own:

>>> SolveInfo(reason="at its rounding floor 8e-4 (eps |J| |u|)").noted("after continuation").notes
('after continuation',)
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

__all__ = ["SolveInfo"]


@dataclass
class SolveInfo:
    """The outcome of a solve on one mesh or of a chain of them: ``converged``, the
    nonlinear ``iterations`` spent (every attempt counted), the final ``residual`` (2-norm,
    scaled units) and its ``history`` per iteration, the closing ``reason`` with the path's
    notes, the continuation ``steps`` passed, the refinement rounds ``adapt_rounds``, and
    Picard's relaxation factors ``omegas`` and block iterations."""

    converged: bool = False
    iterations: int = 0
    residual: float = float("inf")
    history: list = field(default_factory=list)
    reason: str = ""
    steps: list = field(default_factory=list)
    adapt_rounds: int = 0
    omegas: list | None = None
    block_iterations: dict | None = None
    #: the last solve's bounds of its algebraic error per quantity read, where Newton
    #: stopped on them (:mod:`webfem.models.algebraic`); None: solved to the tolerance
    algebraic: dict | None = None
    #: the notes :meth:`after` and :meth:`noted` appended to ``reason``, kept apart: a
    #: solver's own reason may hold parentheses, so the notes cannot be split off the text
    notes: tuple = ()

    @classmethod
    def of(cls, out, steps=(1.0,)) -> "SolveInfo":
        """From a :class:`webfem.fem.newton.NewtonResult` (or anything with ``converged``,
        ``iterations``, ``residual``, ``history`` and ``reason``)."""
        return cls(converged=bool(out.converged), iterations=int(out.iterations),
                   residual=float(out.residual), history=list(out.history),
                   reason=out.reason, steps=list(steps),
                   algebraic=getattr(out, "algebraic", None))

    def after(self, before: "SolveInfo", note: str = "") -> "SolveInfo":
        """This solve as the continuation of ``before``: its iterations added, the residual
        histories joined, ``note`` appended to the reason. Returns a new object."""
        reason = f"{self.reason} ({note})" if note else self.reason
        return dataclasses.replace(self, iterations=before.iterations + self.iterations,
                                   history=list(before.history) + list(self.history),
                                   reason=reason,
                                   notes=tuple(self.notes) + ((note,) if note else ()))

    def noted(self, note: str) -> "SolveInfo":
        """A copy with ``note`` appended to the reason."""
        return dataclasses.replace(self, reason=f"{self.reason} ({note})",
                                   notes=tuple(self.notes) + (note,))
