"""The exact solver's front end on validated inputs: measures of a raw run, one run
(``simulate_exact``), ``simulate_batch`` of many points on threads. ``vines.simulate``
(every solver, keyword arguments) is in ``vines.solvers``."""
from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from .. import progress as _progress
from .conventions import BATCH_FIELDS
from .exact import run_exact
from .params import (
    D_DEFAULT,
    MAX_IMPACTS_DEFAULT,
    PARAM_BOUNDS,
    R_DEFAULT,
    ROOT_TOL_DEFAULT,
    T_END_DEFAULT,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    ModelParams,
    ParameterError,
    SolverSettings,
    as_float_array,
    check_bool,
    check_callable,
    check_conditioning,
    check_int,
    check_param,
)
from .regime import classify_tally, strobe_times
from .result import RawRun, SimulationResult
from .tally import ImpactTally

#: regime label of a run that did not reach t_end, by status. "zeno" (RK reference: impacts
#: accumulate at a wall where the ball may not stick) is chatter; "max_impacts" only says the
#: impact budget ran out before t_end, so the motion over the window is unknown: "unfinished"
#: (the run may be periodic, irregular or chatter). Any other status (e.g. "stalled"):
#: "failed". SPEC 3 lists regime labels as examples ("e.g."); these two label runs that do
#: not cover the window, where no label of the motion can be given.
_UNFINISHED_REGIME = {"zeno": "chatter", "max_impacts": "unfinished"}


def window_measures(p: ModelParams, st: SolverSettings, raw: RawRun) -> dict:
    """Energy measures, impacts per period and regime from a raw run."""
    t_win = st.t_end - st.t_transient
    K_m = 0.5 * raw.int_vm2 / t_win
    K_b = 0.5 * p.eta * raw.int_vb2 / t_win
    total = K_m + K_b
    ke_ratio = K_b / total if total > 0.0 else 0.0
    ts = strobe_times(p.period, st.t_transient, st.t_end)
    tally = raw.impact_tally
    if tally is None:       # the run kept its impact list
        tally = ImpactTally.for_window(st.t_transient, ts)
        tally.add(raw.impacts["t"], raw.impacts["wall"])
    n_win = tally.n_window
    if raw.status == "ok":
        strobe = raw.state_at(ts) if ts.size else np.zeros((4, 0))
        regime, period = classify_tally(tally, strobe, ts, raw.t_stuck_window)
    else:
        regime, period = _UNFINISHED_REGIME.get(raw.status, "failed"), 0
    return dict(K_m=K_m, K_b=K_b, ke_ratio=ke_ratio, xmax=raw.xmax_window,
                xmax_whole_run=raw.xmax_whole_run, n_impacts=raw.n_impacts,
                n_impacts_window=n_win, impacts_per_period=n_win * p.period / t_win,
                regime=regime, period=period, t_stuck=raw.t_stuck_window,
                t_stuck_whole_run=raw.t_stuck_total, n_sticks=raw.n_sticks,
                shortcut_time=raw.shortcut_time, shortcut_period=raw.shortcut_period)


def simulation_result(p: ModelParams, st: SolverSettings, raw: RawRun, solver: str,
                      options: dict) -> SimulationResult:
    """The ``SimulationResult`` of a raw run of ``solver`` with ``options``."""
    m = window_measures(p, st, raw)
    return SimulationResult(params=p, settings=st, solver=solver, solver_options=options,
                            impacts=raw.impacts, status=raw.status, t_last=raw.t_last,
                            _state_at=raw.state_at, **m)


def simulate_exact(p: ModelParams, st: SolverSettings, *, periodic_shortcut: bool = True,
                   keep_impacts: bool = True) -> SimulationResult:
    """One exact run (``vines.simulate`` with solver "exact") on validated inputs;
    ``keep_impacts=False`` keeps no impact list (memory bounded in t_end)."""
    raw = run_exact(p, st, periodic_shortcut=periodic_shortcut, keep_records=keep_impacts)
    options = {"root_tol": st.root_tol, "periodic_shortcut": periodic_shortcut}
    return simulation_result(p, st, raw, "exact", options)


