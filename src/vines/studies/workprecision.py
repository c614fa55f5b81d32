"""Work-precision study: error against cost of the exact solver and of the RK solvers.

Every run of one case (a parameter point and a horizon [0, t_end], window
[t_transient, t_end]) is compared with the high-precision reference of ``vines.hiprec``:

* impact-time error: max |t_i - t_i_ref| over the *visible* impacts (pre-impact relative
  speed |w'-| >= v_visible, default 1e-3), which must come in the same order on the same
  walls (``sequence_ok``); the micro-bounces of a chatter cascade are left out because how
  many of them a run resolves is set by v_stick, not by the solver's accuracy;
* KE-ratio error and x_max error: absolute differences of the window measures;
* cost: wall-clock seconds per run (best of several timed rounds, each long enough to
  measure) and impacts per second.

:func:`work_precision` returns a :class:`WorkPrecisionResult` (plain arrays over the runs and
the settings of the case); ``vines.data.builders.work_precision_dataset`` makes it a dataset.

Knobs: the exact solver's ``root_tol`` (at the case's v_stick) and ``v_stick`` (the chatter
threshold, a model knob: these runs are compared with a reference at ``v_stick_reference``,
the accumulation limit), the RK solvers' ``rtol`` (atol = rtol * 1e-2) for each method.
"""
from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..core.params import (
    D_DEFAULT,
    R_DEFAULT,
    ROOT_TOL_DEFAULT,
    RTOL_MAX,
    RTOL_MIN,
    V_STICK_DEFAULT,
    V_STICK_MAX,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_callable,
    check_choice,
    check_int,
    check_real,
    check_reals,
)
from ..core.result import SimulationResult
from ..reference.hiprec import (
    DPS_DEFAULT,
    H_SAMPLE_DEFAULT,
    V_STICK_REFERENCE,
    Reference,
    check_reference_params,
    reference_run,
)
from ..solvers import RK_METHODS, run_simulation

V_VISIBLE_DEFAULT = 1e-3
DPS_MIN, DPS_MAX = 20, 100       # digits of the reference (as the config schema)
H_SAMPLE_MAX = 0.5                # largest sampling step of the reference
MIN_TIME_MAX = 3600.0             # longest timing of one setting [s]


def timed(fn: Callable[[], Any], min_time: float = 0.05, rounds: int = 3,
          max_calls: int = 10_000) -> tuple[float, Any]:
    """Best wall-clock seconds per call of ``fn()`` and its (last) result.

    A call slower than ``min_time`` is timed once; faster ones are repeated in ``rounds``
    rounds of about ``min_time`` seconds each and the best round's mean is returned (the one
    least disturbed by other load on the machine).
    """
    t0 = time.perf_counter()
    out = fn()
    best = time.perf_counter() - t0
    if best >= min_time:
        return best, out
    n = max(1, min(max_calls, math.ceil(min_time / max(best, 1e-9))))
    for _ in range(rounds):
        t0 = time.perf_counter()
        for _ in range(n):
            out = fn()
        best = min(best, (time.perf_counter() - t0) / n)
    return best, out


def visible(impacts: np.ndarray, v_visible: float) -> np.ndarray:
    """Impacts whose pre-impact relative speed |w'-| is at least v_visible."""
    return impacts[np.abs(impacts["v_m"] - impacts["v_b"]) >= v_visible]


def errors(res: SimulationResult, ref: Reference,
           v_visible: float = V_VISIBLE_DEFAULT) -> dict:
    """Errors of a SimulationResult against a hiprec.Reference (see module docstring)."""
    a, b = visible(res.impacts, v_visible), visible(ref.impacts, v_visible)
    ok = (res.status == "ok" and a.size == b.size
          and bool(np.array_equal(a["wall"], b["wall"])))
    t_err = float(np.max(np.abs(a["t"] - b["t"]))) if ok and a.size else math.nan
    finite = res.status == "ok"
    return dict(t_error=t_err, sequence_ok=ok, n_visible=int(a.size),
                ke_error=abs(res.ke_ratio - ref.ke_ratio) if finite else math.nan,
                xmax_error=abs(res.xmax - ref.xmax) if finite else math.nan)


