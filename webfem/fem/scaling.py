"""The scaled parameters of a case: what the FE forms see (Eshel-Elrod scaling).

X = x / (R eps^(1/3)), H = h / (R eps^(2/3)), P = (p - p_a) R / T with eps = 6 eta U / T.
The forms in :mod:`webfem.fem.forms` take these numbers, never a case.

Examples
--------
>>> from webfem import Case
>>> prm = FoilParameters.from_case(Case().updated({"roller.speed": 40.0}))
>>> round(prm.beta, 1), prm.contact
(27.7, 1.0)
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..physics.contact import contact_gap
from ..physics.friction import SLIP_COEFFICIENT

__all__ = ["FoilParameters"]


@dataclass(frozen=True)
class FoilParameters:
    """Dimensionless parameters of the scaled problem.

    beta wrap length B/eps^(1/3); K = 12 k/(R t eps^(4/3)) permeation; d = T/(R p_a)
    compressibility (0: incompressible); ds = d/2 (isothermal Darcy sink, density (p + p_a)/2)
    or d (the paper's sink, density p): the compressibility of the sink; slip = 6 a lambda_a /
    (R eps^(2/3)) the first-order slip term of the Poiseuille flux (0: no slip);
    Dn = D/(T (R eps^(1/3))^2) bending; c, S contact
    pressure Pc = c exp(-H/S) (exponential heights, ``law`` 0; Gaussian, ``law`` 1, see
    :func:`webfem.fem.forms.contact_law`); contact 1/0; floor: the scaled film thickness
    below which Reynolds sees a smooth floor (from_case takes it as a fraction of sigma);
    H_c: the scaled gap at which contact alone carries T/R; land: the land fraction a/p_g of
    a grooved roller (1 smooth): asperity contact acts on the lands only, so the web sees
    land Pc(H) (:func:`webfem.fem.forms.web_coefficients`); flow 1: the air flows through the
    flow gap E[(H - z)+] instead of H with the floor (:func:`webfem.fem.forms.flow_gap`);
    couette: the factor of the Couette (entrainment) flux, 1 but on the film-strength path to
    a resting web (:meth:`film_strength`); span: the free span from each wrap edge to the
    neighbouring roller, in X (0: the web held at the ends of the domain, Eq. 20; else the
    problems hold it there through a straight span from the domain's ends,
    :func:`webfem.fem.ends.end_springs`).
    """

    beta: float
    K: float
    d: float
    Dn: float
    c: float
    S: float
    contact: float
    floor: float
    law: int = 0
    H_c: float = 0.0
    ds: float | None = None
    slip: float = 0.0
    land: float = 1.0
    flow: int = 0
    couette: float = 1.0
    span: float = 0.0

    def __post_init__(self):
        if self.ds is None:     # the paper's sink unless told otherwise
            object.__setattr__(self, "ds", self.d)

    @classmethod
    def from_case(cls, case, compressible=True, contact=True, floor=0.1) -> "FoilParameters":
        """The parameters of ``case`` (a :class:`webfem.case.Case`); ``floor`` is a fraction
        of the roughness sigma."""
        # T is the effective tension T_eff = T - rho_w t U_w^2 (web inertia)
        R, T, eps = case.roller.radius, case.tension_eff, case.eps
        w = case.web
        gaussian = case.friction.distribution == "gaussian"
        # exponential: Pc = c exp(-H/S); Gaussian: Pc = c (S/sqrt(2 pi) e^(-H^2/2S^2) - ...)
        c = (w.modulus_thickness * R * case.h_scale / (w.thickness * T) if gaussian else
             w.modulus_thickness * case.sigma * R / (2.0 * w.thickness * T))
        h_c = contact_gap(case.p_bar, w.modulus_thickness, case.sigma, w.thickness,
                          case.friction.distribution)
        d = case.p_bar / case.air.ambient_pressure if compressible else 0.0
        return cls(
            beta=case.beta,
            K=12.0 * w.permeability / (R * w.thickness * eps ** (4 / 3)),
            d=d, ds=0.5 * d if case.permeation_model == "isothermal" else d,
            slip=(6.0 * SLIP_COEFFICIENT * case.air.mean_free_path / case.h_scale
                  if case.slip_model == "first-order" else 0.0),
            Dn=case.bending_used / (T * case.x_scale**2),
            c=c, S=case.sigma / case.h_scale, contact=1.0 if contact else 0.0,
            floor=floor * case.sigma / case.h_scale,
            law=1 if gaussian else 0, H_c=float(h_c / case.h_scale),
            land=case.land_fraction, flow=1 if case.roughness_flow_model == "mean-gap" else 0,
            span=0.0 if case.span_used is None else case.span_used / case.x_scale,
        )

    def as_form_args(self) -> dict:
        """The keyword arguments the forms' coefficient functions take."""
        return dict(beta=self.beta, K=self.K, d=self.d, ds=self.ds, slip=self.slip, Dn=self.Dn,
                    c=self.c, S=self.S, contact=self.contact, floor=self.floor, law=self.law,
                    land=self.land, flow=self.flow, couette=self.couette)

    def homotopy(self, s: float) -> "FoilParameters":
        """Permeation, compressibility and bending scaled by ``s``: s = 0 is the Eshel-Elrod
        problem, which Newton solves from a cold start (continuation)."""
        return replace(self, K=s * self.K, d=s * self.d, ds=s * self.ds, Dn=s * self.Dn)

    def film_strength(self, a: float) -> "FoilParameters":
        """The Couette (entrainment) flux scaled by ``a``: a = 0 has no film pressure (P = 0
        solves the film), so the web rests on its asperities alone; a = 1 is the problem."""
        return replace(self, couette=float(a))
