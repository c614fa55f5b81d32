"""High-precision reference (vines.reference.hiprec) and the work-precision study."""
import math

import numpy as np
import pytest

import vines
from vines.core.params import ModelParams, ParameterError, SolverSettings
from vines.core.result import IMPACT_DTYPE
from vines.data.builders import work_precision_dataset
from vines.reference.hiprec import reference_run
from vines.studies.workprecision import (
    RUN_FIELDS,
    WorkPrecisionResult,
    errors,
    timed,
    visible,
    work_precision,
)

PERIODIC = (0.05, 1.0, 0.05)          # stable 1:1 orbit, regular transient
CHATTER = (0.2, 0.9, 0.8)             # chatter cascades and sticking from t ~ 43


@pytest.fixture(scope="module")
def periodic_ref():
    return reference_run(ModelParams(*PERIODIC), SolverSettings(t_end=150.0, t_transient=50.0))


@pytest.fixture(scope="module")
def chatter_ref():
    return reference_run(ModelParams(*CHATTER), SolverSettings(t_end=50.0, t_transient=20.0))


def test_reference_matches_linear_response_without_impacts():
    """Weak forcing, strong damping: no impact; the LO settles on the analytic harmonic
    response, and the window averages are those of a pure sinusoid."""
    eta, W, F, d = 0.1, 1.5, 0.01, 1.0
    t_tr, t_end = 80.0, 100.0
    ref = reference_run(ModelParams(eta=eta, omega=W, F=F, d=d),
                        SolverSettings(t_end=t_end, t_transient=t_tr))
    C = (F + 1j * d * W * F) / (1.0 - W * W + 1j * d * W)     # z_p = Im(C e^{iWt})
    assert ref.impacts.size == 0 and ref.ke_ratio == 0.0 and ref.K_b == 0.0
    assert ref.xmax == pytest.approx(abs(C), rel=1e-12)
    th = math.atan2(C.imag, C.real)        # z_p' = W |C| cos(W t + th)
    iv2 = (W * abs(C)) ** 2 * ((t_end - t_tr) / 2 + (math.sin(2 * (W * t_end + th))
                                                     - math.sin(2 * (W * t_tr + th))) / (4 * W))
    assert ref.K_m == pytest.approx(iv2 / (2 * (t_end - t_tr)), rel=1e-12)


def test_reference_agrees_with_dop853(periodic_ref):
    """Two independent implementations (40-digit closed form, DOP853 event loop)."""
    rk = vines.simulate(*PERIODIC, t_end=150.0, t_transient=50.0, solver="rk", rtol=1e-12)
    e = errors(rk, periodic_ref)
    assert e["sequence_ok"] and e["n_visible"] > 20
    assert e["t_error"] <= 1e-8 and e["ke_error"] <= 1e-9 and e["xmax_error"] <= 1e-9


def test_exact_solver_error_below_1e11(periodic_ref):
    ex = vines.simulate(*PERIODIC, t_end=150.0, t_transient=50.0)
    e = errors(ex, periodic_ref)
    assert e["sequence_ok"] and e["n_visible"] == periodic_ref.impacts.size
    assert e["t_error"] <= 1e-11 and e["ke_error"] <= 1e-11 and e["xmax_error"] <= 1e-11


def test_reference_chatter_sticks_and_agrees(chatter_ref):
    assert len(chatter_ref.sticks) >= 2
    assert all(b > a for a, b in chatter_ref.sticks)
    # the cascade before each stick: same wall, relative speeds falling by the restitution
    imp = chatter_ref.impacts
    before = imp[imp["t"] < chatter_ref.sticks[0][0]]
    tail = np.abs(before["v_m"] - before["v_b"])[-10:]
    assert np.all(before["wall"][-10:] == before["wall"][-1])
    assert np.all(np.diff(tail) < 0)
    ex = vines.simulate(*CHATTER, t_end=50.0, t_transient=20.0)
    e = errors(ex, chatter_ref)
    assert e["sequence_ok"] and e["t_error"] <= 1e-10 and e["ke_error"] <= 1e-10


def test_reference_v_stick_limit_has_more_micro_bounces(chatter_ref):
    lim = reference_run(ModelParams(*CHATTER), SolverSettings(t_end=50.0, t_transient=20.0),
                        v_stick=1e-14)
    assert lim.impacts.size > chatter_ref.impacts.size
    a, b = visible(lim.impacts, 1e-3), visible(chatter_ref.impacts, 1e-3)
    assert a.size == b.size and np.max(np.abs(a["t"] - b["t"])) <= 1e-8


def test_reference_refuses_degenerate_cases():
    with pytest.raises(ValueError, match="resonance"):
        reference_run(ModelParams(eta=0.05, omega=1.0, F=0.05, d=0.0),
                      SolverSettings(t_end=10.0, t_transient=0.0))
    with pytest.raises(ValueError, match="inside the cavity"):
        reference_run(ModelParams(*PERIODIC),
                      SolverSettings(t_end=10.0, t_transient=0.0, state0=(1.0, 0, 0, 0)))


