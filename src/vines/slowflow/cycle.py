"""The strongly modulated response as a relaxation cycle of the slow flow (docs/slowflow.md,
section 6): the LO's slow amplitude and phase (X, chi) slide down the SIM's upper branch
(the impacts damp the LO) to the fold xi_min, where the impacts stop; the flow without
impacts then carries X up to 1, where the ball at rest in the centre is reached and the
motion jumps back onto the upper branch at the same (X, chi). Both pieces are integrated
(scipy's solve_ivp with events) cycle after cycle from chi = 0 until the phase at the jump
repeats; the result is the cycle's period and the time spent impacting."""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from . import manifold as sim
from .response import Model

#: cycles integrated at most, and the jump phase's agreement that ends them
N_CYCLES_MAX = 40
CHI_TOL = 1e-6
RTOL, ATOL = 1e-9, 1e-12


@dataclass(frozen=True)
class SMRCycle:
    """The predicted relaxation cycle: period (time units 1/w0), time_impacting (on the
    SIM), time_free (without impacts), amplitude_low (the smallest LO amplitude: the fold
    xi_min, or below it where the LO keeps losing amplitude after the impacts stop),
    amplitude_high (1)."""

    period: float
    time_impacting: float
    time_free: float
    amplitude_low: float
    amplitude_high: float

    def to_dict(self) -> dict:
        return asdict(self)


def upper_alpha(X, rh):
    """Impact phase on the SIM's upper (stable and symmetry-breaking) branch at LO
    amplitude X."""
    c = np.clip(rh / (X * math.sqrt(1.0 + rh * rh)), -1.0, 1.0)
    return -sim.beta(rh) - np.arccos(c)


def _field(m: Model, W: float, impacts: bool):
    """(X, chi)' of the slow flow (3) on the upper branch, or without impacts."""
    G = m.F * math.sqrt(1.0 + (m.d * W) ** 2)
    eKW = m.e * m.K * W if impacts else 0.0

    def f(_t, y):
        X, chi = y
        s2 = sc = 0.0
        if impacts:
            a = upper_alpha(X, m.rho)
            s2, sc = math.sin(a) ** 2, math.sin(a) * math.cos(a)
        return [-0.5 * m.d * X - eKW * X * s2 - G * math.cos(chi) / (2.0 * W),
                0.5 * (W * W - 1.0) / W + eKW * sc + G * math.sin(chi) / (2.0 * W * X)]
    return f


def _leg(f, y0, level: float, direction: float, t_max: float):
    """Integrate f from y0 until X crosses level in direction; (time, end state, smallest X
    on the way) or None."""
    from scipy.integrate import solve_ivp  # here: ``import vines.slowflow`` stays light

    def event(_t, y):
        return y[0] - level
    event.terminal, event.direction = True, direction
    if not np.all(np.isfinite(f(0.0, y0))):
        return None
    out = solve_ivp(f, (0.0, t_max), y0, events=event, rtol=RTOL, atol=ATOL,
                    dense_output=True)
    if out.status != 1:
        return None
    t_end = float(out.t_events[0][0])
    x_min = float(out.sol(np.linspace(0.0, t_end, 513))[0].min())
    return t_end, out.y_events[0][0], x_min


def smr_cycle(m: Model, W: float) -> SMRCycle | None:
    """The relaxation cycle at frequency W, or None where the flow does not cycle (a fixed
    point attracts on either piece within the time allowed)."""
    t_max = 50.0 / max(m.d, 1e-3) + 50.0 / max(m.e, 1e-3)
    x_low = sim.xi_min(m.rho) * (1.0 + 1e-9)
    on_sim, free = _field(m, W, True), _field(m, W, False)
    chi, last = 0.0, None
    for _ in range(N_CYCLES_MAX):
        down = _leg(on_sim, [1.0, chi], x_low, -1.0, t_max)
        if down is None:
            return None
        up = _leg(free, down[1], 1.0, 1.0, t_max)
        if up is None:
            return None
        chi_next = float(np.angle(np.exp(1j * up[1][1])))
        if last is not None and abs(np.angle(np.exp(1j * (chi_next - chi)))) < CHI_TOL:
            return SMRCycle(period=down[0] + up[0], time_impacting=down[0],
                            time_free=up[0], amplitude_low=min(up[2], sim.xi_min(m.rho)),
                            amplitude_high=1.0)
        chi, last = chi_next, chi
    return None
