"""The 1:1 family's part of the one continuation loop (``loop.Follower``): its shooting
system ``FamilySystem``, its orbits and test functions, ``OneToOneProblem`` (how its events
are located, placed, kept and end a branch; switching), and ``follow`` / ``switch_at``,
which run the loop (``one_to_one.continue_branch``, method arclength).

The unknowns are those of the family's shooting system (``shooting``) plus the continued
parameter; ``arclength.Tracer`` follows the curve, through folds. Every accepted point is
classified on the exact maps (``periodic.classify_orbit``: admissibility, eigenvalues of
J_P2 J_P1). Test functions of consecutive points (A = Mirror J_P1 the half-map of a
symmetric orbit, B = J_P2 J_P1):

    fold                 d(param)/d(arclength) (the tangent's parameter component)
    symmetry-breaking    det(A + I) (symmetric); s1 - s2 (asymmetric: the branch reaches
                         the symmetric branch, where it ends: the mirror pair counts once)
    flip                 det(B + I) (asymmetric; on symmetric orbits -1 is not generic)
    neimark-sacker       det(A (x) A - I) resp. det(B (x) B - I) (second compound matrix:
                         products of eigenvalue pairs = 1), kept when a complex pair sits
                         on the unit circle (not a real reciprocal pair)
    admissibility-loss   the admissibility flag (either direction)

A sign change between two points (of finite values) is located along the arclength
(``Tracer.locate``) and kept where the test function is small there (a sign change
through a pole, where an impact velocity vanishes, is none); the events of a step are
inserted into the branch in arclength order. A change of the admissibility flag is
bisected (``Tracer.bisect``) only to seed the grazing that causes it, which is then solved
with the continued parameter free (``augmented.grazing_point``): at a grazing arrival the
maps have a pole, and the bisection alone stops where the corrector fails near it. There
the inserted branch point is the bisected one next to the event (the maps are undefined
at the event); the event's parameters are the solved ones.

Termination: the parameter leaves [min(start, stop), max(start, stop)] (the crossing is
located and kept), the branch closes on itself, ``max_inadmissible`` consecutive points are
non-admissible (a non-admissible start point counts), ``max_points`` points, the
asymmetric branch reaches the symmetric one, or the step falls below ``min_step``.

``switch_direction`` gives the start of the asymmetric branch born at a symmetry-breaking
point of the symmetric branch (``switch_at``, ``OneToOneProblem.switch``): the null vector
of the asymmetric system's Jacobian there that is not the symmetric branch's tangent.
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ... import progress
from ...core.params import ModelParams, ParameterError
from ...core.walls import WALL_L, WALL_R
from ..family.augmented import Codim1System, grazing_point
from ..family.family import MIRROR_MATRIX
from ..family.periodic import PeriodicOrbit, classify_orbit
from ..family.systems import compound2, solve
from ..jets import shooting as sh
from ..maps.impact import impact_map, model_array
from .arclength import Step, Tracer
from .branch import Branch, make_branch
from .loop import Follower, Found, Problem
from .settings import ContinuationSettings

TESTS = {"symmetric": ("fold", "symmetry-breaking", "neimark-sacker"),
         "asymmetric": ("fold", "flip", "neimark-sacker", "symmetry-breaking")}
NS_LOCATE_TOL = 1e-3   # |(|lambda| - 1)| of the complex pair at a located neimark-sacker


class FamilySystem:
    """The shooting system of one family with one free parameter: z = (u, param)."""

    def __init__(self, model: sh.Model, family: str, param: str, fixed: dict) -> None:
        self.m, self.family, self.param, self.fixed = model, family, param, dict(fixed)

    def par(self, z: np.ndarray) -> dict:
        p = dict(self.fixed)
        p[self.param] = float(z[-1])
        return p

    def __call__(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return sh.residual_jacobian(self.m, self.family, z[:-1], self.par(z), (self.param,))

    def params(self, z: np.ndarray) -> ModelParams:
        p = self.par(z)
        return ModelParams(eta=p["eta"], omega=p["omega"], F=p["F"], r=self.m.r, d=self.m.d,
                           phi=self.m.phi)

    def orbit(self, z: np.ndarray) -> PeriodicOrbit | None:
        """The orbit at z; None where the maps fail or a step left the valid parameters."""
        try:
            return orbit_at(self.params(z), self.family, z[:-1])
        except ParameterError:
            return None


def orbit_at(p: ModelParams, family: str, u: ArrayLike) -> PeriodicOrbit | None:
    """The PeriodicOrbit of shooting unknowns u (maps, admissibility, eigenvalues)."""
    mdl = model_array(p)
    x = np.array(u[:4], dtype=float)
    s1, s2 = sh.flight_times(family, u, p.omega)
    xR, y2 = np.empty(4), np.empty(4)
    J1, J2 = np.empty((4, 4)), np.empty((4, 4))
    f1 = impact_map(mdl, x, (WALL_L, WALL_R), s1, xR, J1)
    f2 = impact_map(mdl, xR, (WALL_R, WALL_L), s2, y2, J2)
    if not (math.isfinite(f1) and math.isfinite(f2)):
        return None
    res = float(np.max(np.abs(y2 - x - np.array([0.0, 0.0, 0.0, p.period]))))
    return classify_orbit(p, mdl, x, xR, (J1, J2), np.array([f1, f2]), res)


def test_matrix(family: str, o: PeriodicOrbit) -> np.ndarray:
    """A = Mirror J_P1 (symmetric) or B = J_P2 J_P1 (asymmetric) of a 1:1 orbit."""
    J1, J2 = o.jacobians
    return MIRROR_MATRIX @ J1 if family == "symmetric" else J2 @ J1


def test_values(family: str, o: PeriodicOrbit, z: np.ndarray, t: np.ndarray) -> dict:
    """The test functions of the module docstring at one point."""
    A = test_matrix(family, o)
    if family == "symmetric":
        out = {"symmetry-breaking": np.linalg.det(A + np.eye(4))}
    else:
        out = {"flip": np.linalg.det(A + np.eye(4)),
               "symmetry-breaking": o.flight_times[0] - o.flight_times[1]}
    out["neimark-sacker"] = np.linalg.det(np.array(compound2(A.tolist())) - np.eye(6))
    out["fold"] = float(t[-1])
    return out


def is_ns(family: str, o: PeriodicOrbit, tol: float = NS_LOCATE_TOL) -> bool:
    """A complex eigenvalue pair of A (symmetric) or B on the unit circle."""
    ev = np.linalg.eigvals(test_matrix(family, o))
    k = int(np.argmin(np.abs(np.abs(ev) - 1.0)))
    return abs(ev[k].imag) > 1e-6 and abs(abs(ev[k]) - 1.0) < tol


class OneToOneProblem(Problem):
    """The 1:1 family's part of the one loop (``loop.Follower``; module docstring):
    events located along the arclength with the pole check, the grazing solved, the
    located points inserted into the branch in arclength order; the branch ends where the
    parameter leaves [lo, hi], where it closes, and (asymmetric) on the symmetric branch.
    Switching: the asymmetric branch born at each symmetry-breaking point."""

    stops = {"start": "the start point is no orbit",
             "max_points": "max_points = {max_points} reached",
             "min_step": "step below min_step (singular point or end of the branch)",
             "inadmissible": "admissibility lost for good ({max_inadmissible} points)"}

    def __init__(self, system: FamilySystem, cs: ContinuationSettings,
                 z0: np.ndarray) -> None:
        self.sys, self.cs = system, cs
        self.lo, self.hi = cs.bounds
        self.tr_start = z0.copy()
        self.signs = TESTS[system.family]       # located by their sign changes
        self.orbit = system.orbit

    def tests(self, o, z, t) -> dict:
        out = test_values(self.sys.family, o, z, t)
        out["admissibility-loss"] = o.admissible
        out["bound"] = float(z[-1])
        return out

    def changes(self, prev, cur) -> list:
        out = []
        for key in self.signs:
            fa, fb = prev[key], cur[key]
            if np.isfinite(fa) and np.isfinite(fb) and (fa > 0.0) != (fb > 0.0):
                out.append(key)
        if prev["admissibility-loss"] != cur["admissibility-loss"]:
            out.append("admissibility-loss")
        if cur["bound"] > self.hi or cur["bound"] < self.lo:
            out.append("bound")
        return out

    def _bound(self, p_end):
        return self.hi if p_end > self.hi else self.lo if p_end < self.lo else None

    def locate(self, fw, key, st, prev, cur):
        if key == "bound":
            return self._cross(fw, st)
        if key == "admissibility-loss":
            (tau, z, t), near = self._admissibility(fw, st, prev[key])
            return Found(tau, key, z, t, near=near)
        fa, fb = prev[key], cur[key]

        def test(z, t):
            return self._test(z, t, key)

        loc = fw.tr.locate(st, test, fa, fb)
        if key == "symmetry-breaking" and self.sys.family == "asymmetric":
            loc = self._on_symmetric(st if loc is None else loc)
            return None if loc is None else Found(loc[0], key, loc[1], loc[2])
        # a sign change through a pole (the maps' Jacobians blow up where an impact
        # velocity vanishes) is no event
        if loc is not None and abs(test(loc[1], loc[2])) <= 1e-3 * min(abs(fa), abs(fb)):
            return Found(loc[0], key, loc[1], loc[2])
        return None

    def _cross(self, fw, st) -> Found | None:
        """Where the step crosses the end of [lo, hi] it passes (the parameter set to it)."""
        bound = self._bound(st.z1[-1])
        loc = fw.tr.locate(st, lambda z, t: z[-1] - bound, st.z0[-1] - bound,
                           st.z1[-1] - bound)
        if loc is None:
            return None
        loc[1][-1] = bound
        return Found(loc[0], "bound", loc[1], loc[2])

    def order(self, found):
        return sorted(found, key=lambda f: f.tau)

    def place(self, fw, f, s):
        o = fw.add(f.z, f.t, s + f.tau)
        if o is None and f.type == "admissibility-loss":
            # a grazing arrival: the maps have a pole at the event itself; the branch
            # point is the bisected one next to it (the event keeps the solved values)
            o = fw.add(f.near[1], f.near[2], s + f.near[0])
        return o

    def event(self, fw, f, o):
        typ, z = f.type, f.z
        if typ == "bound" or typ == "neimark-sacker" and not is_ns(self.sys.family, o):
            return None
        p = o.params
        if typ == "admissibility-loss":
            p = self.sys.params(z)          # the solved grazing, also next to a pole
        ev = {"type": typ, "at": float(z[-1]), "eta": p.eta, "omega": p.omega, "F": p.F,
              "index": len(fw.points) - 1, "z": z, "t": f.t}
        if typ == "symmetry-breaking":
            ev["connects"] = "asymmetric" if self.sys.family == "symmetric" else "symmetric"
        return ev

    def ends(self, f, ev):
        if f.type == "bound":
            return "left the parameter interval"
        if ev is not None and f.type == "symmetry-breaking" and self.sys.family == "asymmetric":
            return "reached the symmetric branch (symmetry-breaking)"
        return None

    def no_orbit(self, fw, st, s) -> str:
        """The maps fail at the step's end; where that step crossed an end of the
        parameter interval (e.g. into eta < 0) the crossing point ends the branch."""
        if self._bound(st.z1[-1]) is not None:
            f = self._cross(fw, st)
            if f is not None and fw.add(f.z, f.t, s + f.tau) is not None:
                return "left the parameter interval"
        return "the maps have no root (end of the branch)"

    def after_point(self, fw, st):
        """The branch closed on itself: back within half a step of its start."""
        if len(fw.points) < 5:
            return None
        d = st.z1 - self.tr_start
        T = sh.period(self.sys.params(st.z1).omega)
        d[3] = (d[3] + 0.5 * T) % T - 0.5 * T
        if float(np.sqrt(fw.tr.dot(d, d))) < 0.5 * fw.tr.h:
            return "the branch closed on itself"
        return None

    def _admissibility(self, fw, st: Step, flag0: bool):
        """(tau, z, t) of the admissibility change along a step: the flag is bisected to a
        seed, then the grazing that ends admissibility is solved with the continued
        parameter free (``augmented.grazing_point``); the bisected point when no grazing
        is solved within the step. Returns that and the bisected point where the maps are
        defined."""
        def flag(z, t):
            return bool(getattr(self.sys.orbit(z), "admissible", False))

        after, before = fw.tr.bisect(st, flag, flag0)
        # at a grazing arrival (impact velocity 0) the maps have a pole: the point just
        # on the other side seeds the solve when the maps fail at the first
        seed = after if self.sys.orbit(after[1]) is not None else before
        got = self._grazing(fw.tr, st, seed[1])
        return (seed if got is None else got), seed

    def _grazing(self, tr: Tracer, st: Step, z):
        """The solved grazing near the branch point z, as (tau, z, t) on the step, or None
        (no grazing there, or the solution lies off the step)."""
        p = self.sys.par(z)
        got = grazing_point(self.sys.m, self.sys.family, z[:-1], self.sys.param, p)
        if got is None:
            return None
        zg = np.append(got[1], got[2])
        tau = tr.dot(st.t0, zg - st.z0)
        slack = 1e-6 * st.h
        if not -slack <= tau <= st.h + slack:
            return None
        _, Rz = self.sys(zg)
        return min(max(tau, 0.0), st.h), zg, tr.tangent(Rz, st.t0)

    def _on_symmetric(self, loc):
        """The symmetry-breaking point on the symmetric branch near the located point of
        an asymmetric branch (where the bordered system becomes singular): solved on the
        symmetric family's augmented system; (tau, z as an asymmetric point, t) or None."""
        if isinstance(loc, Step):
            tau, z, t = loc.h, loc.z1, loc.t1
        else:
            tau, z, t = loc
        sys = Codim1System(self.sys.m, "symmetric", "symmetry-breaking", (self.sys.param,),
                           self.sys.fixed)
        zs = solve(sys, np.append(z[:4], z[-1]))
        if zs is None:
            return None
        T = sh.period(self.sys.params(zs).omega)
        return tau, np.concatenate([zs[:4], [0.5 * T, zs[-1]]]), t

    def _test(self, z, t, typ):
        if typ == "fold":
            return float(t[-1])
        o = self.sys.orbit(z)
        if o is None:
            return math.nan
        return test_values(self.sys.family, o, z, t)[typ]

    def switch(self, ev):
        """The asymmetric branch born at a symmetry-breaking point (``switch_at``)."""
        if ev["type"] != "symmetry-breaking":
            return None
        sub = switch_at(self.sys.m, self.cs, ev["z"])
        if sub is not None:
            sub.born_at = ev
        return sub


