"""The TMD's travel (stroke) |U - X|/|Y| against an independent time integration of the
base-LO-TMD system, and the travel-limited optimum: unchanged when the limit does not bind,
on the limit (and better than a brute-force grid) when it does, bad input refused."""
import math

import numpy as np
import pytest

from vines import ParameterError
from vines.core.params import D_DEFAULT
from vines.studies import tmd

BAND = (0.8, 1.2)


def _steady_amplitudes(mu, f, zeta, d, w):
    """Amplitudes of x (LO) and u - x (TMD relative to the LO) at steady state under the
    base motion y = sin(w t), from a DOP853 integration of
    x'' = -d (x' - y') - (x - y) - mu (2 zeta f (x' - u') + f^2 (x - u)),
    u'' = -2 zeta f (u' - x') - f^2 (u - x), started at rest, and a least-squares fit of
    a sin + b cos over its last two periods (the slowest free mode decays like exp(-0.096 t):
    exp(-29) by t = 300)."""
    from scipy.integrate import solve_ivp

    def rhs(t, s):
        x, v, u, vu = s
        y, yd = math.sin(w * t), w * math.cos(w * t)
        fa = 2 * zeta * f * (vu - v) + f * f * (u - x)
        return [v, -d * (v - yd) - (x - y) + mu * fa, vu, -fa]

    T = 2 * math.pi / w
    t_end = 300.0
    t = np.linspace(t_end - 2 * T, t_end, 401)
    sol = solve_ivp(rhs, (0, t_end), [0, 0, 0, 0], method="DOP853", rtol=1e-12, atol=1e-13,
                    t_eval=t)
    basis = np.column_stack([np.sin(w * t), np.cos(w * t)])
    amp = [np.hypot(*np.linalg.lstsq(basis, s, rcond=None)[0])
           for s in (sol.y[0], sol.y[2] - sol.y[0])]
    return amp


@pytest.mark.parametrize("w", [0.85, 1.07])
def test_travel_formula_against_time_integration(w):
    mu, f, zeta, d = 0.1, 0.9, 0.2, 0.05
    x_amp, travel_amp = _steady_amplitudes(mu, f, zeta, d, w)
    assert tmd.tmd_ratio(w, d, mu, f, zeta) == pytest.approx(x_amp, rel=1e-6)
    assert tmd.tmd_travel(w, d, mu, f, zeta) == pytest.approx(travel_amp, rel=1e-6)


def test_travel_broadcasts_and_limits():
    w = np.linspace(0.5, 1.5, 7)
    f = np.array([[0.8], [1.0]])
    out = tmd.tmd_travel(w, 0.01, 0.05, f, 0.1)
    assert out.shape == (2, 7)
    np.testing.assert_array_equal(out[1], tmd.tmd_travel(w, 0.01, 0.05, 1.0, 0.1))
    # a locked absorber (huge damping) does not move relative to the LO; a quasi-static base
    # (omega -> 0) moves LO and absorber together
    assert tmd.tmd_travel(1.0, 0.01, 0.05, 1.0, 1e9) < 1e-7
    assert tmd.tmd_travel(1e-4, 0.01, 0.05, 1.0, 0.1) < 1e-7


@pytest.fixture(scope="module")
def free():
    return tmd.optimal_tmd(0.1, D_DEFAULT, BAND)


def test_free_optimum_reports_its_band_travel(free):
    w = np.linspace(*BAND, 200001)
    assert free.worst_travel == pytest.approx(free.travel(w, D_DEFAULT).max(), rel=1e-9)
    # the figure: about 10.8 base amplitudes at the default case
    assert 10.5 < free.worst_travel < 11.1


def test_travel_limit_binds_exactly_when_the_free_travel_exceeds_it(free):
    # not binding: the free optimum, bit for bit (a dataclass compares every field)
    for limit in (None, 1e3, free.worst_travel, free.worst_travel * (1 + 1e-12)):
        assert tmd.optimal_tmd(0.1, D_DEFAULT, BAND, max_travel=limit) == free
    # binding by 0.1 %: another tuning, on the limit, and worse than the free optimum
    limit = free.worst_travel * (1 - 1e-3)
    bound = tmd.optimal_tmd(0.1, D_DEFAULT, BAND, max_travel=limit)
    assert (bound.frequency_ratio, bound.damping_ratio) != (free.frequency_ratio,
                                                            free.damping_ratio)
    assert bound.worst_travel == pytest.approx(limit, rel=1e-9)
    assert free.worst_ratio < bound.worst_ratio < free.worst_ratio * 1.01


@pytest.mark.parametrize("limit", [7.07, 3.0])
def test_travel_limited_optimum_beats_a_brute_force_grid(limit):
    """No tuning of a dense (f, zeta) grid that meets the limit does better (band maxima on
    4001 points: they can only underestimate, hence the margin of 1e-4)."""
    t = tmd.optimal_tmd(0.1, D_DEFAULT, BAND, max_travel=limit)
    assert t.worst_travel == pytest.approx(limit, rel=1e-9)
    w = np.linspace(*BAND, 4001)[:, None, None]
    f = np.linspace(0.3, 1.8, 76)[None, :, None]
    z = np.geomspace(1e-2, 1e2, 81)[None, None, :]
    travel = tmd.tmd_travel(w, D_DEFAULT, 0.1, f, z).max(axis=0)
    ratio = tmd.tmd_ratio(w, D_DEFAULT, 0.1, f, z).max(axis=0)
    best = ratio[travel <= limit].min()
    assert t.worst_ratio <= best * (1 + 1e-4)
    # and it is the local optimum along the limit: detuned either way along it is worse
    edge = tmd._TravelBoundary(0.1, D_DEFAULT, BAND, limit)
    for df in (0.98, 1.02):
        assert edge.worst_ratio(t.frequency_ratio * df, exact=True) > t.worst_ratio


def test_travel_limit_on_an_undamped_host():
    # d = 0, both Den Hartog peaks in the band: the free travel, then a limit 20 % lower
    band = (0.5, 1.5)
    free = tmd.optimal_tmd(0.05, 0.0, band)
    bound = tmd.optimal_tmd(0.05, 0.0, band, max_travel=0.8 * free.worst_travel)
    assert bound.worst_travel == pytest.approx(0.8 * free.worst_travel, rel=1e-9)
    assert bound.worst_ratio > free.worst_ratio


@pytest.mark.parametrize("limit", [0, -1.0, math.nan, math.inf, "x"])
def test_bad_travel_limit_is_refused(limit):
    with pytest.raises(ParameterError, match="max_travel"):
        tmd.optimal_tmd(0.1, D_DEFAULT, BAND, max_travel=limit)


def test_unreachable_travel_limit_is_refused():
    # undamped host with the locked resonance 1/sqrt(1.1) in the band: the damper is the
    # only damping, and no damping ratio up to ZETA_MAX_LIMITED keeps the travel this small
    with pytest.raises(ParameterError, match="max_travel.*every tuning"):
        tmd.optimal_tmd(0.1, 0.0, (0.5, 1.5), max_travel=1e-3)
