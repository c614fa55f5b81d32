"""The one continuation loop of every family: ``Follower`` steps an ``arclength.Tracer``
along a branch, classifies each accepted point, compares the test functions of consecutive
points, locates the events between them, inserts and records them, ends the branch and
switches onto the branches born at its branch points.

What differs per family is a ``Problem``: its system R(z) with Jacobian (the tracer's
``fun``), the orbit at z, its test functions, how an event is located, where its point
goes, whether it is kept and whether it ends the branch, the stop messages and how a
branch point is switched onto. The 1:1 family gives ``follower.OneToOneProblem`` (shooting
on Taylor jets), every wall sequence ``sequence.SequenceProblem`` (the impact maps).

One step of ``Follower.run``:

1. ``Tracer.step``; no step: the branch ends (``stops["min_step"]``);
2. the orbit at the new point (``Problem.orbit``); none: ``Problem.no_orbit`` ends it;
3. its test values (``Problem.tests``); for each key of the test values whose event lies
   between the two points (``Problem.changes``), the event ``located`` on the step (a
   ``Found`` or None); in the problem's ``order``, each is ``placed`` (its branch point,
   inserted or not), recorded (``Problem.event``: the event dict, or None when not kept)
   and may end the branch (``Problem.ends``);
4. the point is appended; the branch ends after ``max_points`` points, after
   ``max_inadmissible`` consecutive non-admissible points or where ``Problem.after_point``
   says so (the 1:1 branch closed; a wall sequence left its interval).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ... import progress
from .arclength import Step, Tracer


@dataclass
class Found:
    """An event located on a step: tau (arclength from the step's start), its type, the
    point (z, t), and what the problem attached (the orbit there, a point next to it)."""

    tau: float
    type: str
    z: np.ndarray | None
    t: np.ndarray | None
    orbit: object = None
    near: tuple | None = None


class Problem:
    """What one family gives the loop (the defaults: events in the order located, no
    work after a step's events, no point ends the branch, no switching).

    stops             the stop messages: "start", "max_points", "min_step",
                      "inadmissible" (``str.format`` with max_points, max_inadmissible)
    count_start       whether a non-admissible start point counts towards
                      ``max_inadmissible``
    """

    stops: dict
    count_start: bool = True

    def orbit(self, z: np.ndarray):
        """The classified orbit at z, or None."""
        raise NotImplementedError

    def tests(self, o, z: np.ndarray, t: np.ndarray) -> dict:
        """The test values at the point z (tangent t) with orbit o."""
        raise NotImplementedError

    def changes(self, prev: dict, cur: dict) -> list:
        """The keys of the test values whose events lie between two points, in the order
        they are located."""
        raise NotImplementedError

    def locate(self, fw: Follower, key: str, st: Step, prev: dict, cur: dict) -> Found | None:
        """The event of ``key`` on the step, or None."""
        raise NotImplementedError

    def order(self, found: list) -> list:
        return found

    def place(self, fw: Follower, f: Found, s: float):
        """The orbit of the event's branch point (appended to the branch, or not), or None
        (no event); s: the arclength at the step's start."""
        raise NotImplementedError

    def event(self, fw: Follower, f: Found, o) -> dict | None:
        """The event record, or None where the event is not kept."""
        raise NotImplementedError

    def ends(self, f: Found, ev: dict | None) -> str | None:
        """Why the branch ends at this event, or None."""
        return None

    def after_events(self, st: Step) -> None:
        """Work after a step's events (before its point is appended)."""

    def no_orbit(self, fw: Follower, st: Step, s: float) -> str:
        """Why the branch ends where the corrected point has no orbit."""
        raise NotImplementedError

    def after_point(self, fw: Follower, st: Step) -> str | None:
        """Why the branch ends after this step's point, or None."""
        return None

    def switch(self, ev: dict):
        """The branch switched onto at this event, or None."""
        return None


class Follower:
    """One branch continuation: its points (parameter values, orbits, arclengths), events
    and why it stopped (module docstring)."""

    def __init__(self, problem: Problem, tracer: Tracer, max_points: int,
                 max_inadmissible: int) -> None:
        self.problem, self.tr = problem, tracer
        self.max_points, self.max_inadmissible = max_points, max_inadmissible
        self.values, self.points, self.arc, self.events = [], [], [], []
        self.stopped = "done"

    def add(self, z: np.ndarray, t: np.ndarray, s: float):
        """Append the orbit at z (arclength s) and return it, or None where there is none."""
        o = self.problem.orbit(z)
        if o is not None:
            self._append(z, o, s)
        return o

    def _append(self, z, o, s: float) -> None:
        self.values.append(float(z[-1]))
        self.points.append(o)
        self.arc.append(s)

    def _stop(self, key: str) -> None:
        self.stopped = self.problem.stops[key].format(
            max_points=self.max_points, max_inadmissible=self.max_inadmissible)

    def run(self) -> None:
        """Follow the branch until it ends (module docstring); sets ``stopped``."""
        P, tr = self.problem, self.tr
        o = self.add(tr.z, tr.t, 0.0)
        if o is None:
            self._stop("start")
            return
        prev = P.tests(o, tr.z, tr.t)
        s = 0.0
        n_bad = 0 if o.admissible or not P.count_start else 1
        while True:
            if len(self.points) >= self.max_points:
                self._stop("max_points")
                return
            st = tr.step()
            if st is None:
                self._stop("min_step")
                return
            o = P.orbit(st.z1)
            if o is None:
                self.stopped = P.no_orbit(self, st, s)
                return
            cur = P.tests(o, st.z1, st.t1)
            end = self._events(st, s, prev, cur)
            s += st.h
            if end:
                return
            self._append(st.z1, o, s)
            progress.advance()
            n_bad = 0 if o.admissible else n_bad + 1
            if n_bad >= self.max_inadmissible:
                self._stop("inadmissible")
                return
            why = P.after_point(self, st)
            if why is not None:
                self.stopped = why
                return
            prev = cur

    def _events(self, st: Step, s: float, prev: dict, cur: dict) -> bool:
        """Locate, place and record the events of one step; True when the branch ends."""
        P = self.problem
        found = []
        for key in P.changes(prev, cur):
            f = P.locate(self, key, st, prev, cur)
            if f is not None:
                found.append(f)
        for f in P.order(found) if found else ():
            o = P.place(self, f, s)
            ev = None if o is None else P.event(self, f, o)
            if ev is not None:
                self.events.append(ev)
            why = P.ends(f, ev)
            if why is not None:
                self.stopped = why
                return True
        P.after_events(st)
        return False

    def switched(self) -> list:
        """The branches switched onto at this branch's events (``Problem.switch``)."""
        out = []
        for ev in self.events:
            sub = self.problem.switch(ev)
            if sub is not None:
                out.append(sub)
        return out
