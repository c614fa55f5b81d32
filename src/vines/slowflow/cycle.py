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


# --------------------------------------------------------------------------- from rest

#: where the slow flow's attractor from rest is not decided, the exact solver's regime from
#: rest (``core.regime`` labels) is read as the slow flow's: periodic -> two-impact
EXACT_REGIMES = {"no-impact": "no impact"}
#: a state on the SIM within this distance of an attracting fixed point (|X - X*|, and the
#: flow's speed there) has reached it
X_TOL = 1e-6


@dataclass(frozen=True)
class FromRest:
    """The regime reached from rest (LO at rest, ball at rest in the centre), decided by
    following the slow flow: regime ('two-impact', 'SMR', 'no impact'), jumps (times the
    LO reached X = 1 and the motion jumped onto the SIM's upper branch), jump_phase (chi at
    the first jump, None without one), amplitude (the attractor's LO amplitude: the fixed
    point's X, 1 for SMR, the linear amplitude without impacts), decided_by ('slow flow'
    or 'exact solver: <regime>' where the slow flow could not decide)."""

    regime: str
    jumps: int
    jump_phase: float | None
    amplitude: float
    decided_by: str

    def to_dict(self) -> dict:
        return asdict(self)


def _free_first_passage(m: Model, W: float, z0: complex, t_max: float):
    """The flow without impacts in closed form: with z = X exp(-i chi) it is linear,
    z' = lam z - G/(2W), lam = -(d/2 + i (W^2 - 1)/(2W)), so
    z(t) = z0 e^(lam t) + (G/(2W)) (1 - e^(lam t))/lam. The first time |z| = 1 (the ball at
    rest in the centre is reached) and chi there, or None (|z| < 1 up to t_max)."""
    from scipy.optimize import brentq
    G = m.F * math.sqrt(1.0 + (m.d * W) ** 2)
    lam = -complex(0.5 * m.d, 0.5 * (W * W - 1.0) / W)

    def z(t):
        e = np.exp(lam * t)
        small = -t * (1.0 + 0.5 * lam * t)         # (1 - e^(lam t))/lam for |lam t| small
        with np.errstate(divide="ignore", invalid="ignore"):
            growth = np.where(np.abs(lam * t) > 1e-8, (1.0 - e) / (lam or 1.0), small)
        return z0 * e + 0.5 * G / W * growth

    ts = np.linspace(0.0, t_max, 20001)
    over = np.flatnonzero(np.abs(z(ts)) >= 1.0)
    if over.size == 0:
        return None
    k = int(over[0])
    if k == 0:
        return 0.0, float(-np.angle(z0))
    t = brentq(lambda s: abs(z(s)) - 1.0, ts[k - 1], ts[k], xtol=1e-13)
    return t, float(-np.angle(z(t)))


def _on_sim(m: Model, W: float, chi: float, x_low: float, t_max: float):
    """The slow flow on the SIM's upper branch from (X, chi) = (1, chi): ('fold', state)
    where X falls to x_low, else ('end', state) at t_max."""
    from scipy.integrate import solve_ivp
    f = _field(m, W, True)

    def fold(_t, y):
        return y[0] - x_low
    fold.terminal, fold.direction = True, -1.0
    out = solve_ivp(f, (0.0, t_max), [1.0, chi], events=fold, rtol=RTOL, atol=ATOL)
    if out.status == 1:
        return "fold", out.y_events[0][0]
    return ("end", out.y[:, -1]) if out.status == 0 else ("failed", None)


def from_rest(m: Model, W: float, attracting_X, x_linear: float) -> FromRest:
    """The slow flow followed from rest at frequency W: the LO grows without impacts (in
    closed form) until X = 1, or stays below it ('no impact'); at X = 1 the motion jumps
    onto the SIM's upper branch at the same (X, chi) and the slow flow (3) is integrated
    to its attractor: an attracting fixed point (``attracting_X``: their X;
    'two-impact'), or the fold xi_min, where the impacts stop and the free flow takes over
    again, jump after jump until the jump's phase repeats (CHI_TOL: 'SMR') or X stays
    below 1 ('no impact'). Where the flow reaches the fold while a fixed point attracts
    (whether it is caught then hinges on the motion near the fold, where the averaging is
    singular, and on the ball after the impacts stop, which the slow flow takes at rest),
    or settles on nothing it knows within the time allowed, the exact solver's regime
    from rest decides (``decided_by`` says so)."""
    t_max = 50.0 / max(m.d, 1e-3) + 50.0 / max(m.e, 1e-3)
    x_low = sim.xi_min(m.rho) * (1.0 + 1e-9)
    z0, first, last = 0j, None, None
    for jumps in range(N_CYCLES_MAX + 1):
        up = _free_first_passage(m, W, z0, t_max)
        if up is None:
            return FromRest("no impact", jumps, first, float(x_linear), "slow flow")
        chi = up[1]
        first = chi if first is None else first
        if last is not None and abs(np.angle(np.exp(1j * (chi - last)))) < CHI_TOL:
            return FromRest("SMR", jumps + 1, first, 1.0, "slow flow")
        how, y = _on_sim(m, W, chi, x_low, t_max)
        if how == "fold" and len(attracting_X) == 0:
            z0, last = y[0] * np.exp(-1j * y[1]), chi
            continue
        if how == "end":
            speed = np.hypot(*_field(m, W, True)(0.0, y))
            near = [x for x in attracting_X if abs(y[0] - x) < X_TOL]
            if near and speed < X_TOL:
                return FromRest("two-impact", jumps + 1, first, float(near[0]), "slow flow")
        break
    return _exact_from_rest(m, W, jumps + 1, first)


def _exact_from_rest(m: Model, W: float, jumps: int, first) -> FromRest:
    """The exact solver's regime from rest (SPEC defaults) read as the slow flow's."""
    from ..core.simulation import simulate_batch
    out = simulate_batch(m.eta, W, m.F, r=m.r, d=m.d, n_threads=1)
    label = str(out["regime"])
    regime = EXACT_REGIMES.get(label, "two-impact" if label == "1:1" else "SMR")
    return FromRest(regime, jumps, first, float(out["xmax"]), f"exact solver: {label}")
