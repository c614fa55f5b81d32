"""Natural-parameter continuation of every family: ``follow_natural`` steps the continued
parameter over a ``NaturalProblem`` (the 1:1 family: ``one_to_one``; a wall sequence:
``sequence``), which solves the family's orbit at a parameter value from a guess.

Predictor: secant through the last two points (the family's unknowns, e.g. x_L with its
impact time unwrapped and the flight times, extrapolated linearly in the parameter);
corrector: the family's Newton at the predicted parameter. A failed correction (or one
whose flight times jumped, ``NaturalProblem.jumped``) halves the step; when the step falls
below ``min_step`` the branch has (almost surely) reached a fold, which is recorded at the
last converged parameter and ends the continuation.

Events between consecutive points are bisected in the parameter to ``event_tol`` on the
signature (the number of multipliers outside the unit circle, the admissibility flag, the
symmetric flag):

* a change of the number outside the unit circle: the crossing multiplier (the one closest
  to the unit circle at the bracket's end nearer |lambda_max| = 1) gives the type
  (``crossing_type``): complex pair -> neimark-sacker, real -1 -> flip, real +1 -> fold;
  on a symmetric orbit the monodromy matrix is A^2 with A = M J_{h-1} ... J_0 the half map
  (M = diag(-1, -1, -1, 1), h half the impacts): a +1 crossing where A has the multiplier
  -1 is a symmetry-breaking (pitchfork), +1 a fold;
* a change of the admissibility flag: admissibility-loss (either direction: a grazing);
* a change of the symmetric flag: symmetry-breaking.
"""
from __future__ import annotations

import numpy as np

from ... import progress
from ..family.family import MIRROR_MATRIX
from ..maps.newton import monodromy


class NaturalProblem:
    """What one family gives the natural mode. A point is (value, orbit, x): x the
    family's unknowns at the orbit (the predictor's vector)."""

    def solve(self, value: float, x: np.ndarray):
        """(orbit, x) at the parameter value from the guess x, or None."""
        raise NotImplementedError

    def jumped(self, o, x_pred: np.ndarray, value: float) -> bool:
        """The corrected orbit is not the predicted one (its flights jumped)."""
        raise NotImplementedError

    def half_map(self, value: float, o) -> np.ndarray | None:
        """A = M J_{h-1} ... J_0 of a symmetric orbit, None for an asymmetric one."""
        raise NotImplementedError

    def event(self, typ: str, at: float, index: int, o) -> dict:
        """The event record (o: the orbit next to it; index: the branch point it lies
        before)."""
        return {"type": typ, "at": at}


def n_outside(o) -> int:
    """The number of multipliers outside the unit circle."""
    return int(np.sum(np.abs(o.eigenvalues) > 1.0))


def crossing_type(o, A: np.ndarray | None = None) -> str:
    """The type of the multiplier crossing at o (module docstring); A: the half map of a
    symmetric orbit (None: fold for a real +1 crossing)."""
    ev = o.eigenvalues
    k = int(np.argmin(np.abs(np.abs(ev) - 1.0)))
    lam = ev[k]
    if abs(lam.imag) > 1e-6 * max(1.0, abs(lam)):
        return "neimark-sacker"
    if lam.real < 0.0:
        return "flip"
    if o.symmetric and A is not None:
        mu = np.linalg.eigvals(A)
        j = int(np.argmin(np.abs(np.abs(mu) - 1.0)))
        if abs(mu[j].imag) < 1e-6 and mu[j].real < 0.0:
            return "symmetry-breaking"
    return "fold"


def half_map(jacobians) -> np.ndarray:
    """M J_{h-1} ... J_0 from the n map Jacobians of a symmetric orbit (h = n/2)."""
    return MIRROR_MATRIX @ monodromy(jacobians[:len(jacobians) // 2])


def follow_natural(problem: NaturalProblem, start: float, stop: float, step: float,
                   min_step: float, event_tol: float, orbit, x: np.ndarray):
    """Natural continuation from (start, orbit, x) to stop (module docstring); returns
    (points [(value, orbit, x)], events sorted along the branch, why it stopped)."""
    sign = 1.0 if stop >= start else -1.0
    pts = [(start, orbit, x)]
    events = []
    h = step
    stopped = "done"
    while True:
        v_prev, o_prev, x_prev = pts[-1]
        if (stop - v_prev) * sign <= 1e-12 * max(1.0, abs(stop)):
            break
        v = v_prev + sign * h
        if (v - stop) * sign > 0.0:
            v = stop
        pred = _predict(v, pts)
        got = problem.solve(v, pred)
        if got is None or problem.jumped(got[0], pred, v):
            h *= 0.5
            if h < min_step:
                events.append(problem.event("fold", v_prev, len(pts) - 1, o_prev))
                stopped = "fold or loss of convergence"
                break
            continue
        _locate_events(problem, pts[-1], (v, *got), events, event_tol, len(pts))
        pts.append((v, *got))
        progress.advance(abs(v - v_prev))
        h = min(step, 1.5 * h)
    events.sort(key=lambda e: sign * e["at"])
    return pts, events, stopped


def _predict(v, pts):
    """Secant (or constant) prediction of the unknowns at parameter v."""
    if len(pts) == 1:
        return pts[-1][2]
    (v0, _, a), (v1, _, b) = pts[-2], pts[-1]
    if v1 == v0:
        return b
    return b + (b - a) * (v - v1) / (v1 - v0)


def _interp(v, va, a, vb, b):
    return a + (b - a) * (v - va) / (vb - va)


def _signature(o):
    return n_outside(o), o.admissible, o.symmetric


def _locate_events(problem, pa, pb, events, tol, index):
    """Bisect each signature change between the points pa and pb (module docstring)."""
    (va, oa, xa), (vb, ob, xb) = pa, pb
    sa, sb = _signature(oa), _signature(ob)
    if sa == sb:
        return
    for idx, kind in ((0, "stability"), (1, "admissibility-loss"), (2, "symmetry-breaking")):
        if sa[idx] == sb[idx]:
            continue
        lo, olo, xlo, hi, ohi, xhi = va, oa, xa, vb, ob, xb
        while abs(hi - lo) > tol:
            mid = 0.5 * (lo + hi)
            got = problem.solve(mid, _interp(mid, lo, xlo, hi, xhi))
            if got is None:
                break
            if _signature(got[0])[idx] == sa[idx]:
                lo, (olo, xlo) = mid, got
            else:
                hi, (ohi, xhi) = mid, got
        at = 0.5 * (lo + hi)
        # the point just outside/inside, whichever is closer to |lambda| = 1
        near = olo if abs(olo.lambda_max - 1.0) < abs(ohi.lambda_max - 1.0) else ohi
        if kind == "stability":
            v_near = lo if near is olo else hi
            typ = crossing_type(near, problem.half_map(v_near, near) if near.symmetric
                                else None)
        else:
            typ = kind
        events.append(problem.event(typ, at, index, near))
