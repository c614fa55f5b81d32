"""Exact event-driven solver: invariants, paper behaviours, grazing, batch determinism."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

import vines
from vines.core.exact import run_exact
from vines.core.params import D_DEFAULT


def _energy(st, eta):
    """Mechanical energy (dimensionless, M = 1): LO kinetic + spring + ball kinetic."""
    return 0.5 * st[1] ** 2 + 0.5 * st[0] ** 2 + 0.5 * eta * st[3] ** 2


SHORT = dict(t_end=300.0, t_transient=100.0)
POINTS = [  # (eta, omega, F): the paper's named parameter points
    (0.05, 1.0, 0.05), (0.085, 1.0, 0.05), (0.07, 1.0, 0.1), (0.08, 1.0, 0.1),
    (0.2, 0.8, 0.4), (0.2, 0.9, 0.4), (0.55, 1.0, 0.4), (0.45, 1.1, 0.4),
    (0.2, 0.909396, 0.4), (0.2, 1.2, 0.4), (0.5, 1.1, 0.4),
]


@pytest.mark.parametrize("eta,omega,F", POINTS)
def test_ball_stays_in_cavity(eta, omega, F):
    res = vines.simulate(eta, omega, F, **SHORT)
    t = np.linspace(0.0, res.t_last, 60001)
    t = np.union1d(t, res.impacts["t"])
    st = res.state_at(t)
    w = st[0] - st[2]
    assert np.max(np.abs(w)) <= 1.0 + 1e-12
    # impacts sit exactly on their wall: the kernel stores z_b = fl(z_m - wall) and the gap is
    # (z_m - z_b) - wall, two correctly rounded IEEE operations (the same on every CPU):
    # |gap| <= u (1 + |z_m|) + u (1 + u (1 + |z_m|)) <= 2.2e-16 (1 + |z_m|), u = 2^-53
    gap = res.impacts["z_m"] - res.impacts["z_b"] - res.impacts["wall"]
    assert np.all(np.abs(gap) <= 4e-16 * (1 + np.abs(res.impacts["z_m"])))


@pytest.mark.parametrize("eta,omega,F", POINTS)
def test_impact_law_momentum_and_restitution(eta, omega, F):
    res = vines.simulate(eta, omega, F, **SHORT)
    imp = res.impacts
    post = res.state_at(imp["t"])       # the segment starting at the impact: post-impact
    # Round-off bounds from the problem's scale, not from relative errors of differences:
    # the post-impact velocities are a few correctly rounded operations on v_m, v_b (Eq. 10),
    # read back through state_at at the segment's start (closed-form parts of size <= scale);
    # the errors are k u scale, u = 2^-53 (measured k <= 16 for restitution, <= 10 for
    # momentum over POINTS), so 1e-13 scale (k = 900) holds on any IEEE CPU. A relative bound
    # on dw would be ill-conditioned at the small dw of chatter (cancellation in v_m - v_b).
    scale = 1.0 + np.abs(imp["v_m"]) + np.abs(imp["v_b"])
    mom_pre = imp["v_m"] + eta * imp["v_b"]
    mom_post = post[1] + eta * post[3]
    assert np.all(np.abs(mom_post - mom_pre) <= 1e-13 * (1.0 + eta) * scale)
    dw_pre = imp["v_m"] - imp["v_b"]
    dw_post = post[1] - post[3]
    stuck = np.abs(dw_post) < 1e-15         # plastic: the ball stuck at this impact
    r = vines.core.params.R_DEFAULT
    assert np.all(np.abs(dw_post + r * dw_pre)[~stuck] <= 1e-13 * scale[~stuck])
    # approach: w' > 0 at L, w' < 0 at R
    assert np.all(dw_pre * imp["wall"] > 0)


@pytest.mark.parametrize("eta,omega,F", [(0.05, 1.0, 0.05), (0.2, 0.8, 0.4), (0.2, 0.9, 0.4),
                                         (0.55, 1.0, 0.4)])
def test_energy_balance(eta, omega, F):
    """E(t1) - E(0) = forcing work - damping loss - impact (and sticking) losses."""
    d = D_DEFAULT
    res = vines.simulate(eta, omega, F, t_end=120.0, t_transient=50.0)
    imp = res.impacts
    traj = res._state_at
    seg_t = np.append(traj.segments[:, 0], res.t_last)

    def power(t):
        z, v, _, _ = traj(np.array([t]))[:, 0]
        f = F * math.sin(omega * t) + d * omega * F * math.cos(omega * t)
        return v * (f - d * v)

    work = quad_err = 0.0
    for a, b in zip(seg_t[:-1], seg_t[1:], strict=False):
        if b > a:
            # one segment at a time: quad's Gauss-Kronrod nodes lie strictly inside (a, b),
            # so state_at (which picks the segment by time) never reads the next segment
            val, err = quad(lambda t: float(power(t)), a, b, epsabs=1e-14, epsrel=1e-12,
                            limit=200)
            work += val
            quad_err += err
    post = traj(imp["t"])
    pre_e = 0.5 * imp["v_m"] ** 2 + 0.5 * eta * imp["v_b"] ** 2
    post_e = 0.5 * post[1] ** 2 + 0.5 * eta * post[3] ** 2
    impact_loss = np.sum(pre_e - post_e)
    assert np.all(pre_e - post_e >= -1e-14)
    e0 = _energy(np.zeros(4), eta)
    e1 = _energy(traj(np.array([res.t_last]))[:, 0], eta)
    # quad's own error estimates (<= 1.2e-12 summed) plus the rounding of sums of ~100 terms
    # of size <= E + losses (~100 u (E + loss) <= 3e-12); measured <= 1.3e-13. (Trimming
    # 1e-13 t off each segment end, as before, cost up to 2.2e-9 in chatter: 140 segments.)
    assert abs((e1 - e0) - (work - impact_loss)) <= 10.0 * quad_err + 1e-12 * (
        1.0 + e1 + impact_loss)


def test_named_1to1_point_fig4a():
    """(eta 0.05, W 1, F 0.05): 1:1 with |w'| about 0.958, phase at R in (pi, 2 pi)."""
    res = vines.simulate(0.05, 1.0, 0.05)
    assert res.regime == "1:1"
    win = res.impacts["t"] >= 4000.0
    dw = np.abs(res.impact_dw[win])
    assert np.all(np.abs(dw - 0.958) < 0.005)
    ph_R = res.impact_phase[win][res.impacts["wall"][win] == -1]
    assert np.all((ph_R > math.pi) & (ph_R < 2 * math.pi))


