"""Python driver of the exact event-driven kernel: buffers, resumption, dense output."""
from __future__ import annotations

import math

import numpy as np

from . import kernel as eng
from .flow import make_osc
from .params import ModelParams, SolverSettings, check_conditioning
from .result import IMPACT_DTYPE, RawRun


def oscillators(p: ModelParams) -> tuple[np.ndarray, np.ndarray]:
    """Packed oscillators of the free LO (mass 1) and the stuck body (mass 1 + eta).

    Raises ParameterError for near-resonant points the closed form cannot resolve
    (``params.check_conditioning``).
    """
    check_conditioning(p.eta, p.omega, p.F, p.d)
    return make_osc(1.0, p.d, p.omega, p.F), make_osc(1.0 + p.eta, p.d, p.omega, p.F)


class Trajectory:
    """Dense evaluation of a recorded trajectory (piecewise closed form)."""

    def __init__(self, params: ModelParams, segments: np.ndarray, t_last: float):
        self.params = params
        self.segments = segments
        self.t_last = t_last
        self._osc_f, self._osc_s = oscillators(params)

    def __call__(self, times) -> np.ndarray:
        times = np.ascontiguousarray(np.atleast_1d(times), dtype=float)
        seg = self.segments
        if seg.shape[0] == 0 or np.any(times < seg[0, 0]) or np.any(times > self.t_last):
            lo = seg[0, 0] if seg.shape[0] else math.nan
            raise ValueError(f"times must lie in the recorded span [{lo:g}, {self.t_last:g}]")
        idx = np.searchsorted(seg[:, 0], times, side="right") - 1
        out = np.empty((4, times.size))
        eng.dense_states(seg, idx.astype(np.int64), times, self._osc_f, self._osc_s,
                         self.params.omega, self.params.phi, out)
        return out


def run_exact(params: ModelParams, settings: SolverSettings, record_from: float = 0.0,
              state0=None, t0: float = 0.0) -> RawRun:
    """Integrate one trajectory exactly from ``state0`` (default settings.state0) at t0.

    Impacts and segments are kept from ``record_from`` on (0: everything; t_transient:
    what the measures and the regime need).
    """
    p, st = params, settings
    osc_f, osc_s = oscillators(p)
    s0 = st.state0 if state0 is None else state0
    cur = np.array([t0, s0[0], s0[1], s0[2], s0[3], 0.0, 0.0])
    acc = np.zeros(eng.N_ACC)
    acc[eng.A_XMAX_ALL] = abs(s0[0])
    acc[eng.A_XMAX_WIN] = abs(s0[0]) if t0 >= st.t_transient else 0.0
    cnt = np.zeros(eng.N_CNT, dtype=np.int64)
    n_periods = (st.t_end - max(record_from, t0)) / p.period
    cap = int(min(st.max_impacts + 1, 6 * n_periods + 64))
    imp = np.empty((cap, 6))
    seg = np.empty((2 * cap + 16, 6))
    while True:
        rc = eng.run_kernel(osc_f, osc_s, p.eta, p.r, p.omega, p.phi, st.t_end, st.t_transient,
                            st.v_stick, st.root_tol, st.max_impacts, record_from, cur, acc, cnt,
                            imp, seg)
        if rc != eng.RC_BUFFER_FULL:
            break
        if seg.shape[0] > 4 * st.max_impacts + 100_000:
            rc = eng.RC_STALLED          # segments without impacts: never grow without bound
            break
        if cnt[eng.C_NIMP_REC] >= imp.shape[0]:
            imp = np.concatenate([imp, np.empty_like(imp)])
        if cnt[eng.C_NSEG_REC] >= seg.shape[0]:
            seg = np.concatenate([seg, np.empty_like(seg)])
    n_imp = int(cnt[eng.C_NIMP_REC])
    impacts = np.empty(n_imp, dtype=IMPACT_DTYPE)
    for k, name in enumerate(("t", "z_m", "v_m", "z_b", "v_b")):
        impacts[name] = imp[:n_imp, k]
    impacts["wall"] = imp[:n_imp, 5].astype(np.int8)
    # The stroboscopic section and dense output need the segment active at the end.
    segments = seg[: int(cnt[eng.C_NSEG_REC])].copy()
    t_last = float(cur[0])
    return RawRun(
        impacts=impacts,
        int_vm2=float(acc[eng.A_INT_VM2]),
        int_vb2=float(acc[eng.A_INT_VB2]),
        xmax_window=float(acc[eng.A_XMAX_WIN]),
        xmax_whole_run=float(acc[eng.A_XMAX_ALL]),
        t_stuck_window=float(acc[eng.A_TSTUCK_WIN]),
        t_stuck_total=float(acc[eng.A_TSTUCK_ALL]),
        n_impacts=int(cnt[eng.C_NIMP_TOTAL]),
        status=eng.STATUS_TEXT[rc],
        t_last=t_last,
        state_at=Trajectory(p, segments, t_last),
        n_sticks=int(acc[eng.A_NSTICK]),
        solver_info={"root_tol": st.root_tol, "n_steps": int(acc[eng.A_NEVAL]),
                     "final_state": cur[1:5].copy(), "final_mode": int(cur[5])},
    )
