"""Attractor census (vines.attractors): basins, reproducibility and independent checks."""
import json
import math

import numpy as np
import pytest
from conftest import run_vines

import vines
from vines.attractors import census, sample_states
from vines.attractors.census import _same_orbit
from vines.attractors.endstate import EndState
from vines.core.params import ParameterError
from vines.orbits.family.periodic import find_1to1


@pytest.fixture(scope="module")
def acceptance():
    """The issue's point (eta, omega, F) = (0.13, 1, 0.1), default box, 256 states."""
    return census(0.13, 1.0, 0.1, n=256, seed=0)


def _total(c):
    return sum(a.basin_fraction for a in c.attractors) + c.unsettled_fraction


def test_fractions_sum_to_one(acceptance):
    assert _total(acceptance) == pytest.approx(1.0, abs=1e-12)
    assert sum(a.count for a in acceptance.attractors) == 256
    c = census(0.3, 0.9, 0.2, n=24, seed=3)      # two mirror-image 2:1 orbits (and rest)
    assert _total(c) == pytest.approx(1.0, abs=1e-12)
    for a in c.attractors:
        assert a.ci[0] <= a.basin_fraction <= a.ci[1]


def test_acceptance_point(acceptance):
    """1:1 holds most of the basin; chatter is the rest, and from rest reaches 1:1."""
    atts = acceptance.attractors
    one = [a for a in atts if a.regime == "1:1"]
    chat = [a for a in atts if a.regime == "chatter"]
    assert len(one) == 1 and one[0].periodic and one[0].orbit["stable"]
    assert atts[acceptance.from_rest] is one[0]
    assert 0.8 <= one[0].basin_fraction <= 1.0
    # at t_end = 7000 a few states still chatter; more were chattering in their window
    assert len(chat) == 1 and 0.0 < chat[0].basin_fraction <= 0.2
    in_window = one[0].window_regimes.get("chatter", 0) + chat[0].count
    assert 0.03 <= in_window / 256 <= 0.2
    assert one[0].ke_ratio == pytest.approx(0.787, abs=0.005)
    assert 0.3 < chat[0].ke_ratio < 0.5


def test_chatter_is_a_transient_at_the_acceptance_point():
    """Run longer, every state of the same sample ends on the 1:1 orbit."""
    c = census(0.13, 1.0, 0.1, n=256, seed=0, t_end=20000.0, t_transient=17000.0)
    assert [a.regime for a in c.attractors] == ["1:1"] and c.attractors[0].count == 256


def _long_run(eta, omega, F, state0):
    """Exact run without the shortcut from state0 at t = 0 (the section t = k T), window
    [600 T, 1000 T] of whole periods (less 1e-9: the last strobe time must not pass t_end
    by a rounding)."""
    T = 2 * math.pi / omega
    return vines.simulate(eta, omega, F, state0=tuple(state0), t_end=1000 * T - 1e-9,
                          t_transient=600 * T, periodic_shortcut=False)


def test_1to1_equals_map_orbit_and_long_run(acceptance):
    a = next(a for a in acceptance.attractors if a.regime == "1:1")
    orbits = [o for o in find_1to1(0.13, 1.0, 0.1) if o.stable]
    best = min(orbits, key=lambda o: abs(o.dw_L - a.orbit["dw_L"]))
    assert abs(best.dw_L - a.orbit["dw_L"]) <= 1e-8
    assert abs(best.dw_R - a.orbit["dw_R"]) <= 1e-8
    # independent: a long run without the shortcut, started on the section state, over a
    # window of whole periods
    run = _long_run(0.13, 1.0, 0.1, a.section_state)
    assert run.regime == "1:1"
    assert abs(run.ke_ratio - a.ke_ratio) <= 1e-8
    assert abs(run.xmax_m - a.xmax_m) <= 1e-8 * 0.015