def test_named_four_impacts_fig9a():
    res = vines.simulate(0.2, 0.8, 0.4)
    # a finite-window count: a window of n = t_win / T periods of an orbit with 4 impacts per
    # period holds 4 n impacts up to the 4 of one partial period, so |per period - 4| <= 4 / n
    # (here one impact in ~3400 periods: 3e-4)
    st = res.settings
    n_periods = (st.t_end - st.t_transient) / res.params.period
    assert abs(res.impacts_per_period - 4.0) <= 4.0 / n_periods
    assert res.t_stuck == 0.0


def test_named_chatter_fig9c():
    chat = vines.simulate(0.2, 0.9, 0.4)
    calm = vines.simulate(0.2, 0.8, 0.4)
    assert chat.regime == "chatter" and chat.t_stuck > 0.0 and chat.n_sticks > 0
    assert chat.xmax > 3.0 * calm.xmax


@pytest.mark.parametrize("eta,omega", [(0.55, 1.0), (0.45, 1.1)])
def test_named_efficient_1to1_fig10(eta, omega):
    res = vines.simulate(eta, omega, 0.4)
    assert res.regime == "1:1"
    assert res.ke_ratio > 0.7


def test_grazing_impact_is_not_missed():
    """Undamped, unforced LO z_m = A sin t, ball at rest at 0: w reaches 1 only if A > 1.

    With A = 1 + 1e-10 the contact lasts ~3e-5 time units around t = pi/2 (a near-tangency
    that sampling-based event detection misses); with A = 1 - 1e-10 there is no contact.
    """
    for A, hits in ((1.0 + 1e-10, True), (1.0 - 1e-10, False)):
        res = vines.simulate(0.05, 1.0, 0.0, d=0.0, t_end=2.0, t_transient=1.0,
                             state0=(0.0, A, 0.0, 0.0))
        if hits:
            assert res.n_impacts == 1
            t_hit = math.asin(1.0 / A)
            assert abs(res.impacts["t"][0] - t_hit) < 1e-7
            assert res.impacts["wall"][0] == 1
        else:
            assert res.n_impacts == 0


