"""Lyapunov spectra by saltation matrices (``core.variational``, ``attractors.lyapunov``).

Oracles that share no code with the tangent pass: the map Jacobian of ``orbits.maps.impact``
(implicit differentiation of the impact-to-impact maps), central differences of the exact
flow map, the phase-volume contraction (damping between impacts, det = r^2 per impact), the
linear oscillator without impacts, and finite-difference estimates of lambda_1 and lambda_2
(Benettin's method on perturbed trajectories of the exact solver, ``_fd_lyapunov``).
"""
import math

import numpy as np
import pytest
from _fd_lyapunov import benettin, flow_map

import vines
from vines.attractors.lyapunov import spectrum
from vines.core.exact import kernel_params, oscillators
from vines.core.params import ModelParams, ParameterError, SolverSettings
from vines.core.variational import (
    monodromy,
    saltation_impact,
    saltation_impact_stick,
    stick_projection,
)
from vines.core.walls import impact_velocities
from vines.orbits.family.periodic import find_1to1

#: chaotic points found by a random search (irregular from rest, lambda_1 > 0 from every
#: state tried, windows up to 3e4)
CHAOTIC = ((0.2026, 0.917, 0.1345), (0.4387, 0.9858, 0.3917))
#: stable 1:1 orbits: Fig 4(a) and the efficient orbit of the Fig 16 point
ONE_TO_ONE = ((0.05, 1.0, 0.05), (0.5, 0.9, 0.3077))
#: chaotic motion with chatter and sticks whose two leading exponents are positive
HYPERCHAOTIC = (0.524, 1.101, 0.2)


def _stable_1to1(eta, omega, F):
    orbits = [o for o in find_1to1(eta, omega, F) if o.stable]
    assert orbits, "the test point must have a stable 1:1 orbit"
    return ModelParams(eta=eta, omega=omega, F=F), orbits[0]


def _after_L_impact(p, orbit):
    """A state on the orbit just after its L impact, and its time."""
    vm, vb, zb, t_L = orbit.x_L
    vm_p, vb_p = impact_velocities(p.eta, p.r, vm, vb)
    return (zb + 1.0, vm_p, zb, vb_p), float(t_L)


@pytest.mark.parametrize("point", ONE_TO_ONE)
def test_monodromy_equals_map_jacobian_eigenvalues(point):
    """The product of state-transition and saltation matrices over one period of a 1:1
    orbit has the eigenvalues of J_P2 J_P1 (the map's implicit differentiation)."""
    p, orbit = _stable_1to1(*point)
    x0, t_L = _after_L_impact(p, orbit)
    s = 0.5 * orbit.flight_times[0]         # start mid-flight: one L and one R impact
    x_mid, _ = flow_map(p, oscillators(p), x0, t_L, t_L + s)
    M, tr = monodromy(p, SolverSettings(), oscillators(p), x_mid, t_L + s, p.period)
    assert tr.n_impacts == 2
    mu = np.sort_complex(np.linalg.eigvals(M))
    ref = np.sort_complex(orbit.eigenvalues)
    assert np.max(np.abs(mu - ref)) < 1e-8


def test_monodromy_equals_finite_differences_on_a_chaotic_trajectory():
    """Along 20 time units of chaotic motion (10 impacts) the matrix product equals central
    differences of the exact flow map (h = 1e-7: truncation ~ h^2 |x'''| << 1e-5)."""
    p = ModelParams(eta=CHAOTIC[0][0], omega=CHAOTIC[0][1], F=CHAOTIC[0][2])
    oscs = oscillators(p)
    x, _ = flow_map(p, oscs, (0.0, 0.0, 0.0, 0.0), 0.0, 500.0)
    M, tr = monodromy(p, SolverSettings(), oscs, x, 500.0, 20.0)
    assert tr.n_impacts >= 5
    h = 1e-7
    J = np.empty((4, 4))
    for j in range(4):
        dx = np.zeros(4)
        dx[j] = h
        (a, na), (b, nb) = (flow_map(p, oscs, x + dx, 500.0, 520.0),
                            flow_map(p, oscs, x - dx, 500.0, 520.0))
        assert na == nb == tr.n_impacts        # no impact gained or lost by the perturbation
        J[:, j] = (a - b) / (2.0 * h)
    assert np.max(np.abs(M - J)) < 1e-5 * np.max(np.abs(J))


def test_saltation_determinant_and_sticking_rank():
    """det S = r^2 for any impact (det D R = -r, n.f+ = -r n.f-); an impact that sticks
    and the stick projection have rank 2 and map into the stuck manifold."""
    p = ModelParams(eta=0.3, omega=0.8, F=0.2, r=0.65)
    kp = kernel_params(oscillators(p), p, SolverSettings(), 1.0, 0.0, 0.0)
    rng = np.random.default_rng(3)
    S = np.empty((4, 4))
    for _ in range(20):
        zm, vm, vb, t = rng.normal(size=4)
        if abs(vm - vb) < 0.05:
            continue
        saltation_impact(kp, t, zm, vm, vb, S)
        assert np.linalg.det(S) == pytest.approx(p.r ** 2, rel=1e-12)
        saltation_impact_stick(kp, t, zm, vm, vb, S)
        assert np.linalg.matrix_rank(S) == 2
        assert np.array_equal(S[0], S[2]) and np.array_equal(S[1], S[3])
    stick_projection(p.eta, S)
    assert np.linalg.matrix_rank(S) == 2


