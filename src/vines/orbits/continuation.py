"""Natural-parameter continuation of a 1:1 orbit in eta, omega or F.

Predictor: secant through the last two points (the orbit's x_L with unwrapped impact time
and the flight times, extrapolated linearly in the parameter); corrector: the Newton
iteration of ``vines.periodic`` on P2∘P1. A failed correction halves the step; when the
step falls below ``min_step`` the branch has (almost surely) reached a fold, which is
recorded at the last converged parameter and ends the continuation (no pseudo-arclength:
the branch is not followed around the fold).

Events between consecutive points are located by bisection to ``event_tol`` in the
parameter:

* the number of eigenvalues of J_P2 J_P1 outside the unit circle changes: the crossing
  eigenvalue (the one closest to the unit circle at the located point) gives the type:
  complex pair -> neimark-sacker, real -1 -> flip, real +1 -> fold. On a symmetric orbit
  J_P2 J_P1 = (M J_P1)^2 with M = diag(-1, -1, -1, 1) (the mirror); a +1 crossing whose
  half-map multiplier mu of M J_P1 is -1 is a symmetry-breaking (pitchfork), mu = +1 a fold;
* the admissibility flag changes: admissibility-loss (either direction: a grazing contact);
* the symmetric flag changes: symmetry-breaking.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..core.exact import oscillators
from ..core.walls import WALL_L, WALL_R
from ..core.params import (MAX_POINTS_DEFAULT, MAX_POINTS_MAX, PARAM_NAMES, D_DEFAULT,
                           R_DEFAULT, ModelParams, ParameterError, check_int, check_param,
                           check_real, check_step_points)
from .periodic import PeriodicOrbit, find_1to1, solve_orbit

PARAMS = PARAM_NAMES
EVENT_TYPES = ("fold", "flip", "neimark-sacker", "admissibility-loss", "symmetry-breaking")
MIRROR = np.diag([-1.0, -1.0, -1.0, 1.0])


@dataclass
class Branch:
    """A continued 1:1 branch: one entry per converged point, in continuation order."""

    param: str
    values: np.ndarray
    eta: np.ndarray
    omega: np.ndarray
    F: np.ndarray
    lambda_max: np.ndarray
    abs_eigenvalues: np.ndarray          # (n, 4), sorted decreasing
    stable: np.ndarray
    symmetric: np.ndarray
    admissible: np.ndarray
    dw_L: np.ndarray
    dw_R: np.ndarray
    phase_L: np.ndarray
    phase_R: np.ndarray
    events: list = field(default_factory=list)
    orbits: list = field(default_factory=list, repr=False)
    stopped: str = "done"

    def __len__(self):
        return len(self.values)

    def to_dict(self) -> dict:
        pts = [{"eta": float(self.eta[i]), "omega": float(self.omega[i]), "F": float(self.F[i]),
                "lambda_max": float(self.lambda_max[i]), "stable": bool(self.stable[i]),
                "symmetric": bool(self.symmetric[i]), "admissible": bool(self.admissible[i]),
                "dw_L": float(self.dw_L[i])} for i in range(len(self.values))]
        return {"param": self.param, "branch": pts,
                "events": [{"type": e["type"], "at": float(e["at"])} for e in self.events],
                "stopped": self.stopped}


def _n_outside(o: PeriodicOrbit) -> int:
    return int(np.sum(np.abs(o.eigenvalues) > 1.0))


def _crossing_type(o: PeriodicOrbit, J1=None) -> str:
    ev = o.eigenvalues
    k = int(np.argmin(np.abs(np.abs(ev) - 1.0)))
    lam = ev[k]
    if abs(lam.imag) > 1e-6 * max(1.0, abs(lam)):
        return "neimark-sacker"
    if lam.real < 0.0:
        return "flip"
    if o.symmetric and J1 is not None:
        mu = np.linalg.eigvals(MIRROR @ J1)
        j = int(np.argmin(np.abs(np.abs(mu) - 1.0)))
        if abs(mu[j].imag) < 1e-6 and mu[j].real < 0.0:
            return "symmetry-breaking"
    return "fold"


class _Continuer:
    def __init__(self, param, fixed, r, d, phi):
        self.param = param
        self.fixed = dict(fixed)
        self.r, self.d, self.phi = r, d, phi

    def params(self, value) -> ModelParams:
        kw = dict(self.fixed)
        kw[self.param] = value
        return ModelParams(eta=kw["eta"], omega=kw["omega"], F=kw["F"], r=self.r, d=self.d,
                           phi=self.phi)

    def solve(self, value, x, s1, s2):
        p = self.params(value)
        o = solve_orbit(p, x, s1, s2)
        if o is None:
            return None
        # unwrap t_L towards the prediction
        T = p.period
        k = round((x[3] - o.x_L[3]) / T)
        if k:
            o.x_L[3] += k * T
            o.x_R[3] += k * T
        return o

    def jac1(self, value, o):
        from .maps import map_jacobian
        return map_jacobian(self.params(value), o.x_L, WALL_L, WALL_R,
                            t_guess=o.x_L[3] + o.flight_times[0])


def _state(o):
    return np.concatenate([o.x_L, o.flight_times])


def _predict(v, pts):
    """Secant (or constant) prediction of (x_L, s1, s2) at parameter v from [(v, orbit)]."""
    if len(pts) == 1:
        return _state(pts[-1][1])
    (v0, o0), (v1, o1) = pts[-2], pts[-1]
    a, b = _state(o0), _state(o1)
    if v1 == v0:
        return b
    return b + (b - a) * (v - v1) / (v1 - v0)


def _interp(v, va, oa, vb, ob):
    a, b = _state(oa), _state(ob)
    return a + (b - a) * (v - va) / (vb - va)


def continue_branch(param: str, start, stop, step=None, fixed: dict | None = None,
                    orbit: PeriodicOrbit | None = None, r=R_DEFAULT, d=D_DEFAULT, phi=0.0,
                    min_step=1e-6, event_tol=1e-6,
                    max_points=MAX_POINTS_DEFAULT) -> Branch:
    """Follow a 1:1 orbit from param = start to stop (both included when reached).

    ``fixed`` gives the two other parameters of eta/omega/F (not ``param`` itself).
    ``orbit`` is the starting orbit (default: the preferred orbit of ``find_1to1`` at start:
    stable and admissible first). ``step`` defaults to (stop - start)/100; its sign is taken
    from stop - start. A step that needs more than ``max_points`` points (|stop - start|/step
    > max_points, default 100000, at most 1e7) is refused; ``min_step`` and ``event_tol``
    lie in [1e-12, 1].
    """
    if not isinstance(param, str) or param not in PARAMS:
        raise ParameterError("param", param, "must be one of eta, omega, F")
    fixed = dict(fixed or {})
    if param in fixed:
        raise ParameterError(param, fixed[param],
                             f"must not be fixed when continuing in {param} (it runs from "
                             f"start to stop; fix only {' and '.join(q for q in PARAMS if q != param)})")
    others = [q for q in PARAMS if q != param]
    for q in others:
        if q not in fixed:
            raise ParameterError(q, None, f"is required when continuing in {param}")
    unknown = sorted(set(fixed) - set(others))
    if unknown:
        raise ParameterError("fixed", unknown[0], f"is not a parameter; fix only {' and '.join(others)}")
    start = check_param(param, start)
    try:
        stop = check_param(param, stop)
    except ParameterError as err:
        raise ParameterError("stop", stop, f"{err.allowed} ({param})") from None
    max_points = check_int("max_points", max_points, lo=1, hi=MAX_POINTS_MAX)
    min_step = check_real("min_step", min_step, lo=1e-12, hi=1.0)
    event_tol = check_real("event_tol", event_tol, lo=1e-12, hi=1.0)
    if step is None:
        step = (stop - start) / 100.0 if stop != start else 1.0
    step = abs(check_real("step", step))
    if step == 0.0:
        raise ParameterError("step", step, "must be a number != 0")
    check_step_points(step, abs(stop - start), step, max_points)
    sign = 1.0 if stop >= start else -1.0
    cont = _Continuer(param, {q: fixed[q] for q in others}, r, d, phi)
    p0 = cont.params(start)                 # validates every parameter
    cont.params(stop)
    if orbit is None:
        cands = find_1to1(p0, None, None)
        if not cands:
            return _make_branch(param, [], [], "no 1:1 orbit at start")
        orbit = cands[0]
    else:
        orbit = cont.solve(start, orbit.x_L, *orbit.flight_times)
        if orbit is None:
            return _make_branch(param, [], [], "the given orbit does not converge at start")
    pts = [(start, orbit)]
    events = []
    h = step
    stopped = "done"
    while True:
        v_prev, o_prev = pts[-1]
        if (stop - v_prev) * sign <= 1e-12 * max(1.0, abs(stop)):
            break
        v = v_prev + sign * h
        if (v - stop) * sign > 0.0:
            v = stop
        pred = _predict(v, pts)
        o = cont.solve(v, pred[:4], pred[4], pred[5])
        if o is None or abs(o.flight_times[0] - pred[4]) > 0.25 * cont.params(v).period:
            h *= 0.5
            if h < min_step:
                events.append({"type": "fold", "at": v_prev})
                stopped = "fold or loss of convergence"
                break
            continue
        _locate_events(cont, v_prev, o_prev, v, o, events, event_tol)
        pts.append((v, o))
        h = min(step, 1.5 * h)
    events.sort(key=lambda e: sign * e["at"])
    return _make_branch(param, pts, events, stopped, cont)


def _signature(cont, o):
    return _n_outside(o), o.admissible, o.symmetric


def _locate_events(cont, va, oa, vb, ob, events, tol):
    sa, sb = _signature(cont, oa), _signature(cont, ob)
    if sa == sb:
        return
    for idx, kind in ((0, "stability"), (1, "admissibility-loss"), (2, "symmetry-breaking")):
        if sa[idx] == sb[idx]:
            continue
        lo, olo, hi, ohi = va, oa, vb, ob
        while abs(hi - lo) > tol:
            mid = 0.5 * (lo + hi)
            pred = _interp(mid, lo, olo, hi, ohi)
            om = cont.solve(mid, pred[:4], pred[4], pred[5])
            if om is None:
                break
            if _signature(cont, om)[idx] == sa[idx]:
                lo, olo = mid, om
            else:
                hi, ohi = mid, om
        at = 0.5 * (lo + hi)
        if kind == "stability":
            # type from the point just outside/inside, whichever is closer to |lambda| = 1
            o_near = olo if abs(olo.lambda_max - 1.0) < abs(ohi.lambda_max - 1.0) else ohi
            v_near = lo if o_near is olo else hi
            typ = _crossing_type(o_near, cont.jac1(v_near, o_near) if o_near.symmetric else None)
        else:
            typ = kind
        events.append({"type": typ, "at": at})


def _make_branch(param, pts, events, stopped, cont=None) -> Branch:
    n = len(pts)
    vals = np.array([v for v, _ in pts], float)
    orbits = [o for _, o in pts]
    par = {q: np.empty(n) for q in PARAMS}
    for i, (v, o) in enumerate(pts):
        p = o.params
        par["eta"][i], par["omega"][i], par["F"][i] = p.eta, p.omega, p.F
    absev = np.array([np.sort(np.abs(o.eigenvalues))[::-1] for o in orbits]).reshape(n, 4)
    get = lambda name, dt=float: np.array([getattr(o, name) for o in orbits], dtype=dt)  # noqa
    return Branch(param=param, values=vals, eta=par["eta"], omega=par["omega"], F=par["F"],
                  lambda_max=get("lambda_max"), abs_eigenvalues=absev,
                  stable=get("stable", bool), symmetric=get("symmetric", bool),
                  admissible=get("admissible", bool), dw_L=get("dw_L"), dw_R=get("dw_R"),
                  phase_L=get("phase_L"), phase_R=get("phase_R"), events=events,
                  orbits=orbits, stopped=stopped)
