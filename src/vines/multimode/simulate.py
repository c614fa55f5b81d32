"""``simulate_model``: the exact engine's front end, its settings and its result.

Measures (window [t_transient, t_end], exact time integrals of the closed form; a regime
seen in the window may be a transient): per host degree of freedom x_max = max |x_j| and
the largest absolute acceleration |x_j''|; per absorber its travel max |w_i| (w_i = x_j - y_i),
the energy its damper and its impacts dissipate, its kinetic-energy ratio
K_i / (K_host + sum_l K_l) (K = time average of the kinetic energy; the 1-DOF model's KE
ratio for one absorber), impacts, time stuck and regime. The whole run's energy balance
E(t_end) - E(0) = W_forcing - D_host - sum_i (D_i + Q_i) is reported (``energy_balance``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..core.params import (
    MAX_IMPACTS_DEFAULT,
    MAX_IMPACTS_MAX,
    T_END_DEFAULT,
    T_END_MAX,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    V_STICK_MAX,
    ParameterError,
    check_int,
    check_real,
)
from ..core.regime import CHATTER_RUN, longest_same_wall_run
from .model import HostModel
from .system import pack

ROOT_TOL_DEFAULT = 1e-13
N_RECORD_DEFAULT = 4096
N_RECORD_MAX = 10_000_000
#: regimes are read off the last this many forcing periods of the window
REGIME_PERIODS = 64
MAX_PERIOD = 16
PHASE_TOL = 1e-6
STATE_MAX = 1e12


@dataclass(frozen=True)
class ModelSettings:
    """Run settings: end of the run, start of the measurement window, sticking speed,
    contact tolerance (in units of each gap), impact budget, impacts kept (the last n)."""

    t_end: float = T_END_DEFAULT
    t_transient: float = T_TRANSIENT_DEFAULT
    v_stick: float = V_STICK_DEFAULT
    root_tol: float = ROOT_TOL_DEFAULT
    max_impacts: int = MAX_IMPACTS_DEFAULT
    n_record: int = N_RECORD_DEFAULT

    def __post_init__(self):
        t_end = check_real("t_end", self.t_end, lo=0.0, lo_open=True, hi=T_END_MAX)
        object.__setattr__(self, "t_end", t_end)
        object.__setattr__(self, "t_transient", check_real("t_transient", self.t_transient,
                                                           lo=0.0, hi=t_end, hi_open=True))
        object.__setattr__(self, "v_stick", check_real("v_stick", self.v_stick, lo=0.0, hi=V_STICK_MAX))
        object.__setattr__(self, "root_tol", check_real("root_tol", self.root_tol, lo=0.0, hi=1e-3))
        object.__setattr__(self, "max_impacts", check_int("max_impacts", self.max_impacts, lo=1,
                                                          hi=MAX_IMPACTS_MAX))
        object.__setattr__(self, "n_record", check_int("n_record", self.n_record, lo=0,
                                                       hi=N_RECORD_MAX))


IMPACT_FIELDS = ("t", "absorber", "wall", "dw_before", "dw_after", "stuck")


@dataclass
class ModelResult:
    """What ``simulate_model`` returns (arrays per host dof or per absorber)."""

    model: HostModel
    settings: ModelSettings
    status: str
    x_max: np.ndarray
    accel_max: np.ndarray
    x_max_whole_run: np.ndarray
    travel: np.ndarray
    travel_whole_run: np.ndarray
    ke_ratio: np.ndarray
    dissipated_damper: np.ndarray
    dissipated_impacts: np.ndarray
    dissipated_host: float
    forcing_work: float
    n_impacts: np.ndarray
    n_impacts_whole_run: np.ndarray
    t_stuck: np.ndarray
    regime: list
    energy_balance: dict
    impacts: dict
    final_state: dict
    counters: dict = field(default_factory=dict)

    def summary(self) -> dict:
        """Plain values (the JSON of ``vines simulate --model``)."""
        return {"status": self.status,
                "window": [self.settings.t_transient, self.settings.t_end],
                "host": {"x_max": self.x_max, "accel_max": self.accel_max,
                         "x_max_whole_run": self.x_max_whole_run,
                         "dissipated_damping": self.dissipated_host,
                         "forcing_work": self.forcing_work},
                "absorbers": [{"kind": a.kind, "dof": a.dof, "travel": self.travel[i],
                               "travel_whole_run": self.travel_whole_run[i],
                               "ke_ratio": self.ke_ratio[i],
                               "dissipated_damper": self.dissipated_damper[i],
                               "dissipated_impacts": self.dissipated_impacts[i],
                               "n_impacts": int(self.n_impacts[i]),
                               "n_impacts_whole_run": int(self.n_impacts_whole_run[i]),
                               "t_stuck": self.t_stuck[i], "regime": self.regime[i]}
                              for i, a in enumerate(self.model.absorbers)],
                "energy_balance": self.energy_balance,
                "regime_note": "regimes over the last periods of the window (may be a transient)"}


def _state0(model: HostModel, state0):
    N, na = model.n_dof, model.n_absorbers
    P, V = np.zeros(N + na), np.zeros(N + na)
    if state0 is None:
        return P, V
    names = {"x": (P, 0, N), "v": (V, 0, N), "y": (P, N, na), "dy": (V, N, na)}
    for key, value in dict(state0).items():
        if key not in names:
            raise ParameterError(f"state0.{key}", value, "unknown key (allowed: x, v, y, dy)")
        arr, off, n = names[key]
        vals = np.asarray(value, dtype=float).reshape(-1) if not isinstance(value, str) else None
        if vals is None or vals.size != n:
            raise ParameterError(f"state0.{key}", value, f"must be a list of {n} numbers")
        for v in vals:
            check_real(f"state0.{key}", v, lo=-STATE_MAX, hi=STATE_MAX)
        arr[off:off + n] = vals
    for i, a in enumerate(model.absorbers):
        w = P[a.dof] - P[N + i]
        if abs(w) > a.gap:
            raise ParameterError(f"state0.y[{i}]", P[N + i], f"must be within its gap of host dof "
                                 f"{a.dof}: |x - y| <= {a.gap:g}")
    return P, V


def energy(model: HostModel, t: float, P, V) -> float:
    """Total mechanical energy: kinetic of host and absorbers, elastic of the host relative
    to the base's rigid motion and of the absorbers' links."""
    h, N = model.host, model.n_dof
    f = model.forcing
    e = P[:N] - h.influence * f.displacement(t)
    E = 0.5 * V[:N] @ h.mass @ V[:N] + 0.5 * e @ h.stiffness @ e
    for i, a in enumerate(model.absorbers):
        E += 0.5 * a.mass * V[N + i] ** 2 + 0.5 * a.stiffness * (P[a.dof] - P[N + i]) ** 2
    return float(E)


def run_engine(model: HostModel, settings: ModelSettings, state0=None, record_from=None):
    """The compiled engine's raw arrays: (acc, rec, cnt, state, (P0, V0))."""
    from . import kernel as K

    pk = pack(model)
    P0, V0 = _state0(model, state0)
    N, na = model.n_dof, model.n_absorbers
    acc = np.zeros((K.N_ACC, max(N, na, 1)))
    rec = np.zeros((settings.n_record, K.N_REC))
    cnt = np.zeros(K.N_CNT, np.int64)
    state = np.zeros(1 + 2 * (N + na) + na)
    rf = settings.t_transient if record_from is None else float(record_from)
    K.run_model(pk.lam, pk.ns, pk.phi, pk.vinv, pk.zq, pk.hp, pk.qidx, pk.minv, pk.M, pk.C,
                pk.K, pk.iota, pk.ab, pk.forcing, pk.omega_max, 0.0, P0, V0,
                np.zeros(na, np.int64), settings.t_end, settings.t_transient, settings.v_stick,
                settings.root_tol, settings.max_impacts, rf, acc, rec, cnt, state)
    return acc, rec, cnt, state, (P0, V0)


