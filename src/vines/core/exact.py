"""Python driver of the exact event-driven kernel: buffers, resumption, dense output.

``run_exact`` integrates one trajectory; with ``periodic_shortcut`` it stops once the
motion has settled on a periodic orbit and completes the run from one period of it
(``vines.core.shortcut``, ``_periodic_run``).
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from . import kernel as eng
from . import shortcut as sc
from .flow import make_osc
from .params import ModelParams, SolverSettings, check_conditioning
from .regime import strobe_times
from .result import IMPACT_DTYPE, RawRun
from .tally import ImpactTally

#: rows of the impact buffer of a run that keeps no records (``KernelRun.stream``)
STREAM_ROWS = 1 << 15

#: the packed oscillators of ``oscillators``: free LO, stuck body
Oscillators = tuple[np.ndarray, np.ndarray]


def oscillators(p: ModelParams) -> tuple[np.ndarray, np.ndarray]:
    """Packed oscillators of the free LO (mass 1) and the stuck body (mass 1 + eta).

    Raises ParameterError for near-resonant points the closed form cannot resolve
    (``params.check_conditioning``).
    """
    check_conditioning(p.eta, p.omega, p.F, p.d)
    return make_osc(1.0, p.d, p.omega, p.F), make_osc(1.0 + p.eta, p.d, p.omega, p.F)


class Trajectory:
    """Dense evaluation of a recorded trajectory (piecewise closed form); ``osc``: the
    run's ``oscillators(params)`` when at hand (else computed). A time equal to a segment
    start (an impact, stick or release: the kernel starts the next segment at exactly the
    recorded event time) is evaluated on the last segment starting there: the state after
    the event."""

    def __init__(self, params: ModelParams, segments: np.ndarray, t_last: float,
                 osc: Oscillators | None = None):
        self.params = params
        self.segments = segments
        self.t_last = t_last
        self._osc_f, self._osc_s = oscillators(params) if osc is None else osc

    def __call__(self, times) -> np.ndarray:
        times = np.ascontiguousarray(np.atleast_1d(times), dtype=float)
        seg = self.segments
        if seg.shape[0] == 0 or (times.size and (times.min() < seg[0, 0]
                                                 or times.max() > self.t_last)):
            lo = seg[0, 0] if seg.shape[0] else math.nan
            raise ValueError(f"times must lie in the recorded span [{lo:g}, {self.t_last:g}]")
        return self.on_segments(seg[:, 0].searchsorted(times, side="right") - 1, times)

    def on_segments(self, idx, times) -> np.ndarray:
        """States (4, n) at ``times`` on the closed form of the recorded segments ``idx``
        (a time on a segment boundary: the segment named, not the one after it)."""
        times = np.ascontiguousarray(times, dtype=float)
        out = np.empty((4, times.size))
        eng.dense_states(self.segments, np.ascontiguousarray(idx, dtype=np.int64), times,
                         self._osc_f, self._osc_s, self.params.omega, self.params.phi, out)
        return out


# The kernel's impact rows (t, z_m, z_m', z_b, z_b', wall: six float64) seen as two
# fields, the five state columns as one block of 40 bytes and the wall, and the same two
# fields of an IMPACT_DTYPE record (``impact_records``).
_ROW_FIELDS = np.dtype({"names": ["state", "wall"], "formats": ["V40", "f8"],
                        "offsets": [0, 40], "itemsize": 48})
_RECORD_FIELDS = np.dtype({"names": ["state", "wall"], "formats": ["V40", "i1"],
                           "offsets": [0, 40], "itemsize": IMPACT_DTYPE.itemsize})


def impact_records(rows: np.ndarray) -> np.ndarray:
    """The kernel's impact rows (n, 6) as an IMPACT_DTYPE array: each row's five state
    numbers copied as one block of bytes and the wall cast to int8 (three times faster than
    column by column; the same bytes)."""
    rows = np.ascontiguousarray(rows, dtype=np.float64)
    out = np.empty(rows.shape[0], dtype=IMPACT_DTYPE)
    src = rows.view(_ROW_FIELDS)[:, 0]
    dst = out.view(_RECORD_FIELDS)
    dst["state"] = src["state"]
    dst["wall"] = src["wall"]
    return out


def kernel_params(osc, p: ModelParams, st: SolverSettings, t_end: float, t_tr: float,
                  record_from: float) -> eng.KernelParams:
    """The kernel's ``KernelParams`` of a run of model p with settings st over [t0, t_end]
    (window from t_tr, records from record_from); osc = ``oscillators(p)``."""
    osc_f, osc_s = osc
    return eng.KernelParams(osc_f, osc_s, float(p.eta), float(p.r), float(p.omega),
                            float(p.phi), float(t_end), float(t_tr), float(st.v_stick),
                            float(st.root_tol), int(st.max_impacts), float(record_from))


class Span(NamedTuple):
    """Where a kernel run ends, where its measurement window starts and from when it
    records impacts and segments (dimensionless times)."""

    t_end: float
    t_tr: float
    record_from: float


class KernelRun:
    """One kernel trajectory: its state (cur, acc, cnt) and growing impact/segment buffers.

    Starts at t0 in ``state0`` = (z_m, z_m', z_b, z_b') with segment ``mode`` (0 free, +-1
    stuck on that wall); ``span``: end, window [t_tr, t_end] and records from record_from.
    """

    def __init__(self, p: ModelParams, st: SolverSettings, osc, state0, t0: float,
                 span: Span, mode: int = 0):
        self.p, self.st, self.osc = p, st, osc
        t_end, t_tr, record_from = span
        self.t_end, self.t_tr, self.record_from = t_end, t_tr, record_from
        self.kp = kernel_params(osc, p, st, t_end, t_tr, record_from)
        self.cur = np.array([t0, state0[0], state0[1], state0[2], state0[3], mode, 0.0])
        self.acc = np.zeros(eng.N_ACC)
        self.acc[eng.A_XMAX_ALL] = abs(state0[0])
        self.acc[eng.A_XMAX_WIN] = abs(state0[0]) if t0 >= t_tr else 0.0
        self.cnt = np.zeros(eng.N_CNT, dtype=np.int64)
        n_periods = (t_end - max(record_from, t0)) / p.period
        cap = int(min(st.max_impacts + 1, 6 * max(n_periods, 0.0) + 64))
        self.imp = np.empty((cap, 6))
        self.seg = np.empty((2 * cap + 16, 6))
        self.tally, self.t_tail = None, -math.inf

    def stream(self, tally: ImpactTally, t_tail: float) -> None:
        """Keep no records: impacts go into ``tally`` block by block (``_flush``) and the
        segments before the one holding t_tail are dropped, so memory does not grow with
        t_end or max_impacts; the trajectory is then known from that segment on."""
        self.tally, self.t_tail = tally, t_tail
        cap = min(self.imp.shape[0], STREAM_ROWS)
        self.imp = np.empty((cap, 6))
        self.seg = np.empty((2 * cap + 16, 6))

    def _flush(self) -> None:
        """Streamed run: recorded impacts into the tally, segments before t_tail dropped."""
        n = int(self.cnt[eng.C_NIMP_REC])
        self.tally.add(self.imp[:n, 0], self.imp[:n, 5].astype(np.int8))
        self.cnt[eng.C_NIMP_REC] = 0
        m = int(self.cnt[eng.C_NSEG_REC])
        i0 = max(int(np.searchsorted(self.seg[:m, 0], self.t_tail, side="right")) - 1, 0)
        self.seg[:m - i0] = self.seg[i0:m]
        self.cnt[eng.C_NSEG_REC] = m - i0

    def run(self, fn=eng.run_kernel, *extra) -> int:
        """Call ``fn(kp, (cur, acc, cnt), imp, seg, *extra)`` (run_kernel, run_kernel_until,
        shortcut.run_detect) until it returns anything but RC_BUFFER_FULL; grows buffers."""
        st = self.st
        while True:
            rc = fn(self.kp, (self.cur, self.acc, self.cnt), self.imp, self.seg, *extra)
            if rc != eng.RC_BUFFER_FULL:
                return rc
            if self.tally is not None:
                self._flush()
            if self.seg.shape[0] > 4 * st.max_impacts + 100_000:
                return eng.RC_STALLED    # segments without impacts: never grow without bound
            if self.cnt[eng.C_NIMP_REC] >= self.imp.shape[0]:
                self.imp = np.concatenate([self.imp, np.empty_like(self.imp)])
            if self.cnt[eng.C_NSEG_REC] >= self.seg.shape[0]:
                self.seg = np.concatenate([self.seg, np.empty_like(self.seg)])

    def impacts(self, n: int | None = None) -> np.ndarray:
        """The first n (default all) recorded impacts as an IMPACT_DTYPE array."""
        n = int(self.cnt[eng.C_NIMP_REC]) if n is None else int(n)
        return impact_records(self.imp[:n])

    def segments(self, n: int | None = None) -> np.ndarray:
        n = int(self.cnt[eng.C_NSEG_REC]) if n is None else int(n)
        return self.seg[:n].copy()

    def raw(self, rc: int) -> RawRun:
        """RawRun of a finished run (return code rc of the kernel)."""
        acc, cnt = self.acc, self.cnt
        t_last = float(self.cur[0])
        if self.tally is not None:
            self._flush()
        return RawRun(
            impacts=self.impacts(), int_vm2=float(acc[eng.A_INT_VM2]),
            int_vb2=float(acc[eng.A_INT_VB2]), xmax_window=float(acc[eng.A_XMAX_WIN]),
            xmax_whole_run=float(acc[eng.A_XMAX_ALL]),
            t_stuck_window=float(acc[eng.A_TSTUCK_WIN]),
            t_stuck_total=float(acc[eng.A_TSTUCK_ALL]), n_impacts=int(cnt[eng.C_NIMP_TOTAL]),
            status=eng.STATUS_TEXT[rc], t_last=t_last,
            # the stroboscopic section and dense output need the segment active at the end
            state_at=Trajectory(self.p, self.segments(), t_last, self.osc),
            n_sticks=int(acc[eng.A_NSTICK]),
            solver_info={"root_tol": self.st.root_tol, "n_steps": int(acc[eng.A_NEVAL]),
                         "final_state": self.cur[1:5].copy(), "final_mode": int(self.cur[5])},
            impact_tally=self.tally,
        )


def run_exact(params: ModelParams, settings: SolverSettings, record_from: float = 0.0,
              state0=None, t0: float = 0.0, periodic_shortcut: bool = False,
              keep_records: bool = True) -> RawRun:
    """Integrate one trajectory exactly from ``state0`` (default settings.state0) at t0.

    Impacts and segments are kept from ``record_from`` on (0: everything; t_transient:
    what the measures and the regime need). ``periodic_shortcut``: stop integrating once
    the motion has settled on a periodic orbit and take the rest of the run from one period
    of it (``vines.core.shortcut``); the RawRun then has ``shortcut_time`` (else NaN).
    ``keep_records=False``: no impact list (the RawRun's ``impact_tally`` holds the
    window's counts) and only the segments from the first stroboscopic time of
    ``regime.strobe_times`` on: memory does not grow with t_end or max_impacts.
    """
    p, st = params, settings
    s0 = st.state0 if state0 is None else state0
    run = KernelRun(p, st, oscillators(p), s0, t0, Span(st.t_end, st.t_transient, record_from))
    if not keep_records:
        ts = strobe_times(p.period, st.t_transient, st.t_end)
        run.stream(ImpactTally.for_window(st.t_transient, ts),
                   float(ts[0]) if ts.size else st.t_end)
    if not periodic_shortcut:
        return run.raw(run.run())
    return _run_with_shortcut(run)


# ------------------------------------------------------------------ periodic shortcut

def _run_with_shortcut(run: KernelRun) -> RawRun:
    """Run with section-by-section detection (``shortcut.run_detect``); on a confirmed
    periodic orbit (or a ball at rest out of reach: ``_orbit_at_rest``), complete the run
    from one period of it (``_periodic_raw``). A rejected candidate lets the run go on."""
    p, st = run.p, run.st
    det = sc.new_detector(p.period, st.t_transient, float(run.cur[0]), st.t_end)
    sec = np.full(eng.N_SEC, math.nan)
    sec[eng.S_TREACHED] = -math.inf
    hist, dr, ist, fst = det
    while True:
        rc = run.run(sc.run_detect, sec, det)
        if rc == sc.RC_PERIODIC:
            orbit = _detected_orbit(run, det)
        elif rc == sc.RC_AT_REST:
            orbit = _orbit_at_rest(run, sec)
        else:
            return run.raw(rc)
        if orbit is not None:
            return _periodic_raw(run, sec, orbit)
        if rc == sc.RC_AT_REST:
            ist[0, sc.I_REST] = 0
        else:
            ist[1, ist[0, sc.I_FOUND]] = ist[0, sc.I_K]     # count returns anew


class _Orbit:
    """A confirmed periodic orbit: section time t_s, state x_s and mode there, period
    P = pp T, and the kernel run over one period [t_s, t_s + P] from (x_s, mode)."""

    def __init__(self, t_s, x_s, mode, pp, P, one):
        self.t_s, self.x_s, self.mode, self.pp, self.P, self.one = t_s, x_s, mode, pp, P, one


def _detected_orbit(run: KernelRun, det) -> _Orbit | None:
    """The orbit found by ``run_detect`` at its last section, confirmed (``_confirm``);
    None if not confirmed or if it would not pay (then no further detection)."""
    p, st = run.p, run.st
    hist, dr, ist, fst = det
    pp, k = int(ist[0, sc.I_FOUND]), int(ist[0, sc.I_K]) - 1
    H = hist.shape[0]
    row, row_p = k % H, (k - pp) % H
    t_s, P = float(hist[row, sc.H_T]), pp * p.period
    per = hist[row, sc.H_NIMP:sc.H_TSTUCK + 1] - hist[row_p, sc.H_NIMP:sc.H_TSTUCK + 1]
    n_left = per[0] * math.ceil((st.t_end - t_s) / P)
    if st.t_end - t_s < sc.END_MARGIN * P or hist[row, sc.H_NIMP] + n_left >= st.max_impacts:
        fst[0, sc.F_TSTOP] = -math.inf          # no shortcut for this run
        return None
    x_s, mode = hist[row, sc.H_X:sc.H_X + 4].copy(), int(hist[row, sc.H_MODE])
    return _confirm(run, t_s, x_s, mode, pp, per)


def _orbit_at_rest(run: KernelRun, sec: np.ndarray) -> _Orbit | None:
    """``shortcut.at_rest``: the run is the snapshot segment up to t_transient (its closed
    form there is the kernel's state, bit for bit), then periodic with period T and no
    events, to ERR_TOL; confirmed like any orbit."""
    p, st = run.p, run.st
    t_s = st.t_transient
    x_s = np.array(sc.section_state(*run.osc, p.omega, p.phi, sec, t_s))
    return _confirm(run, t_s, x_s, eng.MODE_FREE, 1, np.zeros(4))


def _confirm(run: KernelRun, t_s, x_s, mode, pp, per) -> _Orbit | None:
    """Integrate one period pp T from (x_s, mode) at t_s; the orbit if it returns to x_s
    (SEC_TOL) with the events ``per`` (impacts, on L, stick starts, time stuck), else
    None."""
    p, st = run.p, run.st
    P = pp * p.period
    one = KernelRun(p, st, run.osc, x_s, t_s, Span(t_s + P, t_s, t_s), mode)
    if one.run() != eng.RC_DONE:
        return None
    back = sc.rel_diff(one.cur[1:5], x_s) <= sc.SEC_TOL
    same = (int(one.cur[5]) == mode and one.cnt[eng.C_NIMP_TOTAL] == per[0]
            and one.cnt[eng.C_NIMP_L] == per[1] and one.acc[eng.A_NSTICK] == per[2]
            and abs(one.acc[eng.A_TSTUCK_ALL] - per[3]) <= sc.SEC_TOL * p.period)
    return _Orbit(t_s, x_s, mode, pp, P, one) if back and same else None


def _pieces(a: float, b: float, t_s: float, P: float) -> list:
    """[(tau1, tau2, count)]: [a, b] (t_s <= a <= b) on a trajectory of period P from t_s
    is ``count`` copies of [t_s + tau1, t_s + tau2] each (whole periods and the ends)."""
    na, ta = divmod(a - t_s, P)
    nb, tb = divmod(b - t_s, P)
    if na == nb:
        return [(ta, tb, 1)] if tb > ta else []
    out = [(ta, P, 1)]
    if nb - na > 1:
        out.append((0.0, P, int(nb - na - 1)))
    if tb > 0.0:
        out.append((0.0, tb, 1))
    return out


def _before_shortcut(run: KernelRun, sec: np.ndarray, t_s: float) -> dict:
    """Integrals and counts of the actual run over [0, t_s] (window part from t_transient):
    the pause snapshot at the start of the segment holding t_s plus that segment's part up
    to t_s. (The maxima may include the last step beyond t_s: it lies on the orbit.)"""
    p, st = run.p, run.st
    t0, mode = sec[eng.S_T0], int(sec[eng.S_MODE])
    in_win = t0 >= st.t_transient
    vm2, vb2 = sc.segment_integrals(*run.osc, p.omega, p.phi, sec, t_s)
    stuck = (t_s - t0) if mode != eng.MODE_FREE else 0.0
    return dict(
        int_vm2=sec[eng.S_INT_VM2] + (vm2 if in_win else 0.0),
        int_vb2=sec[eng.S_INT_VB2] + (vb2 if in_win else 0.0),
        t_stuck_win=sec[eng.S_TSTUCK_WIN] + (stuck if in_win else 0.0),
        t_stuck_all=sec[eng.S_TSTUCK_ALL] + stuck, n_impacts=int(sec[eng.S_NIMP]),
        n_sticks=int(sec[eng.S_NSTICK]), xmax_win=float(run.acc[eng.A_XMAX_WIN]),
        xmax_all=float(run.acc[eng.A_XMAX_ALL]), n_steps=int(run.acc[eng.A_NEVAL]))


def _piece_sums(run: KernelRun, orbit: _Orbit, pieces: list, cache: dict) -> dict:
    """Sums over ``pieces`` (``_pieces``) of the window integrals, time stuck, impacts and
    stick starts, and the largest |z_m|; each distinct piece is one kernel run from x_s
    (window from t_s + tau1, cached)."""
    out = dict(int_vm2=0.0, int_vb2=0.0, t_stuck=0.0, n_impacts=0, n_sticks=0, xmax=0.0)
    for tau1, tau2, count in pieces:
        key = (tau1, tau2)
        if key not in cache:
            t_s = orbit.t_s
            g = KernelRun(run.p, run.st, run.osc, orbit.x_s, t_s,
                          Span(t_s + tau2, t_s + tau1, t_s + tau1), orbit.mode)
            if g.run() != eng.RC_DONE:
                raise RuntimeError(f"periodic shortcut: piece [{tau1}, {tau2}] of the orbit "
                                   f"from t = {t_s} did not finish")
            cache[key] = g
        g = cache[key]
        out["int_vm2"] += count * g.acc[eng.A_INT_VM2]
        out["int_vb2"] += count * g.acc[eng.A_INT_VB2]
        out["t_stuck"] += count * g.acc[eng.A_TSTUCK_WIN]
        out["n_impacts"] += count * int(g.cnt[eng.C_NIMP_REC])
        out["n_sticks"] += count * int(g.acc[eng.A_NSTICK])
        out["xmax"] = max(out["xmax"], float(g.acc[eng.A_XMAX_WIN]))
    return out


def _replicate(rows: np.ndarray, t_s: float, P: float, t_end: float, j0: int = 0,
               j1: int | None = None) -> np.ndarray:
    """Copies of ``rows`` (time in column 0, within [t_s, t_s + P)) shifted by j P,
    j = j0, j0 + 1, ... (before j1), up to t_end, in time order."""
    if rows.shape[0] == 0:
        return rows
    rel = rows[:, 0] - t_s
    j_end = int((t_end - t_s) // P) + 1
    j = np.arange(j0, j_end if j1 is None else min(j1, j_end))
    out = np.repeat(rows[None], j.size, axis=0)
    out[:, :, 0] = t_s + j[:, None] * P + rel[None, :]
    out = out.reshape(-1, rows.shape[1])
    return out[out[:, 0] <= t_end]


def _periodic_records(run: KernelRun, sec, orbit: _Orbit) -> tuple:
    """(impacts, segments) from record_from to t_end: the actual run's before t_s, then the
    orbit's period repeated (the same records an uninterrupted run would produce, to the
    detection tolerance). An orbit without events (no impact, no stick or release) is one
    segment from t_s, as the kernel would record it: memory does not grow with t_end."""
    t_s, P, t_end = orbit.t_s, orbit.P, run.t_end
    imp = run.imp[:int(run.cnt[eng.C_NIMP_REC])]
    seg = run.seg[:int(run.cnt[eng.C_NSEG_REC])]
    one_imp = orbit.one.imp[:int(orbit.one.cnt[eng.C_NIMP_REC])]
    one_seg = orbit.one.seg[:int(orbit.one.cnt[eng.C_NSEG_REC])]
    if run.tally is not None:
        return _streamed_records(run, orbit, imp, seg, one_imp, one_seg)
    rep_imp = _replicate(one_imp[one_imp[:, 0] < t_s + P], t_s, P, t_end)
    if one_imp.shape[0] == 0 and one_seg.shape[0] == 1:
        rep_seg = one_seg       # no events: one segment from t_s on (not one per period)
    else:
        rep_seg = _replicate(one_seg[one_seg[:, 0] < t_s + P], t_s, P, t_end)
    lo = run.record_from
    rep_imp = rep_imp[rep_imp[:, 0] >= lo]
    rep_seg = rep_seg[max(np.searchsorted(rep_seg[:, 0], lo, side="right") - 1, 0):]
    imp_all = np.concatenate([imp[imp[:, 0] < t_s], rep_imp])
    seg_all = np.concatenate([seg[seg[:, 0] < t_s], rep_seg])
    return impact_records(imp_all), seg_all


def _streamed_records(run: KernelRun, orbit: _Orbit, imp, seg, one_imp, one_seg) -> tuple:
    """``_periodic_records`` of a run that keeps no records (``KernelRun.stream``): the
    impacts go into its tally (the period's copies in blocks of about STREAM_ROWS rows) and
    only the segments from the one holding t_tail on are built. Returns (no impacts,
    segments)."""
    t_s, P, t_end, lo = orbit.t_s, orbit.P, run.t_end, run.record_from
    pre = imp[imp[:, 0] < t_s]
    run.tally.add(pre[:, 0], pre[:, 5].astype(np.int8))
    rows = one_imp[one_imp[:, 0] < t_s + P]
    n_j = int((t_end - t_s) // P) + 1
    step = max(1, STREAM_ROWS // max(rows.shape[0], 1))
    for j0 in range(0, n_j if rows.shape[0] else 0, step):
        block = _replicate(rows, t_s, P, t_end, j0, j0 + step)
        block = block[block[:, 0] >= lo]
        run.tally.add(block[:, 0], block[:, 5].astype(np.int8))
    if one_imp.shape[0] == 0 and one_seg.shape[0] == 1:
        rep_seg = one_seg       # no events: one segment from t_s on
    else:
        j_tail = max(int((run.t_tail - t_s) // P) - 1, 0)
        rep_seg = _replicate(one_seg[one_seg[:, 0] < t_s + P], t_s, P, t_end, j_tail)
    rep_seg = rep_seg[max(np.searchsorted(rep_seg[:, 0], lo, side="right") - 1, 0):]
    seg_all = np.concatenate([seg[seg[:, 0] < t_s], rep_seg])
    i0 = max(int(np.searchsorted(seg_all[:, 0], run.t_tail, side="right")) - 1, 0)
    return np.empty(0, dtype=IMPACT_DTYPE), seg_all[i0:].copy()


def _periodic_raw(run: KernelRun, sec: np.ndarray, orbit: _Orbit) -> RawRun:
    """RawRun of the whole run [t0, t_end]: the actual run up to t_s, then whole periods of
    the orbit and the exact partial periods at the window's ends."""
    st, t_s, P, t_end = run.st, orbit.t_s, orbit.P, run.t_end
    pre = _before_shortcut(run, sec, t_s)
    cache = {(0.0, P): orbit.one}
    win = _piece_sums(run, orbit, _pieces(max(st.t_transient, t_s), t_end, t_s, P), cache)
    whole = _piece_sums(run, orbit, _pieces(t_s, t_end, t_s, P), cache)
    tb = divmod(t_end - t_s, P)[1]
    end = cache[(0.0, tb)] if tb > 0.0 else None
    final = end.cur[1:5].copy() if end is not None else orbit.x_s.copy()
    impacts, segments = _periodic_records(run, sec, orbit)
    return RawRun(
        impacts=impacts, int_vm2=pre["int_vm2"] + win["int_vm2"],
        int_vb2=pre["int_vb2"] + win["int_vb2"],
        xmax_window=max(pre["xmax_win"], win["xmax"]),
        xmax_whole_run=max(pre["xmax_all"], whole["xmax"]),
        t_stuck_window=pre["t_stuck_win"] + win["t_stuck"],
        t_stuck_total=pre["t_stuck_all"] + whole["t_stuck"],
        n_impacts=pre["n_impacts"] + whole["n_impacts"], status="ok", t_last=t_end,
        state_at=Trajectory(run.p, segments, t_end, run.osc),
        n_sticks=pre["n_sticks"] + whole["n_sticks"],
        solver_info={"root_tol": st.root_tol,
                     "n_steps": pre["n_steps"] + sum(int(g.acc[eng.A_NEVAL])
                                                     for g in cache.values()),
                     "final_state": final, "final_mode": int(end.cur[5]) if end else orbit.mode,
                     "shortcut_time": t_s, "shortcut_period": orbit.pp},
        shortcut_time=t_s, shortcut_period=orbit.pp, impact_tally=run.tally,
    )
