"""Exact periodic shortcut: pauses never change the trajectory; measures, records and sweeps
agree with full runs; the switch and the recorded shortcut time."""
import json
import math

import numpy as np
import pytest

import vines
from vines import cli
from vines.core import kernel as k
from vines.core.exact import kernel_params, oscillators, run_exact
from vines.core.params import ModelParams, SolverSettings
from vines.core.shortcut import ERR_TOL
from vines.core.sweep import bifurcation_sweep

# The shortcut starts modelling the orbit once its state is within ERR_TOL = 1e-10 (relative)
# of it; a measure then differs from the full run's by ERR_TOL times the measure's
# sensitivity to the state, not by round-off. The most sensitive is the chatter's time stuck
# (sticking onsets end a bounce sequence): 3.7e-10 relative in test_sticking_orbit. TOL is
# 10 ERR_TOL.
TOL = 10.0 * ERR_TOL


def _agree(a, b):
    """Acceptance of the issue: KE ratio (absolute), x_max (relative), impacts per period,
    regime."""
    assert abs(a.ke_ratio - b.ke_ratio) <= TOL
    assert abs(a.xmax - b.xmax) <= TOL * b.xmax
    assert abs(a.impacts_per_period - b.impacts_per_period) <= TOL
    assert a.regime == b.regime and a.status == b.status


def _kernel_run(p, st, pauses):
    """run_kernel_until paused at every time of ``pauses`` (then to the end)."""
    osc_f, osc_s = oscillators(p)
    cur, acc = np.zeros(7), np.zeros(k.N_ACC)
    cnt = np.zeros(k.N_CNT, dtype=np.int64)
    imp, seg, sec = np.empty((100_000, 6)), np.empty((300_000, 6)), np.empty(k.N_SEC)
    it = iter(sorted(pauses))
    tp, n_mid, n_close = next(it, math.inf), 0, 0
    while True:
        kp = kernel_params((osc_f, osc_s), p, st, st.t_end, st.t_transient, 0.0)
        rc = k.run_kernel_until(kp, (cur, acc, cnt), imp, seg, tp, sec)
        if rc != k.RC_PAUSED:
            break
        assert sec[k.S_T0] <= tp <= sec[k.S_TREACHED]
        n_mid += cnt[k.C_SEG_STEP] > 0
        n_close += cnt[k.C_SEG_STEP] == 0
        while tp <= sec[k.S_TREACHED]:
            tp = next(it, math.inf)
    out = (cur.copy(), acc[:k.A_SEG_S].copy(), cnt[:k.C_SEG_STEP].copy(),
           imp[:cnt[k.C_NIMP_REC]].copy(), seg[:cnt[k.C_NSEG_REC]].copy())
    return rc, out, n_mid, n_close


@pytest.mark.parametrize("eta,omega,F", [(0.2, 0.9, 0.4), (0.3077, 1.0, 0.3077)])
def test_pauses_do_not_change_the_trajectory(eta, omega, F):
    """Pausing inside segments and right before events, then resuming: bit-identical."""
    p = ModelParams(eta=eta, omega=omega, F=F)
    st = SolverSettings(t_end=400.0, t_transient=200.0)
    rc0, ref, _, _ = _kernel_run(p, st, [])
    times = ref[3][::3, 0] - 1e-9                        # just before impacts
    times = np.concatenate([times, ref[4][::4, 0] - 1e-11, np.arange(0.3, 400.0, 0.77)])
    rc1, got, n_mid, n_close = _kernel_run(p, st, times[times > 0])
    assert rc0 == rc1 == k.RC_DONE and n_mid > 50 and n_close > 5
    for a, b in zip(ref, got, strict=False):
        assert np.array_equal(a, b)


def test_never_settling_run_is_bit_identical_with_the_shortcut():
    kw = dict(t_end=3000.0, t_transient=1500.0)
    a = vines.simulate(0.3077, 1.0, 0.3077, **kw)
    b = vines.simulate(0.3077, 1.0, 0.3077, periodic_shortcut=False, **kw)
    assert math.isnan(a.shortcut_time) and a.shortcut_period == 0
    assert a.regime == "irregular"
    assert np.array_equal(a.impacts, b.impacts)
    for f in ("ke_ratio", "xmax", "xmax_whole_run", "t_stuck", "n_impacts", "K_m", "K_b"):
        assert getattr(a, f) == getattr(b, f), f


