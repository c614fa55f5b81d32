"""The slow invariant manifold (SIM) of the symmetric two-impact regime, in closed form.

Leading order in eta (docs/slowflow.md, sections 2-3): the LO moves as
z_m = X cos(theta), theta = Omega t + psi, and the ball hits wall L (w = +1) at theta = alpha,
wall R at alpha + pi. Matching the ball's flight (half a period) with the impact law gives the
SIM

    -X sin(alpha) = rho (1 - X cos(alpha)),      rho = (2/pi) (1 - r) / (1 + r),

i.e. X(alpha) = rho / (rho cos(alpha) - sin(alpha)) for alpha in (-pi/2 - beta, 0),
tan(beta) = 1/rho. Lengths are in units of L (half the cavity), angles in radians.
The ball's impact map (LO prescribed) has determinant r^2 and trace
2 r - (pi/2)(1 - r^2) cot(alpha): it is stable for -rho < cot(alpha) < 4/(pi^2 rho), between
the fold (alpha = -beta, the activation threshold xi_min = rho/sqrt(1 + rho^2)) and the
symmetry-breaking point (cot(alpha) = 4/(pi^2 rho)). That map is the half-period map
composed with the mirror (the alternating signs removed): its eigenvalue -1 there is +1 of
the full-period map, a symmetry-breaking pitchfork where a 1:1 orbit with unequal flights
is born (not a period doubling: that comes much later, near X = 1). The former names
``alpha_flip``, ``x_flip`` and ``BRANCH_FLIP`` are deprecated aliases.
"""
from __future__ import annotations

import math
import warnings

import numpy as np

#: SIM branch codes (the FRC's ``branch``)
BRANCH_STABLE = 1      # between the fold and the symmetry-breaking point: stable impacts
BRANCH_UNSTABLE = 2    # between the fold and X = 1 (zero impact velocity): saddle
BRANCH_SYMMETRY_BREAKING = 3   # beyond the symmetry-breaking point: the symmetric motion is
#                                unstable, a 1:1 orbit with unequal flights takes over
BRANCH_NAMES = {BRANCH_STABLE: "stable", BRANCH_UNSTABLE: "unstable",
                BRANCH_SYMMETRY_BREAKING: "symmetry-breaking"}


def rho(r: float) -> float:
    """rho = (2/pi)(1 - r)/(1 + r): 2/pi for r = 0, 0 for r = 1 (no dissipation)."""
    return 2.0 / math.pi * (1.0 - r) / (1.0 + r)


def beta(rh: float) -> float:
    """The fold's angle: alpha = -beta at the fold, tan(beta) = 1/rho (0 < beta <= pi/2)."""
    return math.atan2(1.0, rh)


def xi_min(rh: float) -> float:
    """The SIM's fold: the smallest LO amplitude (units of L) with two impacts per period."""
    return rh / math.sqrt(1.0 + rh * rh)


def alpha_symmetry_breaking(rh: float) -> float:
    """Impact phase alpha in (-pi, -pi/2) of the symmetry-breaking point:
    cot(alpha) = 4/(pi^2 rho)."""
    cf = 4.0 / (math.pi ** 2 * rh)
    return -math.pi + math.atan2(1.0, cf)


def x_symmetry_breaking(rh: float) -> float:
    """LO amplitude (units of L) at the symmetry-breaking point, the upper end of the
    SIM's stable branch."""
    return float(amplitude(alpha_symmetry_breaking(rh), rh))


#: deprecated name -> (its new name, the object); for one release (``__getattr__``)
_DEPRECATED = {"alpha_flip": "alpha_symmetry_breaking", "x_flip": "x_symmetry_breaking",
               "BRANCH_FLIP": "BRANCH_SYMMETRY_BREAKING"}


def __getattr__(name: str):
    if name in _DEPRECATED:
        new = _DEPRECATED[name]
        warnings.warn(f"vines.slowflow.manifold.{name} is deprecated: use {new} (it is a "
                      "symmetry-breaking pitchfork, not a flip)", DeprecationWarning,
                      stacklevel=2)
        return globals()[new]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def amplitude(alpha, rh):
    """The SIM: LO amplitude X(alpha) = rho/(rho cos(alpha) - sin(alpha)) (units of L)."""
    return rh / (rh * np.cos(alpha) - np.sin(alpha))


def ball_amplitude(alpha, X):
    """Ball's largest |z_b| (units of L): it flies between +-(1 - X cos(alpha))."""
    return np.abs(1.0 - X * np.cos(alpha))


def dalpha_dX(alpha, rh):
    """d(alpha)/dX along the SIM (infinite at the fold)."""
    den = rh * np.cos(alpha) - np.sin(alpha)
    with np.errstate(divide="ignore"):
        return den * den / (rh * (rh * np.sin(alpha) + np.cos(alpha)))


def branch_of(alpha, rh):
    """SIM branch code of the impact phases alpha (see BRANCH_*)."""
    alpha = np.asarray(alpha, dtype=float)
    out = np.full(alpha.shape, BRANCH_STABLE, dtype=np.int8)
    out[alpha > -beta(rh)] = BRANCH_UNSTABLE
    out[alpha < alpha_symmetry_breaking(rh)] = BRANCH_SYMMETRY_BREAKING
    return out


def to_range(alpha2, rh):
    """Angles alpha (from 2 alpha, any branch of the arccos) mapped into the SIM's range
    (-pi/2 - beta, pi/2 - beta); valid SIM points are those below 0."""
    lo = -0.5 * math.pi - beta(rh)
    return np.mod(0.5 * alpha2 - lo, math.pi) + lo
