"""Extreme parameters: the exact solver agrees with DOP853, with analytic facts, or refuses.

Every extreme of the brief (eta 1e-6 and 50, r 0 and 1, F 0 and 20, W 0.05 and 8, undamped
near resonance, grazing contacts, runs to t = 1e5) is checked against one of three oracles,
never against numbers taken from the code under test:

* the independent RK reference (``solver="rk"``, DOP853 at rtol 1e-12): same wall sequence
  and impact times within 1e-8 over a horizon chosen before the trajectory's own
  sensitivity (or DOP853's error at 1e-12) separates nearby runs; several points have
  chaotic transients (a 1e-14 change of the start separates runs after 40-150 units);
* analytic facts (F = 0: KE ratio exactly 0; r = 1: |w'+| = |w'-|; r = 0: w'+ = 0;
  eta -> 0: LO amplitude -> linear response; closed-form grazing and sticking times);
* invariants (|w| <= 1 up to round-off of the positions, momentum at impacts, finiteness).

Damping extremes d = 0 (W = 1), 2 and 2.5 are compared with DOP853 in
test_exact_vs_rk.py; here they only get the CLI / no-NaN checks.
"""
import json
import math

import numpy as np
import pytest
from conftest import run_vines
from scipy.optimize import brentq

import vines
from vines.core import kernel
from vines.core.linear import stuck_amplitude
from vines.core.params import D_DEFAULT, R_DEFAULT

RK = dict(solver="rk", rtol=1e-12)


def _agree(ex, rk, horizon, tol=1e-8, min_dw=0.0):
    """Same impacts (walls and times within tol) up to ``horizon``; returns the max error.

    min_dw > 0 compares only impacts with |w'-| > min_dw: the tail of a chatter sequence
    (bounces of 1e-11 L and less) is below the round-off of both solvers when the LO
    moves by hundreds of L (F = 20); the resolved impacts around it must still agree.
    """
    sel_a = (ex.impacts["t"] <= horizon) & (np.abs(ex.impact_dw) > min_dw)
    sel_b = (rk.impacts["t"] <= horizon) & (np.abs(rk.impact_dw) > min_dw)
    ta, tb = ex.impacts["t"][sel_a], rk.impacts["t"][sel_b]
    assert ta.size == tb.size and ta.size > 0, (ta.size, tb.size)
    assert np.array_equal(ex.impacts["wall"][sel_a], rk.impacts["wall"][sel_b])
    err = float(np.max(np.abs(ta - tb)))
    # the error is the DOP853 reference's: for r = 1, F = 0.4 (the largest, 2.8e-9 at rtol
    # 1e-12) the exact times are 13x closer to DOP853 at rtol 1e-13 (2.1e-10), which moves
    # by 2.6e-9 itself; the horizons end before that error grows past tol
    assert err <= tol, err
    return err


def _assert_sane(res, t_from=0.0, n=20001):
    """Status ok, finite measures and dense states, |w| <= 1 up to round-off, KE in [0, 1]."""
    assert res.status == "ok"
    assert res.t_last == res.settings.t_end
    for x in (res.ke_ratio, res.xmax, res.xmax_whole_run, res.K_m, res.K_b, res.t_stuck):
        assert math.isfinite(x)
    assert 0.0 <= res.ke_ratio <= 1.0
    t = np.linspace(t_from, res.t_last, n)
    if res.impacts.size:
        imp_t = res.impacts["t"]
        t = np.union1d(t, imp_t[imp_t >= t_from])
    st = res.state_at(t)
    assert np.all(np.isfinite(st))
    scale = 1.0 + np.max(np.abs(st[[0, 2]]))       # round-off of w = z_m - z_b
    assert np.max(np.abs(st[0] - st[2])) <= 1.0 + 1e-12 * scale
    return st


# ------------------------------------------------------------------ exact vs DOP853