def test_random_points_agree_with_full_runs():
    """30 of the 1000 points of benchmarks/shortcut_check.py's comparison."""
    rng = np.random.default_rng(0)
    e, w, f = rng.uniform(0.01, 1.0, 30), rng.uniform(0.5, 1.5, 30), rng.uniform(0.01, 0.5, 30)
    a = vines.simulate_batch(e, w, f, n_threads=2)
    b = vines.simulate_batch(e, w, f, n_threads=2, periodic_shortcut=False)
    assert np.max(np.abs(a["ke_ratio"] - b["ke_ratio"])) <= TOL
    assert np.max(np.abs(a["xmax"] - b["xmax"]) / b["xmax"]) <= TOL
    assert np.max(np.abs(a["impacts_per_period"] - b["impacts_per_period"])) <= TOL
    assert np.array_equal(a["regime"], b["regime"])
    taken = np.isfinite(a["shortcut_time"])
    assert taken.sum() >= 10 and np.all(np.isnan(b["shortcut_time"]))
    assert np.all(a["shortcut_time"][taken] < 7000.0)


@pytest.mark.parametrize("t_end,t_transient", [
    (7000.0, 4000.0),        # shortcut long before the window
    (3000.0, 100.0),         # shortcut inside the window (actual run + periodic part)
    (2000.0, 1997.5),        # window shorter than one period
])
def test_windows_and_whole_run_measures(t_end, t_transient):
    kw = dict(t_end=t_end, t_transient=t_transient)
    a = vines.simulate(0.55, 1.0, 0.4, **kw)              # 1:1 orbit, settles by t ~ 900
    b = vines.simulate(0.55, 1.0, 0.4, periodic_shortcut=False, **kw)
    assert a.shortcut_period == 1 and a.shortcut_time < 1000.0
    _agree(a, b)
    assert abs(a.xmax_whole_run - b.xmax_whole_run) <= TOL * b.xmax_whole_run
    assert a.n_impacts == b.n_impacts and a.n_impacts_window == b.n_impacts_window
    assert abs(a.K_m - b.K_m) <= TOL * b.K_m and abs(a.K_b - b.K_b) <= TOL * b.K_b


def test_sticking_orbit():
    """Periodic chatter with sticking phases (Fig 9b): time stuck and sticks per period."""
    a = vines.simulate(0.2, 0.9, 0.4)
    b = vines.simulate(0.2, 0.9, 0.4, periodic_shortcut=False)
    assert a.regime == "chatter" and a.shortcut_time < 6000.0
    _agree(a, b)
    assert abs(a.t_stuck - b.t_stuck) <= TOL * b.t_stuck and a.n_sticks == b.n_sticks
    assert abs(a.t_stuck_whole_run - b.t_stuck_whole_run) <= TOL * b.t_stuck_whole_run
    assert a.n_impacts == b.n_impacts


def test_records_after_the_shortcut_repeat_the_period():
    kw = dict(t_end=3000.0, t_transient=1500.0)
    a = vines.simulate(0.45, 1.1, 0.4, **kw)
    b = vines.simulate(0.45, 1.1, 0.4, periodic_shortcut=False, **kw)
    assert a.shortcut_time < 1000.0
    ia, ib = a.impacts, b.impacts
    assert ia.size == ib.size and np.array_equal(ia["wall"], ib["wall"])
    for f in ("t", "z_m", "v_m", "z_b", "v_b"):
        assert np.max(np.abs(ia[f] - ib[f])) <= 1e-8, f
    t = np.linspace(0.0, 3000.0, 20001)
    assert np.max(np.abs(a.state_at(t) - b.state_at(t))) <= 1e-8
    # right after a replicated impact the trajectory holds the post-impact state
    post = a.state_at(ia["t"])
    dw_post = post[1] - post[3]
    assert np.allclose(dw_post, -a.params.r * a.impact_dw, rtol=1e-9, atol=1e-12)
    raw_a = run_exact(a.params, a.settings, periodic_shortcut=True)
    raw_b = run_exact(b.params, b.settings)
    assert np.max(np.abs(raw_a.solver_info["final_state"]
                         - raw_b.solver_info["final_state"])) <= 1e-8
    assert raw_a.solver_info["final_mode"] == raw_b.solver_info["final_mode"]