def follow(model: sh.Model, family: str, cs: ContinuationSettings, z0: np.ndarray,
           direction: np.ndarray | float, switch: bool = False) -> Branch:
    """Continue the branch of ``family`` through z0 = (shooting unknowns, parameter) by
    pseudo-arclength (``loop.Follower`` on ``OneToOneProblem``); returns a ``Branch``,
    with ``switch`` and the asymmetric branches born at its symmetry-breaking points.

    direction: the initial tangent's orientation (a vector of len(z0)), or the sign of the
    parameter's initial change (a number).
    """
    system = FamilySystem(model, family, cs.param, cs.fixed)
    z0 = np.asarray(z0, dtype=float)
    if np.isscalar(direction):
        d = np.zeros(len(z0))
        d[-1] = float(direction)
        direction = d
    tracer = cs.tracer(system, z0, direction)
    f = Follower(OneToOneProblem(system, cs, tracer.z), tracer, cs.max_points,
                 cs.max_inadmissible)
    with progress.task(None, f"{family} branch in {cs.param}", "points"):
        f.run()
    for e in f.events:
        e.pop("t", None)
    br = make_branch(cs.param, list(zip(f.values, f.points, strict=True)), f.events, f.stopped,
                     family=family, arclength=f.arc)
    if switch:
        br.switched.extend(f.switched())
    return br


