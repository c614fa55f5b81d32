"""Quasi-periodic motion in the census's asymptotic view (``attractors.torus``)."""
import math

import numpy as np
import pytest

from vines.attractors import census, torus
from vines.attractors.orbit import section_of_1to1
from vines.core.exact import oscillators, run_exact
from vines.core.params import ModelParams, SolverSettings
from vines.orbits.family.periodic import find_1to1

GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0
FIBONACCI = {1, 2, 3, 5, 8, 13, 21, 34, 55, 89, 144, 233, 377, 610, 987, 1597, 2584}
#: past the Neimark-Sacker curve of the symmetric 1:1 orbit at F = 0.484 (docs/attractors.md)
TORUS = (0.511, 1.26, 0.484)


def _curve(theta: np.ndarray) -> np.ndarray:
    """A closed curve in R^4 (not star-shaped in any plane, a steep stretch as in a
    relaxation cycle)."""
    return np.stack([np.cos(theta), np.sin(2 * theta), np.tanh(8 * np.sin(theta)),
                     0.3 * np.cos(3 * theta)], axis=1)


def test_irrational_rotation_fills_a_closed_curve():
    """x_k on a closed curve at angle 2 pi k rho, rho the golden mean: a closed curve; its
    return lag is a best approximation's denominator of rho, a Fibonacci number."""
    k = np.arange(4096)
    res = torus.closed_curve(_curve(2 * np.pi * GOLDEN * k))
    assert res["closed"] and not res["periodic"]
    assert res["lag"] in FIBONACCI and res["lag"] >= 987
    # its error: the curve's largest slope (tanh: 8 of 2 per unit angle, over the range)
    # times the angle 2 pi |lag rho - round(lag rho)|
    q = res["lag"]
    dtheta = 2 * np.pi * abs(q * GOLDEN - round(q * GOLDEN))
    assert 0.0 < res["return_error"] <= 4.0 * dtheta


def test_rational_rotation_is_periodic_and_chaos_is_not_a_curve():
    k = np.arange(1024)
    per = torus.closed_curve(_curve(2 * np.pi * (3.0 / 17.0) * k))
    assert per["periodic"] and not per["closed"] and per["lag"] == 17
    # the Henon map's chaotic attractor (a = 1.4, b = 0.3): no lag returns everywhere
    x = np.zeros((2048 + 100, 4))
    x[0, :2] = 0.1, 0.1
    for i in range(1, x.shape[0]):
        x[i, 0] = 1.0 - 1.4 * x[i - 1, 0] ** 2 + x[i - 1, 1]
        x[i, 1] = 0.3 * x[i - 1, 0]
    chaos = torus.closed_curve(x[100:])
    assert not chaos["closed"] and chaos["return_error"] > 0.5
    few = torus.closed_curve(_curve(np.arange(100.0)))
    assert few["closed"] is None


def test_envelope_of_the_linear_response():
    """Far below resonance with the ball at rest mid-cavity nothing hits: the envelope is
    the base-excited linear amplitude F sqrt((1 + (d W)^2) / ((1 - W^2)^2 + (d W)^2))
    (a smooth maximum: sampled to (pi / 64)^2 / 2 = 0.12 %)."""
    p = ModelParams(eta=0.1, omega=0.5, F=0.2)
    st = SolverSettings(t_end=4000.0, t_transient=2000.0)
    raw = run_exact(p, st)
    assert raw.impacts["t"].size == 0
    T = p.period
    env = torus.envelope(raw, T, math.ceil(3500 / T), math.floor(3990 / T))
    dW = p.d * p.omega
    amp = p.F * math.sqrt((1 + dW ** 2) / ((1 - p.omega ** 2) ** 2 + dW ** 2))
    assert np.all(np.abs(env / amp - 1.0) <= (np.pi / 64) ** 2 / 2 + 1e-9)
    assert math.isnan(torus.modulation_period(env))


def test_past_neimark_sacker_quasi_periodic_and_persistent():
    """At TORUS the symmetric 1:1 orbit has just lost stability through a complex pair of
    multipliers (|mu| crosses 1 between Omega = 1.24 and 1.26: a Neimark-Sacker curve):
    the census finds a lasting motion that is quasi-periodic and persistent (it was
    'unresolved' before, its exponent over [t_end, t_max] being slightly negative)."""
    for omega, outside in ((1.24, False), (1.26, True)):
        sym = [o for o in find_1to1(eta=TORUS[0], omega=omega, F=TORUS[2])
               if o.symmetric and abs(o.eigenvalues[0].imag) > 0.0]
        assert sym and (np.abs(sym[0].eigenvalues).max() > 1.0) == outside
    unstable = sym
    c = census(*TORUS, n=4, seed=0, t_max=30000.0, n_threads=2).to_dict()
    qp = [a for a in c["attractors"] if a["regime_asymptotic"] == "quasi-periodic"]
    assert qp and qp[0]["status"] == "persistent"
    assert sum(a["count"] for a in qp) == 4 and c["from_rest_asymptotic"] == c["from_rest"]
    m = qp[0]["modulation"]
    assert m["closed"] and m["return_error"] < 0.01
    assert m["lambda_1_ci"][0] <= 0.0 <= m["lambda_1_ci"][1]
    # a small torus about the orbit that just lost stability: the envelope brackets the
    # unstable orbit's max |z_m| over its period, within 20 % of it
    p = ModelParams(eta=TORUS[0], omega=TORUS[1], F=TORUS[2])
    xmax = section_of_1to1(p, SolverSettings(), oscillators(p), unstable[0])["xmax"]
    assert 0.8 * xmax < m["amplitude"][0] < xmax < m["amplitude"][1] < 1.2 * xmax