def test_two_impacts_closer_than_any_sampling_step():
    """A chatter sequence: consecutive impacts far closer than typical solver steps."""
    res = vines.simulate(0.2, 0.9, 0.4, t_end=300.0, t_transient=100.0)
    gaps = np.diff(res.impacts["t"])
    # A regime property, not round-off: each chatter sequence ends when the relative speed
    # after an impact drops to ~v_stick = 1e-6, near the LO's extreme excursions where
    # |w''| = |z_m''| ~ 5.5; the last flights last 2 w'+ / |w''| ~ 7.3e-7..8e-7. About 40
    # such flights in this window are shorter than 1e-6, so the minimum is far from the
    # bound's edge (a perturbed, e.g. other-CPU, trajectory keeps dozens of them).
    assert gaps.min() < 1e-6
    assert np.count_nonzero(gaps < 1e-6) >= 10
    assert np.all(gaps > 0)


def test_max_impacts_guard():
    res = vines.simulate(0.2, 0.9, 0.4, t_end=300.0, t_transient=100.0, max_impacts=50)
    assert res.status == "max_impacts"
    assert res.n_impacts == 50


def test_no_forcing_no_motion():
    res = vines.simulate(0.1, 1.0, 0.0)
    assert res.n_impacts == 0 and res.ke_ratio == 0.0 and res.xmax == 0.0
    assert res.regime == "no-impact"


def test_long_unforced_decay_runs_to_the_end():
    """F = 0, LO decaying under a ball drifting slowly across the cavity: one free flight
    of 15000 units, e^(-d s / 2) far below round-off of 1 (it once divided by zero in the
    v'^2 integral). Energy balance: the integral of z_m'^2 is E0/d (E(t_end) ~ e^-750)."""
    d, v0, vb = 0.05, 1e-4, 5e-5
    p = vines.ModelParams(eta=0.1, omega=1.0, F=0.0, d=d)
    st = vines.SolverSettings(t_end=15000.0, t_transient=0.0, state0=(0.0, v0, 0.0, vb))
    raw = run_exact(p, st)
    assert raw.status == "ok" and raw.n_impacts == 0 and raw.t_last == 15000.0
    # a sum of ~1.5e4 panels' Gauss rules: relative error <= n u ~ 2e-12
    assert abs(raw.int_vm2 - 0.5 * v0 * v0 / d) <= 1e-11 * 0.5 * v0 * v0 / d
    assert abs(raw.int_vb2 - vb * vb * 15000.0) <= 1e-14 * vb * vb * 15000.0


def test_batch_matches_single_runs_and_thread_count():
    eta = np.array([0.05, 0.2, 0.55])
    omega = np.array([1.0, 0.8, 1.0])
    F = np.array([0.05, 0.4, 0.4])
    kw = dict(t_end=800.0, t_transient=400.0)
    b1 = vines.simulate_batch(eta, omega, F, n_threads=1, **kw)
    b2 = vines.simulate_batch(eta, omega, F, n_threads=2, **kw)
    for k in b1:
        np.testing.assert_array_equal(b1[k], b2[k], err_msg=k)   # NaN == NaN
    for i in range(3):
        r = vines.simulate(eta[i], omega[i], F[i], **kw)
        assert b1["ke_ratio"][i] == r.ke_ratio
        assert b1["xmax"][i] == r.xmax
        assert b1["regime"][i] == r.regime


def test_batch_rejects_bad_point_before_work():
    with pytest.raises(vines.ParameterError, match="eta"):
        vines.simulate_batch([0.1, -0.2], 1.0, 0.1)


@pytest.mark.parametrize("solver, t_end", [("exact", 7000.0), ("exact", 300.0),
                                           ("rk", 300.0)])
def test_result_numbers_are_python_scalars(solver, t_end):
    # every number of a result is a Python float or int (json, repr and type checks alike),
    # also when the periodic shortcut completes the run (t_end 7000: it does here)
    res = vines.simulate(eta=0.05, omega=1.0, F=0.05, solver=solver, t_end=t_end,
                         t_transient=t_end - 100.0)
    numbers = {k: v for k, v in vars(res).items() if isinstance(v, (float, int, np.generic))}
    assert {"ke_ratio", "K_m", "K_b", "xmax", "t_stuck", "n_impacts", "period"} <= set(numbers)
    assert {k: type(v) for k, v in numbers.items() if type(v) not in (float, int, bool)} == {}
    assert type(res.ke_ratio) is type(res.xmax_m) is float
    assert res.ke_ratio == res.K_b / (res.K_m + res.K_b)