@pytest.mark.parametrize("point", ONE_TO_ONE)
def test_spectrum_on_stable_1to1_orbit_equals_log_multipliers(point):
    """All four exponents = log |mu_i| / T (mu_i: eigenvalues of the map Jacobian,
    T = 2 pi / omega), to 2e-3 (measured: <= 2e-4 over the window [4000, 7000])."""
    p, orbit = _stable_1to1(*point)
    x0, t_L = _after_L_impact(p, orbit)
    st = SolverSettings(t_end=t_L + 7000.0, t_transient=t_L + 4000.0)
    res = spectrum(p, st, x0, t0=t_L)
    ref = np.sort(np.log(np.abs(orbit.eigenvalues)) / p.period)[::-1]
    assert res.regime == "1:1" and res.n_sticks == 0
    assert np.max(np.abs(res.exponents - ref)) < 2e-3
    assert np.all(np.diff(res.exponents) <= 0.0)


def test_no_impact_limit():
    """Without impacts the LO's two exponents are -d/2 and the ball's free drift two
    zeros; the drift's polynomial growth biases them by ~log(t_end/t_transient)/window."""
    d = vines.D_DEFAULT
    res = vines.lyapunov(eta=0.5, omega=0.5, F=0.05, state0=(0.1, 0.0, 0.1, 0.0))
    assert res.regime == "no-impact" and res.n_impacts == 0
    drift = math.log(7000.0 / 4000.0) / 3000.0
    assert np.all(np.abs(res.exponents[:2]) <= 1.5 * drift)
    assert np.max(np.abs(res.exponents[2:] + d / 2)) < 1e-5
    assert res.exponents[0] > 0.0 > res.exponents[1]


@pytest.mark.parametrize("point,state0", [(ONE_TO_ONE[1], (0.0, 0.0, 0.0, 0.0)),
                                          (CHAOTIC[0], (0.5, -0.3, 0.2, 0.4))])
def test_sum_of_exponents_is_the_phase_volume_contraction(point, state0):
    """sum lambda_i = -d + 2 ln(r) (impacts in the window) / (window length)."""
    eta, omega, F = point
    res = vines.lyapunov(eta=eta, omega=omega, F=F, state0=state0)
    assert res.n_sticks == 0 and res.n_impacts > 100
    expect = -vines.D_DEFAULT + 2.0 * math.log(0.65) * res.n_impacts / 3000.0
    assert abs(res.exponents.sum() - expect) < 1e-9 * (1.0 + abs(expect)) + 1e-10


def test_sticking_removes_two_directions():
    """Chatter with sticking: lambda_3 = lambda_4 = -inf, the others finite."""
    res = vines.lyapunov(eta=0.2, omega=0.9, F=0.4, t_end=2000.0, t_transient=1000.0)
    assert res.n_sticks > 0 and res.regime == "chatter"
    assert np.all(np.isneginf(res.exponents[2:])) and np.all(np.isfinite(res.exponents[:2]))
    d = res.to_dict()
    assert d["ci"][3] == [-math.inf, -math.inf]


@pytest.mark.parametrize("point", CHAOTIC)
def test_chaotic_lambda1_positive_independent_of_state_and_window(point):
    eta, omega, F = point
    est = []
    for state0, t_end in (((0.0, 0.0, 0.0, 0.0), 7000.0), ((0.5, -0.3, 0.2, 0.4), 7000.0),
                          ((-1.0, 0.8, -0.5, -0.2), 20000.0)):
        res = vines.lyapunov(eta=eta, omega=omega, F=F, state0=state0, t_end=t_end,
                             t_transient=t_end - 3000.0)
        assert res.regime == "irregular"
        assert res.ci[0][0] > 0.0
        est.append(res)
    for a in est[1:]:
        half = 0.5 * (est[0].ci[0][1] - est[0].ci[0][0]) + 0.5 * (a.ci[0][1] - a.ci[0][0])
        assert abs(a.exponents[0] - est[0].exponents[0]) < half


def test_chaotic_lambda1_agrees_with_two_trajectory_estimate():
    eta, omega, F = CHAOTIC[0]
    p = ModelParams(eta=eta, omega=omega, F=F)
    x0 = (0.0, 0.0, 0.0, 0.0)
    (fd,), (fd_half,) = benettin(p, x0, 4000.0, 10000.0, k=1)
    res = vines.lyapunov(eta=eta, omega=omega, F=F, state0=x0, t_end=10000.0,
                         t_transient=4000.0)
    half = 0.5 * (res.ci[0][1] - res.ci[0][0])
    assert fd > 0.0 and abs(res.exponents[0] - fd) < fd_half + half


