"""Result objects shared by the solvers.

Conventions: times are dimensionless absolute times t = w0 t_dim; wall = +1 is the
left end L (w = z_m - z_b = +1), wall = -1 the right end R (w = -1). Impact records hold
pre-impact values (superscript '-' in the paper).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .params import L_HALF_M, ModelParams, SolverSettings
from .tally import ImpactTally
from .walls import WALL_L, WALL_R  # noqa: F401  (re-exported)

#: dtype of ``SimulationResult.impacts``, one impact a row (time, pre-impact state, wall hit)
IMPACT_DTYPE = np.dtype([("t", "f8"), ("z_m", "f8"), ("v_m", "f8"),
                         ("z_b", "f8"), ("v_b", "f8"), ("wall", "i1")])



@dataclass
class RawRun:
    """What a solver backend returns; ``simulate`` turns it into a SimulationResult.

    int_vm2, int_vb2   exact integrals of z_m'^2 and z_b'^2 over [t_transient, t_end]
    xmax_window        max |z_m| over [t_transient, t_end] (dimensionless)
    xmax_whole_run     max |z_m| over [0, t_end]
    t_stuck_window     time spent stuck inside the window; t_stuck_total over the run
    t_last             time reached (t_end unless status != "ok")
    state_at           callable: array of times -> array (4, n) of (z_m, z_m', z_b, z_b');
                       at an event instant the state after it (post-impact)
    shortcut_time      time t_s from which the run was completed from one period of a
                       settled periodic orbit (``vines.core.shortcut``); NaN: integrated
                       to the end. shortcut_period: that period in forcing periods (0: none)
    impact_tally       the window's impact counts when the impacts were not kept
                       (``exact.run_exact(keep_records=False)``: ``impacts`` is then empty)
    """

    impacts: np.ndarray
    int_vm2: float
    int_vb2: float
    xmax_window: float
    xmax_whole_run: float
    t_stuck_window: float
    t_stuck_total: float
    n_impacts: int
    status: str
    t_last: float
    state_at: Callable[[np.ndarray], np.ndarray]
    n_sticks: int = 0
    solver_info: dict = field(default_factory=dict)
    shortcut_time: float = math.nan
    shortcut_period: int = 0
    impact_tally: ImpactTally | None = None


@dataclass
class SimulationResult:
    """Outcome of ``vines.simulate``: energy-transfer measures and the trajectory.

    ::

        ke_ratio        K_b/(K_m + K_b) with K_m = <z_m'^2>/2, K_b = eta <z_b'^2>/2, exact
                        time averages over [t_transient, t_end] (0 when there is no motion)
        xmax, xmax_m    max |z_m| over the window, dimensionless and in metres (x L)
        xmax_whole_run(_m)  the same over the whole run [0, t_end]
        n_impacts       impacts in the whole run; impacts_per_period: in the window per T
        regime          "1:1", "2:2", "2:1", "period-p", "chatter", "irregular", "no-impact";
                        "unfinished" (stopped at max_impacts), "failed" (solver stalled)
        t_stuck         time spent stuck (ball and LO moving as one body) in the window
        impacts         structured array (t, z_m, v_m, z_b, v_b, wall), pre-impact values
        status          "ok", or why the run stopped early ("max_impacts", ...)
        shortcut_time   time from which the run was completed from one period of a settled
                        periodic orbit (``vines.core.shortcut``; NaN: integrated to t_end);
                        shortcut_period: that period in forcing periods (0 when not taken).
                        Impacts and ``state_at`` after shortcut_time repeat that period.
    """

    params: ModelParams
    settings: SolverSettings
    solver: str
    solver_options: dict
    impacts: np.ndarray
    K_m: float
    K_b: float
    ke_ratio: float
    xmax: float
    xmax_whole_run: float
    n_impacts: int
    n_impacts_window: int
    impacts_per_period: float
    regime: str
    period: int
    t_stuck: float
    t_stuck_whole_run: float
    n_sticks: int
    status: str
    t_last: float
    _state_at: Callable = field(repr=False, default=None)
    shortcut_time: float = math.nan
    shortcut_period: int = 0

    def __post_init__(self):
        # every number a Python float or int, whatever a backend computed it in (a numpy
        # scalar's .item() is the same number)
        for name, value in vars(self).items():
            if isinstance(value, np.generic):
                setattr(self, name, value.item())

    @property
    def xmax_m(self) -> float:
        return self.xmax * L_HALF_M

    @property
    def xmax_whole_run_m(self) -> float:
        return self.xmax_whole_run * L_HALF_M

    @property
    def impact_phase(self) -> np.ndarray:
        """phi_i = mod(omega t_i + phi, 2 pi) of every impact [rad]."""
        p = self.params
        return np.mod(p.omega * self.impacts["t"] + p.phi, 2.0 * math.pi)

    @property
    def impact_dw(self) -> np.ndarray:
        """Relative velocity just before each impact, w'_i = v_m- - v_b-."""
        return self.impacts["v_m"] - self.impacts["v_b"]

    def state_at(self, t) -> np.ndarray:
        """State (z_m, z_m', z_b, z_b') at absolute times ``t``: array of shape (4, n).

        At an event instant (a time of ``impacts["t"]``, a stick or release) the state is
        the one *after* every event at that instant: post-impact velocities (or the common
        velocity when the ball sticks there); any earlier time, even by one ulp, is on the
        flight before it (the pre-impact velocities are those of ``impacts``). Both solvers,
        and the records repeated after a periodic shortcut, follow this convention."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        if np.any(t < 0.0) or np.any(t > self.t_last):
            raise ValueError(f"times must lie in [0, {self.t_last:g}]")
        return self._state_at(t)

    def to_dict(self) -> dict:
        """JSON-ready summary (the keys of the `vines simulate --json` contract)."""
        return {
            "ke_ratio": self.ke_ratio,
            "xmax_m": self.xmax_m,
            "xmax": self.xmax,
            "xmax_whole_run_m": self.xmax_whole_run_m,
            "xmax_whole_run": self.xmax_whole_run,
            "n_impacts": self.n_impacts,
            "n_impacts_window": self.n_impacts_window,
            "impacts_per_period": self.impacts_per_period,
            "regime": self.regime,
            "period": self.period,
            "t_stuck": self.t_stuck,
            "t_stuck_whole_run": self.t_stuck_whole_run,
            "status": self.status,
            "shortcut_time": self.shortcut_time,
            "shortcut_period": self.shortcut_period,
            "solver": self.solver,
            "params": {**self.params.as_dict(), **self.settings.as_dict(), **self.solver_options},
        }
