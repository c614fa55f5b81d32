"""Measures derived from raw runs: metres, masks, the stuck linear reference, time histories.

Plain arrays in, plain arrays out (datasets are built by ``vines.data``).
"""
from __future__ import annotations

import math

import numpy as np

from .linear import stuck_amplitude
from .params import L_HALF_M, T_END_DEFAULT, T_TRANSIENT_DEFAULT, ModelParams, SolverSettings


def derived_measures(fields: dict, eta, omega, F, d: float) -> dict:
    """Grid measures in metres, the stuck-linear amplitude (Eq. 28) and regime masks.

    ``fields``: ``simulate_batch`` arrays over the grid (eta, omega, F) given by the 1-D
    axes ``eta``, ``omega``, ``F``. Returns arrays of the same shape (masks as int8).
    """
    e, w, f = np.meshgrid(np.asarray(eta), np.asarray(omega), np.asarray(F), indexing="ij")
    amp = stuck_amplitude(e, w, f, d)
    return {
        "xmax_m": np.asarray(fields["xmax"]) * L_HALF_M,
        "xmax_whole_run_m": np.asarray(fields["xmax_whole_run"]) * L_HALF_M,
        "xmax_stuck_linear": amp,
        "xmax_stuck_linear_m": amp * L_HALF_M,
        "impacting": (np.asarray(fields["impacts_per_period"]) > 0).astype("i1"),
        "chatter": (np.asarray(fields["regime"]) == "chatter").astype("i1"),
        "failed": (np.asarray(fields["status"]) != "ok").astype("i1"),
    }


def section_marks(axis, values, dim: str) -> np.ndarray:
    """int8 marks of ``axis`` entries that are one of ``values`` (exact floats).

    Raises ValueError naming the values that are not on the axis.
    """
    axis = np.asarray(axis, dtype=float)
    mark = np.isin(axis, np.asarray(values, dtype=float))
    missing = set(map(float, values)) - set(axis[mark].tolist())
    if missing:
        raise ValueError(f"section {dim} = {sorted(missing)} is not on the grid axis")
    return mark.astype("i1")


#: sampled state variables (last periods: t, z_m, ...; whole window: window_t, window_z_m, ...)
STATE_NAMES = ("z_m", "v_m", "z_b", "v_b")
#: default samples per forcing period of the whole measurement window (phase portraits)
WINDOW_SAMPLES_PER_PERIOD = 40


def _window_samples(points, simulation: dict, per_period: int) -> int:
    """Samples of the whole measurement window [t_transient, t_end]: ``per_period`` per
    forcing period of the point with the most periods in it (0: none)."""
    if per_period <= 0:
        return 0
    span = (float(simulation.get("t_end", T_END_DEFAULT))
            - float(simulation.get("t_transient", T_TRANSIENT_DEFAULT)))
    most = max(span * p["omega"] / (2 * math.pi) for p in points)
    return int(math.ceil(most)) * int(per_period) + 1


def time_histories(points: list[dict], *, model: dict, simulation: dict,
                   n_periods: int, samples_per_period: int,
                   window_samples_per_period: int = WINDOW_SAMPLES_PER_PERIOD) -> dict:
    """Single runs at ``points``: the last ``n_periods`` forcing periods sampled densely
    (``samples_per_period`` each, from the exact trajectory: ``t``, ``z_m`` ...), the whole
    measurement window [t_transient, t_end] at ``window_samples_per_period`` per period of the
    fastest point (``window_t``, ``window_z_m`` ...; none if 0), the impacts of the window
    (concatenated, ``row_size`` per point) and the scalar measures of each run
    (``shortcut_time``: after it, samples and impacts repeat one period of the settled
    orbit, see ``simulate``)."""
    from .simulation import simulate_exact  # numba: not needed by the derived measures
    n_s = int(n_periods) * int(samples_per_period) + 1
    n_w = _window_samples(points, simulation, int(window_samples_per_period))
    P = len(points)
    out = {k: np.empty((P, n_s)) for k in ("t",) + STATE_NAMES}
    if n_w:
        out.update({f"window_{k}": np.empty((P, n_w)) for k in ("t",) + STATE_NAMES})
    out.update(ke_ratio=np.empty(P), xmax=np.empty(P), regime=np.empty(P, dtype="U16"),
               status=np.empty(P, dtype="U16"), shortcut_time=np.empty(P))
    imp_t, imp_dw, imp_phase, imp_wall, row_size = [], [], [], [], np.zeros(P, dtype=np.int64)
    settings = {k: v for k, v in simulation.items() if k != "periodic_shortcut"}
    st = SolverSettings(**settings)
    shortcut = bool(simulation.get("periodic_shortcut", True))
    for i, pt in enumerate(points):
        p = ModelParams(eta=pt["eta"], omega=pt["omega"], F=pt["F"], **model)
        res = simulate_exact(p, st, periodic_shortcut=shortcut)
        t1 = res.t_last
        t_tr = min(float(simulation.get("t_transient", T_TRANSIENT_DEFAULT)), t1)
        t0 = max(0.0, t1 - n_periods * 2 * math.pi / pt["omega"])
        _sample(out, "", i, res, np.linspace(t0, t1, n_s))
        if n_w:
            _sample(out, "window_", i, res, np.linspace(t_tr, t1, n_w))
        for k in ("ke_ratio", "xmax", "regime", "status", "shortcut_time"):
            out[k][i] = getattr(res, k)
        sel = res.impacts["t"] >= t_tr
        imp_t.append(res.impacts["t"][sel])
        imp_dw.append(res.impact_dw[sel])
        imp_phase.append(res.impact_phase[sel])
        imp_wall.append(res.impacts["wall"][sel].astype("i1"))
        row_size[i] = int(sel.sum())
    out.update(impact_t=np.concatenate(imp_t), impact_dw=np.concatenate(imp_dw),
               impact_phase=np.concatenate(imp_phase), impact_wall=np.concatenate(imp_wall),
               row_size=row_size)
    return out


def _sample(out: dict, prefix: str, i: int, res, ts) -> None:
    """State of run ``res`` at the times ``ts`` into row ``i`` of ``out[prefix + name]``."""
    st = res.state_at(ts)
    out[prefix + "t"][i] = ts
    for j, k in enumerate(STATE_NAMES):
        out[prefix + k][i] = st[j]