# (eta, omega, F, options, horizon, min_dw): horizons end before DOP853 at rtol 1e-12 and
# 1e-13 disagree with each other (or before a 1e-14 change of the start separates runs).
AGAINST_RK = [
    pytest.param(1e-6, 1.0, 0.05, {}, 100.0, 0.0, id="eta=1e-6"),
    pytest.param(1e-6, 1.0, 0.05, {"d": 0.0}, 85.0, 0.0, id="eta=1e-6,d=0"),
    pytest.param(50.0, 1.0, 0.05, {}, 150.0, 0.0, id="eta=50"),
    pytest.param(50.0, 1.0, 0.5, {}, 200.0, 0.0, id="eta=50,F=0.5"),
    pytest.param(0.05, 1.0, 0.05, {"r": 0.0}, 200.0, 0.0, id="r=0"),
    pytest.param(0.2, 0.8, 0.4, {"r": 0.0}, 60.0, 0.0, id="r=0,F=0.4"),
    pytest.param(0.05, 1.0, 0.05, {"r": 0.0, "v_stick": 0.0}, 200.0, 0.0, id="r=0,v_stick=0"),
    pytest.param(0.05, 1.0, 0.05, {"r": 1.0}, 80.0, 0.0, id="r=1"),
    pytest.param(0.2, 0.8, 0.4, {"r": 1.0}, 40.0, 0.0, id="r=1,F=0.4"),
    pytest.param(0.05, 1.0, 20.0, {}, 60.0, 1e-3, id="F=20"),
    pytest.param(0.5, 1.0, 20.0, {}, 60.0, 1e-3, id="F=20,eta=0.5"),
    pytest.param(0.05, 0.05, 2.0, {}, 75.0, 0.0, id="W=0.05"),
    pytest.param(0.05, 0.05, 20.0, {}, 100.0, 0.0, id="W=0.05,F=20"),
    pytest.param(50.0, 0.05, 5.0, {}, 200.0, 0.0, id="W=0.05,eta=50"),
    pytest.param(0.05, 8.0, 20.0, {}, 100.0, 0.0, id="W=8,F=20"),
    # undamped within 1e-7 of the LO resonance and at the stuck-body resonance
    # W = 1/sqrt(1 + eta) (rounded): the cancellation-free near-resonant closed form
    pytest.param(0.05, 1.0 + 1e-7, 0.05, {"d": 0.0}, 100.0, 0.0, id="d=0,W=1+1e-7"),
    pytest.param(0.05, 1.0 / math.sqrt(1.05), 0.4, {"d": 0.0}, 32.0, 0.0,
                 id="d=0,W=1/sqrt(1+eta)"),
]


@pytest.mark.parametrize("eta,omega,F,opts,horizon,min_dw", AGAINST_RK)
def test_impact_times_match_dop853(eta, omega, F, opts, horizon, min_dw):
    kw = dict(t_end=horizon, t_transient=horizon / 2, **opts)
    ex = vines.simulate(eta, omega, F, **kw)
    rk = vines.simulate(eta, omega, F, **RK, **kw)
    assert rk.status == "ok"
    _assert_sane(ex)
    _agree(ex, rk, horizon, min_dw=min_dw)
    assert ex.n_sticks == rk.n_sticks
    # window measures: exact time averages over [horizon/2, horizon] of the same trajectory
    # (F = 20: the unresolved chatter tails shift each sticking onset by ~1e-5)
    tol = 1e-8 if min_dw == 0.0 else 1e-5
    assert abs(ex.ke_ratio - rk.ke_ratio) <= tol
    assert abs(ex.xmax - rk.xmax) <= 1e-8 * (1.0 + rk.xmax)


@pytest.mark.parametrize("eta,omega,F,horizon", [
    (0.05, 1.0, 0.0, 60.0),          # F = 0
    (0.05, 0.05, 0.05, 140.0),       # W = 0.05: one forcing period, LO follows quasi-statically
    (0.2, 8.0, 0.5, 60.0),           # W = 8: far above resonance, no impact
    (50.0, 0.14, 0.5, 100.0),        # eta = 50 near the stuck frequency, no impact
])
def test_no_impact_extremes_match_dop853(eta, omega, F, horizon):
    """Without impacts the whole state must equal DOP853's (and the KE ratio is 0)."""
    state0 = (0.3, -0.2, 0.0, 0.0)        # moving LO, ball at rest inside the cavity
    kw = dict(t_end=horizon, t_transient=horizon / 2, state0=state0)
    ex = vines.simulate(eta, omega, F, **kw)
    rk = vines.simulate(eta, omega, F, **RK, **kw)
    assert ex.n_impacts == 0 and rk.n_impacts == 0
    assert ex.ke_ratio == 0.0 and ex.regime == "no-impact"
    t = np.linspace(0.0, horizon, 4001)
    assert np.max(np.abs(ex.state_at(t) - rk.state_at(t))) <= 1e-9
    assert abs(ex.K_m - rk.K_m) <= 1e-9 * rk.K_m
    assert abs(ex.xmax - rk.xmax) <= 1e-9