def test_period2_orbits_exact_and_grouped_up_to_shifts():
    c = census(0.1, 1.0, 0.4, n=32, seed=0)
    per2 = [a for a in c.attractors if a.period == 2]
    assert len(per2) == 2 and sum(a.count for a in per2) == 32   # a mirror-image pair
    T = 2 * math.pi
    for a in per2:
        run = _long_run(0.1, 1.0, 0.4, a.section_state)
        assert abs(run.ke_ratio - a.ke_ratio) <= 1e-8
        one = run.state_at([600 * T, 601 * T, 602 * T])
        assert np.max(np.abs(one[:, 2] - one[:, 0])) < 1e-8         # period 2 ...
        assert np.max(np.abs(one[:, 1] - one[:, 0])) > 1e-3         # ... not 1


def test_section_match_up_to_whole_period_shift():
    sec = np.array([[0.1, 0.2, 0.3, 0.4], [0.5, -0.6, 0.7, -0.8]])
    a = EndState("orbit", "period-2", 0.2, 1.0, "ok", section=sec, modes=np.zeros(2, int))
    b = EndState("orbit", "period-2", 0.2, 1.0, "ok", section=sec[::-1].copy(),
                 modes=np.zeros(2, int))
    c = EndState("orbit", "period-2", 0.2, 1.0, "ok", section=sec + 1e-4,
                 modes=np.zeros(2, int))
    assert _same_orbit(a, b) and not _same_orbit(a, c)


def test_thread_count_independent():
    one = census(0.3077, 0.9, 0.5, n=32, seed=1, n_threads=1).to_dict()
    two = census(0.3077, 0.9, 0.5, n=32, seed=1, n_threads=2).to_dict()
    assert json.dumps(one) == json.dumps(two)


def test_seed_reproducible_bitwise():
    a, b = sample_states(100, seed=7), sample_states(100, seed=7)
    assert a.tobytes() == b.tobytes()
    assert sample_states(100, seed=8).tobytes() != a.tobytes()
    w = a[:, 0] - a[:, 2]
    assert np.all(np.abs(w) <= 1.0) and np.all(np.abs(a[:, [0, 1, 3]]) <= 1.5)
    assert sample_states(64, 7)[:10].tobytes() == sample_states(10, 7).tobytes()
    x = census(0.13, 1.0, 0.1, n=16, seed=5).to_dict()
    y = census(0.13, 1.0, 0.1, n=16, seed=5).to_dict()
    assert json.dumps(x) == json.dumps(y)


@pytest.mark.parametrize("kw, name", [
    ({"n": 0}, "n"), ({"seed": -1}, "seed"), ({"box": ((0, 1), (0, 1), (-2, 1), (0, 1))}, "box.w"),
    ({"box": ((1, 0), (0, 1), (0, 1), (0, 1))}, "box.z_m"), ({"box": {"q": (0, 1)}}, "box"),
    ({"t_end": 100.0}, "t_transient"),
])
def test_bad_input_api(kw, name):
    with pytest.raises(ParameterError) as err:
        census(0.13, 1.0, 0.1, **kw)
    assert err.value.name == name


def _cli(*args):
    return run_vines("attractors", *args)


def test_cli_json_keys():
    proc = _cli("--eta", "0.13", "--omega", "1", "--F", "0.1", "--n", "8", "--seed", "2",
                "--json")
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert {"attractors", "from_rest", "unsettled_fraction"} <= set(out)
    for a in out["attractors"]:
        assert {"regime", "ke_ratio", "xmax_m", "basin_fraction", "ci", "example_state"} <= set(a)
    assert out["attractors"][out["from_rest"]]["regime"] == "1:1"


@pytest.mark.parametrize("args, flag", [
    (("--n", "0"), "--n"), (("--seed", "x"), "--seed"), (("--threads", "0"), "--threads"),
    (("--t-transient", "9000"), "--t-transient"), (("--bogus",), "--bogus"),
])
def test_cli_bad_input(args, flag):
    proc = _cli("--eta", "0.13", "--omega", "1", "--F", "0.1", *args, "--json")
    assert proc.returncode == 2 and proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and flag in lines[0]
