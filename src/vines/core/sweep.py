"""Bifurcation sweeps: simulate along a parameter, each point starting from the last state.

This is the numerical continuation of the paper (Figs 3, 6, 14, 15): for each parameter value
the VINES is simulated for ``t_settle`` (the first point, from rest) or ``t_step`` (the next
ones, from the final state of the previous point), and the impacts of the last ``n_record``
forcing periods are kept. The forcing phase is carried over (phi of the next point is the
forcing phase reached by the previous one), so the motion continues smoothly.

Output is a contiguous ragged array (CF discrete sampling geometry): impacts of all points
one after another, with ``row_size`` impacts per parameter value.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .exact import run_exact
from .params import (
    D_DEFAULT,
    MAX_IMPACTS_MAX,
    MAX_IMPACTS_PER_PERIOD_DEFAULT,
    N_RECORD_DEFAULT,
    PARAM_BOUNDS,
    PARAM_NAMES,
    R_DEFAULT,
    T_END_MAX,
    T_SETTLE_DEFAULT,
    T_STEP_DEFAULT,
    V_STICK_DEFAULT,
    V_STICK_MAX,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_bool,
    check_choice,
    check_int,
    check_param,
    check_real,
    check_reals,
)


def sweep_point(params: ModelParams, state, t_run: float, n_record: int, v_stick: float,
                max_impacts_per_period: float, periodic_shortcut: bool):
    """One point of a sweep: run ``params`` for ``t_run`` from ``state`` (z_m, z_m', z_b,
    z_b'), recording the impacts of the last ``n_record`` forcing periods.

    Returns (raw, settings, next_state, theta): the RawRun and its SolverSettings, the
    state to start the next point from (rest if this run failed) and the forcing phase
    omega t + phi reached.
    """
    p = params
    t_record = n_record * p.period
    st = SolverSettings(t_end=t_run, t_transient=t_run - t_record, v_stick=v_stick,
                        max_impacts=int(max_impacts_per_period * t_run / p.period) + 100,
                        state0=state)
    raw = run_exact(p, st, record_from=st.t_transient, periodic_shortcut=periodic_shortcut)
    fs = raw.solver_info["final_state"]
    nxt = inside_cavity(float(fs[0]), float(fs[1]), float(fs[2]), float(fs[3]))
    if raw.status != "ok" or not np.all(np.isfinite(fs)):
        nxt = (0.0, 0.0, 0.0, 0.0)
    return raw, st, nxt, p.omega * raw.t_last + p.phi


#: largest excess of |z_m - z_b| over 1, in units of the state's size, that is round-off
WALL_ROUNDOFF = 8 * np.finfo(float).eps


def inside_cavity(z_m, v_m, z_b, v_b) -> tuple:
    """The state with z_b moved by round-off so that |z_m - z_b| <= 1 holds in floating point.

    A ball at rest on a wall far from the origin (|z| ~ 10) can end a run 1 ulp outside the
    cavity (z_m and z_b are kept separately); ``state0`` refuses |z_m - z_b| > 1. Larger
    excesses are left alone (and refused downstream)."""
    w = z_m - z_b
    excess = abs(w) - 1.0
    if 0.0 < excess <= WALL_ROUNDOFF * max(1.0, abs(z_m), abs(z_b)):
        z_b = z_m - math.copysign(1.0, w)
        while abs(z_m - z_b) > 1.0:
            z_b = math.nextafter(z_b, z_m)
    return z_m, v_m, z_b, v_b


@dataclass(frozen=True)
class SweepLine:
    """One sweep line, validated on construction (ParameterError naming a bad value).

    ``param`` (one of PARAM_NAMES) runs through ``values`` in sweep order with the other two
    of eta, omega, F fixed (the swept one's own field is not used); r and d as in
    ``ModelParams``. Each point runs for t_settle (the first, from rest) or t_step (the
    next ones, from the last state), plus n_record forcing periods that are recorded
    (dimensionless time); v_stick as in ``SolverSettings``; each run may have
    max_impacts_per_period impacts per forcing period (+ 100); periodic_shortcut as in
    ``simulate``.
    """

    param: str
    values: np.ndarray
    eta: float | None = None
    omega: float | None = None
    F: float | None = None
    r: float = R_DEFAULT
    d: float = D_DEFAULT
    t_settle: float = T_SETTLE_DEFAULT
    t_step: float = T_STEP_DEFAULT
    n_record: int = N_RECORD_DEFAULT
    v_stick: float = V_STICK_DEFAULT
    max_impacts_per_period: float = MAX_IMPACTS_PER_PERIOD_DEFAULT
    periodic_shortcut: bool = True

    def __post_init__(self):
        set_ = object.__setattr__
        param = check_choice("param", self.param, PARAM_NAMES)
        for name in PARAM_NAMES:
            if name != param and getattr(self, name) is None:
                raise ParameterError(name, None, f"must be given when sweeping {param}")
            if name != param:
                set_(self, name, check_param(name, getattr(self, name)))
        lo, lo_open, hi = PARAM_BOUNDS[param]
        set_(self, "values", check_reals("values", self.values, lo=lo, lo_open=lo_open, hi=hi,
                                         min_size=0))
        set_(self, "t_settle", check_real("t_settle", self.t_settle, lo=0.0, lo_open=True,
                                          hi=T_END_MAX))
        set_(self, "t_step", check_real("t_step", self.t_step, lo=0.0, lo_open=True,
                                        hi=T_END_MAX))
        set_(self, "n_record", check_int("n_record", self.n_record, lo=1))
        set_(self, "max_impacts_per_period",
             check_real("max_impacts_per_period", self.max_impacts_per_period, lo=0.0,
                        lo_open=True))
        set_(self, "periodic_shortcut", check_bool("periodic_shortcut",
                                                   self.periodic_shortcut))
        set_(self, "r", check_param("r", self.r))
        set_(self, "d", check_param("d", self.d))
        set_(self, "v_stick", check_real("v_stick", self.v_stick, lo=0.0, hi=V_STICK_MAX))
        _check_run_lengths(self)

    def point(self, k: int, theta: float) -> ModelParams:
        """The model of point k, its forcing phase phi = theta mod 2 pi (theta: the phase
        omega t + phi the previous point reached)."""
        kw = {"eta": self.eta, "omega": self.omega, "F": self.F, self.param: self.values[k]}
        return ModelParams(eta=kw["eta"], omega=kw["omega"], F=kw["F"], r=self.r, d=self.d,
                           phi=math.fmod(theta, 2.0 * math.pi))

    def t_run(self, k: int, p: ModelParams) -> float:
        """Length of point k's run (model p): t_settle or t_step plus n_record periods."""
        return (self.t_settle if k == 0 else self.t_step) + self.n_record * p.period

    def run_point(self, k: int, p: ModelParams, state):
        """``sweep_point`` of point k (model p) from ``state``."""
        return sweep_point(p, state, self.t_run(k, p), self.n_record, self.v_stick,
                           self.max_impacts_per_period, self.periodic_shortcut)


def bifurcation_sweep(param, values, *, eta=None, omega=None, F=None, r=R_DEFAULT, d=D_DEFAULT,
                      t_settle=T_SETTLE_DEFAULT, t_step=T_STEP_DEFAULT,
                      n_record=N_RECORD_DEFAULT, v_stick=V_STICK_DEFAULT,
                      max_impacts_per_period=MAX_IMPACTS_PER_PERIOD_DEFAULT,
                      periodic_shortcut=True) -> dict:
    """Sweep ``param`` through ``values`` (in the given order) with the other two fixed
    (arguments as the fields of ``SweepLine``).

    Returns dict with 1-D arrays over the values: value, row_size, phi (phase used at the
    start of each point), status, shortcut_time (time of the point's run, from its start,
    from which it was completed from one period of a settled orbit; NaN: not taken, see
    ``simulate``); and over the impacts: dw (relative velocity w' = z_m' - z_b' just
    before impact), phase (impact phase mod(omega t + phi, 2 pi) with t counted from the
    start of the sweep so phases are comparable), wall (+1 L, -1 R). With the shortcut the
    next point starts from the periodic orbit's state at the end of the run (equal to the
    full run's to ~1e-10; a chaotic point amplifies such differences).
    """
    return sweep_line(SweepLine(
        param, values, eta=eta, omega=omega, F=F, r=r, d=d, t_settle=t_settle, t_step=t_step,
        n_record=n_record, v_stick=v_stick, max_impacts_per_period=max_impacts_per_period,
        periodic_shortcut=periodic_shortcut))


def sweep_line(line: SweepLine) -> dict:
    """``bifurcation_sweep`` of a validated line."""
    values = line.values
    state = (0.0, 0.0, 0.0, 0.0)
    theta = 0.0           # forcing phase omega t + phi carried from point to point
    dws, phases, walls = [], [], []
    row_size = np.zeros(values.size, dtype=np.int64)
    phis = np.zeros(values.size)
    status = np.empty(values.size, dtype="U16")
    shortcut_time = np.full(values.size, np.nan)
    for k in range(values.size):
        p = line.point(k, theta)
        raw, _, state, theta = line.run_point(k, p, state)
        imp = raw.impacts
        dws.append(imp["v_m"] - imp["v_b"])
        phases.append(np.mod(p.omega * imp["t"] + p.phi, 2.0 * math.pi))
        walls.append(imp["wall"])
        row_size[k] = imp.size
        phis[k] = p.phi
        status[k] = raw.status
        shortcut_time[k] = raw.shortcut_time

    def cat(xs, dt):
        return np.concatenate(xs).astype(dt) if xs else np.zeros(0, dt)

    return {"value": values, "row_size": row_size, "phi": phis, "status": status,
            "shortcut_time": shortcut_time, "dw": cat(dws, float),
            "phase": cat(phases, float), "wall": cat(walls, np.int8)}


def _check_run_lengths(line: SweepLine) -> None:
    """Refuse a sweep whose runs (t_settle for the first point, t_step for the others, plus
    n_record forcing periods) exceed T_END_MAX or may need more than MAX_IMPACTS_MAX
    impacts (``sweep_point``)."""
    param, values, omega = line.param, line.values, line.omega
    t_settle, t_step, n_record = line.t_settle, line.t_step, line.n_record
    max_impacts_per_period = line.max_impacts_per_period
    if values.size == 0:
        return
    omegas = values if param == "omega" else np.full(values.size, omega)
    with np.errstate(invalid="ignore", over="ignore"):
        period = 2.0 * math.pi / omegas
        t_run = np.where(np.arange(values.size) == 0, t_settle, t_step) + n_record * period
        impacts = max_impacts_per_period * t_run / period + 100
    k = int(np.argmax(~(t_run <= T_END_MAX))) if not np.all(t_run <= T_END_MAX) else None
    if k is not None:
        raise ParameterError("n_record", n_record,
                             f"needs runs of t_settle (or t_step) + n_record forcing periods "
                             f"<= {T_END_MAX:g}; at {param} = {values[k]:g}: {t_run[k]:.3g}")
    if not np.all(impacts <= MAX_IMPACTS_MAX):
        raise ParameterError("max_impacts_per_period", max_impacts_per_period,
                             f"allows {np.max(impacts):.3g} impacts per run > {MAX_IMPACTS_MAX}")