def _imps(times, walls, dw=1.0):
    a = np.zeros(len(times), dtype=IMPACT_DTYPE)
    a["t"], a["wall"], a["v_m"] = times, walls, dw
    return a


def test_errors_flag_a_different_sequence():
    class R:
        status, ke_ratio, xmax = "ok", 0.5, 1.0

    ref = R()
    ref.impacts = _imps([1.0, 2.0, 3.0], [1, -1, 1])
    run = R()
    run.impacts = _imps([1.0, 2.0 + 1e-9, 3.0], [1, -1, 1])
    assert errors(run, ref)["t_error"] == pytest.approx(1e-9, rel=1e-6)
    run.impacts = _imps([1.0, 3.0], [1, 1])                  # one impact lost
    e = errors(run, ref)
    assert not e["sequence_ok"] and math.isnan(e["t_error"])
    run.impacts = np.concatenate([ref.impacts, _imps([2.5], [-1], dw=1e-5)])
    run.impacts.sort(order="t")                              # a micro-bounce is not visible
    assert errors(run, ref)["sequence_ok"]


def test_timed_repeats_fast_calls():
    calls = []
    sec, out = timed(lambda: calls.append(1) or len(calls), min_time=0.01, rounds=2)
    assert sec > 0 and out == len(calls) and len(calls) > 3


def test_every_timed_solver_runs_once_untimed_first(monkeypatch):
    """Kernel loading and imports happen before the timings: the first timed call of each
    solver (exact without the shortcut, every RK method) repeats a call already made."""
    import vines.studies.workprecision as wp
    calls, timed_calls = [], []
    real_run, real_timed = wp._run, wp.timed

    def run(p, st, **kw):
        calls.append((kw.get("solver", "exact"), kw.get("method")))
        return real_run(p, st, **kw)

    def timed_(fn, **kw):
        timed_calls.append(len(calls))
        return real_timed(fn, **kw)

    monkeypatch.setattr(wp, "_run", run)
    monkeypatch.setattr(wp, "timed", timed_)
    work_precision(*PERIODIC, t_end=20.0, t_transient=10.0, root_tols=(1e-9,),
                   rk_methods=("RK45", "LSODA"), rtols=(1e-4,), min_time=0.001, dps=20)
    before = set(calls[:timed_calls[0]])
    assert before == {("exact", None), ("rk", "RK45"), ("rk", "LSODA")}


def test_work_precision_dataset():
    res = work_precision(*PERIODIC, t_end=100.0, t_transient=40.0, root_tols=(1e-13,),
                         v_sticks=(1e-4,), rk_methods=("DOP853",), rtols=(1e-5, 1e-10),
                         min_time=0.005)
    assert isinstance(res, WorkPrecisionResult) and res.n_runs == 4
    assert set(res.runs) == set(RUN_FIELDS)
    assert all(isinstance(a, np.ndarray) and a.shape == (4,) for a in res.runs.values())
    assert res.runs["sequence_ok"].dtype == np.int8
    assert res.reference["v_stick"] == 1e-6 and res.reference_limit["v_stick"] == 1e-14
    assert res.reference["n_impacts"] > 0 and res.case["t_end"] == 100.0
    ds = work_precision_dataset(res, {"title": "wp"})
    assert ds.sizes["run"] == 4 and list(ds.data_vars) == list(RUN_FIELDS)
    for k in RUN_FIELDS:
        np.testing.assert_array_equal(ds[k].values, res.runs[k])
    for v in ds.data_vars.values():
        assert "long_name" in v.attrs and "units" in v.attrs
    flags = ds["sequence_ok"].attrs["flag_values"]        # CF 3.5: the variable's type
    assert ds["sequence_ok"].dtype == flags.dtype == np.int8 and flags.tolist() == [0, 1]
    assert ds.attrs["title"] == "wp" and ds.attrs["reference_n_impacts"] == \
        res.reference["n_impacts"] and ds.attrs["reference_limit_v_stick"] == 1e-14
    assert list(ds["knob"].values) == ["root_tol", "v_stick", "rtol", "rtol"]
    assert bool(np.all(ds["sequence_ok"].values == 1))
    te = ds["t_error"].values
    assert te[0] <= 1e-11 and te[2] > te[3] > te[0]          # DOP853 converges, exact best
    np.testing.assert_allclose(ds["impacts_per_second"] * ds["seconds"], ds["n_impacts"])
    with pytest.raises(ParameterError, match="rk_methods"):
        work_precision(*PERIODIC, t_end=10.0, t_transient=0.0, rk_methods=("Euler",))
