"""Closed-form local-time flow against an independent numerical integration."""
import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from vines.core import flow as fl

# (m, d, W, F): LO and stuck body, under-, critically, over-damped, undamped, resonance
CASES = [
    (1.0, 0.011998, 1.0, 0.05),
    (1.2, 0.011998, 0.9, 0.4),      # stuck body near its resonance
    (1.0, 2.0, 1.0, 0.3),           # critical
    (1.0, 2.5, 1.3, 0.3),           # overdamped
    (1.0, 1.999999, 0.8, 0.3),      # just underdamped
    (1.0, 0.0, 1.0, 0.2),           # undamped exact resonance (secular term)
    (1.0, 0.0, 0.7, 0.2),           # undamped
    (1.5, 0.3, 2.0, 1.0),
    (51.0, 0.011998, 0.14, 20.0),   # very heavy stuck body
]
X0, V0, TH0 = 0.3, -0.4, 1.1


def _reference(m, d, W, F, s_end):
    def rhs(t, y):
        th = TH0 + W * t
        return [y[1], (F * math.sin(th) + d * W * F * math.cos(th) - d * y[1] - y[0]) / m]
    return solve_ivp(rhs, (0.0, s_end), [X0, V0], method="DOP853", rtol=1e-13, atol=1e-15,
                     dense_output=True)


@pytest.mark.parametrize("m,d,W,F", CASES)
def test_flow_matches_numerical_integration(m, d, W, F):
    osc = fl.make_osc(m, d, W, F)
    ref = _reference(m, d, W, F, 40.0)
    for s in (0.0, 0.37, 3.1, 11.0, 40.0):
        z, v, a, j, _ = fl.flow(osc, X0, V0, math.sin(TH0), math.cos(TH0), s)
        zr, vr = ref.sol(s)
        # DOP853's error at rtol 1e-13 over 40 units (measured <= 1.5e-12); the closed form
        # has round-off only
        assert abs(z - zr) <= 1e-10 * (1 + abs(zr))
        assert abs(v - vr) <= 1e-10 * (1 + abs(vr))
        # z'' from the equation of motion itself
        f = fl.forcing(osc, math.sin(TH0), math.cos(TH0), s)
        assert abs(a - (f - d * v - z) / m) <= 1e-12 * (1 + abs(a))


@pytest.mark.parametrize("m,d,W,F", CASES)
def test_velocity_square_integral(m, d, W, F):
    osc = fl.make_osc(m, d, W, F)
    sth, cth = math.sin(TH0), math.cos(TH0)
    for L in (0.01, 2.3, 17.0):
        exact = fl.v2_integral(osc, X0, V0, sth, cth, L)
        num = quad(lambda s: fl.flow(osc, X0, V0, sth, cth, s)[1] ** 2, 0.0, L,
                   epsabs=1e-15, epsrel=1e-13, limit=400)[0]
        # quad asked for epsrel 1e-13 (measured 1.4e-13 relative, 1.75e-12 absolute)
        assert abs(exact - num) <= 1e-11 * max(1.0, abs(num))


@pytest.mark.parametrize("m,d,W,F", CASES)
def test_derivative_bounds_hold_for_all_later_times(m, d, W, F):
    """The event search relies on these bounds: they must hold on [s, s + span]."""
    osc = fl.make_osc(m, d, W, F)
    sth, cth = math.sin(TH0), math.cos(TH0)
    s0 = 1.7
    _, _, _, _, b1 = fl.flow(osc, X0, V0, sth, cth, s0)
    span = 30.0
    B2 = fl.deriv_bound(osc, b1, 2, s0 + span)
    B3 = fl.deriv_bound(osc, b1, 3, s0 + span)
    for s in np.linspace(s0, s0 + span, 2001):
        _, _, a, j, _ = fl.flow(osc, X0, V0, sth, cth, s)
        assert abs(a) <= B2 * (1 + 1e-12)
        assert abs(j) <= B3 * (1 + 1e-12)


def test_local_time_is_translation_invariant():
    """Starting a segment later with the shifted phase gives the same motion."""
    osc = fl.make_osc(1.0, 0.011998, 1.0, 0.1)
    z1, v1, *_ = fl.flow(osc, X0, V0, math.sin(TH0), math.cos(TH0), 2.0)
    th = TH0 + 1.0 * 2.0
    z2, v2, *_ = fl.flow(osc, z1, v1, math.sin(th), math.cos(th), 3.0)
    z3, v3, *_ = fl.flow(osc, X0, V0, math.sin(TH0), math.cos(TH0), 5.0)
    # round-off of two closed-form evaluations of size ~1 (measured 2e-15): 1e-13 is 900 u (u = 2^-53)
    assert abs(z2 - z3) < 1e-13 and abs(v2 - v3) < 1e-13


