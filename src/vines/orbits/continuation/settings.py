"""How a branch is continued: ``ContinuationSettings``, the one settings object of the 1:1
continuation (``one_to_one.continue_branch``) and of any wall sequence
(``sequence.continue_sequence``), validated on construction.

``max_points`` means one thing for both: the most points of an arclength branch, and a step
given that needs more than ``max_points`` points to cover |stop - start| is refused (the
default step, |stop - start|/100, is not checked; the natural mode takes the steps it
needs). Settings made without ``param`` (those given to ``continue_sequence``) hold the step
and the limits only; the continuation binds them to its parameter interval (``bound``).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ...core.params import (
    BRANCH_KINDS,
    CONTINUATION_METHODS,
    MAX_INADMISSIBLE_DEFAULT,
    MAX_POINTS_DEFAULT,
    MAX_POINTS_MAX,
    PARAM_NAMES,
    ParameterError,
    check_bool,
    check_choice,
    check_int,
    check_param,
    check_real,
    check_step_points,
)
from .arclength import Tracer


@dataclass(frozen=True)
class ContinuationSettings:
    """How one branch is continued, validated once on construction.

    ::

        param, start, stop  the continued parameter and its interval (None: unbound, see
                            ``bound``)
        step              the parameter step (natural) or largest arclength step, |step| (None:
                          |stop - start|/100, ``step_size``); a step given that needs more than
                          ``max_points`` points to cover |stop - start| is refused
        fixed             the two parameters not continued
        max_points        most points of an arclength branch (None: the continuation's
                          default, ``MAX_POINTS_DEFAULT`` for 1:1,
                          ``sequence.MAX_BRANCH_POINTS_DEFAULT`` for a wall sequence)
        max_inadmissible  end after this many consecutive non-admissible points
        switch            also continue the branches born at symmetry-breaking (and, for a
                          wall sequence, flip) points
        method            arclength or natural (``natural``), for every family
        min_step, event_tol: the natural mode and the 1:1 arclength continuation (a wall
                          sequence's arclength: smallest step step * 1e-6)
        branch            the 1:1 continuation only
    """

    param: str | None = None
    start: float | None = None
    stop: float | None = None
    step: float | None = None
    fixed: dict = field(default_factory=dict)
    min_step: float = 1e-6
    event_tol: float = 1e-6
    max_points: int | None = None
    method: str = "arclength"
    branch: str = "symmetric"
    switch: bool = False
    max_inadmissible: int = MAX_INADMISSIBLE_DEFAULT

    def __post_init__(self):
        set_ = object.__setattr__
        param = self.param
        if param is not None and (not isinstance(param, str) or param not in PARAM_NAMES):
            raise ParameterError("param", param, "must be one of eta, omega, F")
        set_(self, "method", check_choice("method", self.method, CONTINUATION_METHODS))
        set_(self, "branch", check_choice("branch", self.branch, BRANCH_KINDS))
        set_(self, "switch", check_bool("switch", self.switch))
        set_(self, "max_inadmissible", check_int("max_inadmissible", self.max_inadmissible,
                                                 lo=1, hi=MAX_POINTS_MAX))
        if param is None:
            self._check_limits(self.max_points)
            if self.step is not None:
                set_(self, "step", _check_step(self.step))
            return
        set_(self, "fixed", _fixed_others(param, self.fixed))
        start = check_param(param, self.start)
        try:
            stop = check_param(param, self.stop)
        except ParameterError as err:
            raise ParameterError("stop", self.stop, f"{err.allowed} ({param})") from None
        max_points = self._check_limits(MAX_POINTS_DEFAULT if self.max_points is None
                                        else self.max_points)
        set_(self, "start", start)
        set_(self, "stop", stop)
        if self.step is None:
            _check_step(self.step_size)
        else:
            step = _check_step(self.step)
            check_step_points(step, abs(stop - start), step, max_points)
            set_(self, "step", step)

    @property
    def step_size(self) -> float:
        """The step in use: ``step``, or |stop - start|/100 where it is None (1 where
        stop == start)."""
        if self.step is not None:
            return self.step
        stop, start = self.stop, self.start
        return abs((stop - start) / 100.0 if stop != start else 1.0)

    def _check_limits(self, max_points) -> int | None:
        """Validates max_points (None kept), min_step and event_tol in place."""
        set_ = object.__setattr__
        if max_points is not None:
            max_points = check_int("max_points", max_points, lo=1, hi=MAX_POINTS_MAX)
        set_(self, "max_points", max_points)
        set_(self, "min_step", check_real("min_step", self.min_step, lo=1e-12, hi=1.0))
        set_(self, "event_tol", check_real("event_tol", self.event_tol, lo=1e-12, hi=1.0))
        return max_points

    def bound(self, param: str, start: float, stop: float, fixed: dict,
              max_points: int) -> ContinuationSettings:
        """These settings for continuing ``param`` from start to stop, the other two
        parameters at ``fixed``; ``max_points``: the value where these leave it unset."""
        return replace(self, param=param, start=start, stop=stop, fixed=fixed,
                       max_points=max_points if self.max_points is None else self.max_points)

    @property
    def bounds(self) -> tuple[float, float]:
        return (min(self.start, self.stop), max(self.start, self.stop))

    @property
    def sign(self) -> float:
        """+1 when the parameter increases from start to stop, else -1."""
        return 1.0 if self.stop >= self.start else -1.0

    def tracer(self, system, z0: np.ndarray, direction: np.ndarray) -> Tracer:
        """The arclength tracer of ``system`` (a ``follower.FamilySystem``) from z0 with
        these steps."""
        h = self.step_size
        return Tracer(system, z0, direction, h=h, h_min=self.min_step, h_max=h)


def _check_step(step) -> float:
    """|step|, a number != 0."""
    step = abs(check_real("step", step))
    if step == 0.0:
        raise ParameterError("step", step, "must be a number != 0")
    return step


def _fixed_others(param: str, fixed: dict) -> dict:
    """The two parameters not continued, from ``fixed`` (exactly those two)."""
    if param in fixed:
        raise ParameterError(param, fixed[param],
                             f"must not be fixed when continuing in {param} (it runs from "
                             f"start to stop; fix only {' and '.join(q for q in PARAM_NAMES if q != param)})")
    others = [q for q in PARAM_NAMES if q != param]
    for q in others:
        if q not in fixed:
            raise ParameterError(q, None, f"is required when continuing in {param}")
    unknown = [k for k in fixed if k not in others]
    if unknown:
        raise ParameterError("fixed", unknown[0], f"is not a parameter; fix only {' and '.join(others)}")
    return {q: fixed[q] for q in others}