def run_measured(p: ModelParams, st: SolverSettings, state0=None,
                 periodic_shortcut: bool = True, keep_records: bool = True
                 ) -> tuple[RawRun, dict]:
    """One exact run from ``state0`` (default ``st.state0``) at t = 0 that records the
    window only (nothing with keep_records=False: ``run_exact``), and its measures (a dict
    holding every ``simulate_batch`` field). The caller validates ``state0``
    (``SolverSettings`` does)."""
    raw = run_exact(p, st, record_from=st.t_transient, state0=state0,
                    periodic_shortcut=periodic_shortcut, keep_records=keep_records)
    m = window_measures(p, st, raw)
    m["status"] = raw.status
    return raw, m


def _batch_point(eta, omega, F, r, d, phi, st: SolverSettings, shortcut: bool) -> tuple:
    p = ModelParams(eta=eta, omega=omega, F=F, r=r, d=d, phi=phi)
    m = run_measured(p, st, periodic_shortcut=shortcut, keep_records=False)[1]
    return tuple(m[k] for k in BATCH_FIELDS)


#: the progress task of ``simulate_batch`` (``vines.progress``): description, unit
TASK = ("simulate", "points")


def simulate_batch(eta, omega, F, *, r=R_DEFAULT, d=D_DEFAULT, phi=0.0, t_end=T_END_DEFAULT,
                   t_transient=T_TRANSIENT_DEFAULT, v_stick=V_STICK_DEFAULT,
                   max_impacts=MAX_IMPACTS_DEFAULT, root_tol=ROOT_TOL_DEFAULT,
                   periodic_shortcut=True, n_threads=None, progress=None) -> dict:
    """Exact measures at many parameter points (eta, omega, F broadcast together).

    Points run on ``n_threads`` threads (default: all cores) over the nogil kernel; every
    point is computed independently from the same initial state, so the numbers do not
    depend on the split. ``periodic_shortcut``: as in ``simulate`` (field
    ``shortcut_time``, NaN where not taken). ``progress(n_done, n_total)`` is called as
    points finish. Returns a dict of arrays with the broadcast shape (keys: BATCH_FIELDS).
    """
    st = SolverSettings(t_end=t_end, t_transient=t_transient, v_stick=v_stick,
                        max_impacts=max_impacts, root_tol=root_tol, state0=(0.0, 0.0, 0.0, 0.0))
    shortcut = check_bool("periodic_shortcut", periodic_shortcut)
    progress = check_callable("progress", progress)
    arrays = [as_float_array(name, v) for name, v in (("eta", eta), ("omega", omega), ("F", F))]
    try:
        e, w, f = np.broadcast_arrays(*arrays)
    except ValueError:
        raise ParameterError("omega", omega, f"must broadcast with eta (shape {arrays[0].shape}) "
                             f"and F (shape {arrays[2].shape})") from None
    shape = e.shape
    e, w, f = e.ravel(), w.ravel(), f.ravel()
    n = e.size
    if n:   # validate every point before any work (the bounds of ModelParams)
        for name, arr in (("eta", e), ("omega", w), ("F", f)):
            lo, lo_open, hi = PARAM_BOUNDS[name]
            with np.errstate(invalid="ignore"):
                bad = ~np.isfinite(arr) | ((arr <= lo) if lo_open else (arr < lo)) | (arr > hi)
            if bad.any():
                check_param(name, arr[bad][0])
        p0 = ModelParams(eta=1.0, omega=1.0, F=0.0, r=r, d=d, phi=phi)
        for i in range(n):      # near-resonant points the closed form cannot resolve
            check_conditioning(float(e[i]), float(w[i]), float(f[i]), p0.d)
    n_threads = check_int("n_threads", n_threads if n_threads is not None else (os.cpu_count() or 1), lo=1)
    out = {k: np.empty(n, dtype=dt) for k, dt in BATCH_FIELDS.items()}

    def work(i):
        vals = _batch_point(e[i], w[i], f[i], r, d, phi, st, shortcut)
        for k, v in zip(BATCH_FIELDS, vals, strict=False):
            out[k][i] = v
        return i

    if n_threads == 1 or n <= 1:
        for done, _ in enumerate(_progress.track(map(work, range(n)), n, *TASK), 1):
            if progress:
                progress(done, n)
    else:
        with ThreadPoolExecutor(max_workers=n_threads) as ex:
            for done, _ in enumerate(_progress.track(ex.map(work, range(n)), n, *TASK), 1):
                if progress:
                    progress(done, n)
    return {k: v.reshape(shape) for k, v in out.items()}
