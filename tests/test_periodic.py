"""1:1 orbits from the maps: agreement with long simulations and the paper's qualitative
statements (Sec. 3, Figs. 6, 15). What every family's orbits satisfy (fixed point of the
integrated flights, flags, mirror pairs, eigenvalues) is in ``test_orbit_families``."""
import math

import numpy as np
import pytest

import vines
from vines.core.walls import WALL_L, WALL_R
from vines.orbits.family.periodic import PeriodicOrbit, find_1to1


@pytest.mark.parametrize("eta, W, F", [(0.05, 1.0, 0.05), (0.55, 1.0, 0.4), (0.45, 1.1, 0.4)])
def test_stable_orbit_is_the_simulated_attractor(eta, W, F):
    res = vines.simulate(eta, W, F)            # default t_end = 7000
    assert res.regime == "1:1"
    orbits = [o for o in find_1to1(eta, W, F, simulation=False) if o.stable]
    assert len(orbits) == 1
    o = orbits[0]
    walls = res.impacts["wall"]
    dw = res.impact_dw
    ph = res.impact_phase
    kL = np.nonzero(walls == WALL_L)[0][-1]
    kR = np.nonzero(walls == WALL_R)[0][-1]

    def close_phase(a, b):
        d = abs(a - b) % (2 * math.pi)
        return min(d, 2 * math.pi - d)

    assert abs(abs(dw[kL]) - abs(o.dw_L)) <= 1e-8
    assert abs(abs(dw[kR]) - abs(o.dw_R)) <= 1e-8
    assert close_phase(ph[kL], o.phase_L) <= 1e-8
    assert close_phase(ph[kR], o.phase_R) <= 1e-8


def test_simulation_seed_finds_the_same_orbit():
    with_sim = find_1to1(0.05, 1.0, 0.05)
    without = find_1to1(0.05, 1.0, 0.05, simulation=False)
    assert len(with_sim) == len(without)
    assert with_sim[0].stable
    np.testing.assert_allclose(with_sim[0].x_L, without[0].x_L, atol=1e-10)


def test_user_seeds_are_polished():
    o = find_1to1(0.55, 1.0, 0.4, simulation=False)[0]
    x0 = o.x_L + np.array([1e-3, -1e-3, 1e-3, 1e-2])
    again = find_1to1(0.55, 1.0, 0.4, simulation=False, seeds=[x0, (x0, o.flight_times), o])
    assert len(again) == len(find_1to1(0.55, 1.0, 0.4, simulation=False))


def test_paper_window_at_resonance_small_forcing():
    # Fig. 6: at W = 1, F = 0.05 the symmetric 1:1 branch is stable only in a window near
    # eta = 0.04-0.06, where an eigenvalue stays close to the unit circle.
    etas = np.round(np.arange(0.01, 0.2001, 0.005), 4)
    stable_sym = []
    for eta in etas:
        for o in find_1to1(eta, 1.0, 0.05, simulation=False):
            if o.symmetric and o.stable:
                stable_sym.append((eta, o.lambda_max))
    assert stable_sym
    for eta, _ in stable_sym:
        assert 0.03 <= eta <= 0.07
    assert any(0.04 <= e <= 0.06 for e, _ in stable_sym)
    # eigenvalue close to 1 in the window (at the paper's point eta = 0.05 and below)
    assert all(lam > 0.9 for e, lam in stable_sym if e <= 0.05)


@pytest.mark.parametrize("W", [0.9, 1.1])
def test_paper_strongly_stable_orbits_at_F_03077(W):
    lams = []
    for eta in np.arange(0.05, 1.0, 0.05):
        lams += [o.lambda_max for o in find_1to1(eta, W, 0.3077, simulation=False)
                 if o.stable]
    assert lams and min(lams) < 0.9


def test_no_forcing_no_orbit_and_bad_input():
    assert find_1to1(0.1, 1.0, 0.0, simulation=False) == []
    with pytest.raises(vines.ParameterError):
        find_1to1(-0.1, 1.0, 0.1)
    assert isinstance(find_1to1(0.3, 1.1, 0.3077, simulation=False)[0], PeriodicOrbit)


# --------------------------------------------------------------------------- continuation

from vines.orbits.atlas.stability_map import stability_map  # noqa: E402
from vines.orbits.continuation.one_to_one import continue_branch  # noqa: E402


def _preferred(eta, W, F):
    return find_1to1(eta, W, F, simulation=False)[0]