# ------------------------------------------------------------------ analytic facts

@pytest.mark.parametrize("state0", [(0.0, 0.0, 0.0, 0.0), (0.4, 0.3, -0.2, 0.0)])
def test_no_forcing_gives_zero_ke_ratio(state0):
    res = vines.simulate(0.1, 1.0, 0.0, state0=state0, t_end=2000.0, t_transient=1000.0)
    _assert_sane(res)
    assert res.n_impacts == 0
    assert res.ke_ratio == 0.0                   # the ball never moves: K_b = 0 exactly
    assert res.regime == "no-impact"
    assert res.xmax <= abs(state0[0]) + abs(state0[1]) + 1e-15


@pytest.mark.parametrize("eta,omega,F", [(0.05, 1.0, 0.05), (0.2, 0.8, 0.4), (50.0, 1.0, 0.5),
                                         (0.05, 8.0, 20.0)])
def test_elastic_impacts_keep_relative_speed_and_energy(eta, omega, F):
    """r = 1: |w'+| = |w'-| and the kinetic energy is unchanged at every impact."""
    res = vines.simulate(eta, omega, F, r=1.0, t_end=300.0, t_transient=100.0)
    _assert_sane(res)
    imp = res.impacts
    assert imp.size > 10
    post = res.state_at(imp["t"])             # the segment starting at an impact: post values
    dw_pre = imp["v_m"] - imp["v_b"]
    dw_post = post[1] - post[3]
    scale = 1.0 + np.abs(imp["v_m"]) + np.abs(imp["v_b"])
    assert np.all(np.abs(dw_post + dw_pre) <= 1e-13 * scale)
    e_pre = imp["v_m"] ** 2 + eta * imp["v_b"] ** 2
    e_post = post[1] ** 2 + eta * post[3] ** 2
    assert np.all(np.abs(e_post - e_pre) <= 1e-12 * (1.0 + eta) * scale ** 2)
    mom_pre = imp["v_m"] + eta * imp["v_b"]
    assert np.all(np.abs(post[1] + eta * post[3] - mom_pre) <= 1e-13 * (1.0 + eta) * scale)


@pytest.mark.parametrize("eta,omega,F,v_stick", [(0.05, 1.0, 0.05, 1e-6), (0.2, 0.9, 0.4, 1e-6),
                                                 (0.05, 1.0, 0.05, 0.0)])
def test_plastic_impacts_stick_or_leave_with_zero_relative_speed(eta, omega, F, v_stick):
    """r = 0: w'+ = 0 at every impact; the ball then sticks, or leaves with w' = 0 and the
    relative acceleration pulling it away (it cannot cross the wall)."""
    res = vines.simulate(eta, omega, F, r=0.0, v_stick=v_stick, t_end=300.0,
                         t_transient=100.0)
    _assert_sane(res)
    imp = res.impacts
    assert imp.size > 10 and res.n_sticks > 0
    post = res.state_at(imp["t"])               # (dense output: exact up to round-off)
    scale = 1.0 + np.abs(imp["v_m"]) + np.abs(imp["v_b"])
    assert np.all(np.abs(post[1] - post[3]) <= 1e-14 * scale)   # w'+ = 0
    # common velocity (v_m + eta v_b) / (1 + eta): a few roundings of the momentum's terms,
    # read back by state_at at the segment start: k u (1 + eta)(1 + scale), measured k <= 4;
    # 1e-14 is k = 90 (a bound relative to |momentum| is ill-conditioned when it cancels)
    mom_pre = imp["v_m"] + eta * imp["v_b"]
    assert np.all(np.abs(post[1] * (1.0 + eta) - mom_pre) <= 1e-14 * (1.0 + eta) * scale)
    # just after each impact the ball is still on (or moving off) that wall, not beyond it
    st = res.state_at(np.minimum(imp["t"] + 1e-6, res.t_last))
    w = st[0] - st[2]
    assert np.all(w * imp["wall"] <= 1.0 + 1e-12)
    assert np.all(w * imp["wall"] >= 1.0 - 1e-10)      # < 1e-6 away within 1e-6 time


