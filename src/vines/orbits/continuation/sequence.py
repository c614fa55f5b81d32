"""Continuation of an orbit of any wall sequence in eta, omega or F: ``continue_sequence``.

Pseudo-arclength (``arclength.Tracer``) on R(x_0, p) = P_{n-1}∘...∘P_0(x_0) - x_0 -
(0, 0, 0, N T) (4 equations, unknowns x_0 and the parameter p): the state columns of R's
Jacobian are the exact product of the map Jacobians minus I; the parameter column is
exact as well (``map_systems.exact_derivatives``, Taylor jets of the composed flights), or
a central difference with ``_System.derivatives = "differences"`` and where the jets do
not apply (it steers the predictor and the corrector's convergence only: every point is a
root of R to the corrector's tolerance, whatever that column's error). Each
accepted point is classified on the maps (``sequence``: admissibility, eigenvalues).

Events between consecutive points (located along the arclength by ``Tracer.locate`` on the
test function, or ``Tracer.bisect`` on a flag):

| event | test |
|---|---|
| fold | the tangent's parameter component |
| flip | det(B + I), B = J_{n-1} ... J_0 (kept where an eigenvalue lies within 1e-3 of -1) |
| symmetry-breaking | det(B - I) without a fold, on a symmetric orbit |
| branch-point | det(B - I) without a fold, on an asymmetric orbit |
| neimark-sacker | the number of complex eigenvalues outside the unit circle (flag) |
| admissibility-loss | the admissibility flag |

With ``switch`` (``ContinuationSettings``), at every flip point the period-doubled family (the
sequence twice over, twice the periods) is solved just past the flip from
``sequence.flip_seeds`` and continued; at every symmetry-breaking point the asymmetric
orbit born there (one of the mirror pair; the other is its mirror image) is solved just
past the point, on the side where it exists, from ``sequence.pitchfork_seeds`` and
continued, with switching at its own flips (``SequenceBranch.switched``). The 1:1
continuation of ``continuation``/``branches`` is unchanged; this module does not touch it.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ... import progress
from ...core.params import (
    PARAM_NAMES,
    ModelParams,
    ParameterError,
    check_choice,
    check_param,
    check_params_arg,
)
from ..family.family import Family, check_periods, check_walls
from ..family.map_systems import (
    MapSystem,
    exact_derivatives,
    orbit_residual,
    param_columns,
    with_values,
)
from ..family.sequence import (
    SequenceOrbit,
    find_sequence,
    flip_seeds,
    pitchfork_seeds,
    solve_sequence,
)
from ..family.systems import solve
from ..maps.newton import monodromy
from .arclength import Tracer
from .branch import SequenceBranch
from .settings import ContinuationSettings

FLIP_NEAR = 1e-3        # a located flip needs an eigenvalue this close to -1 (not a pole)
#: the default ``max_points`` of ``continue_sequence`` (``continue_branch``'s:
#: ``core.params.MAX_POINTS_DEFAULT``)
MAX_BRANCH_POINTS_DEFAULT = 2000


#: the settings of ``continue_sequence``: one ``ContinuationSettings`` for every family (this
#: name kept for one release)
ContinueSettings = ContinuationSettings


@dataclass(frozen=True)
class _Run:
    """One branch to follow: the family, the parameter interval and the settings (bound to
    the first branch's interval: a switched branch keeps its step)."""

    params: ModelParams         # the starting point
    walls: str
    periods: int
    param: str
    start: float
    stop: float
    settings: ContinuationSettings
    born_at: dict | None = None

    @property
    def lo(self) -> float:
        return min(self.start, self.stop)

    @property
    def hi(self) -> float:
        return max(self.start, self.stop)

    @property
    def step(self) -> float:
        return self.settings.step_size


class _System:
    """R(z), z = (x_0, parameter value), with the flight-time guesses of the last point."""

    def __init__(self, base: ModelParams, param: str, walls: str, periods: int):
        self.base, self.param = base, param
        self.walls, self.periods = walls, periods
        self.fam = Family(walls, periods, False)
        self.s = np.full(len(walls), -1.0)

    def params(self, v) -> ModelParams:
        return with_values(self.base, {self.param: v})

    def residual(self, x0, v):
        got = orbit_residual(self.params(v), self.fam, np.asarray(x0, float), self.s)
        if got is None:
            return None, None
        return got[0], got[1]

    #: the derivative method of the parameter column (``map_systems.DERIVATIVES``)
    derivatives = "jets"

    def __call__(self, z):
        nan = (np.full(4, np.nan), np.full((4, 5), np.nan))
        if self.derivatives == "jets":
            got = self._exact(z)
            if got is not None:
                return got if got[0] is not None else nan
        try:
            R, P = self.residual(z[:4], z[4])
            h = 1e-7 * (1.0 + abs(z[4]))
            Rp, _ = self.residual(z[:4], z[4] + h)
            Rm, _ = self.residual(z[:4], z[4] - h)
        except ParameterError:          # the parameter left its allowed range
            return nan
        if R is None or Rp is None or Rm is None:
            return nan
        Rz = np.empty((4, 5))
        Rz[:, :4] = P - np.eye(4)
        Rz[:, 4] = (Rp - Rm) / (2.0 * h)
        return R, Rz

    def _exact(self, z):
        """(R, R_z) with the exact parameter column (``map_systems.exact_derivatives``);
        (None, None) where R fails, None where the jets do not apply."""
        try:
            p = self.params(z[4])
        except ParameterError:          # the parameter left its allowed range
            return None, None
        x0 = np.asarray(z[:4], float)
        got = orbit_residual(p, self.fam, x0, self.s)
        if got is None:
            return None, None
        R, P, fl = got
        exact = exact_derivatives(p, self.fam, x0, fl)
        if exact is None:
            return None
        Rz = np.empty((4, 5))
        Rz[:, :4] = P - np.eye(4)
        Rz[:, 4] = exact[0][:, param_columns((self.param,))[0]]
        return R, Rz

    def orbit(self, z) -> SequenceOrbit | None:
        """The classified orbit at z (a converged point); updates the flight guesses."""
        p = self.params(z[4])
        o = solve_sequence(p, self.walls, self.periods, z[:4], self.s.copy())
        if o is not None:
            self.s = o.flight_times.copy()
        return o


def _tests(o: SequenceOrbit, t) -> dict:
    B = monodromy(o.jacobians)
    ev = o.eigenvalues
    return {"fold": float(t[4]), "flip": float(np.linalg.det(B + np.eye(4))),
            "branch": float(np.linalg.det(B - np.eye(4))),
            "ns": int(np.sum((np.abs(ev.imag) > 1e-9) & (np.abs(ev) > 1.0))),
            "adm": bool(o.admissible)}


def continue_sequence(params: ModelParams, walls: str, periods: int, param: str, stop, *,
                      orbit: SequenceOrbit | None = None,
                      settings: ContinuationSettings | None = None) -> SequenceBranch:
    """Follow an orbit of ``walls``/``periods`` from ``params`` along ``param`` (eta, omega
    or F) towards ``stop``. ``orbit``: the starting orbit (default: the first of
    ``find_sequence`` at ``params``: stable admissible first). ``settings``
    (``ContinuationSettings`` without param): step, switching and limits (default
    ``max_points``: ``MAX_BRANCH_POINTS_DEFAULT``). Ends when the parameter leaves
    [start, stop], after ``max_points`` points, ``max_inadmissible`` consecutive
    non-admissible points, or when the step cannot be corrected."""
    params = check_params_arg("params", params)
    walls, periods = check_walls(walls), check_periods(periods)
    param = check_choice("param", param, PARAM_NAMES)
    start = getattr(params, param)
    try:
        stop = check_param(param, stop)
    except ParameterError as err:
        raise ParameterError("stop", stop, f"{err.allowed} ({param})") from None
    if stop == start:
        raise ParameterError("stop", stop, f"must differ from the start {param} = {start:g}")
    settings = _check_settings(settings, params, param, stop)
    if orbit is not None and not (isinstance(orbit, SequenceOrbit)
                                  and len(orbit.flight_times) == len(walls)):
        raise ParameterError("orbit", orbit, f"must be None or a SequenceOrbit of {walls}/"
                             f"{periods} (find_sequence)")
    if orbit is None:
        found = find_sequence(params, walls, periods)
        if not found:
            return SequenceBranch(walls=walls, periods=periods, param=param, points=[],
                                  stopped=f"no {walls}/{periods} orbit at start")
        orbit = found[0]
    with progress.task(None, f"{walls}/{periods} branch in {param}", "points"):
        return _trace(_Run(params, walls, periods, param, start, stop, settings), orbit)


def _check_settings(settings, params: ModelParams, param: str,
                    stop: float) -> ContinuationSettings:
    """The settings bound to ``param`` from its value in ``params`` to ``stop``."""
    if settings is None:
        settings = ContinuationSettings()
    if not isinstance(settings, ContinuationSettings) or settings.param is not None:
        raise ParameterError("settings", settings,
                             "must be None or a ContinuationSettings without param")
    fixed = {q: getattr(params, q) for q in PARAM_NAMES if q != param}
    return settings.bound(param, getattr(params, param), stop, fixed,
                          MAX_BRANCH_POINTS_DEFAULT)


def _trace(run: _Run, orbit: SequenceOrbit) -> SequenceBranch:
    sys_ = _System(run.params, run.param, run.walls, run.periods)
    sys_.s = orbit.flight_times.copy()
    sign = 1.0 if run.stop > run.start else -1.0
    z0 = np.concatenate([orbit.states[0], [run.start]])
    step = run.step
    tr = Tracer(sys_, z0, np.array([0, 0, 0, 0, sign]), step, step * 1e-6, step, np.ones(5))
    o = sys_.orbit(z0)
    if o is None:
        return SequenceBranch(walls=run.walls, periods=run.periods, param=run.param,
                              points=[], stopped="the orbit does not converge")
    points, events = [o], []
    stopped = _follow(run, (tr, sys_), points, events)
    for ev in events:
        ev["at"] = float(getattr(ev["_orbit"].params, run.param))
    br = SequenceBranch(walls=run.walls, periods=run.periods, param=run.param, points=points,
                        events=events, stopped=stopped, born_at=run.born_at)
    if run.settings.switch:
        for ev in events:
            sub = _switch(run, ev)
            if sub is not None:
                br.switched.append(sub)
    return br


def _follow(run: _Run, tracing, points: list, events: list) -> str:
    """Step along the branch from points[0], appending points and events; why it
    stopped."""
    tr, sys_ = tracing
    prev = _tests(points[0], tr.t)
    n_bad = 0
    while len(points) < run.settings.max_points:
        st = tr.step()
        if st is None:
            return "step too small (no correction)"
        o = sys_.orbit(st.z1)
        if o is None:
            return "the maps failed at a corrected point"
        cur = _tests(o, st.t1)
        _events(tr, st, sys_, (prev, cur), events, len(points))
        points.append(o)
        progress.advance()
        prev = cur
        n_bad = 0 if o.admissible else n_bad + 1
        if n_bad >= run.settings.max_inadmissible:
            return "admissibility lost for good"
        if not run.lo - 1e-12 <= st.z1[4] <= run.hi + 1e-12:
            return "left the interval"
    return "max_points"


def _event(typ, o: SequenceOrbit, index: int) -> dict:
    p = o.params
    return {"type": typ, "at": None, "eta": p.eta, "omega": p.omega, "F": p.F,
            "index": index, "_orbit": o}


def _events(tr, st, sys_, tests, events, index):
    prev, cur = tests

    def orbit_at(z):
        return sys_.orbit(z) if z is not None else None

    fold = (prev["fold"] > 0) != (cur["fold"] > 0)
    if fold:
        got = tr.locate(st, lambda z, t: float(t[4]), prev["fold"], cur["fold"])
        _add(events, "fold", orbit_at(got[1] if got else None), index, st)
    for key, typ in (("flip", "flip"), ("branch", "branch-point")):     # EVENT_TYPES
        if key == "branch" and fold:
            continue
        if (prev[key] > 0) != (cur[key] > 0):
            o = _symmetry_breaking(sys_, st) if key == "branch" else None
            if o is None:
                got = tr.locate(st, lambda z, t, k=key: _tests(sys_.orbit(z), t)[k]
                                if sys_.orbit(z) is not None else math.nan, prev[key],
                                cur[key])
                o = orbit_at(got[1] if got else None)
            target = -1.0 if key == "flip" else 1.0
            if o is not None and np.min(np.abs(o.eigenvalues - target)) <= FLIP_NEAR:
                _add(events, "symmetry-breaking" if o.symmetric and key == "branch" else typ,
                     o, index, st)
    for key, typ in (("ns", "neimark-sacker"), ("adm", "admissibility-loss")):
        if prev[key] != cur[key]:
            after, _ = tr.bisect(st, lambda z, t, k=key: _flag(sys_, z, t, k), prev[key])
            _add(events, typ, orbit_at(after[1]), index, st)
    sys_.orbit(st.z1)                   # flight guesses back at the accepted point


def _symmetry_breaking(sys_, st) -> SequenceOrbit | None:
    """The symmetry-breaking point within a step between symmetric orbits, solved as the
    square system of ``map_systems.MapSystem`` (half-map eigenvalue -1, regular there,
    where the bordered system of the full residual is singular), or None."""
    o1 = sys_.orbit(st.z1)
    if o1 is None or not o1.symmetric:
        return None
    fam = Family(sys_.walls, sys_.periods, True)
    system = MapSystem(sys_.params(st.z1[4]), fam, "symmetry-breaking", (sys_.param,))
    z = solve(system, st.z1)
    if z is None or not min(st.z0[4], st.z1[4]) <= z[4] <= max(st.z0[4], st.z1[4]):
        return None
    return solve_sequence(sys_.params(z[4]), sys_.walls, sys_.periods, z[:4],
                          system.flights(z))


def _flag(sys_, z, t, key):
    o = sys_.orbit(z)
    return None if o is None else _tests(o, t)[key]


def _add(events, typ, o, index, st):
    if o is None:
        return
    events.append(_event(typ, o, index))


def _switch(run: _Run, ev: dict) -> SequenceBranch | None:
    """The branch born at a flip (period-doubled) or symmetry-breaking point (asymmetric),
    or None (another event, or nothing found on either side)."""
    if ev["type"] == "flip":
        return _switch_onto(run, ev, _doubled)
    if ev["type"] == "symmetry-breaking":
        return _switch_onto(run, ev, _asymmetric)
    return None


def _doubled(p: ModelParams, base: SequenceOrbit):
    """The period-doubled orbit near ``base`` just past a flip, or None."""
    found = find_sequence(p, base.walls * 2, base.periods * 2, simulation=False,
                          seeds=flip_seeds(base, eps=(1e-4, 1e-3, 1e-2)))
    return found[0] if found else None


def _asymmetric(p: ModelParams, base: SequenceOrbit):
    """The asymmetric orbit nearest the symmetric ``base`` just past a symmetry-breaking
    point, from ``pitchfork_seeds``, or None."""
    found = [solve_sequence(p, base.walls, base.periods, x0, fl)
             for x0, fl in pitchfork_seeds(base, eps=(1e-3, 1e-2, 5e-2))]
    asym = [o for o in found if o is not None and not o.symmetric]
    if not asym:
        return None
    return min(asym, key=lambda o: float(np.linalg.norm(o.states[0] - base.states[0])))


def _switch_onto(run: _Run, ev: dict, born) -> SequenceBranch | None:
    """The branch ``born(p, base)`` just past the event (first side where it exists),
    continued to the interval's end on that side."""
    o = ev["_orbit"]
    at = ev["at"]
    for d in (1.0, -1.0):
        v = at + d * 0.05 * run.step
        if not run.lo <= v <= run.hi:
            continue
        p = with_values(o.params, {run.param: v})
        base = solve_sequence(p, run.walls, run.periods, o.states[0], o.flight_times)
        if base is None:
            continue
        new = born(p, base)
        if new is not None:
            child = _Run(p, new.walls, new.periods, run.param, v, run.hi if d > 0 else run.lo,
                         dataclasses.replace(run.settings, switch=born is _asymmetric),
                         born_at={k: ev[k] for k in ("type", "at", "eta", "omega", "F")})
            return _trace(child, new)
    return None
