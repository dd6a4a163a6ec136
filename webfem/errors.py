"""Errors webfem raises beyond input validation (:class:`webfem.case.CaseError`)."""

from __future__ import annotations

__all__ = ["ConvergenceError", "ValidityWarning"]


class ValidityWarning(UserWarning):
    """A legal input outside a model's validity (Eq. 21's range, incompressibility, slip
    flow); the result is computed and carries the same text in its ``warnings`` key."""


class ConvergenceError(RuntimeError):
    """A solve did not meet its tolerance.

    ``result`` is the last iterate as a :class:`webfem.result.Result` with
    ``converged = False`` (for inspection only, never an answer) and ``history`` the
    residual norms per iteration.
    """

    def __init__(self, message: str, result=None, history=None):
        super().__init__(message)
        self.result = result
        self.history = list(history or [])