#: per-run values of a WorkPrecisionResult (arrays over the runs, in this order)
RUN_FIELDS = ("solver", "method", "knob", "tolerance", "v_stick", "t_error", "ke_error",
              "xmax_error", "seconds", "impacts_per_second", "n_impacts", "n_visible",
              "sequence_ok", "status")


@dataclass(frozen=True)
class WorkPrecisionResult:
    """Error and cost of every run of one case.

    ``runs``: RUN_FIELDS -> array over the runs (``sequence_ok`` int8 0/1, strings for
    solver, method, knob, status). ``case``: eta, omega, F, r, d, t_end, t_transient,
    v_visible as given. ``reference``: the high-precision reference at the case's v_stick
    (v_stick, dps, h_sample, n_impacts, ke_ratio, xmax, n_sticks); ``reference_limit``: the
    one at v_stick_reference the v_stick runs are compared with (v_stick, n_impacts,
    ke_ratio, xmax), None without v_stick runs.
    """

    runs: dict
    case: dict
    reference: dict
    reference_limit: dict | None = None

    @property
    def n_runs(self) -> int:
        return len(self.runs["solver"])


def _plan(root_tols, v_sticks, rk_methods, rtols, v_stick, ref, ref_limit) -> list[tuple]:
    """(solver, method, knob, value, v_stick, reference, simulate kwargs) of every run."""
    plan = [("exact", "exact", "root_tol", tol, v_stick, ref,
             dict(root_tol=tol, v_stick=v_stick)) for tol in root_tols]
    plan += [("exact", "exact", "v_stick", vs, vs, ref_limit, dict(v_stick=vs))
             for vs in v_sticks]
    plan += [("rk", m, "rtol", tol, v_stick, ref,
              dict(solver="rk", method=m, rtol=tol, v_stick=v_stick))
             for m in rk_methods for tol in rtols]
    return plan


def _run(p: ModelParams, st: SolverSettings, *, solver: str = "exact", method: str = "DOP853",
         rtol: float | None = None, root_tol: float | None = None,
         v_stick: float | None = None):
    """One run of the study (no periodic shortcut) with one knob changed from ``st``."""
    knobs = {k: v for k, v in (("root_tol", root_tol), ("v_stick", v_stick)) if v is not None}
    st = replace(st, **knobs) if knobs else st
    if solver == "rk":
        return run_simulation(p, st, solver="rk", method=method, rtol=rtol)
    return run_simulation(p, st, periodic_shortcut=False)


def _warm_up(p: ModelParams, rk_methods) -> None:
    """One short untimed run of every solver the study times, through ``_run`` (the exact
    kernel without the shortcut, each RK method): kernels load and imports happen here, not
    inside the first timed run (which would otherwise be timed once at ~0.1 s)."""
    st = SolverSettings(t_end=1.0, t_transient=0.0)
    _run(p, st)
    for method in rk_methods:
        _run(p, st, solver="rk", method=method, rtol=1e-3)


def _references(p, st, v_sticks, v_stick_reference, dps, h_sample, say):
    """The reference at st.v_stick and (with v_sticks) the one at v_stick_reference."""
    t0 = time.perf_counter()
    ref = reference_run(p, st, dps=dps, h_sample=h_sample)
    say(f"reference (v_stick {st.v_stick:g}): {ref.impacts.size} impacts, "
        f"{time.perf_counter() - t0:.1f} s")
    ref_limit = None
    if len(v_sticks):
        t0 = time.perf_counter()
        ref_limit = reference_run(p, st, dps=dps, h_sample=h_sample, v_stick=v_stick_reference)
        say(f"reference (v_stick {v_stick_reference:g}): {ref_limit.impacts.size} impacts, "
            f"{time.perf_counter() - t0:.1f} s")
    return ref, ref_limit


