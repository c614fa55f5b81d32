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
* ``natural``: natural-parameter continuation, the one natural mode of every family
  (``natural.follow_natural``) on the 1:1 family's ``_Continuer``: secant predictor on the
  orbit's x_L (impact time unwrapped) and flight times, corrector the Newton iteration of
  ``vines.periodic`` on P2∘P1; it ends at the first fold (the step falls below
  ``min_step``); events bisected in the parameter to ``event_tol`` on the eigenvalue count
  and the admissible and symmetric flags, a crossing typed on the half map M J_P1 of a
  symmetric orbit (fold vs symmetry-breaking). It is the published cross-check of the
  arclength branches (``tests/test_arclength.py``) and the stored branch of ``map_solve``.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ... import progress
from ...core.params import (
    D_DEFAULT,
    MAX_INADMISSIBLE_DEFAULT,
    MAX_POINTS_DEFAULT,
    PARAM_NAMES,
    R_DEFAULT,
    ModelParams,
    ParameterError,
    check_choice,
)
from ...core.walls import WALL_L, WALL_R
from ..family.family import MIRROR_MATRIX, ONE_TO_ONE
from ..family.periodic import PeriodicOrbit, orbits_1to1, solve_orbit
from ..jets import shooting as sh
from ..maps.impact import map_jacobian
from .branch import EVENT_TYPES, Branch, make_branch
from .follower import follow, start_unknowns
from .natural import NaturalProblem, follow_natural
from .settings import ContinuationSettings

__all__ = ["continue_branch", "continue_orbit", "ContinuationSettings", "Branch", "EVENT_TYPES"]


class _Continuer(NaturalProblem):
    """Orbits along the continued parameter (natural mode, ``natural.NaturalProblem``): the
    model p0 with the parameter set to a value; the unknowns (x_L, s1, s2)."""

    def __init__(self, cs: ContinuationSettings, p0: ModelParams):
        self.param, self.p0 = cs.param, p0

    def params(self, value: float) -> ModelParams:
        return replace(self.p0, **{self.param: value})

    def orbit(self, value: float, x: np.ndarray, s1: float, s2: float) -> PeriodicOrbit | None:
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

    def solve(self, value: float, x: np.ndarray):
        o = self.orbit(value, x[:4], x[4], x[5])
        return None if o is None else (o, _state(o))

    def jumped(self, o: PeriodicOrbit, x_pred: np.ndarray, value: float) -> bool:
        return abs(o.flight_times[0] - x_pred[4]) > 0.25 * self.params(value).period

    def half_map(self, value: float, o: PeriodicOrbit) -> np.ndarray | None:
        if not o.symmetric:
            return None
        J1 = map_jacobian(self.params(value), o.x_L, WALL_L, WALL_R,
                          t_guess=o.x_L[3] + o.flight_times[0])
        return MIRROR_MATRIX @ J1


def _state(o):
    return np.concatenate([o.x_L, o.flight_times])


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
    param = check_choice("param", param, PARAM_NAMES)   # required (None: settings unbound)
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
        orbit = cont.orbit(cs.start, orbit.x_L, *orbit.flight_times)
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
    """Natural-parameter continuation (``natural.follow_natural``)."""
    pts, events, stopped = follow_natural(cont, cs.start, cs.stop, cs.step_size, cs.min_step,
                                          cs.event_tol, orbit, _state(orbit))
    return make_branch(cs.param, [(v, o) for v, o, _ in pts], events, stopped)
