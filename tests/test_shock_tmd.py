"""The TMD after a shock (vines.studies.shock_tmd): the fastest tuning's decay rate against
numpy's eigenvalues and a grid, the peak travel against a DOP853 integration, the
travel-limited tuning on its limit and no slower than a brute-force grid, and the ball
starts of ``shock``."""
import math

import numpy as np
import pytest

from vines import ParameterError
from vines.core.params import D_DEFAULT
from vines.studies import shock_tmd as st
from vines.studies.shock import ball_starts, shock, tmd_system

X0 = np.array([0.0, 1.0, 0.0, 0.0])


@pytest.mark.parametrize("mu", [0.02, 0.1])
def test_fastest_tuning_closed_form_on_an_undamped_host(mu):
    f, zeta, rate = st.tmd_fastest(mu, 0.0)
    assert f == pytest.approx(1 / (1 + mu), rel=1e-15)
    assert zeta == pytest.approx(math.sqrt(mu / (1 + mu)), rel=1e-15)
    lam = np.linalg.eigvals(tmd_system(0.0, mu, f, zeta)[0])
    # a double pair (a Jordan block): numpy's eigenvalues are off by ~sqrt(eps)
    np.testing.assert_allclose(-lam.real, rate, rtol=1e-6)


@pytest.mark.parametrize("d", [0.0, D_DEFAULT, 0.1])
def test_fastest_tuning_decay_rate_is_the_eigenvalues_and_a_maximum(d):
    mu = 0.1
    f, zeta, rate = st.tmd_fastest(mu, d)
    lam = np.linalg.eigvals(tmd_system(d, mu, f, zeta)[0])
    np.testing.assert_allclose(-lam.real, rate, rtol=1e-6)       # both modes coalesce
    assert np.ptp(np.abs(lam.imag)) < 1e-6
    # no tuning nearby decays faster (a grid of +-5 % in f, +-20 % in zeta)
    grid = [st.decay_rate(tmd_system(d, mu, f * a, zeta * b)[0])
            for a in np.linspace(0.95, 1.05, 11) for b in np.linspace(0.8, 1.2, 11)]
    assert max(grid) <= rate * (1 + 1e-7)


def test_peak_travel_against_time_integration():
    """Peak |y - x| and |x| after the unit shock against DOP853 with dense output: the
    integrated peak (maximised over its dense output) agrees to 1e-7."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import minimize_scalar
    for f, zeta in ((0.9067, 0.1864), (0.92, 0.5), (0.9, 0.02)):
        A, P, _, _ = tmd_system(D_DEFAULT, 0.1, f, zeta)
        sol = solve_ivp(lambda t, x, A=A: A @ x, (0, 300), X0, method="DOP853", rtol=1e-12,
                        atol=1e-14, dense_output=True).sol
        t = np.linspace(0, 300, 300001)
        for c in (st.TRAVEL, st.LO_DISPLACEMENT):
            z = np.abs(c @ sol(t))
            k = int(z.argmax())
            res = minimize_scalar(lambda s, c=c, sol=sol: -abs(c @ sol(s)),
                                  bounds=(t[k - 1], t[k + 1]), method="bounded",
                                  options={"xatol": 1e-12})
            peak, where = st.peak_response(A, P, c, X0)
            assert peak == pytest.approx(-res.fun, rel=1e-7)
            assert where == pytest.approx(res.x, abs=1e-4)


def test_equal_travel_tuning_binds_exactly_when_the_fastest_exceeds_it():
    mu, d = 0.1, D_DEFAULT
    fastest = st.tmd_fastest(mu, d)
    travel = st.shock_peaks(d, mu, *fastest[:2])["travel"]
    assert st.tmd_equal_travel(mu, d, travel * (1 + 1e-9)) == fastest
    limit = 0.5 * travel
    f, zeta, rate = st.tmd_equal_travel(mu, d, limit)
    peaks = st.shock_peaks(d, mu, f, zeta)
    assert peaks["travel"] == pytest.approx(limit, rel=1e-8)
    assert peaks["rate"] == pytest.approx(rate, rel=1e-12) and rate < fastest[2]
    # no tuning of a grid meeting the limit decays faster
    best = 0.0
    for fg in np.linspace(0.6, 1.3, 36):
        for zg in np.geomspace(0.05, 5.0, 41):
            if st.shock_peaks(d, mu, fg, zg)["travel"] <= limit:
                best = max(best, st.decay_rate(tmd_system(d, mu, fg, zg)[0]))
    assert best <= rate * (1 + 1e-6)


@pytest.mark.parametrize("limit", [0, -1.0, math.nan, "x"])
def test_bad_travel_limit_is_refused(limit):
    with pytest.raises(ParameterError, match="max_travel"):
        st.tmd_equal_travel(0.1, D_DEFAULT, limit)


def test_ball_starts_are_seeded_and_inside_the_cavity():
    a, b = ball_starts(64, 3)
    a2, b2 = ball_starts(64, 3)
    np.testing.assert_array_equal(a, a2)
    np.testing.assert_array_equal(b, b2)
    assert np.all(np.abs(a) < 1) and np.all(np.abs(b) < 1)
    assert not np.array_equal(a, ball_starts(64, 4)[0])


def test_shock_keeps_the_centred_start_and_adds_the_distribution():
    kw = dict(eta=0.1, clearance_m=0.0424, velocity_m_s=3.0, periods=2.0)
    plain = shock(**kw)
    more = shock(**kw, starts=6, seed=1)
    for key in ("vines", "tmd", "lo_alone"):
        for k, v in plain[key].items():
            if k != "design":
                assert more[key][k] == v
    st_ = more["starts"]
    assert plain["starts"] is None and st_["n"] == 6
    q = st_["dissipated_fraction_quantiles"]
    assert len(q) == 5 and q == sorted(q) and q[0] > 0 and q[-1] < 1
    assert min(st_["dissipated_fraction"]) <= q[0] <= q[-1] <= max(st_["dissipated_fraction"])
    # strokes: the VI NES's is L; the TMD within L is on its limit, the band-tuned beyond
    assert more["vines"]["stroke_m"] == 0.0424
    assert more["tmd_equal_travel"]["stroke_m"] == pytest.approx(0.0424, rel=1e-8)
    assert more["tmd"]["stroke_m"] > 0.0424
    with pytest.raises(ParameterError, match="starts"):
        shock(**kw, starts=-1)


@pytest.mark.parametrize("kw, name", [(dict(mu=0.0, d=0.01), "mu"), (dict(mu=0.1, d=-1.0), "d"),
                                      (dict(mu=math.nan, d=0.01), "mu")])
def test_bad_mass_or_damping_is_refused(kw, name):
    with pytest.raises(ParameterError, match=name):
        st.tmd_fastest(**kw)
