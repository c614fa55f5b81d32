"""Continuation of an orbit of any wall sequence in eta, omega or F: ``continue_sequence``.

Pseudo-arclength (``arclength.Tracer``) on R(x_0, p) = P_{n-1}∘...∘P_0(x_0) - x_0 -
(0, 0, 0, N T) (4 equations, unknowns x_0 and the parameter p): the state columns of R's
Jacobian are the exact product of the map Jacobians minus I; the parameter column is a
central difference (it steers the predictor and the corrector's convergence only: every
point is a root of R to the corrector's tolerance, whatever that column's error). Each
accepted point is classified on the maps (``sequence``: admissibility, eigenvalues).

Events between consecutive points (located along the arclength by ``Tracer.locate`` on the
test function, or ``Tracer.bisect`` on a flag):

| event | test |
|---|---|
| fold | the tangent's parameter component |
| flip | det(B + I), B = J_{n-1} ... J_0 (kept where an eigenvalue lies within 1e-3 of -1) |
| branch-point | det(B - I) without a fold (on a symmetric family: symmetry-breaking) |
| neimark-sacker | the number of complex eigenvalues outside the unit circle (flag) |
| admissibility-loss | the admissibility flag |

With ``switch``, at every flip point the period-doubled family (the sequence twice over,
twice the periods) is solved just past the flip from ``sequence.flip_seeds`` and continued
(``SequenceBranch.switched``). The 1:1 continuation of ``continuation``/``branches`` is
unchanged; this module does not touch it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from .. import progress
from ..core.exact import oscillators
from ..core.params import (
    MAX_INADMISSIBLE_DEFAULT,
    MAX_POINTS_MAX,
    PARAM_NAMES,
    ModelParams,
    ParameterError,
    check_bool,
    check_choice,
    check_int,
    check_param,
    check_params_arg,
    check_real,
)
from .arclength import Tracer
from .maps import map_kernel
from .sequence import (
    SequenceOrbit,
    _codes,
    check_periods,
    check_walls,
    find_sequence,
    flip_seeds,
    solve_sequence,
)

FLIP_NEAR = 1e-3        # a located flip needs an eigenvalue this close to -1 (not a pole)
MAX_POINTS_DEFAULT = 2000


@njit(cache=True, nogil=True)
def _chain(osc, eta, r, omega, phi, codes, x0, s_guess, xs, Js, fl):
    """xs[k+1] = P_k(xs[k]) from xs[0] = x0 with flight guesses; False when a map fails."""
    n = codes.size
    for i in range(4):
        xs[0, i] = x0[i]
    for k in range(n):
        s = map_kernel(osc, eta, r, omega, phi, xs[k], codes[k], codes[(k + 1) % n],
                       s_guess[k], xs[k + 1], Js[k])
        if not math.isfinite(s):
            return False
        fl[k] = s
    return True


@dataclass
class SequenceBranch:
    """A continued family: points (orbits with their parameter point), events, why it
    stopped, and the branches switched onto at its flip points."""

    walls: str
    periods: int
    param: str
    points: list
    events: list
    stopped: str
    switched: list = field(default_factory=list)
    born_at: dict | None = None

    def to_dict(self) -> dict:
        pts = []
        for o in self.points:
            p = o.params
            d = o.to_dict()
            pts.append({"eta": p.eta, "omega": p.omega, "F": p.F,
                        **{k: d[k] for k in ("lambda_max", "stable", "symmetric", "admissible",
                                             "dw", "phases", "flight_times")}})
        out = {"walls": self.walls, "periods": self.periods,
               "family": self.points[0].family if self.points else None,
               "param": self.param, "branch": pts,
               "events": [{k: v for k, v in e.items() if k != "_orbit"} for e in self.events],
               "stopped": self.stopped,
               "switched": [b.to_dict() for b in self.switched]}
        if self.born_at is not None:
            out["born_at"] = self.born_at
        return out


class _System:
    """R(z), z = (x_0, parameter value), with the flight-time guesses of the last point."""

    def __init__(self, base: ModelParams, param: str, walls: str, periods: int):
        self.base, self.param = base, param
        self.walls, self.periods = walls, periods
        self.codes = _codes(walls)
        n = len(walls)
        self.s = np.full(n, -1.0)
        self.xs = np.empty((n + 1, 4))
        self.Js = np.empty((n, 4, 4))
        self.fl = np.empty(n)

    def params(self, v) -> ModelParams:
        kw = self.base.as_dict()
        kw[self.param] = float(v)
        return ModelParams(**kw)

    def residual(self, x0, v):
        p = self.params(v)
        osc = oscillators(p)[0]
        ok = _chain(osc, p.eta, p.r, p.omega, p.phi, self.codes, np.asarray(x0, float),
                    self.s, self.xs, self.Js, self.fl)
        if not ok:
            return None, None
        R = self.xs[-1] - self.xs[0]
        R[3] -= self.periods * p.period
        P = self.Js[0]
        for J in self.Js[1:]:
            P = J @ P
        return R, P

    def __call__(self, z):
        nan = (np.full(4, np.nan), np.full((4, 5), np.nan))
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

    def orbit(self, z) -> SequenceOrbit | None:
        """The classified orbit at z (a converged point); updates the flight guesses."""
        p = self.params(z[4])
        o = solve_sequence(p, self.walls, self.periods, z[:4], self.s.copy())
        if o is not None:
            self.s = o.flight_times.copy()
        return o


def _tests(o: SequenceOrbit, t) -> dict:
    B = _monodromy(o)
    ev = o.eigenvalues
    return {"fold": float(t[4]), "flip": float(np.linalg.det(B + np.eye(4))),
            "branch": float(np.linalg.det(B - np.eye(4))),
            "ns": int(np.sum((np.abs(ev.imag) > 1e-9) & (np.abs(ev) > 1.0))),
            "adm": bool(o.admissible)}


def _monodromy(o):
    P = o.jacobians[0]
    for J in o.jacobians[1:]:
        P = J @ P
    return P


def continue_sequence(params: ModelParams, walls: str, periods: int, param: str, stop, *,
                      step=None, orbit: SequenceOrbit | None = None, switch: bool = False,
                      max_points=MAX_POINTS_DEFAULT,
                      max_inadmissible=MAX_INADMISSIBLE_DEFAULT) -> SequenceBranch:
    """Follow an orbit of ``walls``/``periods`` from ``params`` along ``param`` (eta, omega
    or F) towards ``stop``. ``orbit``: the starting orbit (default: the first of
    ``find_sequence`` at ``params``: stable admissible first). ``step``: largest arclength
    step (default |stop - start|/100). Ends when the parameter leaves [start, stop], after
    ``max_points`` points, ``max_inadmissible`` consecutive non-admissible points, or when
    the step cannot be corrected."""
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
    step = abs(check_real("step", step, lo=0.0, lo_open=True)) if step is not None \
        else abs(stop - start) / 100.0
    max_points = check_int("max_points", max_points, lo=2, hi=MAX_POINTS_MAX)
    max_inadmissible = check_int("max_inadmissible", max_inadmissible, lo=1, hi=MAX_POINTS_MAX)
    switch = check_bool("switch", switch)
    if orbit is not None and not (isinstance(orbit, SequenceOrbit)
                                  and len(orbit.flight_times) == len(walls)):
        raise ParameterError("orbit", orbit, f"must be None or a SequenceOrbit of {walls}/"
                             f"{periods} (find_sequence)")
    if orbit is None:
        found = find_sequence(params, walls, periods)
        if not found:
            return SequenceBranch(walls, periods, param, [], [],
                                  f"no {walls}/{periods} orbit at start")
        orbit = found[0]
    with progress.task(None, f"{walls}/{periods} branch in {param}", "points"):
        return _trace(params, walls, periods, param, start, stop, step, orbit, switch,
                      max_points, max_inadmissible)


def _trace(params, walls, periods, param, start, stop, step, orbit, switch, max_points,
           max_inadmissible, born_at=None) -> SequenceBranch:
    sys_ = _System(params, param, walls, periods)
    sys_.s = orbit.flight_times.copy()
    lo, hi = min(start, stop), max(start, stop)
    sign = 1.0 if stop > start else -1.0
    z0 = np.concatenate([orbit.states[0], [start]])
    scale = np.ones(5)
    tr = Tracer(sys_, z0, np.array([0, 0, 0, 0, sign]), step, step * 1e-6, step, scale)
    o = sys_.orbit(z0)
    if o is None:
        return SequenceBranch(walls, periods, param, [], [], "the orbit does not converge")
    points, events = [o], []
    prev = _tests(o, tr.t)
    stopped, n_bad = "max_points", 0
    while len(points) < max_points:
        st = tr.step()
        if st is None:
            stopped = "step too small (no correction)"
            break
        o = sys_.orbit(st.z1)
        if o is None:
            stopped = "the maps failed at a corrected point"
            break
        cur = _tests(o, st.t1)
        _events(tr, st, sys_, prev, cur, events, len(points))
        points.append(o)
        progress.advance()
        prev = cur
        n_bad = 0 if o.admissible else n_bad + 1
        if n_bad >= max_inadmissible:
            stopped = "admissibility lost for good"
            break
        v = st.z1[4]
        if not lo - 1e-12 <= v <= hi + 1e-12:
            stopped = "left the interval"
            break
    for ev in events:
        ev["at"] = float(getattr(ev["_orbit"].params, param))
    br = SequenceBranch(walls, periods, param, points, events, stopped, born_at=born_at)
    if switch:
        for ev in events:
            if ev["type"] == "flip":
                sub = _switch_flip(params, walls, periods, param, ev, lo, hi, step,
                                   max_points, max_inadmissible)
                if sub is not None:
                    br.switched.append(sub)
    return br


def _event(typ, o: SequenceOrbit, index: int) -> dict:
    p = o.params
    return {"type": typ, "at": None, "eta": p.eta, "omega": p.omega, "F": p.F,
            "index": index, "_orbit": o}


def _events(tr, st, sys_, prev, cur, events, index):
    def orbit_at(z):
        return sys_.orbit(z) if z is not None else None

    fold = (prev["fold"] > 0) != (cur["fold"] > 0)
    if fold:
        got = tr.locate(st, lambda z, t: float(t[4]), prev["fold"], cur["fold"])
        _add(events, "fold", orbit_at(got[1] if got else None), index, st)
    for key, typ in (("flip", "flip"), ("branch", "branch-point")):
        if key == "branch" and fold:
            continue
        if (prev[key] > 0) != (cur[key] > 0):
            got = tr.locate(st, lambda z, t, k=key: _tests(sys_.orbit(z), t)[k]
                            if sys_.orbit(z) is not None else math.nan, prev[key], cur[key])
            o = orbit_at(got[1] if got else None)
            target = -1.0 if key == "flip" else 1.0
            if o is not None and np.min(np.abs(o.eigenvalues - target)) <= FLIP_NEAR:
                _add(events, typ, o, index, st)
    for key, typ in (("ns", "neimark-sacker"), ("adm", "admissibility-loss")):
        if prev[key] != cur[key]:
            after, _ = tr.bisect(st, lambda z, t, k=key: _flag(sys_, z, t, k), prev[key])
            _add(events, typ, orbit_at(after[1]), index, st)
    sys_.orbit(st.z1)                   # flight guesses back at the accepted point


def _flag(sys_, z, t, key):
    o = sys_.orbit(z)
    return None if o is None else _tests(o, t)[key]


def _add(events, typ, o, index, st):
    if o is None:
        return
    events.append(_event(typ, o, index))


def _switch_flip(params, walls, periods, param, ev, lo, hi, step, max_points,
                 max_inadmissible) -> SequenceBranch | None:
    """The period-doubled branch just past a flip point, continued to the interval's end
    on that side."""
    o = ev["_orbit"]
    at = ev["at"]
    for d in (1.0, -1.0):
        v = at + d * 0.05 * step
        if not lo <= v <= hi:
            continue
        kw = o.params.as_dict()
        kw[param] = v
        p = ModelParams(**kw)
        base = solve_sequence(p, walls, periods, o.states[0], o.flight_times)
        if base is None:
            continue
        doubled = find_sequence(p, walls * 2, periods * 2, simulation=False,
                                seeds=flip_seeds(base, eps=(1e-4, 1e-3, 1e-2)))
        if doubled:
            stop = hi if d > 0 else lo
            return _trace(p, walls * 2, periods * 2, param, v, stop, step, doubled[0], False,
                          max_points, max_inadmissible,
                          born_at={k: ev[k] for k in ("type", "at", "eta", "omega", "F")})
    return None