def test_drifting_ball_is_never_periodic():
    """No impacts, LO at rest, the ball drifting slowly: velocities and w = z_m - z_b alone
    repeat, the ball's position does not."""
    kw = dict(F=0.0, t_end=3000.0, t_transient=1000.0, state0=(0.0, 0.0, 0.0, 1e-4))
    a = vines.simulate(0.1, 1.0, **kw)
    b = vines.simulate(0.1, 1.0, periodic_shortcut=False, **kw)
    assert math.isnan(a.shortcut_time) and a.n_impacts == 0
    assert a.ke_ratio == b.ke_ratio > 0.0
    rest = vines.simulate(0.1, 1.0, F=0.0, t_end=3000.0, t_transient=1000.0)
    assert rest.shortcut_time == 1000.0 and rest.ke_ratio == 0.0 and rest.xmax == 0.0


@pytest.mark.parametrize("t_transient", [4000.0, 100.0])
def test_ball_at_rest_out_of_reach(t_transient):
    """No impact ever (W = 0.7, F = 0.1): the flight up to t_transient is one closed form;
    with t_transient = 100 the transient there is too large and the run goes on until the
    section detects the orbit inside the window."""
    kw = dict(t_end=7000.0, t_transient=t_transient)
    a = vines.simulate(0.3, 0.7, 0.1, **kw)
    b = vines.simulate(0.3, 0.7, 0.1, periodic_shortcut=False, **kw)
    assert a.n_impacts == b.n_impacts == 0
    if t_transient == 4000.0:
        assert a.shortcut_time == 4000.0
    else:
        assert 3000.0 < a.shortcut_time < 6000.0
    _agree(a, b)
    assert a.xmax_whole_run == b.xmax_whole_run
    t = np.linspace(0.0, 7000.0, 30001)
    sa, sb = a.state_at(t), b.state_at(t)
    early = t <= a.shortcut_time
    assert np.array_equal(sa[:, early], sb[:, early])
    assert np.max(np.abs(sa - sb)) <= 1e-10 * np.max(np.abs(sb))


def test_sweep_with_and_without_shortcut():
    kw = dict(omega=1.1, F=0.4, t_settle=2000.0, t_step=1000.0, n_record=10)
    vals = [0.4, 0.45, 0.5]
    a = bifurcation_sweep("eta", vals, **kw)
    b = bifurcation_sweep("eta", vals, periodic_shortcut=False, **kw)
    assert np.all(np.isfinite(a["shortcut_time"])) and np.all(np.isnan(b["shortcut_time"]))
    assert np.array_equal(a["row_size"], b["row_size"])
    assert np.array_equal(a["wall"], b["wall"])
    assert np.max(np.abs(a["dw"] - b["dw"])) <= 1e-8
    assert np.max(np.abs(a["phase"] - b["phase"])) <= 1e-8


def test_switch_reaches_the_cli_json(capsys):
    args = ["simulate", "--eta", "0.55", "--omega", "1", "--F", "0.4", "--t-end", "2000",
            "--t-transient", "1000", "--json"]
    assert cli.main(args) == 0
    on = json.loads(capsys.readouterr().out)
    assert cli.main(args + ["--no-periodic-shortcut"]) == 0
    off = json.loads(capsys.readouterr().out)
    assert on["shortcut_time"] < 1000.0 and on["shortcut_period"] == 1
    assert off["shortcut_time"] is None and off["shortcut_period"] == 0
    assert on["params"]["periodic_shortcut"] is True
    assert off["params"]["periodic_shortcut"] is False
    assert abs(on["ke_ratio"] - off["ke_ratio"]) <= TOL


def test_bad_switch_values_are_refused():
    with pytest.raises(vines.ParameterError, match="periodic_shortcut"):
        vines.simulate(0.1, 1.0, 0.1, periodic_shortcut="no")
    with pytest.raises(vines.ParameterError, match="periodic_shortcut"):
        vines.simulate_batch([0.1], 1.0, 0.1, periodic_shortcut=2)
    with pytest.raises(vines.ParameterError, match="periodic_shortcut"):
        bifurcation_sweep("eta", [0.1], omega=1.0, F=0.1, periodic_shortcut=None)