def switch_at(model: sh.Model, cs: ContinuationSettings, z_sym: np.ndarray) -> Branch | None:
    """The asymmetric branch born at the symmetry-breaking point z_sym of the symmetric
    branch (a ``Branch`` starting one step away from the branch point), or None."""
    z, v = switch_direction(model, cs.param, cs.fixed, z_sym)
    system = FamilySystem(model, "asymmetric", cs.param, cs.fixed)
    tracer = cs.tracer(system, z, v)
    h = cs.step_size
    while h >= cs.min_step:
        got = tracer.correct(z + h * v, v, z, h)
        if got is not None and abs(got[0][4] - z[4]) > 0.1 * h * abs(v[4]):
            break
        h *= 0.5
    else:
        return None
    z1 = got[0]
    return follow(model, "asymmetric", cs, z1, z1 - z)


def start_unknowns(o: PeriodicOrbit, family: str) -> np.ndarray:
    u = list(o.x_L)
    if family == "asymmetric":
        u.append(o.flight_times[0])
    return np.array(u)


def switch_direction(model: sh.Model, param: str, fixed: dict,
                     z_sym: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(z, v): the symmetric point z_sym = (u, param) as an asymmetric-system point and the
    unit direction of the asymmetric branch born there."""
    u = np.asarray(z_sym[:-1], dtype=float)
    p = dict(fixed)
    p[param] = float(z_sym[-1])
    T = sh.period(p["omega"])
    z = np.concatenate([u, [0.5 * T, z_sym[-1]]])
    _, Jz = sh.residual_jacobian(model, "asymmetric", z[:-1], p, (param,))
    V = np.linalg.svd(Jz)[2][-2:]            # the 2-dimensional null space at the branch point
    # the symmetric branch keeps s1 - T/2 = 0: its tangent has d(s1) = d(T/2)/d(param) dp
    dT2 = -0.5 * T / p["omega"] if param == "omega" else 0.0
    c = np.array([0.0, 0.0, 0.0, 0.0, 1.0, -dT2])     # c . v = d(s1 - T/2)
    v = V.T @ (V @ c)
    v /= np.linalg.norm(v)
    return z, v
