"""One JSON shape (``vines.cli.orbit_json``): ``vines periodic``, ``continue`` and
``boundaries`` print the same keys for the 1:1 orbits and with ``--walls``; the old 1:1 keys
are aliases equal to the new ones; the 1:1 output only gains keys (the CLI runs of both
routes are in tests/test_cli_walls.py)."""
import pytest
from conftest import json_paths

from vines.cli import orbit_json as oj
from vines.cli.common import jsonable

PARAMS = {"eta": 0.2, "omega": 1.0, "F": 0.3}
EIG = [[0.5, 0.1], [0.5, -0.1], [0.0, 0.0], [0.0, 0.0]]
#: a 1:1 orbit as ``PeriodicOrbit.to_dict`` gives it, and the same orbit as ``SequenceOrbit``
ONE = {"symmetric": True, "admissible": True, "stable": True, "lambda_max": 0.51,
       "eigenvalues": EIG, "dw_L": 1.5, "dw_R": -1.5, "phase_L": 0.25, "phase_R": 3.39,
       "flight_times": [3.1, 3.2], "x_L": [0.0] * 4, "x_R": [0.0] * 4}
SEQ = {"walls": "LR", "periods": 1, "family": "LR/1", "paper_label": "1:1", "symmetric": True,
       "admissible": True, "stable": True, "lambda_max": 0.51, "eigenvalues": EIG,
       "dw": [1.5, -1.5], "phases": [0.25, 3.39], "flight_times": [3.1, 3.2],
       "states": [[0.0] * 4] * 2}


def test_periodic_both_routes_same_keys_and_values():
    one = oj.periodic_json([ONE], "LR", 1, PARAMS)
    seq = oj.periodic_json([SEQ], "LR", 1, PARAMS)
    assert one == seq
    assert list(one) == ["walls", "periods", "family", "solutions", "params"]
    assert (one["walls"], one["periods"], one["family"]) == ("LR", 1, "LR/1")
    s = one["solutions"][0]
    assert set(s) == set(oj.SOLUTION_KEYS) | {"dw_L", "dw_R", "phase_L", "phase_R"}
    # the aliases are the impacts at L and R of the orbit
    assert (s["dw_L"], s["dw_R"], s["phase_L"], s["phase_R"]) == (1.5, -1.5, 0.25, 3.39)
    assert s["dw"] == [1.5, -1.5] and s["phases"] == [0.25, 3.39]


def test_other_families_carry_no_alias():
    sol = dict(SEQ, walls="LLRR", family="LLRR/1", paper_label="2:2", dw=[1.0, 2.0, -1.0, -2.0],
               phases=[0.1, 0.2, 0.3, 0.4])
    d = oj.periodic_json([sol], "LLRR", 1, PARAMS)
    assert list(d["solutions"][0]) == list(oj.SOLUTION_KEYS)
    assert d["family"] == "LLRR/1" and d["solutions"][0]["paper_label"] == "2:2"


def test_spec_keys_of_the_1to1_orbit_keep_their_values():
    """SPEC section 7 names the 1:1 keys: every one is there with the orbit's value."""
    s = oj.periodic_json([ONE], "LR", 1, PARAMS)["solutions"][0]
    for k in ("symmetric", "admissible", "stable", "lambda_max", "eigenvalues", "dw_L", "dw_R",
              "phase_L", "phase_R", "flight_times"):
        assert s[k] == ONE[k], k


def test_boundaries_both_routes_same_keys():
    curve = {"type": "fold", "family": "symmetric", "points": [[0.1, 0.9], [0.2, 0.95]]}
    plain = {"F": 0.3, "eta_range": [0.1, 0.4], "omega_range": [0.9, 1.2], "curves": [curve]}
    walls = dict(plain, walls="LLRR", periods=1, curves=[dict(curve, family="LLRR/1-sym")])
    a, b = oj.boundaries_json(plain, "LR", 1), oj.boundaries_json(walls, "LLRR", 1)
    assert list(a) == list(b) and json_paths(a) == json_paths(b)
    assert (a["walls"], a["periods"], a["family"]) == ("LR", 1, "LR/1")
    assert {k: a[k] for k in plain} == plain