def _ordered_records(rec, n_total):
    n = rec.shape[0]
    if n_total <= n:
        return rec[:n_total]
    k = n_total % n
    return np.concatenate((rec[k:], rec[:k]))


def _regime(times, walls, t_stuck, period, t0, t_end, complete) -> str:
    """Regime of one absorber from its impacts in [t0, t_end] (times, walls)."""
    if t_stuck > 0.0 or longest_same_wall_run(walls) >= CHATTER_RUN:
        return "chatter"
    if times.size == 0:
        return "no-impact" if complete else "unresolved"
    n_per = int(math.floor((t_end - t0) / period + 1e-9))
    for p in range(1, MAX_PERIOD + 1):
        if 2 * p > n_per:
            break
        span = p * period
        a = (times >= t_end - span)
        b = (times >= t_end - 2 * span) & (times < t_end - span)
        if a.sum() != b.sum() or a.sum() == 0:
            continue
        if np.all(walls[a] == walls[b]) and np.allclose(times[a] - span, times[b],
                                                        atol=PHASE_TOL * span, rtol=0.0):
            if p > 1:
                return f"period-{p}"
            nL, nR = int((walls[a] == 1).sum()), int((walls[a] == -1).sum())
            return f"{max(nL, nR)}:{min(nL, nR)}"
    return "irregular"