def test_vanishing_ball_mass_gives_the_linear_response():
    """eta -> 0: the LO amplitude tends to F |H(W)| of the LO alone, linearly in eta."""
    for omega, F in ((1.0, 0.05), (0.9, 0.4), (0.5, 0.9)):
        a_lin = float(stuck_amplitude(0.0, omega, F, d=D_DEFAULT))
        errs = []
        for eta in (1e-4, 1e-6):
            res = vines.simulate(eta, omega, F)
            assert res.status == "ok" and res.n_impacts > 100
            errs.append(abs(res.xmax - a_lin) / a_lin)
        # first order in eta: errs = C eta, C <= 17 over these points (errs[1] = 1.7e-5 at
        # W 0.9); 1e-4 allows C = 100. A property of the linear response, not round-off
        assert errs[1] <= 1e-4
        assert 30.0 <= errs[0] / errs[1] <= 300.0       # first order in eta


# ------------------------------------------------------------------ grazing

@pytest.mark.parametrize("A", [1.0 + 1e-12, 1.0 - 1e-12, -(1.0 + 1e-12), -(1.0 - 1e-12),
                               1.0 + 1e-13])
def test_grazing_undamped_amplitude_1_pm_1e12(A):
    """z_m = A sin t, ball at rest at 0: contact iff |A| > 1, at asin(1/|A|) with w' = A cos."""
    res = vines.simulate(0.05, 1.0, 0.0, d=0.0, t_end=2.0, t_transient=1.0,
                         state0=(0.0, A, 0.0, 0.0))
    _assert_sane(res, n=200001)
    if abs(A) < 1.0:
        assert res.n_impacts == 0
        return
    assert res.n_impacts == 1
    c = math.sqrt(A * A - 1.0)                     # closing speed at the wall
    t_hit = math.asin(1.0 / abs(A))
    # contact is declared within root_tol = 1e-13 of the wall: time error <= 1e-13/c
    assert abs(res.impacts["t"][0] - t_hit) <= 2e-13 / c
    assert res.impacts["wall"][0] == (1 if A > 0 else -1)
    # ... and w' within |w''| x (that time error) of c
    assert abs(abs(res.impact_dw[0]) - c) <= 0.01 * c + 1e-13 / c


@pytest.mark.parametrize("eps", [1e-12, -1e-12, 1e-10])
def test_grazing_damped_first_maximum(eps):
    """Damped free LO from (0, v0): its first maximum is 1 + eps (closed form)."""
    d = 0.1
    sigma, wd = d / 2.0, math.sqrt(1.0 - d * d / 4.0)
    t_star = math.atan2(wd, sigma) / wd                 # first zero of z'
    v0 = (1.0 + eps) * wd * math.exp(sigma * t_star) / math.sin(wd * t_star)

    def z(t):
        return v0 / wd * math.exp(-sigma * t) * math.sin(wd * t)

    res = vines.simulate(0.05, 1.0, 0.0, d=d, t_end=3.0, t_transient=1.0,
                         state0=(0.0, v0, 0.0, 0.0))
    _assert_sane(res, n=100001)
    if eps < 0:
        assert res.n_impacts == 0
        return
    t_hit = brentq(lambda t: z(t) - 1.0, t_star - 0.1, t_star, xtol=1e-15)
    c = math.sqrt(2.0 * eps)                            # |z''| = 1 at the maximum
    assert res.n_impacts >= 1 and res.impacts["wall"][0] == 1
    assert abs(res.impacts["t"][0] - t_hit) <= 1e-13 / c + 1e-12


