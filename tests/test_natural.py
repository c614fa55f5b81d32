"""The natural-parameter continuation of every family (``continuation.natural``) on the wall
sequences LLRR/1-sym and LRLR/2: every point is a fixed point of the composed impact maps
(recomputed here map by map), its events are those the arclength continuation of the same
orbit locates (to the natural mode's ``event_tol``), and a fold ends the natural branch
where the arclength branch turns back (to the natural mode's smallest step)."""
import json

import numpy as np
import pytest
from conftest import json_paths, run_vines

from vines.core.params import ModelParams, ParameterError
from vines.orbits.continuation.sequence import ContinueSettings, continue_sequence
from vines.orbits.family.sequence import find_sequence, flip_seeds
from vines.orbits.maps.impact import apply_map

#: LLRR/1-sym (Fig 9's 2:2 orbits): a fold near omega 0.7911, symmetry-breaking near 0.8146
LLRR = ModelParams(eta=0.2, omega=0.81, F=0.4)
#: LRLR/2, born at the flip of LR/1-asym (omega 0.758), flips itself near omega 0.7711
LRLR = ModelParams(eta=0.142, omega=0.765, F=0.2)
EVENT_TOL = ContinueSettings().event_tol
MIN_STEP = ContinueSettings().min_step
CODES = {"L": 1, "R": -1}


@pytest.fixture(scope="module")
def llrr():
    return next(o for o in find_sequence(LLRR, "LLRR", 1, simulation=False) if o.symmetric)


@pytest.fixture(scope="module")
def lrlr():
    one = next(o for o in find_sequence(LRLR, "LR", 1, simulation=False)
               if o.admissible and not o.symmetric)
    return next(o for o in find_sequence(LRLR, "LRLR", 2, simulation=False,
                                         seeds=flip_seeds(one)) if o.stable)


def _both(orbit, stop, step):
    """The natural and the arclength branch of ``orbit`` in omega to ``stop``."""
    p = orbit.params
    return [continue_sequence(p, orbit.walls, orbit.periods, "omega", stop, orbit=orbit,
                              settings=ContinueSettings(step=step, method=m))
            for m in ("natural", "arclength")]


def _residual(o) -> float:
    """|P_{n-1} ... P_0(x_0) - x_0 - (0, 0, 0, N T)|, the maps applied one by one (each
    flight's impact sought near the orbit's impact time), and the flights' error."""
    p, x = o.params, o.states[0]
    n = len(o.walls)
    err = 0.0
    for k in range(n):
        y, s = apply_map(p, x, CODES[o.walls[k]], CODES[o.walls[(k + 1) % n]],
                         t_guess=x[3] + o.flight_times[k])
        err = max(err, abs(s - o.flight_times[k]))
        x = y
    back = x - o.states[0] - np.array([0.0, 0.0, 0.0, o.periods * p.period])
    return max(err, float(np.abs(back).max()))


def _events(br):
    return [(e["type"], e["at"]) for e in br.events]


@pytest.mark.parametrize("case, stop, step, typ", [
    ("llrr", 0.83, 0.005, "symmetry-breaking"),
    ("lrlr", 0.78, 0.002, "flip"),
])
def test_natural_branch_solves_the_maps_and_meets_the_arclength_events(case, stop, step, typ,
                                                                       request):
    orbit = request.getfixturevalue(case)
    nat, arc = _both(orbit, stop, step)
    assert nat.stopped == "done" and len(nat.points) > 3
    omegas = [o.params.omega for o in nat.points]
    assert omegas[0] == orbit.params.omega and omegas[-1] == stop
    assert np.all(np.diff(omegas) > 0.0)
    # the Newton of solve_sequence stops at ~1e-12; the maps are well conditioned here
    assert max(_residual(o) for o in nat.points) < 1e-9
    # the same event, where the arclength branch locates it (to ~1e-9): the natural one is
    # the middle of a bracket narrower than event_tol
    assert [t for t, _ in _events(nat)] == [t for t, _ in _events(arc)] == [typ]
    assert abs(nat.events[0]["at"] - arc.events[0]["at"]) <= EVENT_TOL
    ev = nat.events[0]
    assert ev["omega"] == ev["at"] and (ev["eta"], ev["F"]) == (orbit.params.eta,
                                                               orbit.params.F)
    assert omegas[ev["index"] - 1] < ev["at"] <= omegas[ev["index"]]


def test_a_fold_ends_the_natural_branch_where_the_arclength_branch_turns(llrr):
    nat, arc = _both(llrr, 0.7, 0.005)
    (fold,) = [e["at"] for e in arc.events if e["type"] == "fold"]
    assert arc.stopped == "left the interval" and fold > 0.7
    assert nat.stopped == "fold or loss of convergence"
    assert [e["type"] for e in nat.events] == ["fold"]
    at = nat.events[0]["at"]
    # at the last converged omega: on the side where the orbits exist, the failed step
    # (< 2 min_step) beyond it
    assert fold - 1e-9 <= at <= fold + 2.0 * MIN_STEP
    assert at == nat.points[-1].params.omega
    assert max(_residual(o) for o in nat.points) < 1e-9


def test_natural_refuses_switching():
    with pytest.raises(ParameterError) as err:
        continue_sequence(LLRR, "LLRR", 1, "omega", 0.83,
                          settings=ContinueSettings(method="natural", switch=True))
    assert err.value.name == "switch"


def test_cli_walls_natural_prints_the_arclength_keys():
    args = ["continue", "--walls", "LLRR", "--periods", "1", "--param", "omega", "--start",
            "0.81", "--stop", "0.83", "--step", "0.005", "--eta", "0.2", "--F", "0.4", "--json"]
    out = {}
    for method in ("natural", "arclength"):
        proc = run_vines(*args, "--method", method)
        assert proc.returncode == 0, proc.stderr
        out[method] = json.loads(proc.stdout)
    assert json_paths(out["natural"]) == json_paths(out["arclength"])
    ev = out["natural"]["events"]
    assert [e["type"] for e in ev] == ["symmetry-breaking"] and ev[0]["meets"] is None


def test_the_lr_family_on_both_engines_gives_one_natural_branch():
    """LR/1-asym by the 1:1 solver (``continue_branch``) and as the wall sequence LR (the
    maps' Newton of ``solve_sequence``): the same points and the same flip (to event_tol)."""
    from vines.orbits.continuation.one_to_one import continue_branch
    p = ModelParams(eta=0.142, omega=0.74, F=0.2)
    one = continue_branch("omega", 0.74, 0.78, 0.002, {"eta": 0.142, "F": 0.2},
                          method="natural", branch="asymmetric")
    orbit = next(o for o in find_sequence(p, "LR", 1, simulation=False)
                 if o.admissible and not o.symmetric)
    seq = continue_sequence(p, "LR", 1, "omega", 0.78, orbit=orbit,
                            settings=ContinueSettings(step=0.002, method="natural"))
    assert [o.params.omega for o in seq.points] == pytest.approx(one.values, abs=1e-12)
    assert [o.lambda_max for o in seq.points] == pytest.approx(one.lambda_max, rel=1e-8)
    assert [e["type"] for e in seq.events] == [e["type"] for e in one.events] == ["flip"]
    assert abs(seq.events[0]["at"] - one.events[0]["at"]) <= EVENT_TOL
