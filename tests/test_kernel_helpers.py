"""Named constants and small helpers of the event-driven kernel (vines.core.kernel)."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest
from conftest import ROOT, SRC

from vines.core import kernel as k
from vines.core.exact import kernel_params, oscillators, run_exact
from vines.core.params import V_STICK_DEFAULT, ModelParams, SolverSettings


def test_named_codes_are_distinct_and_match_the_conventions():
    assert k.MODE_FREE == 0 and (k.WALL_L, k.WALL_R) == (1, -1)   # stuck mode = wall
    events = (k.EV_STOP, k.EV_IMPACT, k.EV_RELEASE, k.EV_STICK, k.EV_STALLED)
    assert len(set(events)) == len(events) and k.MODE_FREE not in events
    assert tuple(range(7)) == (k.CUR_T, k.CUR_ZM, k.CUR_VM, k.CUR_ZB, k.CUR_VB, k.CUR_MODE,
            k.CUR_RELEASED)
    rcs = (k.RC_DONE, k.RC_BUFFER_FULL, k.RC_MAX_IMPACTS, k.RC_STALLED)
    assert len(set(rcs)) == 4
    assert abs(k.CONTACT_PRESSED * k.WALL_L) not in (0, 1)      # never an impact code


def test_clamp_step_caps_at_h_cap_and_stops_at_s_stop():
    assert k._clamp_step(1.0, 5.0, 0.5, 10.0) == (1.5, False)
    assert k._clamp_step(1.0, 0.25, 0.5, 10.0) == (1.25, False)
    assert k._clamp_step(9.9, 0.25, 0.5, 10.0) == (10.0, True)


def test_common_velocity_conserves_momentum():
    eta, vm, vb = 0.3, 0.7, -1.1
    vc = k._common_velocity(eta, vm, vb)
    assert math.isclose((1.0 + eta) * vc, vm + eta * vb, rel_tol=1e-15)


def test_stick_speed_floor_is_a_round_off_bounce():
    osc_f, _ = oscillators(ModelParams(eta=0.05, omega=1.0, F=0.05))
    v1 = k._stick_speed_floor(osc_f, 1.0, 0.5, -0.5, 0.1, 0.0)
    v4 = k._stick_speed_floor(osc_f, 4.0, 0.5, -0.5, 0.1, 0.0)
    # apex v1^2 / (2 |g|) = ROUNDOFF max(16 zscale, 4 (zscale + parts)) (zscale = 2, parts =
    # 4.27 here): a bounce of 5.7e-14 L, v1 = 3.4e-7 for |g| = 1, whatever the CPU (IEEE
    # sqrt). The bound 1e-6 is V_STICK_DEFAULT: the floor must stay below the default chatter
    # threshold at |g| ~ 1 so that v_stick, not round-off, decides sticking
    assert 32.0 * k.ROUNDOFF * (1.0 - 1e-14) <= v1 * v1 / 2.0 <= 4.0 * k.ROUNDOFF * (2.0 + 8.0)
    assert 0.0 < v1 < V_STICK_DEFAULT
    assert math.isclose(v4, 2.0 * v1, rel_tol=1e-14)            # apex v^2 / (2 |g|)
    assert k._stick_speed_floor(osc_f, 0.0, 0.5, -0.5, 0.1, 0.0) == 0.0


def _run(buf_rows, t_end=300.0):
    p = ModelParams(eta=0.2, omega=0.9, F=0.4)                    # chatter with sticking
    st = SolverSettings(t_end=t_end, t_transient=t_end / 2)
    osc_f, osc_s = oscillators(p)
    cur = np.zeros(7)
    acc = np.zeros(k.N_ACC)
    cnt = np.zeros(k.N_CNT, dtype=np.int64)
    imp, seg = np.empty((buf_rows, 6)), np.empty((2 * buf_rows, 6))
    n_full = 0
    while True:
        kp = kernel_params((osc_f, osc_s), p, st, st.t_end, st.t_transient, 0.0)
        rc = k.run_kernel(kp, (cur, acc, cnt), imp, seg)
        if rc != k.RC_BUFFER_FULL:
            break
        n_full += 1
        imp = np.concatenate([imp, np.empty_like(imp)])
        seg = np.concatenate([seg, np.empty_like(seg)])
    return rc, n_full, cur, acc, cnt, imp[:cnt[k.C_NIMP_REC]], seg[:cnt[k.C_NSEG_REC]]


def test_run_kernel_resumes_after_buffer_full_with_identical_numbers():
    rc_a, full_a, *a = _run(100_000)
    rc_b, full_b, *b = _run(8)
    assert rc_a == rc_b == k.RC_DONE and full_a == 0 and full_b > 0
    for x, y in zip(a, b, strict=False):
        assert np.array_equal(x, y)
    cur, acc, cnt, imp, seg = a
    assert cur[k.CUR_T] == 300.0 and acc[k.A_NSTICK] > 0
    assert set(np.unique(imp[:, 5])) <= {k.WALL_L, k.WALL_R}
    assert set(np.unique(seg[:, 5])) <= {k.MODE_FREE, k.WALL_L, k.WALL_R}
    assert np.any(seg[:, 5] != k.MODE_FREE)                        # stuck segments occur


def _dense_max(osc, x0, v0, sth, cth, sa, sb):
    """max |z| on [sa, sb]: dense sampling, then golden-section refinement of the best."""
    from scipy.optimize import minimize_scalar

    from vines.core.flow import flow
    ss = np.linspace(sa, sb, 4001)
    zs = np.array([abs(flow(osc, x0, v0, sth, cth, s)[0]) for s in ss])
    i = int(np.argmax(zs))
    lo, hi = ss[max(i - 1, 0)], ss[min(i + 1, ss.size - 1)]
    r = minimize_scalar(lambda s: -abs(flow(osc, x0, v0, sth, cth, s)[0]), bounds=(lo, hi),
                        method="bounded", options={"xatol": 1e-12})
    return max(zs.max(), -r.fun)


def test_interval_max_matches_a_dense_search():
    """The x_max refinement (bounds, Hermite test, Newton on z') finds max |z| on a step."""
    from vines.core.flow import flow, flow_start, part_bounds, state_bounds
    rng = np.random.default_rng(3)
    for eta, omega, F in ((0.05, 1.0, 0.05), (0.2, 0.9, 0.4), (0.3, 1.6, 0.5)):
        osc = oscillators(ModelParams(eta=eta, omega=omega, F=F))[0]
        for _ in range(40):
            x0, v0, th = rng.normal(0, 0.5), rng.normal(0, 0.5), rng.uniform(0, 2 * math.pi)
            sth, cth = math.sin(th), math.cos(th)
            sa = rng.uniform(0, 3)
            sb = sa + rng.uniform(0.01, 1.0)
            za, va, _, _, b1 = flow(osc, x0, v0, sth, cth, sa)
            zb, vb, _, _, _ = flow(osc, x0, v0, sth, cth, sb)
            B2, _, B4 = state_bounds(osc, za, va, 0.0, sb - sa)
            B2, B4 = min(B2, part_bounds(osc, b1, sb)[2]), min(B4, part_bounds(osc, b1, sb)[4])
            ref = _dense_max(osc, x0, v0, sth, cth, sa, sb)
            # from below the interval's max (refined) and from above (nothing to do)
            ends = (osc, flow_start(osc, x0, v0, sth, cth), (sa, za, va), (sb, zb, vb), B2, B4)
            got = k._interval_max(*ends, 0.0, np.empty(k.N_STACK))
            # z' = 0 at the maximum, so the two searches' times differ harmlessly (second
            # order); what is left is flow's round-off of z, a few u (1 + |z| + parts):
            # measured 8.9e-16, 1e-14 is 90 u (u = 2^-53)
            assert abs(got - ref) <= 1e-14 * (1 + ref)
            assert k._interval_max(*ends, ref + 1e-3, np.empty(k.N_STACK)) == ref + 1e-3


@pytest.mark.parametrize("state0,wall", [((0.0, 0.0, -1.0, -0.2), 1), ((1.0, 0.2, 0.0, 0.0), 1),
                                         ((0.0, 0.0, 1.0, 0.2), -1)])
def test_first_contact_from_a_wall_moving_into_it_is_an_impact_at_zero(state0, wall):
    """The start state of ``test_start_on_a_wall_moving_into_it_is_an_impact_at_t0``
    (test_exact.py) given to first_contact: no step is possible there; it returned
    (0, nan, nan, nan) (the no-step exit) and now answers as run_kernel, an impact at s = 0."""
    osc_f, _ = oscillators(ModelParams(eta=0.1, omega=1.0, F=0.0))
    got = k.first_contact(osc_f, state0, (0.0, 1.0), 10.0, 1e-13)
    assert got == (wall, 0.0, state0[0], state0[1])


def test_first_contact_that_cannot_finish_says_so_with_numbers():
    """Steps that neither meet a wall nor reach s_max (here MAX_STEPS_PER_SEGMENT steps of at
    most 1/rate cannot cover s_max = 1e6: a flight far from both walls) end with
    CONTACT_STALLED and the point reached, not NaN."""
    osc_f, _ = oscillators(ModelParams(eta=0.05, omega=3.0, F=0.001))
    wall, s, z, v = k.first_contact(osc_f, (0.0, 0.0, 0.0, 0.0), (0.0, 1.0), 1e6, 1e-13)
    assert wall == k.CONTACT_STALLED and 0.0 < s < 1e6
    assert math.isfinite(z) and math.isfinite(v) and abs(z) < 0.01


@pytest.mark.parametrize("t_transient", [0.0, 1e5])
def test_a_flight_longer_than_the_step_limit_is_no_stall(t_transient):
    """A run without impacts whose first flight needs more than MAX_STEPS_PER_SEGMENT steps
    (omega = 3, F = 0.001: the LO's amplitude ~1e-4 L never reaches a wall; steps <= 1/3)
    "stalled at t = 0" (the segment's start) without the periodic shortcut: the
    reconstructed stall of issue 52. The long segment is now cut into pieces; in a window
    after the transient (e^(-d t / 2) ~ e^-600) the amplitude and the mean of z_m'^2 are
    the linear steady state's."""
    p = ModelParams(eta=0.05, omega=3.0, F=0.001)
    st = SolverSettings(t_end=3e5, t_transient=t_transient)
    raw = run_exact(p, st)
    assert raw.status == "ok" and raw.n_impacts == 0 and raw.t_last == 3e5
    if t_transient == 0.0:
        return
    # steady state of z'' + d z' + z = F sin(theta) + d omega F cos(theta) (core.flow):
    # z = X sin(theta - psi), X = F |1 + i d omega| / |1 - omega^2 + i d omega|
    X = p.F * abs(1.0 + 1j * p.d * p.omega) / abs(1.0 - p.omega**2 + 1j * p.d * p.omega)
    assert raw.xmax_window == pytest.approx(X, rel=1e-9)
    mean_v2 = raw.int_vm2 / (st.t_end - st.t_transient)     # (omega X)^2 / 2, to 1/(omega T)
    assert mean_v2 == pytest.approx(0.5 * (p.omega * X) ** 2, rel=1e-5)


def test_a_kernel_test_runs_in_pure_python_with_numba_disabled():
    """``NUMBA_DISABLE_JIT=1`` (how a user steps through a kernel in a debugger): vines'
    ``njit`` gives back the plain functions and a kernel test passes in pure Python (a
    grazing contact found by the exact stepping, ~2 s)."""
    env = {**os.environ, "NUMBA_DISABLE_JIT": "1",
           "PYTHONPATH": os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")])}
    test = "tests/test_exact.py::test_grazing_impact_is_not_missed"
    r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                        test, "-c", str(ROOT / "pyproject.toml")],
                       capture_output=True, text=True, env=env, cwd=ROOT, timeout=300)
    assert r.returncode == 0 and "1 passed" in r.stdout, r.stdout + r.stderr
    probe = ("import vines.core.kernel as k; import numba; "
             "print(numba.config.DISABLE_JIT, type(k.first_contact).__name__)")
    r = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                       env=env, cwd=ROOT, timeout=120)
    assert r.stdout.split() == ["1", "function"], r.stdout + r.stderr