def test_continuation_events_are_located_and_consistent():
    br = continue_branch("eta", 0.05, 0.08, 0.0025, {"omega": 1.0, "F": 0.05})
    assert br.values[0] == pytest.approx(0.05) and br.values[-1] == pytest.approx(0.08)
    assert np.all(br.symmetric) and br.stable[0] and not br.stable[-1]
    ns = [e for e in br.events if e["type"] == "neimark-sacker"]
    assert len(ns) == 1
    at = ns[0]["at"]
    # stability really changes within 1e-5 of the located point, through a complex pair
    below = _preferred(at - 1e-5, 1.0, 0.05)
    above = _preferred(at + 1e-5, 1.0, 0.05)
    assert below.stable and not above.stable
    lam = above.eigenvalues[0]
    # transversal crossing: |lam| - 1 = (d|lam|/d eta) x 1e-5 = 161 x 1e-5 = 1.6e-3 here (the
    # event itself is solved to ~4e-12 in eta: |lam| - 1 = 6e-10 there); 1e-2 is a slope of
    # 1000, the property asked is a complex pair just outside the unit circle
    assert abs(lam.imag) > 1e-3 and abs(abs(lam) - 1.0) < 1e-2
    # branch points agree with independent solves
    for i in (0, len(br) // 2, len(br) - 1):
        o = _preferred(br.values[i], 1.0, 0.05)
        assert br.lambda_max[i] == pytest.approx(o.lambda_max, rel=1e-8)
        assert br.dw_L[i] == pytest.approx(o.dw_L, rel=1e-9)
    d = br.to_dict()
    assert {"branch", "events"} <= set(d)
    assert {"eta", "omega", "F", "lambda_max", "stable", "symmetric", "admissible",
            "dw_L"} <= set(d["branch"][0])
    assert br.abs_eigenvalues.shape == (len(br), 4)


def test_continuation_detects_symmetry_breaking():
    br = continue_branch("eta", 0.05, 0.025, 0.005, {"omega": 1.0, "F": 0.05})
    sb = [e for e in br.events if e["type"] == "symmetry-breaking"]
    assert len(sb) == 1
    at = sb[0]["at"]
    # below the pitchfork a pair of asymmetric orbits exists, above it does not
    asym_below = [o for o in find_1to1(at - 1e-4, 1.0, 0.05, simulation=False)
                  if not o.symmetric]
    asym_above = [o for o in find_1to1(at + 1e-4, 1.0, 0.05, simulation=False)
                  if not o.symmetric]
    assert len(asym_below) == 2 and not asym_above


def test_continuation_in_omega_and_F_end_on_the_same_orbits():
    br = continue_branch("omega", 1.1, 1.15, 0.01, {"eta": 0.3, "F": 0.3077})
    o = _preferred(0.3, 1.15, 0.3077)
    assert br.dw_L[-1] == pytest.approx(o.dw_L, rel=1e-9)
    br = continue_branch("F", 0.3077, 0.35, 0.01, {"eta": 0.3, "omega": 1.1})
    o = _preferred(0.3, 1.1, 0.35)
    assert br.dw_L[-1] == pytest.approx(o.dw_L, rel=1e-9)
    with pytest.raises(vines.ParameterError):
        continue_branch("xi", 0.1, 0.2, 0.01, {"omega": 1.0, "F": 0.1})
    with pytest.raises(vines.ParameterError):
        continue_branch("eta", 0.1, 0.2, 0.01, {"omega": 1.0})


def test_stability_map_threads_and_classes():
    eta = np.linspace(0.02, 0.9, 9)
    omega = np.linspace(0.85, 1.15, 7)
    m1 = stability_map(eta, omega, 0.3077, n_threads=1)
    m2 = stability_map(eta, omega, 0.3077, n_threads=2)
    for k in ("lambda_max", "cls", "dw_L", "symmetric"):
        assert m1[k].shape == (9, 7)
        np.testing.assert_array_equal(m1[k], m2[k])
    cls, lam = m1["cls"], m1["lambda_max"]
    assert set(np.unique(cls)) <= {0, 1, 2, 3}
    assert np.all(np.isnan(lam[cls == 0])) and np.all(np.isfinite(lam[cls > 0]))
    assert np.all(lam[(cls == 1) | (cls == 2)] < 1.0) and np.all(lam[cls == 3] >= 1.0)
    assert np.all(m1["symmetric"][cls == 1]) and not np.any(m1["symmetric"][cls == 2])
    # every stable point agrees with a direct solve
    for i, j in zip(*np.nonzero((cls == 1) | (cls == 2)), strict=False):
        direct = [o for o in find_1to1(eta[i], omega[j], 0.3077, simulation=False) if o.stable]
        assert any(abs(o.lambda_max - lam[i, j]) < 1e-8 for o in direct)
    assert (cls == 1).any()


def test_grazing_arrival_in_a_degenerate_corner_is_no_map_not_a_crash():
    """r = 0 with tiny eta, omega and large F: a Newton iterate lands on an arrival with
    relative velocity exactly 0 (the pole of the map's Jacobian). That flight is no impact
    map; the search goes on and answers with orbits or none, never ZeroDivisionError."""
    orbits = find_1to1(0.000651, 0.000651, 1e4, r=0.0, d=0.000651)
    for o in orbits:
        assert np.isfinite(o.lambda_max)
        assert np.all(np.isfinite(o.flight_times)) and min(o.flight_times) > 0.0