def _agree_within_intervals(fd, fd_half, res):
    """The two leading exponents of both estimates agree within their combined 95 %
    intervals."""
    half = 0.5 * (res.ci[:2, 1] - res.ci[:2, 0])
    assert np.all(np.abs(fd - res.exponents[:2]) < fd_half + half), (fd, fd_half, res.ci[:2])


@pytest.mark.parametrize("point", ONE_TO_ONE)
def test_two_exponents_agree_with_finite_differences_on_stable_1to1(point):
    """On a stable 1:1 orbit both estimates of lambda_1 and lambda_2 (negative) agree with
    each other and with log |mu| / T of the map Jacobian's multipliers."""
    p, orbit = _stable_1to1(*point)
    x0, t_L = _after_L_impact(p, orbit)
    start, stop = t_L + 300.0, t_L + 1300.0          # the frame aligned over 300 units
    fd, fd_half = benettin(p, x0, start, stop, t0=t_L)
    res = spectrum(p, SolverSettings(t_end=stop, t_transient=start), x0, t0=t_L,
                   n_batches=10)
    _agree_within_intervals(fd, fd_half, res)
    ref = np.sort(np.log(np.abs(orbit.eigenvalues)) / p.period)[::-1][:2]
    assert np.all(np.abs(fd - ref) < fd_half) and np.all(fd < 0.0)


def _hyperchaos(state0, t_end):
    p = ModelParams(*HYPERCHAOTIC)
    fd, fd_half = benettin(p, state0, 4000.0, t_end, n_batches=16)
    eta, omega, F = HYPERCHAOTIC
    res = vines.lyapunov(eta=eta, omega=omega, F=F, state0=state0, t_end=t_end,
                         t_transient=4000.0)
    assert res.n_sticks > 0                  # lambda_3,4 = -inf: two directions survive
    _agree_within_intervals(fd, fd_half, res)
    assert fd[1] - fd_half[1] > 0.0 and res.ci[1][0] > 0.0     # two positive exponents


def test_hyperchaos_two_positive_exponents_agree_with_finite_differences():
    """(0.524, 1.101, 0.2) from rest over [4000, 20000]: lambda_1 and lambda_2 both > 0 by
    saltation matrices and by finite differences (measured 0.131, 0.028 and
    0.132 +- 0.005, 0.029 +- 0.003)."""
    _hyperchaos((0.0, 0.0, 0.0, 0.0), 20000.0)


@pytest.mark.parametrize("state0,t_end", [((0.0, 0.0, 0.0, 0.0), 50000.0),
                                          ((0.5, -0.3, 0.2, 0.4), 20000.0),
                                          ((-1.0, 0.8, -0.5, -0.2), 20000.0)])
def test_hyperchaos_from_other_states_and_a_longer_window(state0, t_end):
    _hyperchaos(state0, t_end)


def test_bad_input_names_the_argument():
    with pytest.raises(ParameterError, match="eta"):
        vines.lyapunov(eta=-1.0, omega=1.0, F=0.1)
    with pytest.raises(ParameterError, match="t_transient"):
        vines.lyapunov(eta=0.1, omega=1.0, F=0.1, t_end=100.0, t_transient=200.0)
    with pytest.raises(ParameterError, match="state0"):
        vines.lyapunov(eta=0.1, omega=1.0, F=0.1, state0=(0.0, 0.0, 3.0, 0.0))
    with pytest.raises(ParameterError, match="n_batches"):
        vines.lyapunov(eta=0.1, omega=1.0, F=0.1, t_end=100.0, t_transient=50.0,
                       n_batches=1000)
    with pytest.raises(TypeError):
        vines.lyapunov(0.1, 1.0, 0.1)          # keyword arguments only


def test_tangent_run_follows_the_census_trajectory_bit_for_bit():
    """The spectrum's run (paused every 256 periods) is the trajectory of ``run_measured``
    (the census's runs, paused at sections by the shortcut's detector): same end state,
    same impacts in the window."""
    from vines.core.simulation import run_measured
    from vines.core.variational import TangentRun
    p = ModelParams(eta=CHAOTIC[0][0], omega=CHAOTIC[0][1], F=CHAOTIC[0][2])
    st = SolverSettings()
    s0 = (0.5, -0.3, 0.2, 0.4)
    raw, m = run_measured(p, st, state0=s0)
    tr = TangentRun(p, st, oscillators(p), s0, 0.0, np.linspace(4000.0, 7000.0, 17)).run()
    assert np.array_equal(raw.solver_info["final_state"], tr.run_.cur[1:5])
    assert m["n_impacts_window"] == tr.n_impacts


def test_irregular_torus_has_zero_leading_exponent():
    """"irregular" (no strobe return) is not chaos: at (0.511, 1.26, 0.484) the motion from
    rest has lambda_1 = 0 within its interval (quasi-periodic), the rest negative."""
    res = vines.lyapunov(eta=0.511, omega=1.26, F=0.484, t_end=20000.0, t_transient=4000.0)
    assert res.regime == "irregular"
    assert res.ci[0][0] < 0.0 < res.ci[0][1] and abs(res.exponents[0]) < 1e-3
    assert np.all(res.exponents[2:] < -0.1)
