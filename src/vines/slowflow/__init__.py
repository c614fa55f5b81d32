"""The averaged slow flow of the symmetric two-impact (1:1) regime: a light ball (eta small),
light damping, forcing near the LO's resonance (docs/slowflow.md).

numpy only (no numba): the slow invariant manifold, its fold and symmetry-breaking point
in closed form
(``manifold``), the fixed points of the slow flow in closed form with their stability
(``response``), the public front end with the regime and the warnings (``api``) and the
clearance that minimises the peak LO amplitude over a band (``optimal``).

    rho(r)                                       (2/pi)(1 - r)/(1 + r)
    response(eta, omega, F, *, r, d)             SlowFlowResponse at one point
    frc(eta, omegas, F, *, r, d)                 FRC: every fixed point over frequencies
    optimal_clearance(...), optimal_F(...)       the band's best clearance / F = A/L
"""
from __future__ import annotations

from .api import FRC, SlowFlowOrbit, SlowFlowResponse, frc, response
from .manifold import rho, xi_min
from .optimal import Optimum, optimal_clearance, optimal_F

__all__ = ["rho", "xi_min", "response", "frc", "FRC", "SlowFlowResponse", "SlowFlowOrbit",
           "optimal_clearance", "optimal_F", "Optimum"]
