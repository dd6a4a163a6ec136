"""The fields of a solved state in physical units: along the web at the nodes (every FE model)
and over the 2-D film at its mesh vertices (for VTU files and pictures)."""

from __future__ import annotations

import numpy as np

from ..case import Case
from ..fem import forms
from ..fem.scaling import FoilParameters
from ..physics.friction import friction_for
from ..result import Fields, Film
from .readout import pressure_and_gradient

__all__ = ["node_fields", "film_fields"]


def node_fields(case: Case, problem, u, prm: FoilParameters) -> Fields:
    """Gap, web deflection, (width-averaged) pressure, contact pressure and friction at the
    web's nodes."""
    X = problem.X
    Hs = case.h_scale
    H = problem.gap(u, prm, X)
    h = H * Hs
    # one-sided differences at the ends (the pressure is only defined inside the domain)
    inner = np.clip(X, X[0] + 1e-6, X[-1] - 1e-6)
    p, dpdx = pressure_and_gradient(case, problem, u, inner)
    p_rel = p - case.air.ambient_pressure
    return Fields(x=X * case.x_scale, h=h, w=h - forms.departure(X, prm.beta) * Hs,
                  p_rel=p_rel, p=p, p_contact=forms.contact_law(H, prm.as_form_args())[0]
                  * case.p_bar, in_wrap=forms.in_wrap(X, prm.beta),
                  **friction_for(case, h, resting=True, p=p, dpdx=dpdx))


def film_fields(case: Case, problem, u, prm: FoilParameters) -> Film:
    """The 2-D film at its mesh vertices: pressure, gap (web gap plus groove depth), contact
    pressure (on the lands), contact share, friction and regime."""
    pts = problem.mesh.p
    Hs = case.h_scale
    x, line = np.unique(pts[0], return_inverse=True)     # the vertices lie on the X nodes
    Hx = problem.gap(u, prm, x)
    H = Hx[line]
    groove = (problem.grooves.depth_at(pts[1]) if problem.grooves is not None
              else np.zeros_like(H))
    on_land = groove == 0.0
    h = (H + groove) * Hs          # the film gap: web gap plus groove depth
    p_rel = problem.film_pressure_at_vertices(u) * case.p_bar
    # the web's friction is a function of its gap alone, point by point: once per X line
    # (the base case's 225 instead of its 2,700 vertices), then spread over the vertices
    loc = {k: v[line] for k, v in friction_for(case, Hx * Hs, resting=True).items()
           if k in ("chi_c", "mu", "regime")}
    return Film(
        points=np.vstack([pts * case.x_scale, np.zeros(pts.shape[1])]).T,
        quads=problem.mesh.t.T.copy(),
        p=p_rel + case.air.ambient_pressure, p_rel=p_rel, h=h,
        p_contact=forms.contact_law(H, prm.as_form_args())[0] * case.p_bar * on_land,
        chi_c=loc["chi_c"], mu=loc["mu"], regime=loc["regime"].astype(float))