@pytest.mark.parametrize("eps", [1e-12, -1e-12])
def test_grazing_forced_steady_state(eps):
    """Forced, damped LO on its steady state (linear theory), ball at rest at the centre:
    w = P sin(W t + psi) with P = 1 + eps. Contact iff P > 1, where sin(W t + psi) = 1/P."""
    W, d = 0.8, D_DEFAULT
    H = (1.0 + 1j * d * W) / (1.0 - W * W + 1j * d * W)   # z_p = F Im(H e^{i W t})
    F = (1.0 + eps) / abs(H)
    psi = math.atan2(H.imag, H.real)
    P = F * abs(H)
    state0 = (P * math.sin(psi), P * W * math.cos(psi), 0.0, 0.0)
    res = vines.simulate(0.05, W, F, d=d, t_end=6.0, t_transient=3.0, state0=state0)
    _assert_sane(res, n=100001)
    if eps < 0:
        assert res.n_impacts == 0
        return
    # first crossing of w = 1: W t + psi = asin(1/P) (next 2 pi branch if needed)
    phase = math.asin(1.0 / P)
    t_hit = (phase - psi) / W
    if t_hit < 0:
        t_hit += 2.0 * math.pi / W
    c = P * W * math.cos(phase)
    assert res.n_impacts >= 1 and res.impacts["wall"][0] == 1
    assert abs(res.impacts["t"][0] - t_hit) <= 2e-13 / c + 1e-12


def test_start_on_wall_with_zero_relative_velocity_moving_away():
    """w = 1, w' = 0, w'' < 0: the ball leaves; damped free LO z = e^{-st}(cos + s/wd sin)."""
    d = 0.1
    sigma, wd = d / 2.0, math.sqrt(1.0 - d * d / 4.0)
    res = vines.simulate(0.05, 1.0, 0.0, d=d, t_end=30.0, t_transient=10.0,
                         state0=(1.0, 0.0, 0.0, 0.0))
    _assert_sane(res)
    assert res.n_impacts == 0 and res.n_sticks == 0
    t = np.linspace(0.0, 30.0, 3001)
    z = np.exp(-sigma * t) * (np.cos(wd * t) + sigma / wd * np.sin(wd * t))
    st = res.state_at(t)
    # both sides evaluate exp, cos, sin at arguments <= 30: their rounding (ulp(30) = 3.6e-15)
    # and libm's few ulps bound the difference by ~1e-14 (measured 1.1e-15)
    assert np.max(np.abs(st[0] - z)) <= 1e-13
    assert np.all(st[2] == 0.0) and np.all(st[3] == 0.0)


@pytest.mark.parametrize("eta", [0.05, 1e-6, 50.0])
def test_start_on_wall_pressed_sticks_then_releases(eta):
    """z_m = -1, z_b = -2 (w = 1), at rest, F = d = 0: the spring presses the ball on wall L.

    Stuck: z = -cos(t/sqrt(1+eta)) until the contact force z'' changes sign at
    t_r = (pi/2) sqrt(1+eta); then the ball flies at v = 1/sqrt(1+eta) while the LO
    oscillates, z = v sin(t - t_r), so w = 1 + v (sin tau - tau) reaches -1 (wall R) when
    tau - sin tau = 2/v."""
    m = 1.0 + eta
    res = vines.simulate(eta, 1.0, 0.0, d=0.0, t_end=t_end_for(eta), t_transient=1.0,
                         state0=(-1.0, 0.0, -2.0, 0.0))
    _assert_sane(res)
    v = 1.0 / math.sqrt(m)
    t_r = 0.5 * math.pi * math.sqrt(m)
    tau = brentq(lambda x: x - math.sin(x) - 2.0 / v, 0.0, 2.0 / v + 2.0, xtol=1e-15)
    seg = res._state_at.segments
    stuck = np.flatnonzero(seg[:, 5] == 1)
    assert stuck.size and seg[stuck[0], 0] == 0.0       # stuck on wall L from the start
    free = np.flatnonzero(seg[:, 5] == 0)
    release = seg[free[free > stuck[0]][0], 0]       # (the stuck phase is split at t_transient)
    # release when the contact force ~ z'' (rate |z'''| = m^-1.5) is within root_tol of 0
    assert abs(release - t_r) <= 1e-13 * m ** 1.5 + 1e-12 * (1.0 + t_r)
    assert res.impacts["wall"][0] == -1
    assert abs(res.impacts["t"][0] - (t_r + tau)) <= 1e-9 * (1.0 + t_r + tau)
    rk = vines.simulate(eta, 1.0, 0.0, d=0.0, t_end=t_end_for(eta), t_transient=1.0,
                        state0=(-1.0, 0.0, -2.0, 0.0), **RK)
    assert abs(rk.impacts["t"][0] - res.impacts["t"][0]) <= 1e-8