def test_chaos_is_not_quasi_periodic():
    c = census(0.2026, 0.917, 0.1345, n=2, seed=0, t_max=15000.0).to_dict()
    for a in c["attractors"]:
        assert a["regime_asymptotic"] == a["regime"] != "quasi-periodic"
        assert "modulation" not in a


#: points where the slow flow predicts SMR (no attracting two-impact fixed point, linear
#: amplitude above the clearance): (eta, Omega, F, r, d)
SMR_POINTS = [(0.02, 1.0, 0.015, 0.65, 0.011998), (0.01, 1.0, 0.005, 0.65, 0.005),
              (0.01, 1.0, 0.004, 0.65, 0.003)]
#: the exact envelope's low end may undershoot the slow flow's fold by this share (the
#: ball keeps hitting for a while after the motion has left the SIM; measured 23-25 %)
SMR_LOW_TOL = 0.35


@pytest.mark.parametrize("point", SMR_POINTS)
def test_smr_predicted_by_the_slow_flow_is_chaotic_smr_in_the_exact_model(point):
    """Where the slow flow predicts SMR the exact motion lasts (persistent, no escape) and
    is a chaotic strongly modulated response: lambda_1 > 0, no closed curve, the LO
    amplitude envelope swinging by a factor >= 3 over many forcing periods, its range
    [min, max] within the predicted [xi_min, 1] (low end to SMR_LOW_TOL)."""
    from vines.slowflow import response
    eta, omega, F, r, d = point
    pred = response(eta, omega, F, r=r, d=d)
    assert pred.regime == "SMR"
    low, high = pred.smr
    c = census(eta, omega, F, r=r, d=d, n=2, seed=0, t_max=40000.0, n_threads=1)
    sampled = [a.to_dict() for a in c.attractors if a.count > 0]
    assert sum(a["count"] for a in sampled) == 2       # (split by KE ratio, maybe)
    for a in sampled:
        assert not a["periodic"] and a["status"] == "persistent"
        assert a["lifetime"]["escaped"] == 0 and a["lyapunov_max_ci"][0] > 0.0   # chaos
    a = sampled[0]
    p = ModelParams(eta=eta, omega=omega, F=F, r=r, d=d)
    st = SolverSettings(state0=a["example_state"])
    run = run_exact(p, st, record_from=st.t_end - 1.0)      # one member, to t_end
    m = torus.modulation(p, st, 40000.0, run.solver_info["final_state"])
    assert not m["closed"] and m["lambda_1_ci"][0] > 0.0
    lo, hi = m["amplitude"]
    assert (1.0 - SMR_LOW_TOL) * low <= lo < hi <= high
    assert hi >= 3.0 * lo and m["period"] > 20.0


def test_two_impact_regime_of_the_slow_flow_is_not_modulated():
    """Beside the SMR points, where the slow flow has an attracting two-impact fixed point,
    the exact census ends on the 1:1 orbit: the check above can tell them apart."""
    from vines.slowflow import response
    assert response(0.02, 1.0, 0.02, r=0.65).regime == "two-impact"
    c = census(0.02, 1.0, 0.02, r=0.65, n=2, seed=0, t_max=20000.0, n_threads=1)
    assert c.attractors[c.from_rest_asymptotic].regime == "1:1"


@pytest.mark.slow
def test_torus_point_lies_past_a_neimark_sacker_curve_of_boundaries():
    """``vines boundaries`` at F = 0.484 has a Neimark-Sacker curve of the symmetric 1:1
    orbit crossing eta = 0.511 between Omega = 1.24 and TORUS's 1.26 (15 s)."""
    from vines.orbits.curves.boundaries import boundaries
    b = boundaries(TORUS[2], [0.45, 0.55], [1.2, 1.3], n_scan=3, n_map=0)
    ns = [c for c in b.curves if c.type == "neimark-sacker" and c.family == "symmetric"]
    crossings = []
    for c in ns:
        e, w = c.points[:, 0], c.points[:, 1]
        for i in np.flatnonzero(np.diff(np.sign(e - TORUS[0])) != 0):
            t = (TORUS[0] - e[i]) / (e[i + 1] - e[i])
            crossings.append(w[i] + t * (w[i + 1] - w[i]))
    assert any(1.24 < w < TORUS[1] for w in crossings)