def _seq_branch(walls="LR", periods=1, switched=()):
    pt = {"eta": 0.142, "omega": 0.75, "F": 0.2, "lambda_max": 0.9, "stable": True,
          "symmetric": False, "admissible": True, "dw": [1.0, -2.0], "phases": [0.5, 3.0],
          "flight_times": [3.0, 4.0]}
    ev = {"type": "flip", "at": 0.758, "eta": 0.142, "omega": 0.758, "F": 0.2, "index": 1}
    return {"walls": walls, "periods": periods, "family": f"{walls}/{periods}",
            "param": "omega", "branch": [pt, dict(pt, omega=0.76)], "events": [ev],
            "stopped": "left the interval", "switched": list(switched)}


def test_branch_of_a_sequence_gains_born_at_meets_and_the_aliases():
    child = dict(_seq_branch("LRLR", 2), born_at={"type": "flip", "at": 0.758, "eta": 0.142,
                                                  "omega": 0.758, "F": 0.2})
    d = oj.branch_json(_seq_branch(switched=[child]))
    assert list(d) == list(oj.BRANCH_KEYS) and d["born_at"] is None
    assert d["events"][0]["meets"] == "LRLR/2" == d["events"][0]["connects"]
    assert all(p["dw_L"] == p["dw"][0] for p in d["branch"])
    sub = d["switched"][0]
    assert sub["born_at"]["at"] == 0.758 and (sub["walls"], sub["periods"]) == ("LRLR", 2)
    assert "dw_L" not in sub["branch"][0] and sub["events"][0]["meets"] is None
    assert "connects" not in sub["events"][0]


def test_natural_mode_events_get_their_point_and_index():
    """A natural-continuation event ({type, at} only) gets the parameter point (the fixed
    parameters of every point, the continued one at ``at``) and the first point past it."""
    br = _seq_branch()
    br["branch"] = [dict(br["branch"][0], omega=w) for w in (0.80, 0.79, 0.78)]
    br["events"] = [{"type": "neimark-sacker", "at": 0.785}, {"type": "fold", "at": 0.78}]
    ev = oj.branch_json(br)["events"]
    assert [e["index"] for e in ev] == [2, 2]
    assert (ev[0]["eta"], ev[0]["omega"], ev[0]["F"]) == (0.142, 0.785, 0.2)
    assert all(list(e) == list(oj.EVENT_KEYS) for e in ev)


def _restrict(new, old):
    """``new`` cut down to the keys of ``old`` (recursively)."""
    if isinstance(old, dict):
        return {k: _restrict(new[k], v) for k, v in old.items()}
    if isinstance(old, list):
        return [_restrict(n, o) for n, o in zip(new, old, strict=True)]
    return new


#: what the shape may add to the 1:1 output (key paths)
ADDED = {"walls", "periods", "born_at", "branch.[].dw", "branch.[].phases", "events.[].meets",
         "switched.[].walls", "switched.[].periods", "switched.[].born_at",
         *(f"switched.[].born_at.{k}" for k in ("type", "at", "eta", "omega", "F")),
         "switched.[].branch.[].dw", "switched.[].branch.[].phases",
         "switched.[].events.[].meets"}


@pytest.fixture(scope="module")
def switched_branch():
    from vines.orbits import continue_branch
    return continue_branch("eta", 0.12, 0.3, 0.02, {"omega": 1.1, "F": 0.3077}, switch=True,
                           max_points=40)


def test_1to1_branch_only_gains_keys(switched_branch):
    """The 1:1 branch of ``vines continue`` is ``Branch.to_dict()`` plus the shape's keys;
    ``dw`` and ``phases`` are the orbits' impacts at L and R."""
    br = switched_branch
    old = jsonable(br.to_dict())
    new = jsonable(oj.branch_json(br))
    assert br.switched and any(e.get("connects") for e in old["events"])
    assert _restrict(new, old) == old
    added = json_paths(new) - json_paths(old)
    assert added <= ADDED and {"walls", "periods", "born_at", "branch.[].dw", "events.[].meets",
                               "switched.[].born_at.at", "switched.[].branch.[].dw"} <= added
    for p, o in zip(new["branch"], br.orbits, strict=True):
        assert p["dw"] == [o.dw_L, o.dw_R] and p["phases"] == [o.phase_L, o.phase_R]
    sb = [e for e in new["events"] if e["type"] == "symmetry-breaking"]
    born = new["switched"][0]["born_at"]
    assert sb[0]["meets"] == "asymmetric" and born["type"] == "symmetry-breaking"
    assert born["at"] == sb[0]["at"]
