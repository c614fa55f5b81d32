"""Fixed points of the averaged slow flow (the symmetric 1:1 regime) and their stability.

On the SIM (``manifold``) the LO's slow amplitude X and phase psi (z_m = X cos(Omega t + psi))
obey (docs/slowflow.md, section 4; e = eta/(1 + eta), K = 4/(pi^2 rho),
G = F sqrt(1 + (d Omega)^2), chi = phi + atan(d Omega) - psi)

    X'   = P(X) - G cos(chi)/(2 Omega),        P = -d X/2 - e K Omega X sin^2(alpha)
    chi' = Q(X) + G sin(chi)/(2 Omega X),      Q = (Omega^2 - 1)/(2 Omega)
                                                   + e K Omega sin(alpha) cos(alpha)

Fixed points: a1 cos(2 alpha) + a2 sin(2 alpha) = -a0 (closed form, ``_roots``), at most
two on the SIM per Omega. Stable: on the SIM's stable branch and trace < 0 < det of the
Jacobian of (X, chi).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import manifold as sim

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Roots:
    """Slow-flow fixed points at the frequencies ``omega`` (one entry per fixed point).

    index: the point's position in the frequency array; alpha: impact phase at L relative to
    the LO (rad); X: LO amplitude (units of L); phase: forcing phase mod(Omega t_L + phi,
    2 pi) at the L impact; branch: SIM branch code; trace, det: of the slow Jacobian.
    """

    index: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    X: np.ndarray
    phase: np.ndarray
    branch: np.ndarray
    trace: np.ndarray
    det: np.ndarray

    @property
    def slow_stable(self) -> np.ndarray:
        """Stable in the slow flow (trace < 0 < det), whatever the SIM branch."""
        return (self.trace < 0) & (self.det > 0)

    @property
    def stable(self) -> np.ndarray:
        """Stable orbit: slow-stable on the SIM's stable branch."""
        return (self.branch == sim.BRANCH_STABLE) & self.slow_stable

    @property
    def attracting(self) -> np.ndarray:
        """Slow-stable on the stable branch or beyond the symmetry-breaking point (where a
        1:1 orbit with unequal flights takes over at about this amplitude)."""
        return (self.branch != sim.BRANCH_UNSTABLE) & self.slow_stable

    @property
    def ball_amplitude(self) -> np.ndarray:
        return sim.ball_amplitude(self.alpha, self.X)


@dataclass(frozen=True)
class Model:
    """The scalars of one slow flow: eta, F, r, d (validated by the caller)."""

    eta: float
    F: float
    r: float
    d: float
    rho: float = field(init=False)

    def __post_init__(self):
        object.__setattr__(self, "rho", sim.rho(self.r))

    @property
    def e(self) -> float:
        return self.eta / (1.0 + self.eta)

    @property
    def K(self) -> float:
        return 4.0 / (math.pi ** 2 * self.rho)


def linear_amplitude(m: Model, W: np.ndarray) -> np.ndarray:
    """Exact amplitude of the LO without impacts (the base-excited linear response; inf at
    resonance without damping)."""
    dW = m.d * W
    with np.errstate(divide="ignore"):
        return m.F * np.sqrt((1.0 + dW * dW) / ((1.0 - W * W) ** 2 + dW * dW))


def _coefficients(m: Model, W: np.ndarray):
    """(a0, a1, a2, A1, A2, k): the fixed points solve a1 C + a2 S = -a0, C = cos 2 alpha,
    S = sin 2 alpha; A1 = Omega d + k, A2 = Omega^2 - 1, k = e K Omega^2."""
    rh2 = m.rho * m.rho
    G2 = m.F * m.F * (1.0 + (m.d * W) ** 2)
    k = m.e * m.K * W * W
    A1 = W * m.d + k
    A2 = W * W - 1.0
    a0 = rh2 * (A1 * A1 + A2 * A2 + k * k) - 0.5 * G2 * (1.0 + rh2)
    a1 = -2.0 * rh2 * A1 * k - 0.5 * G2 * (rh2 - 1.0)
    a2 = 2.0 * rh2 * A2 * k + G2 * m.rho
    return a0, a1, a2, A1, A2, k


def _roots(m: Model, W: np.ndarray):
    """(index, alpha) of every fixed point on the SIM, in closed form."""
    a0, a1, a2, *_ = _coefficients(m, W)
    R = np.hypot(a1, a2)
    with np.errstate(divide="ignore", invalid="ignore"):
        c = -a0 / R
    ok = np.abs(c) <= 1.0
    idx = np.flatnonzero(ok)
    delta = np.arctan2(a2[idx], a1[idx])
    acos = np.arccos(c[idx])
    double = acos == 0.0                      # tangent root: one fixed point
    i_all = np.concatenate([idx, idx[~double]])
    a2x = np.concatenate([delta + acos, (delta - acos)[~double]])
    alpha = sim.to_range(a2x, m.rho)
    keep = alpha < 0.0
    order = np.lexsort((alpha[keep], i_all[keep]))
    return i_all[keep][order], alpha[keep][order]


def fixed_points(m: Model, W: np.ndarray) -> Roots:
    """Every slow-flow fixed point at the frequencies W, with its stability."""
    i, alpha = _roots(m, W)
    w = W[i]
    X = sim.amplitude(alpha, m.rho)
    s, c = np.sin(alpha), np.cos(alpha)
    k = m.e * m.K * w * w
    # G cos(chi) and G sin(chi) at the fixed point
    gc = -X * (w * m.d + 2.0 * k * s * s)
    gs = -X * (w * w - 1.0 + 2.0 * k * s * c)
    chi = np.arctan2(gs, gc)
    phase = np.mod(alpha + chi - np.arctan(m.d * w), TWO_PI)
    trace, det = _jacobian(m, w, alpha, X)
    return Roots(index=i, omega=w, alpha=alpha, X=X, phase=phase,
                 branch=sim.branch_of(alpha, m.rho), trace=trace, det=det)


def _jacobian(m: Model, w, alpha, X):
    """Trace and determinant of d(X', chi')/d(X, chi) at fixed points (section 5)."""
    s, c = np.sin(alpha), np.cos(alpha)
    eKw = m.e * m.K * w
    P = -0.5 * m.d * X - eKw * X * s * s
    Q = 0.5 * (w * w - 1.0) / w + eKw * s * c
    da = sim.dalpha_dX(alpha, m.rho)
    with np.errstate(invalid="ignore", over="ignore"):
        dP = -0.5 * m.d - eKw * (s * s + X * 2.0 * s * c * da)
        dQ = eKw * (c * c - s * s) * da
        trace = dP + P / X
        det = dP * P / X + dQ * Q * X + Q * Q
    return trace, det