def work_precision(eta: float, omega: float, F: float, *, t_end: float, t_transient: float,
                   r: float = R_DEFAULT, d: float = D_DEFAULT,
                   v_stick: float = V_STICK_DEFAULT,
                   root_tols: Sequence[float] = (ROOT_TOL_DEFAULT,),
                   v_sticks: Sequence[float] = (),
                   rk_methods: Sequence[str] = ("RK45", "DOP853", "LSODA"),
                   rtols: Sequence[float] = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12),
                   v_stick_reference: float = V_STICK_REFERENCE, dps: int = DPS_DEFAULT,
                   h_sample: float = H_SAMPLE_DEFAULT, v_visible: float = V_VISIBLE_DEFAULT,
                   min_time: float = 0.05, max_impacts: int = 200_000,
                   progress: Callable[[str], None] | None = None) -> WorkPrecisionResult:
    """Error and cost of every solver setting on one case, as a :class:`WorkPrecisionResult`.

    Runs: the exact solver at each of ``root_tols``, then at each of ``v_sticks``, then
    each RK method at each of ``rtols``. Times are dimensionless (t = w0 t_dim), the run
    starts from rest at t = 0. The exact solver runs without the periodic shortcut: the
    study measures the cost and error of integrating every impact. ``progress`` (a callable taking a line of text) reports each
    run as it finishes.
    """
    p = ModelParams(eta=eta, omega=omega, F=F, r=r, d=d)
    st = SolverSettings(t_end=t_end, t_transient=t_transient, v_stick=v_stick,
                        max_impacts=max_impacts)
    if not isinstance(rk_methods, (list, tuple)):
        raise ParameterError("rk_methods", rk_methods, "must be a list of RK method names")
    rk_methods = [check_choice("rk_methods", m, RK_METHODS) for m in rk_methods]
    rtols = list(check_reals("rtols", rtols, lo=RTOL_MIN, hi=RTOL_MAX, min_size=0))
    root_tols = check_reals("root_tols", root_tols, lo=0.0, lo_open=True, hi=1e-3, min_size=0)
    v_sticks = check_reals("v_sticks", v_sticks, lo=0.0, hi=V_STICK_MAX, min_size=0)
    v_stick_reference = check_real("v_stick_reference", v_stick_reference, lo=0.0,
                                   hi=V_STICK_MAX)
    dps = check_int("dps", dps, lo=DPS_MIN, hi=DPS_MAX)
    h_sample = check_real("h_sample", h_sample, lo=0.0, lo_open=True, hi=H_SAMPLE_MAX)
    v_visible = check_real("v_visible", v_visible, lo=0.0, lo_open=True)
    min_time = check_real("min_time", min_time, lo=0.0, lo_open=True, hi=MIN_TIME_MAX)
    say = check_callable("progress", progress) or (lambda line: None)
    check_reference_params(p)
    _warm_up(p, rk_methods)
    ref, ref_limit = _references(p, st, v_sticks, v_stick_reference, dps, h_sample, say)
    rows = []
    for solver, method, knob, tol, vs, reference, kw in _plan(
            root_tols, v_sticks, rk_methods, rtols, v_stick, ref, ref_limit):
        sec, res = timed(lambda kw=kw: _run(p, st, **kw), min_time=min_time)
        e = errors(res, reference, v_visible)
        rows.append(dict(solver=solver, method=method, knob=knob, tolerance=float(tol),
                         v_stick=float(vs), seconds=sec,
                         impacts_per_second=res.n_impacts / sec, n_impacts=res.n_impacts,
                         status=res.status, **e))
        say(f"{method:7s} {knob}={tol:.0e}: t_error {e['t_error']:.2e}, "
            f"ke_error {e['ke_error']:.2e}, {sec:.3g} s, status {res.status}")
    for row in rows:
        row["sequence_ok"] = np.int8(row["sequence_ok"])
    runs = {k: np.asarray([row[k] for row in rows]) for k in RUN_FIELDS}
    case = dict(eta=eta, omega=omega, F=F, r=r, d=d, t_end=t_end, t_transient=t_transient,
                v_visible=v_visible)
    reference = dict(v_stick=v_stick, dps=dps, h_sample=h_sample,
                     n_impacts=int(ref.impacts.size), ke_ratio=ref.ke_ratio, xmax=ref.xmax,
                     n_sticks=len(ref.sticks))
    limit = None
    if ref_limit is not None:
        limit = dict(v_stick=v_stick_reference, n_impacts=int(ref_limit.impacts.size),
                     ke_ratio=ref_limit.ke_ratio, xmax=ref_limit.xmax)
    return WorkPrecisionResult(runs=runs, case=case, reference=reference,
                               reference_limit=limit)
