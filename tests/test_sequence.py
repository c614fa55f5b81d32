"""Periodic orbits of any wall sequence (``vines.orbits.family.sequence``) against the simulation.

Each family is checked at a point where a simulation from some state settles on it: the
simulated steady-state impacts (pre-impact z_m', z_b', z_b and the impact time mod T) equal
the map solution to 1e-7, and the eigenvalues of the product of the map Jacobians equal
those of a central-difference Jacobian of the simulated strobe map (state at t = 0 to the
state at t = periods T). The points were found by simulation scans (F 0.2-0.4); lambda_max
< 0.93 at every one, so the runs converge to ~1e-12 well before their end. The checks every
family passes (fixed point of independently integrated flights, eigenvalues, stability,
mirror images, continuation events, curves) are in ``test_orbit_families`` for LR/1-sym,
LR/1-asym, LLRR/1-sym and LRLR/2; here the families' attractors and the other sequences.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from vines.core.params import ModelParams, ParameterError
from vines.orbits.family.family import canonical_walls, family_name, paper_label
from vines.orbits.family.periodic import orbits_1to1
from vines.orbits.family.sequence import (
    find_sequence,
    flip_seeds,
    record_seed,
    solve_sequence,
    state_at,
)
from vines.solvers import simulate

REST = (0.0, 0.0, 0.0, 0.0)
AGREE = 1e-7


def _run(p, state0, t_end):
    return simulate(p.eta, p.omega, p.F, r=p.r, d=p.d, phi=p.phi, t_end=t_end,
                    t_transient=0.5 * t_end, state0=tuple(state0), periodic_shortcut=False)


def _distance(orbit, imp, k):
    """Largest difference between the orbit's impacts and the record's impacts k, k+1, ...
    (z_m', z_b', z_b; impact times mod T)."""
    T = orbit.params.period
    n = len(orbit.walls)
    rec = np.column_stack([imp["v_m"], imp["v_b"], imp["z_b"], imp["t"]])[k:k + n]
    d = np.abs(rec[:, :3] - orbit.states[:, :3]).max()
    dt = (rec[:, 3] - orbit.states[:, 3]) % T
    return max(d, np.minimum(dt, T - dt).max())


def _settles_on_map_orbit(p, walls, periods, state0, t_end=4000.0, seeds=()):
    """The simulation's last impacts follow ``walls`` and equal a stable admissible map
    solution found from seeds other than those impacts: (orbit, distance)."""
    run = _run(p, state0, t_end)
    imp = run.impacts
    assert record_seed(imp[imp["t"] > t_end - 3 * periods * p.period], walls) is not None, \
        f"the run does not end on {walls}"
    text = "".join("L" if w > 0 else "R" for w in imp["wall"])
    k = text.rfind(walls + walls[0])
    # Newton from an early, unsettled stretch of the run (and the built-in seeds)
    early = imp[imp["t"] < 0.1 * t_end]
    sd = record_seed(early, walls)
    orbits = find_sequence(p, walls, periods, simulation=False,
                           seeds=list(seeds) + ([sd] if sd else []))
    assert orbits, "no map solution"
    best = min(orbits, key=lambda o: _distance(o, imp, k))
    return best, _distance(best, imp, k)


def _strobe_fd_eigenvalues(orbit, h=1e-6):
    p = orbit.params
    NT = orbit.periods * p.period
    s0 = state_at(orbit, 0.0)
    end = _run(p, s0, NT).state_at(NT)[:, 0]
    assert np.abs(end - s0).max() < 1e-9            # the orbit is a fixed point of the strobe map
    J = np.empty((4, 4))
    for j in range(4):
        e = np.zeros(4)
        e[j] = h
        J[:, j] = (_run(p, s0 + e, NT).state_at(NT)[:, 0]
                   - _run(p, s0 - e, NT).state_at(NT)[:, 0]) / (2 * h)
    return np.linalg.eigvals(J)


def _assert_same_spectrum(ev_maps, ev_fd, tol=1e-5):
    a = sorted(ev_maps, key=lambda z: (round(abs(z), 6), z.imag))
    b = sorted(ev_fd, key=lambda z: (round(abs(z), 6), z.imag))
    for za in a:        # match each eigenvalue to the nearest one (pairs may be ordered apart)
        zb = min(b, key=lambda z: abs(z - za))
        assert abs(za - zb) <= tol * max(1.0, abs(za)), (a, b)
        b.remove(zb)


# --------------------------------------------------------------------------- 1:1 exactly

@pytest.mark.parametrize("eta, omega, F", [(0.55, 1.0, 0.4), (0.142, 0.755, 0.2),
                                            (0.2, 0.8, 0.4), (0.05, 1.0, 0.2)])
@pytest.mark.parametrize("simulation", [False, True])
def test_LR_one_period_is_the_1to1_solver(eta, omega, F, simulation):
    p = ModelParams(eta=eta, omega=omega, F=F)
    ref = orbits_1to1(p, simulation=simulation)
    got = find_sequence(p, "LR", 1, simulation=simulation)
    assert len(got) == len(ref) > 0
    for o, q in zip(got, ref, strict=True):
        assert np.array_equal(o.states[0], q.x_L) and np.array_equal(o.states[1], q.x_R)
        assert np.array_equal(o.flight_times, q.flight_times)
        assert np.array_equal(o.eigenvalues, q.eigenvalues)
        assert (o.symmetric, o.admissible, o.stable, o.lambda_max) == \
            (q.symmetric, q.admissible, q.stable, q.lambda_max)
        assert list(o.dw) == [q.dw_L, q.dw_R] and list(o.phases) == [q.phase_L, q.phase_R]
        # the 1:1 orbit reads as an orbit of its family LR/1 (the fields of any family)
        for key in ("walls", "periods", "family", "states", "dw", "phases"):
            assert np.array_equal(getattr(q, key), getattr(o, key)), key


# --------------------------------------------------------------------------- families

def test_2to2_symmetric_fig9_from_rest():
    p = ModelParams(eta=0.2, omega=0.8, F=0.4)          # Fig 9: W = 0.8, regime 2:2
    o, dist = _settles_on_map_orbit(p, "LLRR", 1, REST)
    assert o.symmetric and o.stable and o.admissible and dist < AGREE
    # every R impact in (0, pi), every L impact in (pi, 2 pi) (Fig 9 and the paper's text)
    assert np.all(o.phases[[2, 3]] < math.pi) and np.all(o.phases[[0, 1]] > math.pi)
    # the symmetric ansatz alone finds it (no simulation)
    assert any(q.stable and np.allclose(q.states, o.states)
               for q in find_sequence(p, "LLRR", 1, simulation=False))


def test_2to2_asymmetric_from_rest():
    p = ModelParams(eta=0.16, omega=0.86, F=0.3077)
    o, dist = _settles_on_map_orbit(p, "LLRR", 1, REST)
    assert not o.symmetric and o.stable and dist < AGREE


@pytest.mark.parametrize("eta, omega, F, walls", [(0.16, 0.62, 0.4, "LLR"),
                                                   (0.23, 0.74, 0.3077, "LRR")])
def test_2to1_and_mirror_from_rest(eta, omega, F, walls):
    p = ModelParams(eta=eta, omega=omega, F=F)
    o, dist = _settles_on_map_orbit(p, walls, 1, REST)
    assert o.stable and o.admissible and not o.symmetric and dist < AGREE
    _assert_same_spectrum(o.eigenvalues, _strobe_fd_eigenvalues(o))
    # its mirror image is an orbit of the mirror sequence with the same eigenvalues
    mirror = "LRR" if walls == "LLR" else "LLR"
    m = find_sequence(p, mirror, 1, simulation=False, seeds=[o])
    assert any(abs(q.lambda_max - o.lambda_max) < 1e-9 for q in m)


def test_period2_born_at_flip_of_asymmetric_1to1():
    # the asymmetric 1:1 orbit flips between omega 0.758 (-0.997) and 0.76 (-1.048)
    p = ModelParams(eta=0.142, omega=0.765, F=0.2)
    one = next(o for o in find_sequence(p, "LR", 1, simulation=False)
           if o.admissible and not o.symmetric)
    assert not one.stable and np.min(one.eigenvalues.real) < -1.0
    start = state_at(one, 0.0) + 1e-6                    # leaves the unstable 1:1 orbit
    o, dist = _settles_on_map_orbit(p, "LRLR", 2, start, seeds=flip_seeds(one))
    assert o.stable and o.admissible and dist < AGREE
    assert family_name("RLRL", 2) == "LRLR/2" and paper_label("LRLR", 2) == "period-2"


def test_period2_of_2to1_from_rest():
    p = ModelParams(eta=0.16, omega=0.74, F=0.3077)
    o, dist = _settles_on_map_orbit(p, "LLRLLR", 2, REST)
    assert o.stable and dist < AGREE
    _assert_same_spectrum(o.eigenvalues, _strobe_fd_eigenvalues(o))


# --------------------------------------------------------------------------- invariants

def test_repeated_shorter_orbit_is_not_a_solution():
    p = ModelParams(eta=0.55, omega=1.0, F=0.4)
    one = find_sequence(p, "LR", 1, simulation=False)[0]
    twice = np.concatenate([one.flight_times, one.flight_times])
    assert solve_sequence(p, "LRLR", 2, one.states[0], twice) is None


def test_names_and_bad_input():
    assert canonical_walls("RLLR") == "LLRR" and family_name("RRL", 1) == "LRR/1"
    assert paper_label("LLRR", 1) == "2:2" and paper_label("LRR", 1) == "2:1"
    p = ModelParams(eta=0.2, omega=0.8, F=0.4)
    for walls in ("", "LXR", 3, "L" * 65):
        with pytest.raises(ParameterError, match="walls"):
            find_sequence(p, walls, 1)
    for periods in (0, 1.5, "x", 65):
        with pytest.raises(ParameterError, match="periods"):
            find_sequence(p, "LR", periods)
    assert find_sequence(ModelParams(eta=0.2, omega=0.8, F=0.0), "LR", 1) == []


# --------------------------------------------------------------------------- continuation

def test_continuation_locates_the_1to1_flip_and_switches_to_period2():
    from vines.orbits.continuation.one_to_one import continue_branch
    from vines.orbits.continuation.sequence import ContinueSettings, continue_sequence
    p = ModelParams(eta=0.142, omega=0.74, F=0.2)
    one = next(o for o in find_sequence(p, "LR", 1, simulation=False)
           if o.admissible and not o.symmetric)
    br = continue_sequence(p, "LR", 1, "omega", 0.78, orbit=one,
                           settings=ContinueSettings(step=0.002, switch=True))
    flips = [e for e in br.events if e["type"] == "flip"]
    # the 1:1 shooting continuation (independent derivatives: Taylor jets) finds the same flip
    ref = continue_branch("omega", 0.74, 0.78, fixed={"eta": 0.142, "F": 0.2},
                          branch="asymmetric", step=0.002)
    ref_flips = [e["at"] for e in ref.events if e["type"] == "flip"]
    assert len(flips) == 1 == len(ref_flips)
    assert abs(flips[0]["at"] - ref_flips[0]) < 1e-9
    # the period-2 branch born there: LRLR over two periods, |lambda| ~ 1 at its birth,
    # the orbit of find_sequence (the flip test above) where it passes omega = 0.765
    (sub,) = br.switched
    assert (sub.walls, sub.periods) == ("LRLR", 2) and sub.born_at["type"] == "flip"
    assert abs(sub.points[0].lambda_max - 1.0) < 0.05
    near = min(sub.points, key=lambda o: abs(o.params.omega - 0.765))
    q = find_sequence(ModelParams(eta=0.142, omega=0.765, F=0.2), "LRLR", 2,
                      simulation=False, seeds=[near])
    assert any(o.stable and abs(o.lambda_max - 0.6170245573) < 1e-6 for o in q)
    # every point of both branches is a fixed point of its composed maps (the JSON too)
    d = br.to_dict()
    assert d["switched"][0]["walls"] == "LRLR" and d["events"][0]["type"] == "flip"
    assert all(np.isfinite(pt["lambda_max"]) for pt in d["branch"])
