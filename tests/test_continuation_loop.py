"""The one continuation loop (``continuation.loop.Follower``): its contract on a curve known
in closed form (the unit circle), and the branches of every family it follows (LR/1
symmetric and asymmetric on shooting, LLRR/1 and LRLR/2 on the maps): the events sit where
a multiplier crosses the unit circle, the branches switched onto are the families born
there, each branch ends for its reason."""
from types import SimpleNamespace

import numpy as np
import pytest

from vines.core.params import ModelParams
from vines.orbits.continuation.arclength import Tracer
from vines.orbits.continuation.loop import Follower, Found, Problem
from vines.orbits.continuation.one_to_one import continue_branch
from vines.orbits.continuation.sequence import ContinueSettings, continue_sequence
from vines.orbits.family.sequence import find_sequence

# --------------------------------------------------------------------------- the contract


def circle(z):
    """R(x, p) = x^2 + p^2 - 1: the unit circle, folds in p at (0, +-1)."""
    return np.array([z[0] ** 2 + z[1] ** 2 - 1.0]), np.array([[2.0 * z[0], 2.0 * z[1]]])


class Circle(Problem):
    """The fold test d(p)/ds and two level tests p - a, p - b; events inserted in arclength
    order; the branch ends once it comes back to its start."""

    stops = {"start": "no start", "max_points": "at most {max_points}",
             "min_step": "no step", "inadmissible": "bad for {max_inadmissible}"}

    def __init__(self, levels=(), valid=lambda z: True, admissible=lambda z: True,
                 count_start=True, ending=None):
        self.levels, self.valid, self.admissible = dict(levels), valid, admissible
        self.keys = ("fold",) + tuple(self.levels)
        self.count_start, self.ending = count_start, ending

    def orbit(self, z):
        if not self.valid(z):
            return None
        return SimpleNamespace(admissible=self.admissible(z), z=np.array(z))

    def tests(self, o, z, t):
        return {"fold": t[-1], **{k: z[-1] - a for k, a in self.levels.items()}}

    def changes(self, prev, cur):
        return [k for k in self.keys if (prev[k] > 0) != (cur[k] > 0)]

    def locate(self, fw, key, st, prev, cur):
        def test(z, t):
            return self.tests(None, z, t)[key]

        got = fw.tr.locate(st, test, prev[key], cur[key])
        return None if got is None else Found(*got[:1], key, *got[1:])

    def order(self, found):
        return sorted(found, key=lambda f: f.tau)

    def place(self, fw, f, s):
        return fw.add(f.z, f.t, s + f.tau)

    def event(self, fw, f, o):
        return {"type": f.type, "z": f.z, "index": len(fw.points) - 1}

    def ends(self, f, ev):
        return "ended" if f.type == self.ending else None

    def no_orbit(self, fw, st, s):
        return "no orbit"

    def after_point(self, fw, st):
        back = len(fw.points) > 5 and np.linalg.norm(st.z1 - [1.0, 0.0]) < 0.5 * fw.tr.h
        return "closed" if back else None

    def switch(self, ev):
        return ("born at", ev["type"]) if ev["type"] == "fold" else None


def follow(problem, h=0.1, h_min=1e-6, max_points=1000, max_inadmissible=1000):
    tr = Tracer(circle, [1.0, 0.0], [0.0, 1.0], h, h_min, h)
    fw = Follower(problem, tr, max_points, max_inadmissible)
    fw.run()
    return fw


def test_the_loop_follows_the_circle_through_both_folds_and_closes():
    fw = follow(Circle())
    assert fw.stopped == "closed"
    z = np.array([o.z for o in fw.points])
    assert len(z) > 60 and np.abs(np.hypot(*z.T) - 1.0).max() < 1e-10
    assert [e["type"] for e in fw.events] == ["fold", "fold"]
    # the folds of the circle: (0, 1) then (0, -1), their points inserted where located
    # (the locator's 1e-10 in arclength: x to that, p to its square)
    for ev, p in zip(fw.events, (1.0, -1.0), strict=True):
        assert abs(ev["z"][0]) < 1e-9 and abs(ev["z"][1] - p) < 1e-12
        assert fw.values[ev["index"]] == ev["z"][1]
    assert np.all(np.diff(fw.arc) >= 0.0) and fw.arc[-1] == pytest.approx(2 * np.pi, rel=1e-2)
    assert fw.switched() == [("born at", "fold"), ("born at", "fold")]


def test_events_of_one_step_are_placed_in_the_problems_order():
    # p = 0.25 and p = 0.2 within the first step of 0.5: located in key order, placed by tau
    fw = follow(Circle(levels={"a": 0.25, "b": 0.2}), h=0.5, max_points=3)
    assert [e["type"] for e in fw.events] == ["b", "a"]
    assert [fw.values[e["index"]] for e in fw.events] == pytest.approx([0.2, 0.25], abs=1e-12)
    assert fw.values[1:3] == pytest.approx([0.2, 0.25], abs=1e-12)


def test_an_event_can_end_the_branch():
    fw = follow(Circle(levels={"a": 0.5}, ending="a"))
    assert fw.stopped == "ended" and fw.values[-1] == pytest.approx(0.5, abs=1e-12)


