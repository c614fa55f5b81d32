"""Steady-state amplitude of the stuck linear system (Eq. 28) against direct integration."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from vines.core.linear import stuck_amplitude, stuck_peak, stuck_steady_state
from vines.core.params import D_DEFAULT


def _integrated_amplitude(eta, W, F, d, n_settle_periods, n_periods=5):
    m = 1.0 + eta

    def rhs(t, y):
        return [y[1], (F * math.sin(W * t) + d * W * F * math.cos(W * t) - d * y[1] - y[0]) / m]

    T = 2 * math.pi / W
    t_end = (n_settle_periods + n_periods) * T
    t_eval = np.linspace(n_settle_periods * T, t_end, 4000)
    sol = solve_ivp(rhs, (0.0, t_end), [0.0, 0.0], t_eval=t_eval, rtol=1e-10, atol=1e-12,
                    method="DOP853")
    return np.abs(sol.y[0]).max()


@pytest.mark.parametrize("eta,W,F,d", [(0.2, 0.7, 0.4, 0.3), (0.5, 1.1, 0.4, 0.2),
                                       (0.2, 1.0 / math.sqrt(1.2), 0.1, 0.25),
                                       (0.05, 1.5, 0.05, 0.5)])
def test_amplitude_matches_integration(eta, W, F, d):
    # the transient decays like exp(-d t / (2 (1 + eta))): settle for ~ 30 time constants
    t_settle = 30 * 2 * (1 + eta) / d
    n = int(t_settle * W / (2 * math.pi)) + 1
    amp = _integrated_amplitude(eta, W, F, d, n)
    assert stuck_amplitude(eta, W, F, d) == pytest.approx(amp, rel=2e-4)


def test_limits_and_broadcast():
    # static limit W -> 0: amplitude F; far above resonance ~ F / ((1 + eta) W^2)
    assert stuck_amplitude(0.3, 1e-6, 0.2) == pytest.approx(0.2, rel=1e-9)
    assert stuck_amplitude(0.3, 100.0, 0.2, 0.0) == pytest.approx(0.2 / (1.3 * 1e4 - 1), rel=1e-12)
    # undamped resonance is infinite; zero forcing gives zero
    assert math.isinf(stuck_amplitude(0.44, 1 / 1.2, 0.1, 0.0))
    assert stuck_amplitude(0.44, 1 / 1.2, 0.0, 0.0) == 0.0
    a = stuck_amplitude(np.array([[0.2], [0.5]]), np.linspace(0.5, 1.5, 7), 0.4, D_DEFAULT)
    assert a.shape == (2, 7)
    # peak near the stuck natural frequency 1/sqrt(1 + eta): the grid's argmax is within half
    # a step (2.5e-5) of the damped peak, which lies O(d^2) = O(1.4e-4) from 1/sqrt(1 + eta)
    # (measured 2.1e-5 in all); 1e-3 bounds both with a 5x margin on the worst case
    w = np.linspace(0.5, 1.5, 20001)
    for eta in (0.2, 0.5):
        assert w[np.argmax(stuck_amplitude(eta, w, 0.4))] == pytest.approx(1 / math.sqrt(1 + eta), abs=1e-3)


@pytest.mark.parametrize("eta,F,d", [(0.2, 0.4, D_DEFAULT), (0.5, 0.4, D_DEFAULT),
                                     (0.05, 0.1, 0.3), (1.0, 0.2, 1.0)])
def test_peak_is_the_maximum_found_by_a_40_digit_search(eta, F, d):
    # independent: golden-section search of |z|(omega) in 40-digit arithmetic
    mp = pytest.importorskip("mpmath")
    mp.mp.dps = 40
    a, F_, d_ = 1 + mp.mpf(eta), mp.mpf(F), mp.mpf(d)

    def amp(w):
        return F_ * mp.sqrt(1 + (d_ * w) ** 2) / mp.sqrt((1 - a * w * w) ** 2 + (d_ * w) ** 2)

    lo, hi, g = mp.mpf("0.01"), mp.mpf(3), (mp.sqrt(5) - 1) / 2
    for _ in range(200):
        x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
        lo, hi = (x1, hi) if amp(x1) < amp(x2) else (lo, x2)
    w_ref = (lo + hi) / 2
    omega, peak = stuck_peak(eta, F, d)
    assert omega == pytest.approx(float(w_ref), rel=1e-12)
    assert peak == pytest.approx(float(amp(w_ref)), rel=1e-13)


def test_peak_of_fig11_values():
    # the numbers quoted in Fig 11 and docs/figures.md (F = 0.4, Table 1 damping; L = 15 mm)
    for eta, w, mm in ((0.2, 0.91284356, 548), (0.5, 0.81647699, 613)):
        omega, peak = stuck_peak(eta, 0.4)
        # w is quoted to 8 decimals (rounding <= 5e-9); the peak itself is solved to round-off
        assert omega == pytest.approx(w, abs=1e-8) and round(peak * 15) == mm


@pytest.mark.parametrize("eta,W,F,d,phi", [(0.2, 0.7, 0.4, 0.3, 0.0), (0.5, 1.1, 0.4, 0.2, 1.0)])
def test_steady_state_solves_eq28_and_has_its_amplitude(eta, W, F, d, phi):
    # integrated from the closed form's state at t = 0, Eq. 28 stays on it
    def rhs(t, y):
        force = F * math.sin(W * t + phi) + d * W * F * math.cos(W * t + phi)
        return [y[1], (force - d * y[1] - y[0]) / (1.0 + eta)]

    h = 1e-6
    z0 = stuck_steady_state(0.0, eta, W, F, d, phi)
    v0 = (stuck_steady_state(h, eta, W, F, d, phi)
          - stuck_steady_state(-h, eta, W, F, d, phi)) / (2 * h)
    t = np.linspace(0.0, 3 * 2 * math.pi / W, 3001)
    sol = solve_ivp(rhs, (0.0, t[-1]), [z0, v0], t_eval=t, rtol=1e-11, atol=1e-12,
                    method="DOP853")
    z = stuck_steady_state(t, eta, W, F, d, phi)
    # v0's central difference is off by ~1e-10 (round-off / h): a transient of that size
    assert np.max(np.abs(sol.y[0] - z)) < 1e-8
    # 1000 samples a period: the sampled maximum is within (pi/1000)^2/2 of the amplitude
    assert np.max(np.abs(z)) == pytest.approx(stuck_amplitude(eta, W, F, d), rel=1e-5)
