"""Continuation of a 1:1 orbit in eta, omega or F: ``continue_branch``, the one home of
continuation. Its keywords become one ``ContinuationSettings`` (validated once) that every
step below receives, with the model's fixed constants as a ``ModelParams``.

Two methods:

* ``arclength`` (default): pseudo-arclength continuation of the family's shooting system
  through folds, events located along the arclength: the one loop of every family
  (``loop.Follower``) on the 1:1 family's problem (``follower.OneToOneProblem``, run by
  ``follower.follow``); symmetric or asymmetric orbits (``branch``), and with ``switch``
  the asymmetric branches born at the symmetric branch's symmetry-breaking points
  (``follower.switch_at``).
* ``natural``: natural-parameter continuation. Predictor: secant through the last two
  points (the orbit's x_L with unwrapped impact time and the flight times, extrapolated
  linearly in the parameter); corrector: the Newton iteration of ``vines.periodic`` on
  P2∘P1. A failed correction halves the step; when the step falls below ``min_step`` the
  branch has (almost surely) reached a fold, which is recorded at the last converged
  parameter and ends the continuation.

Natural mode locates events between consecutive points by bisection to ``event_tol`` in
the parameter:

* the number of eigenvalues of J_P2 J_P1 outside the unit circle changes: the crossing
  eigenvalue (the one closest to the unit circle at the located point) gives the type:
  complex pair -> neimark-sacker, real -1 -> flip, real +1 -> fold. On a symmetric orbit
  J_P2 J_P1 = (M J_P1)^2 with M = diag(-1, -1, -1, 1) (the mirror); a +1 crossing whose
  half-map multiplier mu of M J_P1 is -1 is a symmetry-breaking (pitchfork), mu = +1 a fold;
* the admissibility flag changes: admissibility-loss (either direction: a grazing contact);
* the symmetric flag changes: symmetry-breaking.

The natural mode stays 1:1-only and outside the loop: it has no tracer (a fixed parameter
step, the Newton of ``periodic.solve_orbit`` at that parameter, secant predictor on
(x_L, s1, s2)) and no test functions (events bisected in the parameter on eigenvalue
counts and flags), it ends at the first fold by construction, and it is kept as the
published cross-check of the arclength branches (``tests/test_arclength.py``); a wall
sequence is continued by arclength only.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ... import progress
from ...core.params import (
    D_DEFAULT,
    MAX_INADMISSIBLE_DEFAULT,
    MAX_POINTS_DEFAULT,
    R_DEFAULT,
    ModelParams,
    ParameterError,
)
from ...core.walls import WALL_L, WALL_R
from ..family.family import MIRROR_MATRIX, ONE_TO_ONE
from ..family.periodic import PeriodicOrbit, orbits_1to1, solve_orbit
from ..jets import shooting as sh
from ..maps.impact import map_jacobian
from .branch import EVENT_TYPES, Branch, make_branch
from .follower import follow, start_unknowns
from .settings import ContinuationSettings

__all__ = ["continue_branch", "continue_orbit", "ContinuationSettings", "Branch", "EVENT_TYPES"]


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
        mu = np.linalg.eigvals(MIRROR_MATRIX @ J1)
        j = int(np.argmin(np.abs(np.abs(mu) - 1.0)))
        if abs(mu[j].imag) < 1e-6 and mu[j].real < 0.0:
            return "symmetry-breaking"
    return "fold"


class _Continuer:
    """Orbits along the continued parameter (natural mode): the model p0 with the parameter
    set to a value."""

    def __init__(self, cs: ContinuationSettings, p0: ModelParams):
        self.param, self.p0 = cs.param, p0

    def params(self, value: float) -> ModelParams:
        return replace(self.p0, **{self.param: value})

    def solve(self, value: float, x: np.ndarray, s1: float, s2: float) -> PeriodicOrbit | None:
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

    def jac1(self, value: float, o: PeriodicOrbit) -> np.ndarray:
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


def continue_branch(param: str, start: float, stop: float, step: float | None = None,
                    fixed: dict | None = None, orbit: PeriodicOrbit | None = None,
                    r: float = R_DEFAULT, d: float = D_DEFAULT, phi: float = 0.0,
                    min_step: float = 1e-6, event_tol: float = 1e-6,
                    max_points: int = MAX_POINTS_DEFAULT,
                    method: str = "arclength", branch: str = "symmetric",
                    switch: bool = False,
                    max_inadmissible: int = MAX_INADMISSIBLE_DEFAULT) -> Branch:
    """Follow a 1:1 orbit from param = start towards stop; returns a ``Branch``.

    ``fixed`` gives the two other parameters of eta/omega/F (not ``param`` itself).
    ``orbit`` is the starting orbit (default: the preferred orbit of ``find_1to1`` at start
    of the requested ``branch`` kind, symmetric or asymmetric: stable and admissible first).
    ``method``: "arclength" (through folds, until the parameter leaves [start, stop], the
    branch closes, ``max_inadmissible`` consecutive points are non-admissible or
    ``max_points`` points) or "natural" (from start to stop, ends at a fold).
    ``step``: the parameter step (natural) or the largest arclength step (arclength, in the
    norm of the unknowns and the parameter); default (stop - start)/100. A step that needs
    more than ``max_points`` points (|stop - start|/step > max_points, default 100000, at
    most 1e7) is refused; ``min_step`` and ``event_tol`` lie in [1e-12, 1]. ``switch``
    (arclength, symmetric branch): also continue the asymmetric branch born at every
    symmetry-breaking point (``Branch.switched``).
    """
    cs = ContinuationSettings(param=param, start=start, stop=stop, step=step,
                              fixed=_check_fixed(fixed), min_step=min_step, event_tol=event_tol,
                              max_points=max_points, method=method, branch=branch,
                              switch=switch, max_inadmissible=max_inadmissible)
    if orbit is not None and not (isinstance(orbit, PeriodicOrbit)
                                  and (orbit.walls, orbit.periods) == ONE_TO_ONE.key):
        raise ParameterError("orbit", getattr(orbit, "family", type(orbit).__name__),
                             "must be None or a 1:1 PeriodicOrbit (find_1to1)")
    kw = dict(cs.fixed)
    kw[cs.param] = cs.start
    p0 = ModelParams(eta=kw["eta"], omega=kw["omega"], F=kw["F"], r=r, d=d, phi=phi)
    return continue_orbit(cs, p0, orbit)


def continue_orbit(cs: ContinuationSettings, p0: ModelParams,
                   orbit: PeriodicOrbit | None = None) -> Branch:
    """``continue_branch`` with validated settings from the model p0 (its ``cs.param`` at
    ``cs.start``, the other two at ``cs.fixed``)."""
    cont = _Continuer(cs, p0)
    cont.params(cs.stop)                     # validates the end point
    if orbit is None:
        cands = [o for o in orbits_1to1(p0)
                 if o.symmetric == (cs.branch == "symmetric")]
        if not cands:
            return make_branch(cs.param, [], [], f"no {cs.branch} 1:1 orbit at start")
        orbit = cands[0]
    else:
        orbit = cont.solve(cs.start, orbit.x_L, *orbit.flight_times)
        if orbit is None:
            return make_branch(cs.param, [], [], "the given orbit does not converge at start")
    if cs.method == "natural":
        with progress.task(abs(cs.stop - cs.start), f"branch in {cs.param}", cs.param):
            br = _natural(cont, cs, orbit)
        br.family = "symmetric" if orbit.symmetric else "asymmetric"
        return br
    return _arclength(cs, p0, orbit)


def _check_fixed(fixed) -> dict:
    """``fixed`` of ``continue_branch`` as a new dict (None: empty)."""
    if fixed is None:
        return {}
    if not isinstance(fixed, dict):
        raise ParameterError("fixed", fixed, "must be a dict of the two parameters not continued")
    return dict(fixed)


def _arclength(cs: ContinuationSettings, p0: ModelParams, orbit: PeriodicOrbit) -> Branch:
    """Pseudo-arclength continuation from orbit (and the switched branches)."""
    model = sh.Model(p0.r, p0.d, p0.phi)
    kind = "symmetric" if orbit.symmetric else "asymmetric"
    return follow(model, kind, cs, np.append(start_unknowns(orbit, kind), cs.start), cs.sign,
                  switch=cs.switch and kind == "symmetric")


def _natural(cont: _Continuer, cs: ContinuationSettings, orbit: PeriodicOrbit) -> Branch:
    """Natural-parameter continuation (module docstring)."""
    start, stop, step, min_step = cs.start, cs.stop, cs.step_size, cs.min_step
    sign = cs.sign
    param = cs.param
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
        _locate_events(cont, v_prev, o_prev, v, o, events, cs.event_tol)
        pts.append((v, o))
        progress.advance(abs(v - v_prev))
        h = min(step, 1.5 * h)
    events.sort(key=lambda e: sign * e["at"])
    return make_branch(param, pts, events, stopped)


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