@pytest.mark.parametrize("m,d,W,F", CASES)
@pytest.mark.parametrize("x0,v0", [(X0, V0), (0.26, 0.0), (0.0, 3.0)])
def test_state_bounds_hold_over_the_span(m, d, W, F, x0, v0):
    """``state_bounds`` (from the whole state at s0) bound z'', z''', z'''' on [s0, s0 + H]."""
    osc = fl.make_osc(m, d, W, F)
    sth, cth = math.sin(TH0), math.cos(TH0)
    s0 = 0.9
    z, v, _, _, _ = fl.flow(osc, x0, v0, sth, cth, s0)
    for H in (0.3, 1.0 / osc[fl.I_RATE], 6.0):
        B2, B3, B4 = fl.state_bounds(osc, z, v, 0.0, H)
        for s in np.linspace(s0, s0 + H, 801):
            _, _, a, j, _ = fl.flow(osc, x0, v0, sth, cth, s)
            f = fl.forcing(osc, sth, cth, s)
            z4 = (-W * W * f - d * j - a) / m          # the equation differentiated twice
            assert abs(a) <= B2 * (1 + 1e-12) + 1e-14
            assert abs(j) <= B3 * (1 + 1e-12) + 1e-14
            assert abs(z4) <= B4 * (1 + 1e-12) + 1e-14


def test_state_bounds_are_tight_where_the_parts_cancel():
    """Near resonance the parts are ~F/(d omega) while the motion is small: the bound from
    the whole state must be far below the parts' bound (fewer, longer event steps)."""
    osc = fl.make_osc(1.0, 0.011998, 1.0, 0.05)
    sth, cth = math.sin(TH0), math.cos(TH0)
    z, v, a, _, b1 = fl.flow(osc, 0.26, 0.0, sth, cth, 0.0)
    B2, _, _ = fl.state_bounds(osc, z, v, 0.0, 1.0)
    assert 0.25 * fl.deriv_bound(osc, b1, 2, 1.0) > B2
    assert B2 < 2.0 * (0.26 + 0.05) + 0.1


@pytest.mark.parametrize("m,d,W,F", CASES[:2])
@pytest.mark.parametrize("x0,v0", [(0.26, 0.0), (-0.09064843610007449, 0.014744267131689222)])
def test_velocity_square_integral_near_resonance(m, d, W, F, x0, v0):
    """Small motion of a near-resonant oscillator (parts ~4, z' ~0.05): the integral from
    the exponential modes keeps the accuracy of the Gauss rule on ``flow`` (relative)."""
    osc = fl.make_osc(m, d, W, F)
    sth, cth = math.sin(TH0), math.cos(TH0)
    for L in (0.4, 3.14159, 7.8):
        exact = fl.v2_integral(osc, x0, v0, sth, cth, L)
        num = quad(lambda s: fl.flow(osc, x0, v0, sth, cth, s)[1] ** 2, 0.0, L,
                   epsabs=0.0, epsrel=1e-13, limit=400)[0]
        # quad is asked for a relative 1e-13 (epsrel) and the closed form has a few ulps of
        # round-off: 2e-13 is that request's bound, not this CPU's round-off
        assert abs(exact - num) <= 2e-13 * num


@pytest.mark.parametrize("x", [-40.0, -700.0 + 0.3j, -800.0])
def test_exponential_modes_far_in_the_decay(x):
    """(e^x - 1, e^-x - 1) once e^Re(x) is below half an ulp of 1 (e^x - 1 rounds to -1;
    the second once divided by 1 + (e^x - 1) = 0); e^-x overflows to inf beyond ~709."""
    x = complex(x)
    m_p, m_m = fl._em1_pair(x)
    assert m_p == complex(-1.0, 0.0)
    if x.real < -709.8:
        assert m_m.real == math.inf
        return
    exact = math.exp(-x.real) * complex(math.cos(x.imag), -math.sin(x.imag))
    # e^-Re(x) and cos, sin of Im(x) to a few ulps each: 1e-14 relative
    assert abs(m_m - exact) <= 1e-14 * abs(exact)


def _bits(values) -> bytes:
    """The float64 bytes of ``values`` (tells +0.0 from -0.0)."""
    return np.asarray(values, dtype=np.float64).tobytes()


@pytest.mark.parametrize("m,d,W,F", CASES + [(1.0, 0.0, 1.0002, 0.2)])   # + near resonance
def test_flow_at_zero_is_the_closed_form_at_zero_bit_for_bit(m, d, W, F):
    # the kernel starts each segment with flow_at_zero (no exp, sin, cos): it must return
    # the numbers of the general closed form at s = 0, signed zeros included
    osc = fl.make_osc(m, d, W, F)
    for x0, v0, th0 in ((X0, V0, TH0), (0.0, 0.0, 0.0), (-0.0, -0.0, math.pi),
                        (0.0, -0.0, -2.0), (-1.5, 0.0, 0.5 * math.pi), (2.0, 3.0, 4.0)):
        start = fl.flow_start(osc, x0, v0, math.sin(th0), math.cos(th0))
        assert _bits(fl.flow_at_zero(osc, start)) == _bits(fl.flow_from(osc, start, 0.0))
