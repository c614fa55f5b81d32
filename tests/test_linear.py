"""Steady-state amplitude of the stuck linear system (Eq. 28) against direct integration."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from vines.core.linear import stuck_amplitude
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
    # peak near the stuck natural frequency 1/sqrt(1 + eta)
    w = np.linspace(0.5, 1.5, 20001)
    for eta in (0.2, 0.5):
        assert w[np.argmax(stuck_amplitude(eta, w, 0.4))] == pytest.approx(1 / math.sqrt(1 + eta), abs=1e-3)