def t_end_for(eta):
    """A little past the first impact of the pressed-start case."""
    m = 1.0 + eta
    return 0.5 * math.pi * math.sqrt(m) + 2.0 * math.sqrt(m) + 8.0


def test_exact_tangency_keeps_invariants():
    """z_m = cos t touches w = -1 at t = pi with w' = 0 (tangency, F = d = 0).

    A contact with zero approach speed is ambiguous at round-off level: the solver may
    register an impact there, but only with |w'| <= sqrt(2 |w''| root_tol) and at pi."""
    res = vines.simulate(0.05, 1.0, 0.0, d=0.0, t_end=3.5, t_transient=1.0,
                         state0=(1.0, 0.0, 0.0, 0.0))
    _assert_sane(res, n=200001)
    assert res.n_impacts <= 1
    if res.n_impacts:
        # contact is declared once the gap 1 - |w| = (t - pi)^2 / 2 (|w''| = 1) is <= root_tol =
        # 1e-13: |t - pi| <= sqrt(2 root_tol) = 4.5e-7 and |w'| = |sin t| <= the same; the 1%
        # covers |w''| < 1 near pi and the gap's round-off (1e-16 against 1e-13)
        assert abs(res.impacts["t"][0] - math.pi) <= 1e-6
        assert abs(res.impact_dw[0]) <= math.sqrt(2.0 * 1e-13) * 1.01
    t = np.linspace(0.0, 3.1, 3101)
    # the closed form and numpy both evaluate cos t (t <= 3.1): a few ulps each, whatever the
    # SIMD path (measured 2.2e-16; 1e-14 is 90 u)
    assert np.max(np.abs(res.state_at(t)[0] - np.cos(t))) <= 1e-14


# ------------------------------------------------------------------ long runs

T1 = 2.0 * math.pi


def test_long_run_1e5_stays_on_the_periodic_attractor():
    """eta 0.05, W 1, F 0.05 (stable 1:1 orbit): a run to t = 1e5 ends on the same orbit as
    a 7000-unit run: impact phases and velocities per wall equal to 1e-9, window measures
    over the same whole number of periods equal to 1e-9."""
    n_per = 477
    L = vines.simulate(0.05, 1.0, 0.05, t_end=1e5, t_transient=1e5 - n_per * T1)
    S = vines.simulate(0.05, 1.0, 0.05, t_end=7000.0, t_transient=7000.0 - n_per * T1)
    st = _assert_sane(L, t_from=L.settings.t_transient, n=400001)
    assert L.regime == S.regime == "1:1"
    for wall in (1, -1):
        in_l = (L.impacts["t"] >= L.settings.t_transient) & (L.impacts["wall"] == wall)
        in_s = (S.impacts["t"] >= S.settings.t_transient) & (S.impacts["wall"] == wall)
        assert in_l.sum() == in_s.sum() == n_per
        ref_phase = np.mean(S.impact_phase[in_s])
        # both runs sit on the stable orbit to far below 1e-9; the phase of an impact at t ~ 1e5
        # is known to ulp(1e5) = 1.5e-11 (measured 1.7e-11), the velocities to ~5e-13
        assert np.max(np.abs(L.impact_phase[in_l] - ref_phase)) <= 1e-9
        assert np.max(np.abs(L.impact_dw[in_l] - np.mean(S.impact_dw[in_s]))) <= 1e-9
    assert abs(L.ke_ratio - S.ke_ratio) <= 1e-9
    assert abs(L.xmax - S.xmax) <= 1e-9
    # the impact law still holds late in the run (no loss of precision in the exponentials)
    late = L.impacts[L.impacts["t"] > 9.9e4]
    # (the bounds of test_exact.test_impact_law_momentum_and_restitution: k u scale, the
    # segments' closed forms run in local time, so t ~ 1e5 adds nothing)
    post = L.state_at(late["t"])
    scale = 1.0 + np.abs(late["v_m"]) + np.abs(late["v_b"])
    mom_pre = late["v_m"] + 0.05 * late["v_b"]
    assert np.all(np.abs(post[1] + 0.05 * post[3] - mom_pre) <= 1e-13 * 1.05 * scale)
    dw_pre = late["v_m"] - late["v_b"]
    assert np.all(np.abs(post[1] - post[3] + R_DEFAULT * dw_pre) <= 1e-13 * scale)
    assert np.max(np.abs(st[0] - st[2])) <= 1.0 + 1e-12