def simulate_model(model: HostModel, settings: ModelSettings | None = None, *, state0=None,
                   record_from=None) -> ModelResult:
    """Exact event-driven simulation of ``model`` from ``state0`` (default: rest, every
    absorber centred on its host dof; a mapping with keys x, v, y, dy)."""
    from . import kernel as K

    if not isinstance(model, HostModel):
        raise ParameterError("model", type(model).__name__, "must be a vines.HostModel")
    settings = ModelSettings() if settings is None else settings
    if not isinstance(settings, ModelSettings):
        raise ParameterError("settings", type(settings).__name__, "must be a ModelSettings")
    acc, rec, cnt, state, (P0, V0) = run_engine(model, settings, state0, record_from)
    N, na = model.n_dof, model.n_absorbers
    nP = N + na
    t_fin = state[0]
    P1, V1 = state[1:1 + nP], state[1 + nP:1 + 2 * nP]
    win = settings.t_end - settings.t_transient
    ke_h = acc[K.A_KE_HOST, 0]
    ke_a = acc[K.A_KE_ABS, :na]
    total = ke_h + ke_a.sum()
    ratio = ke_a / total if total > 0 else np.zeros(na)
    E0, E1 = energy(model, 0.0, P0, V0), energy(model, t_fin, P1, V1)
    bal = {"E_start": E0, "E_end": E1, "forcing_work": acc[K.A_WORK_ALL, 0],
           "dissipated_host": acc[K.A_DISS_HOST_ALL, 0],
           "dissipated_dampers": acc[K.A_DISS_ABS_ALL, :na].copy(),
           "dissipated_impacts": acc[K.A_IMP_LOSS_ALL, :na].copy()}
    bal["residual"] = (E1 - E0 - bal["forcing_work"] + bal["dissipated_host"]
                       + bal["dissipated_dampers"].sum() + bal["dissipated_impacts"].sum())
    rows = _ordered_records(rec, int(cnt[K.C_NREC]))
    impacts = {name: rows[:, k].astype(int if name in ("absorber", "wall", "stuck") else float)
               for k, name in enumerate(IMPACT_FIELDS)}
    period = 2 * math.pi / model.forcing.frequency
    t0 = max(settings.t_transient, settings.t_end - REGIME_PERIODS * period)
    complete = int(cnt[K.C_NREC]) <= settings.n_record
    if not complete and rows.size:
        t0 = max(t0, rows[0, 0])
    regimes = []
    for i in range(na):
        sel = (impacts["absorber"] == i) & (impacts["t"] >= t0)
        status = int(cnt[K.C_STATUS])
        regimes.append("unfinished" if status != K.RC_DONE else
                       _regime(impacts["t"][sel], impacts["wall"][sel], acc[K.A_TSTUCK, i],
                               period, t0, settings.t_end, complete or rows[0, 0] <= t0))
    return ModelResult(
        model=model, settings=settings, status=K.STATUS_TEXT[int(cnt[K.C_STATUS])],
        x_max=acc[K.A_XMAX, :N].copy(), accel_max=acc[K.A_AMAX, :N].copy(),
        x_max_whole_run=acc[K.A_XMAX_ALL, :N].copy(), travel=acc[K.A_TRAVEL, :na].copy(),
        travel_whole_run=acc[K.A_TRAVEL_ALL, :na].copy(), ke_ratio=ratio,
        dissipated_damper=acc[K.A_DISS_ABS, :na].copy(),
        dissipated_impacts=acc[K.A_IMP_LOSS, :na].copy(),
        dissipated_host=float(acc[K.A_DISS_HOST, 0]), forcing_work=float(acc[K.A_WORK, 0]),
        n_impacts=acc[K.A_NIMP, :na].astype(int), n_impacts_whole_run=acc[K.A_NIMP_ALL, :na].astype(int),
        t_stuck=acc[K.A_TSTUCK, :na].copy(), regime=regimes, energy_balance=bal,
        impacts=impacts, final_state={"t": t_fin, "P": P1.copy(), "V": V1.copy(),
                                      "walls": state[1 + 2 * nP:].astype(int)},
        counters={"steps": int(cnt[K.C_NSTEPS]), "segments": int(cnt[K.C_NSEG]),
                  "impacts": int(cnt[K.C_NIMP]), "window_length": win})