@pytest.mark.parametrize("problem, kw, stopped, n", [
    (Circle(), dict(max_points=4), "at most 4", 4),
    (Circle(valid=lambda z: z[1] < 0.45), {}, "no orbit", 5),
    (Circle(admissible=lambda z: z[1] < 0.25), dict(max_inadmissible=3), "bad for 3", 6),
    # a non-admissible start counts (the 1:1 family) or not (the wall sequences)
    (Circle(admissible=lambda z: False), dict(max_inadmissible=2), "bad for 2", 2),
    (Circle(admissible=lambda z: False, count_start=False), dict(max_inadmissible=2),
     "bad for 2", 3),
    (Circle(valid=lambda z: z[1] < 0.05), {}, "no start", 0),
])
def test_stop_reasons(problem, kw, stopped, n):
    if stopped == "no start":
        tr = Tracer(circle, [1.0, 0.0], [0.0, 1.0], 0.1, 1e-6, 0.1)
        tr.z = np.array([0.0, 1.0])
        fw = Follower(problem, tr, 10, 10)
        fw.run()
    else:
        fw = follow(problem, **kw)
    assert fw.stopped == stopped and len(fw.points) == n


def test_no_step_ends_the_branch():
    def broken(z):
        R, Rz = circle(z)
        return (R, Rz) if z[1] < 0.45 else (R * np.nan, Rz)

    fw = Follower(Circle(), Tracer(broken, [1.0, 0.0], [0.0, 1.0], 0.1, 1e-3, 0.1), 100, 100)
    fw.run()
    assert fw.stopped == "no step" and max(fw.values) < 0.45


# --------------------------------------------------------------------------- the families

FIXED = {"omega": 1.1, "F": 0.3077}


def _lr_sym():
    """LR/1-sym on shooting: the symmetry-breaking point near eta 0.1496 and the asymmetric
    branch born there."""
    return continue_branch("eta", 0.145, 0.155, 0.001, FIXED, switch=True)


def _lr_asym():
    """LR/1-asym on shooting: its flip near omega 0.758."""
    return continue_branch("omega", 0.74, 0.78, 0.002, {"eta": 0.142, "F": 0.2},
                           branch="asymmetric")


def _switching(p, walls, stop, pick):
    """The branch in omega from the first orbit of ``walls``/1 at p that ``pick`` takes,
    with switching."""
    orbit = next(o for o in find_sequence(p, walls, 1, simulation=False) if pick(o))
    return continue_sequence(p, walls, 1, "omega", stop, orbit=orbit,
                             settings=ContinueSettings(step=0.002, switch=True))


def _llrr_sym():
    """LLRR/1-sym on the maps: symmetry-breaking near omega 0.8146, switched onto the
    asymmetric LLRR/1 (which flips, switched onto LLRRLLRR/2)."""
    return _switching(ModelParams(eta=0.2, omega=0.81, F=0.4), "LLRR", 0.83,
                      lambda o: o.symmetric)


def _lrlr():
    """LRLR/2 on the maps: born at the flip of LR/1-asym, flips itself near omega 0.771."""
    (sub,) = _switching(ModelParams(eta=0.142, omega=0.74, F=0.2), "LR", 0.78,
                        lambda o: o.admissible and not o.symmetric).switched
    return sub


def _multipliers(br, ev):
    """The multipliers of the orbit at an event (the branch point located there)."""
    if "_orbit" in ev:
        return ev["_orbit"].eigenvalues
    return br.orbits[ev["index"]].eigenvalues


FAMILY_CASES = {
    # id: (branch, event type, its multiplier, stop reason, the family switched onto)
    # (walls, periods, the families it switches onto in turn)
    "LR/1-sym": (_lr_sym, "symmetry-breaking", 1.0, "left the parameter interval",
                 ("LR", 1, [])),
    "LR/1-asym": (_lr_asym, "flip", -1.0, "left the parameter interval", None),
    # the asymmetric LLRR/1 flips in turn: switched onto the period-doubled LLRRLLRR/2
    "LLRR/1-sym": (_llrr_sym, "symmetry-breaking", 1.0, "left the interval",
                   ("LLRR", 1, [("LLRRLLRR", 2)])),
    "LRLR/2": (_lrlr, "flip", -1.0, "left the interval", None),
}


@pytest.mark.parametrize("name", list(FAMILY_CASES))
def test_every_family_through_the_one_loop(name):
    run, typ, mult, stopped, born = FAMILY_CASES[name]
    br = run()
    assert br.stopped == stopped
    (ev,) = [e for e in br.events if e["type"] == typ]
    # at a located flip / symmetry-breaking point a multiplier of the monodromy matrix is
    # -1 / +1 (the root of the test function to the locator's tolerance)
    assert np.min(np.abs(_multipliers(br, ev) - mult)) < 1e-6
    if born is None:
        return
    (sub,) = br.switched
    assert sub.born_at["type"] == typ and sub.born_at["at"] == ev["at"]
    # one branch type for every family: the asymmetric branch born there
    assert (sub.walls, sub.periods) == born[:2] and not any(o.symmetric for o in sub.orbits)
    assert [(b.walls, b.periods) for b in sub.switched] == born[2]
    # born next to the event (within the first step of 0.001 / 0.002)
    assert abs(getattr(sub.orbits[0].params, sub.param) - ev["at"]) < 0.002


def test_both_engines_locate_the_same_lr_events():
    """The LR/1 family on shooting (Taylor jets) and on the maps (central differences in
    the parameter) through the same loop: the same symmetry-breaking point and flip."""
    sb = [e["at"] for e in _lr_sym().events if e["type"] == "symmetry-breaking"]
    p = ModelParams(eta=0.145, **FIXED)
    sym = next(o for o in find_sequence(p, "LR", 1, simulation=False)
               if o.symmetric and o.admissible)
    seq = continue_sequence(p, "LR", 1, "eta", 0.155, orbit=sym,
                            settings=ContinueSettings(step=0.001))
    assert [e["type"] for e in seq.events] == ["symmetry-breaking"]
    assert seq.events[0]["at"] == pytest.approx(sb[0], abs=1e-9)
    flip = [e["at"] for e in _lr_asym().events if e["type"] == "flip"]
    born = _lrlr().born_at
    assert born["at"] == pytest.approx(flip[0], abs=1e-9)
