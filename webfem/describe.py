"""The readable terminal summary of a :class:`webfem.result.Result`."""

from __future__ import annotations

__all__ = ["describe"]


def describe(result) -> str:
    """Several lines: the operating point, Eq. 21's range, the gaps, the regime, mu and
    delta_T, how the numbers were obtained, and every warning."""
    s, c = result.summary, result.case
    um = 1e6
    lines = [
        f"webfem {s.model}: R = {c.roller.radius:g} m, L = {c.web.width:g} m, "
        f"T = {c.web.tension:g} N/m, B = {c.wrap.angle_deg:g} deg, "
        f"U_r = {c.roller.speed:g} m/s, U_w = {c.web.speed:g} m/s",
        f"  lambda = {s.lambda_:.3g}, beta = {s.beta:.3g}, Eq. 21 range "
        + ("met" if s.eq21_valid else "NOT met (beta > 6 and lambda > 7)"),
        f"  gap: inlet {s.h_inlet * um:.3f} um, centre {s.h_center * um:.3f} um, "
        f"outlet {s.h_outlet * um:.3f} um, minimum {s.h_min * um:.3f} um",
        f"  h_c = {s.h_c * um:.3f} um, 3 sigma = {3 * s.sigma * um:.3f} um; "
        f"regime {s.regime} (wrap shares: boundary {s.share_boundary:.2f}, "
        f"mixed {s.share_mixed:.2f}, fluid {s.share_fluid:.2f})",
        f"  mu = {s.mu:.4f}, tension increase before slip delta_T = {s.delta_T:.3f} N/m",
        f"  converged = {s.converged}, iterations = {s.iterations}, "
        f"n_dofs = {s.n_dofs}, time = {s.solve_time_s * 1e3:.3f} ms",
    ]
    if s.mesh is not None:
        lines.append(f"  {s.method or ''} on {s.mesh}; residual {s.residual:.2e}; contact "
                     f"carries {100 * (s.contact_share or 0.0):.1f} % of the wrap load")
    if s.why is not None:
        err = ("not estimated" if s.estimated_error is None
               else f"{s.estimated_error:.2g} <= {s.tolerance:g}")
        lines.append(f"  model used: {s.model_used} (estimated {s.quantity} error {err}): "
                     f"{s.why}")
    for w in s.warnings:
        lines.append(f"  warning: {w}")
    return "\n".join(lines)