@pytest.mark.parametrize("eta,omega,F,opts", [
    (0.2, 0.9, 0.4, {}),                         # chatter with sticking, ~1e6 impacts
    (0.05, 1.0, 0.05, {"d": 0.0}),               # undamped exact resonance
    (0.05, 1.0, 20.0, {}),                       # F = 20 (stalled at t ~ 107 before the fix)
    (1e-6, 1.0, 0.05, {"d": 0.0}),               # stuck body near resonance, undamped
    # undamped stuck-body resonance W = 1/sqrt(1 + eta) rounded (|1 - m W^2| = 2e-16): the
    # non-resonant closed form had amplitudes ~1e15, crossed a wall at t ~ 75, stalled at 91
    (0.05, 1.0 / math.sqrt(1.05), 0.4, {"d": 0.0}),
])
def test_long_runs_to_1e5_complete(eta, omega, F, opts):
    res = vines.simulate(eta, omega, F, t_end=1e5, t_transient=9.9e4, **opts)
    _assert_sane(res, t_from=9.9e4, n=200001)
    assert res.n_impacts > 1000
    imp = res.impacts[res.impacts["t"] > 9.99e4]
    post = res.state_at(imp["t"])
    mom = imp["v_m"] + eta * imp["v_b"]
    scale = 1.0 + np.abs(imp["v_m"]) + np.abs(imp["v_b"])
    assert np.all(np.abs(post[1] + eta * post[3] - mom) <= 1e-13 * scale)
    # approach: w' > 0 at L, w' < 0 at R
    assert np.all(res.impact_dw * res.impacts["wall"] > 0)


@pytest.mark.parametrize("t_end", [1e7, 1e9])
def test_no_impact_runs_to_1e9_settle_on_the_linear_response(t_end):
    """F 0.001 at resonance: the LO never reaches the ball, so its steady amplitude is that
    of the LO alone (eta only enters at impacts). Runs with t_transient = t_end / 2 used to
    stall (the section times t_tr + j T carry ulp(t_tr) of rounding, 5e-8 here, so returns
    never agreed to 2e-10 and the 200 000-step segment limit ended the run); a periodic
    end state without events is now one recorded segment, not one per period."""
    res = vines.simulate(0.5, 1.0, 0.001, t_end=t_end, t_transient=t_end / 2)
    a_lin = float(stuck_amplitude(0.0, 1.0, 0.001, d=D_DEFAULT))
    assert res.status == "ok" and res.n_impacts == 0 and res.ke_ratio == 0.0
    assert math.isfinite(res.shortcut_time) and res.shortcut_time < 1e4
    # the phase of a time ~t_end is known to ulp(t_end) (1.2e-7 at 1e9): that bounds it
    assert abs(res.xmax - a_lin) <= 1e-7 * a_lin
    late = res.state_at(np.array([t_end / 2, t_end]))
    assert np.all(np.abs(late[0]) <= a_lin * (1 + 1e-7))
    assert np.all(np.abs(late[0] - late[2]) < 1.0)


# ------------------------------------------------------------------ regressions of the fixes

def test_safe_step_has_no_cancellation_when_leaving_a_wall():
    """One ulp of gap after an impact, moving away at c: the step to the return on that wall
    is (c + sqrt(c^2 + 2 B g))/B, not 2 g/(-c + sqrt(...)) (cancellation, up to 10% long)."""
    g, c, B = 2.220446049250313e-16, -0.5112350948509006, 1.686921229453035
    h = kernel._safe_step(g, c, B)
    exact = (-c + math.sqrt(c * c + 2.0 * B * g)) / B
    assert abs(h - exact) <= 1e-15 * exact
    # closing: the safe step never exceeds the time to reach the wall
    assert kernel._safe_step(1e-3, 0.5, 2.0) <= 1e-3 / 0.5


