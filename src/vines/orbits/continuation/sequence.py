"""Continuation of an orbit of any wall sequence in eta, omega or F: ``continue_sequence``.

Pseudo-arclength (``arclength.Tracer``), run by the one loop of every family
(``loop.Follower``) on ``SequenceProblem``, on R(x_0, p) = P_{n-1}∘...∘P_0(x_0) - x_0 -
(0, 0, 0, N T) (4 equations, unknowns x_0 and the parameter p): the state columns of R's
Jacobian are the exact product of the map Jacobians minus I; the parameter column is
exact as well (``map_systems.exact_derivatives``, Taylor jets of the composed flights), or
a central difference with ``_System.derivatives = "differences"`` and where the jets do
not apply (it steers the predictor and the corrector's convergence only: every point is a
root of R to the corrector's tolerance, whatever that column's error). Each
accepted point is classified on the maps (``sequence``: admissibility, eigenvalues).

Events between consecutive points (located along the arclength by ``Tracer.locate`` on the
test function, or ``Tracer.bisect`` on a flag), in this order, each with its orbit solved
at the located point; no point is inserted into the branch (an event's ``index`` is the
point of the step it lies on):

| event | test |
|---|---|
| fold | the tangent's parameter component |
| flip | det(B + I), B = J_{n-1} ... J_0 (kept where an eigenvalue lies within 1e-3 of -1) |
| symmetry-breaking | det(B - I) without a fold, on a symmetric orbit (solved as ``MapSystem``'s symmetry-breaking point where it converges within the step; kept like branch-point) |
| branch-point | det(B - I) without a fold, on an asymmetric orbit (kept where an eigenvalue lies within 1e-3 of +1) |
| neimark-sacker | the number of complex eigenvalues outside the unit circle (flag) |
| admissibility-loss | the admissibility flag |

With ``switch`` (``ContinuationSettings``), at every flip point the period-doubled family (the
sequence twice over, twice the periods) is solved just past the flip from
``sequence.flip_seeds`` and continued; at every symmetry-breaking point the asymmetric
orbit born there (one of the mirror pair; the other is its mirror image) is solved just
past the point, on the side where it exists, from ``sequence.pitchfork_seeds`` and
continued, with switching at its own flips (``SequenceBranch.switched``).

Termination: after the point that left [min(start, stop), max(start, stop)] (kept),
``max_points`` points, ``max_inadmissible`` consecutive non-admissible points (the start
point not counted), or a step that cannot be corrected (smallest step: step * 1e-6).

``method="natural"`` (``ContinuationSettings``): the one natural mode of every family
(``natural.follow_natural``) on ``_NaturalSequence`` instead: parameter steps from start to
stop with ``solve_sequence`` as the corrector, ending at a fold; no switching.
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
from .loop import Follower, Found, Problem
from .natural import NaturalProblem, follow_natural, half_map
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
        """(R, A, flights) of the orbit residual at x0 and the parameter value v, or None
        where a map fails; ParameterError where v left its range."""
        return orbit_residual(self.params(v), self.fam, np.asarray(x0, float), self.s)

    #: the derivative method of the parameter column (``map_systems.DERIVATIVES``)
    derivatives = "jets"

    def __call__(self, z):
        """(R, R_z): R_z's state columns A - I exact (the maps), its parameter column from
        the jets or, where they do not apply, central differences; nan where R fails."""
        nan = (np.full(4, np.nan), np.full((4, 5), np.nan))
        try:
            got = self.residual(z[:4], z[4])
            col = None if got is None else self._param_column(z, got[2])
        except ParameterError:          # the parameter left its allowed range
            return nan
        if col is None:
            return nan
        R, P, _ = got
        Rz = np.empty((4, 5))
        Rz[:, :4] = P - np.eye(4)
        Rz[:, 4] = col
        return R, Rz

    def _param_column(self, z, fl):
        """dR/d(parameter) at z (maps' flight times fl): exact
        (``map_systems.exact_derivatives``) with ``derivatives = "jets"`` where the jets
        apply, else a central difference; None where a map fails."""
        if self.derivatives == "jets":
            exact = exact_derivatives(self.params(z[4]), self.fam, np.asarray(z[:4], float),
                                      fl)
            if exact is not None:
                return exact[0][:, param_columns((self.param,))[0]]
        h = 1e-7 * (1.0 + abs(z[4]))
        plus, minus = self.residual(z[:4], z[4] + h), self.residual(z[:4], z[4] - h)
        if plus is None or minus is None:
            return None
        return (plus[0] - minus[0]) / (2.0 * h)

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


class SequenceProblem(Problem):
    """A wall sequence's part of the one loop (``loop.Follower``; module docstring): the
    events of one step in a fixed order (fold, flip, branch point, neimark-sacker,
    admissibility), each with the orbit solved at its located point; no point is inserted
    (an event's ``index`` is the step's point); the branch ends after the point that left
    [lo, hi]. Switching: the period-doubled branch at each flip, the asymmetric one at each
    symmetry-breaking point (``_switch``)."""

    stops = {"start": "the orbit does not converge", "max_points": "max_points",
             "min_step": "step too small (no correction)",
             "inadmissible": "admissibility lost for good"}
    count_start = False

    def __init__(self, system: _System, run: _Run) -> None:
        self.sys, self.run = system, run
        self.orbit = system.orbit

    def tests(self, o, z, t) -> dict:
        return _tests(o, t)

    def changes(self, prev, cur) -> list:
        fold = (prev["fold"] > 0) != (cur["fold"] > 0)
        out = ["fold"] if fold else []
        for key in ("flip", "branch"):
            if (key != "branch" or not fold) and (prev[key] > 0) != (cur[key] > 0):
                out.append(key)
        return out + [key for key in ("ns", "adm") if prev[key] != cur[key]]

    def _at(self, z):
        return self.sys.orbit(z) if z is not None else None

    def locate(self, fw, key, st, prev, cur):
        tr, sys_ = fw.tr, self.sys
        if key in ("ns", "adm"):
            after, _ = tr.bisect(st, lambda z, t: self._flag(z, t, key), prev[key])
            typ = "neimark-sacker" if key == "ns" else "admissibility-loss"
            return Found(after[0], typ, after[1], after[2], orbit=self._at(after[1]))
        if key == "fold":
            got = tr.locate(st, lambda z, t: float(t[4]), prev[key], cur[key])
            return Found(math.nan, key, None, None, orbit=self._at(got[1] if got else None))
        o = _symmetry_breaking(sys_, st) if key == "branch" else None
        if o is None:
            got = tr.locate(st, lambda z, t: _tests(sys_.orbit(z), t)[key]
                            if sys_.orbit(z) is not None else math.nan, prev[key], cur[key])
            o = self._at(got[1] if got else None)
        typ = "flip" if key == "flip" else "branch-point"
        if o is not None and o.symmetric and key == "branch":
            typ = "symmetry-breaking"
        return Found(math.nan, typ, None, None, orbit=o)

    def _flag(self, z, t, key):
        o = self.sys.orbit(z)
        return None if o is None else _tests(o, t)[key]

    def place(self, fw, f, s):
        return f.orbit

    def event(self, fw, f, o):
        if f.type in ("flip", "branch-point", "symmetry-breaking"):
            # kept where an eigenvalue lies next to -1 (flip) or +1: no pole
            target = -1.0 if f.type == "flip" else 1.0
            if np.min(np.abs(o.eigenvalues - target)) > FLIP_NEAR:
                return None
        p = o.params
        return {"type": f.type, "at": float(getattr(p, self.run.param)), "eta": p.eta,
                "omega": p.omega, "F": p.F, "index": len(fw.points), "_orbit": o}

    def after_events(self, st):
        self.sys.orbit(st.z1)           # flight guesses back at the accepted point

    def no_orbit(self, fw, st, s) -> str:
        return "the maps failed at a corrected point"

    def after_point(self, fw, st):
        run = self.run
        if not run.lo - 1e-12 <= st.z1[4] <= run.hi + 1e-12:
            return "left the interval"
        return None

    def switch(self, ev):
        return _switch(self.run, ev)


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
    if settings.method == "natural" and settings.switch:
        raise ParameterError("switch", settings.switch,
                             "must be False with method natural (switching needs arclength)")
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
    run = _Run(params, walls, periods, param, start, stop, settings)
    if settings.method == "natural":
        return _natural(run, orbit)
    with progress.task(None, f"{walls}/{periods} branch in {param}", "points"):
        return _trace(run, orbit)


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
    fw = Follower(SequenceProblem(sys_, run), tr, run.settings.max_points,
                  run.settings.max_inadmissible)
    fw.run()
    if not fw.points:
        return SequenceBranch(walls=run.walls, periods=run.periods, param=run.param,
                              points=[], stopped=fw.stopped)
    br = SequenceBranch(walls=run.walls, periods=run.periods, param=run.param,
                        points=fw.points, events=fw.events, stopped=fw.stopped,
                        born_at=run.born_at)
    if run.settings.switch:
        br.switched.extend(fw.switched())
    return br


class _NaturalSequence(NaturalProblem):
    """A wall sequence's part of the natural mode (``natural.follow_natural``): the unknowns
    (x_0 with its impact time unwrapped towards the guess, the n flight times), the
    corrector ``solve_sequence``, the half map from the orbit's map Jacobians."""

    def __init__(self, run: _Run) -> None:
        self.run = run

    def params(self, value: float) -> ModelParams:
        return with_values(self.run.params, {self.run.param: value})

    def solve(self, value: float, x: np.ndarray):
        p = self.params(value)
        o = solve_sequence(p, self.run.walls, self.run.periods, x[:4], x[4:])
        return None if o is None else (o, _unknowns(o, x[3], p.period))

    def jumped(self, o: SequenceOrbit, x_pred: np.ndarray, value: float) -> bool:
        jump = float(np.max(np.abs(o.flight_times - x_pred[4:])))
        return jump > 0.25 * self.params(value).period

    def half_map(self, value: float, o: SequenceOrbit) -> np.ndarray | None:
        return half_map(o.jacobians) if o.symmetric else None

    def event(self, typ: str, at: float, index: int, o: SequenceOrbit) -> dict:
        p = self.params(at)
        return {"type": typ, "at": float(at), "eta": p.eta, "omega": p.omega, "F": p.F,
                "index": index, "_orbit": o}


def _unknowns(o: SequenceOrbit, t_guess: float, T: float) -> np.ndarray:
    """(x_0, flight times) of o, its impact time shifted by whole periods T towards
    t_guess."""
    x = np.concatenate([o.states[0], o.flight_times])
    x[3] += round((t_guess - x[3]) / T) * T
    return x


def _natural(run: _Run, orbit: SequenceOrbit) -> SequenceBranch:
    """Natural-parameter continuation from ``orbit`` (solved again at the start)."""
    prob = _NaturalSequence(run)
    got = prob.solve(run.start, np.concatenate([orbit.states[0], orbit.flight_times]))
    if got is None:
        return SequenceBranch(walls=run.walls, periods=run.periods, param=run.param,
                              points=[], stopped=SequenceProblem.stops["start"])
    cs = run.settings
    with progress.task(abs(run.stop - run.start),
                       f"{run.walls}/{run.periods} branch in {run.param}", run.param):
        pts, events, stopped = follow_natural(prob, run.start, run.stop, run.step,
                                              cs.min_step, cs.event_tol, *got)
    return SequenceBranch(walls=run.walls, periods=run.periods, param=run.param,
                          points=[o for _, o, _ in pts], events=events, stopped=stopped)


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