@pytest.mark.parametrize("state0,wall", [((0.0, 0.0, -1.0, -0.2), 1), ((1.0, 0.2, 0.0, 0.0), 1),
                                         ((0.0, 0.0, 1.0, 0.2), -1),
                                         ((0.7, -0.3, 1.7, 0.0), -1)])
@pytest.mark.parametrize("d", [D_DEFAULT, 2.0])
def test_start_on_a_wall_moving_into_it_is_an_impact_at_t0(state0, wall, d):
    """A start state on a wall, approaching it, is an impact at t = 0 (as the RK reference
    has it); the kernel used to find no step and report "stalled" at t = 0 (found by the
    differential fuzz, tests/test_differential_fuzz.py)."""
    kw = dict(d=d, t_end=2.0, t_transient=1.0, state0=state0, periodic_shortcut=False)
    ex = vines.simulate(0.1, 1.0, 0.0, **kw)
    assert ex.status == "ok" and ex.t_last == 2.0
    imp = ex.impacts[0]
    assert imp["t"] == 0.0 and imp["wall"] == wall
    assert (imp["z_m"], imp["v_m"], imp["z_b"], imp["v_b"]) == state0
    kw.pop("periodic_shortcut")
    rk = vines.simulate(0.1, 1.0, 0.0, solver="rk", rtol=1e-12, **kw)
    assert ex.n_impacts == rk.n_impacts
    assert np.max(np.abs(ex.impacts["t"] - rk.impacts["t"])) < 1e-9


@pytest.mark.parametrize("n", [0, 1, 7])
def test_impact_records_are_the_rows_field_by_field(n):
    from vines.core.exact import impact_records
    from vines.core.result import IMPACT_DTYPE
    rng = np.random.default_rng(n)
    rows = rng.normal(size=(n, 6))
    rows[:, 5] = rng.choice([-1.0, 1.0], size=n)
    expected = np.empty(n, dtype=IMPACT_DTYPE)
    for k, name in enumerate(IMPACT_DTYPE.names):
        expected[name] = rows[:, k]
    got = impact_records(rows)
    assert got.dtype == IMPACT_DTYPE
    assert got.tobytes() == expected.tobytes()
    assert impact_records(rows[::2]).tobytes() == expected[::2].tobytes()   # strided rows


@pytest.mark.parametrize("kw", [dict(periodic_shortcut=False), dict(periodic_shortcut=True),
                                dict(solver="rk", rtol=1e-11)])
def test_state_at_an_impact_instant_is_the_state_after_it(kw):
    """``state_at`` at a recorded impact time is defined as the post-impact state (the common
    velocity where the ball sticks there), one ulp earlier the pre-impact one: for both
    solvers and after a periodic shortcut (records repeated), so which side a time of
    ``impacts["t"]`` falls on never depends on rounding. 2:2 (0.2, 0.8, 0.4: the shortcut
    is taken at t ~ 1565) and chatter (0.2, 1, 0.1) with sticking."""
    for eta, omega, F in [(0.2, 0.8, 0.4), (0.2, 1.0, 0.1)]:
        res = vines.simulate(eta, omega, F, t_end=2500.0, t_transient=2000.0, **kw)
        if kw.get("periodic_shortcut") and omega == 0.8:
            assert res.shortcut_time < 2000.0
        imp = res.impacts
        scale = 1.0 + np.abs(imp["v_m"]) + np.abs(imp["v_b"])
        at = res.state_at(imp["t"])
        before = res.state_at(np.nextafter(imp["t"], -np.inf))
        # one ulp earlier: the arriving flight (z'' <= ~1 changes z' by ~ulp(t) there)
        assert np.all(np.abs(before[1] - imp["v_m"]) <= 1e-9 * scale)
        assert np.all(np.abs(before[3] - imp["v_b"]) <= 1e-9 * scale)
        dw_post, dw_pre = at[1] - at[3], imp["v_m"] - imp["v_b"]
        stuck = np.abs(dw_post) <= 1e-12 * scale
        bounced = np.abs(dw_post + res.params.r * dw_pre) <= 1e-9 * scale
        assert np.all(stuck | bounced) and bounced.sum() > 0.9 * imp.size
        # momentum of both bodies is the pre-impact one
        assert np.all(np.abs(at[1] + eta * at[3] - imp["v_m"] - eta * imp["v_b"])
                      <= 1e-9 * (1.0 + eta) * scale)