def test_heavy_ball_elastic_low_frequency_never_crosses_a_wall():
    """eta 50, W 0.05, F 5, r 1 crossed wall R by 0.017 (the step above) before the fix."""
    res = vines.simulate(50.0, 0.05, 5.0, r=1.0, t_end=1000.0, t_transient=500.0)
    _assert_sane(res, n=400001)
    # exact by construction: z_b = fl(z_m - wall) is stored, the gap (z_m - z_b) - wall is two
    # more correctly rounded operations: |gap| <= 2.2e-16 (1 + |z_m|) on any IEEE CPU
    gap = res.impacts["z_m"] - res.impacts["z_b"] - res.impacts["wall"]
    assert np.all(np.abs(gap) <= 1e-15 * (1.0 + np.abs(res.impacts["z_m"])))


@pytest.mark.parametrize("omega", [1.0 + 1e-6, 1.0 - 1e-9, 1.0 / math.sqrt(1.2) * (1 + 1e-8)])
def test_weakly_damped_near_resonance_is_refused(omega):
    with pytest.raises(vines.ParameterError, match="omega") as err:
        vines.simulate(0.2, omega, 0.05, d=1e-7, t_end=100.0, t_transient=50.0)
    assert "natural frequency" in str(err.value) and "\n" not in str(err.value)
    # the reference solver does not need the closed form
    rk = vines.simulate(0.2, omega, 0.05, d=1e-7, t_end=50.0, t_transient=25.0, **RK)
    assert rk.status == "ok"
    with pytest.raises(vines.ParameterError, match="omega"):      # before any work
        vines.simulate_batch([0.2, 0.2], [0.9, omega], 0.05, d=1e-7, t_end=100.0,
                             t_transient=50.0)


# ------------------------------------------------------------------ command line

def _json_out(proc):
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr
    lines = proc.stdout.splitlines()
    assert len(lines) == 1
    return json.loads(lines[0], parse_constant=lambda c: pytest.fail(f"non-JSON {c}"))


@pytest.mark.parametrize("args", [
    ["--eta", "1e-6", "--omega", "1", "--F", "0.05"],
    ["--eta", "50", "--omega", "1", "--F", "0.05"],
    ["--eta", "0.05", "--omega", "1", "--F", "0.05", "--d", "0"],
    ["--eta", "0.3", "--omega", "1", "--F", "2", "--d", "2"],
    ["--eta", "0.3", "--omega", "1", "--F", "2.5", "--d", "2.5"],
    ["--eta", "0.05", "--omega", "1", "--F", "0", "--r", "0"],
    ["--eta", "0.05", "--omega", "1", "--F", "20", "--r", "1"],
    ["--eta", "0.05", "--omega", "0.05", "--F", "2"],
    ["--eta", "0.05", "--omega", "8", "--F", "20"],
])
def test_cli_extremes_run_without_nan(args):
    out = _json_out(run_vines("simulate", *args, "--t-end", "400", "--t-transient", "200",
                              "--json"))
    assert out["status"] == "ok"
    for key in ("ke_ratio", "xmax", "xmax_m", "xmax_whole_run_m", "impacts_per_period",
                "t_stuck"):
        assert out[key] is not None and math.isfinite(out[key]), key
    assert 0.0 <= out["ke_ratio"] <= 1.0
    if "--F" in args and args[args.index("--F") + 1] == "0":
        assert out["ke_ratio"] == 0.0 and out["regime"] == "no-impact"


@pytest.mark.parametrize("args, fragments", [
    (["--eta", "0", "--omega", "1", "--F", "0.05"], ["--eta", "0", "> 0"]),
    (["--eta", "0.05", "--omega", "1", "--F", "0.05", "--r", "-0.1"], ["--r", "-0.1", ">= 0"]),
    (["--eta", "0.05", "--omega", "1", "--F", "0.05", "--r", "1.0000001"],
     ["--r", "1.0000001", "<= 1"]),
    (["--eta", "0.05", "--omega", "1", "--F", "-20"], ["--F", "-20", ">= 0"]),
    (["--eta", "0.05", "--omega", "1.000001", "--F", "0.05", "--d", "1e-8"],
     ["--omega", "1.000001", "natural frequency"]),
])
def test_cli_refuses_with_one_line(args, fragments):
    proc = run_vines("simulate", *args, "--json")
    assert proc.returncode == 2, proc.stderr
    assert proc.stdout == ""
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("vines simulate: error: ")
    for frag in fragments:
        assert frag in lines[0], (frag, lines[0])
