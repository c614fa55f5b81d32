"""Periodic attractors exactly: one period of the orbit, and 1:1 orbits polished by Newton.

* ``one_period``: the kernel over one period P of an orbit from a state on it; the KE
  ratio and x_max are exact time averages / maxima over that period, the regime follows
  from the period's events.
* ``polish_1to1``: a run whose last impacts alternate L, R once per forcing period is
  taken to the 1:1 orbit by the map's Newton solver (``orbits.family.periodic.solve_orbit``) from
  its last L impact. Accepted when the orbit is admissible and stable and the run's impact
  lies within POLISH_TOL of it: a stable orbit attracts such a run, however slowly it
  converges (|lambda| near 1), so slow runs are not mistaken for other periods.
* ``section_of_1to1``: a state of a polished 1:1 orbit on the section t = k T (forcing
  phase phi), by the closed-form flight from the post-impact state at L.
"""
from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..core import kernel as eng
from ..core.exact import KernelRun, Oscillators, Span, Trajectory
from ..core.flow import flow
from ..core.params import ModelParams, SolverSettings
from ..core.regime import CHATTER_RUN, longest_same_wall_run
from ..core.shortcut import rel_diff
from ..core.walls import WALL_L, impact_velocities
from ..orbits.family.periodic import PeriodicOrbit, solve_orbit

#: last impacts a run must have alternating L, R (one pair per forcing period) for a polish
N_TAIL = 16
#: largest distance (relative) of the run's last L impact from the polished 1:1 orbit
POLISH_TOL = 1e-3


def one_period(p: ModelParams, st: SolverSettings, osc: Oscillators, x0: Sequence[float],
               t0: float, P: float,
               mode: int = eng.MODE_FREE) -> dict:
    """Kernel run over [t0, t0 + P] from state x0 (segment ``mode``): ke_ratio and xmax over
    the period, impacts (total, on L), time stuck, the regime label of an orbit of period
    pp = round(P / T), ``return_error`` (rel. difference of the end state from x0) and the
    dense ``trajectory``."""
    run = KernelRun(p, st, osc, np.asarray(x0, float), t0, Span(t0 + P, t0, t0), mode)
    rc = run.run()
    if rc != eng.RC_DONE:
        raise RuntimeError(f"one period of the orbit from t = {t0} stopped: {eng.STATUS_TEXT.get(rc, rc)}")
    K_m = 0.5 * run.acc[eng.A_INT_VM2] / P
    K_b = 0.5 * p.eta * run.acc[eng.A_INT_VB2] / P
    n_imp, n_left = int(run.cnt[eng.C_NIMP_TOTAL]), int(run.cnt[eng.C_NIMP_L])
    t_stuck = float(run.acc[eng.A_TSTUCK_ALL])
    pp = max(1, round(P / p.period))
    return dict(ke_ratio=K_b / (K_m + K_b) if K_m + K_b > 0.0 else 0.0,
                xmax=float(run.acc[eng.A_XMAX_WIN]), n_impacts=n_imp, n_impacts_L=n_left,
                t_stuck=t_stuck,
                regime=orbit_regime(run.impacts()["wall"], n_left, n_imp - n_left, t_stuck, pp),
                period=pp, return_error=float(rel_diff(run.cur[1:5], np.asarray(x0, float))),
                trajectory=Trajectory(p, run.segments(), float(run.cur[0])))


def orbit_regime(walls: np.ndarray, n_left: int, n_right: int, t_stuck: float,
                 pp: int) -> str:
    """Regime label of a periodic orbit from the events of one period (walls of its
    impacts, counts on L and R, time stuck; ``core.regime``'s labels): chatter (sticks, or
    CHATTER_RUN impacts in a row on one wall, also across the period's end), no-impact,
    "a:b" for period 1, "period-p" otherwise."""
    if t_stuck > 0.0 or longest_same_wall_run(np.concatenate([walls, walls])) >= CHATTER_RUN:
        return "chatter"
    if n_left + n_right == 0:
        return "no-impact"
    if pp > 1:
        return f"period-{pp}"
    return f"{max(n_left, n_right)}:{min(n_left, n_right)}"


def alternating_tail(impacts: np.ndarray, t_end: float, T: float) -> int | None:
    """Index of the last L impact when the last N_TAIL impacts alternate L, R, all within
    the last N_TAIL / 2 + 1 forcing periods before t_end (no sticking among them: a stick
    ends a free flight without an impact record of the other wall); else None."""
    if impacts.shape[0] < N_TAIL + 1:
        return None
    tail = impacts[-N_TAIL:]
    w = tail["wall"]
    if np.any(w[1:] == w[:-1]) or tail["t"][0] < t_end - (N_TAIL // 2 + 1) * T:
        return None
    last_L = np.flatnonzero(w == WALL_L)[-1]
    return impacts.shape[0] - N_TAIL + int(last_L)


def polish_1to1(p: ModelParams, osc: Oscillators, impacts: np.ndarray,
                t_end: float) -> PeriodicOrbit | None:
    """The stable admissible 1:1 orbit a run converges to (module docstring), or None."""
    T = p.period
    k = alternating_tail(impacts, t_end, T)
    if k is None or k == 0:
        return None
    t = impacts["t"]
    x0 = np.array([impacts["v_m"][k], impacts["v_b"][k], impacts["z_b"][k], t[k]])
    # flight L -> R: to the next (R) impact, else a period minus the previous R -> L flight
    s1 = t[k + 1] - t[k] if k + 1 < t.size else T - (t[k] - t[k - 1])
    if not 0.0 < s1 < T:
        s1 = 0.5 * T
    orbit = solve_orbit(p, x0, s1, T - s1, osc)
    if orbit is None or not orbit.stable:
        return None
    dt = abs(x0[3] - orbit.x_L[3]) % T
    near_t = min(dt, T - dt) <= POLISH_TOL * (1.0 + T)
    scale = 1.0 + np.abs(orbit.x_L[:3])
    return orbit if near_t and np.all(np.abs(x0[:3] - orbit.x_L[:3]) <= POLISH_TOL * scale) \
        else None


def section_of_1to1(p: ModelParams, st: SolverSettings, oscs: Oscillators,
                    orbit: PeriodicOrbit) -> dict:
    """``one_period`` of a 1:1 orbit started mid-flight after its L impact, plus
    ``section_state``: its state at the first t = k T after that start."""
    vm, vb, zb, t_L = orbit.x_L
    vm_p, vb_p = impact_velocities(p.eta, p.r, vm, vb)
    s = 0.5 * orbit.flight_times[0]
    th0 = p.omega * t_L + p.phi
    z, v, _, _, _ = flow(oscs[0], zb + WALL_L, vm_p, math.sin(th0), math.cos(th0), s)
    x0 = np.array([z, v, zb + vb_p * s, vb_p])
    T = p.period
    one = one_period(p, st, oscs, x0, t_L + s, T)
    t_sec = math.ceil((t_L + s) / T) * T
    one["section_state"] = one["trajectory"](min(t_sec, t_L + s + T))[:, 0]
    return one


