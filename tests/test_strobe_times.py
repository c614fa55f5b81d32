"""Stroboscopic times of the regime classification stay inside the measured window."""
import math

import numpy as np

import vines
from vines.core.regime import N_STROBE, strobe_times


def test_strobe_times_never_pass_t_end_for_windows_of_whole_periods():
    """t_end = t_transient + n T, rounded: the last strobe time t_transient + n T must not
    land a rounding error past t_end (simulate then raised 'times must lie in the
    recorded span')."""
    rng = np.random.default_rng(0)
    n_rounded_up = 0
    for _ in range(20000):
        omega = rng.uniform(0.5, 1.5)
        T = 2 * math.pi / omega
        t_tr = float(rng.integers(0, 8000))
        n = int(rng.integers(N_STROBE, 3000))
        t_end = (t_tr / T + n) * T
        n_rounded_up += t_tr + n * T > t_end
        t = strobe_times(T, t_tr, t_end)
        assert t.size == N_STROBE and t[-1] <= t_end and t[0] >= t_tr
        assert t_end - t[-1] < T * (1 + 1e-9)
    assert n_rounded_up > 100       # the case this test is about does occur


def test_simulate_with_a_window_of_whole_periods_rounded_up():
    res = vines.simulate(0.1, 0.8651101682448286, 0.1, t_end=7394.330749870752,
                         t_transient=5092.0)
    assert res.status == "ok"
