"""Where one initial state ends up: run it until it settles, and name its end state.

Each state runs ``core.simulation.run_measured`` (exact kernel with the periodic shortcut)
from t = 0 to t_end, the measures over [t_transient, t_end]. Its end state is one of

* ``"1:1"``      the run's last impacts alternate L, R and the map's Newton solver takes its
                 last L impact to a stable admissible 1:1 orbit nearby (``orbit.polish_1to1``),
                 whether or not the shortcut confirmed the orbit;
* ``"orbit"``    the shortcut confirmed a periodic orbit of period pp T with impacts: its pp
                 states on the section t = k T (forcing phase phi) and segment modes there;
* ``"motion"``   anything else that finished (chatter, irregular, no-impact, periodic
                 orbits without impacts, or periods the shortcut did not confirm), labelled
                 by ``core.regime`` over the window;
* ``"unsettled"`` the run stopped early (status "max_impacts" or "stalled").

``settle_states`` runs many states on threads; every state is independent and results are
kept by index, so they do not depend on the number of threads.
"""
from __future__ import annotations

import math
import os
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from .. import progress
from ..core.exact import Oscillators, oscillators
from ..core.params import ModelParams, SolverSettings, check_int
from ..core.result import RawRun
from ..core.simulation import run_measured
from ..orbits.family.periodic import PeriodicOrbit
from .orbit import polish_1to1

KINDS = ("1:1", "orbit", "motion", "unsettled")


@dataclass
class EndState:
    """End state of one run. ke_ratio, xmax: the run's window measures (dimensionless
    xmax); orbit: the polished 1:1 orbit (kind "1:1"); section (pp, 4), modes (pp,):
    the confirmed orbit's states and segment modes at t = k T, k = k0 ... k0 + pp - 1
    (kind "orbit"); final_state, final_mode: the state (z_m, z_m', z_b, z_b') and
    segment mode at the end of the run."""

    kind: str
    regime: str
    ke_ratio: float
    xmax: float
    status: str
    orbit: PeriodicOrbit | None = None
    section: np.ndarray | None = None
    modes: np.ndarray | None = None
    t_section: float = math.nan
    final_state: np.ndarray | None = None
    final_mode: int = 0


def _section(raw, T: float, t_end: float, t_transient: float):
    """(section states (pp, 4), modes, t of the first) of a confirmed orbit, or None when
    it has no impacts in its last period (then it is a "motion")."""
    pp = int(raw.shortcut_period)
    k_last = math.floor(t_end / T)
    times = (np.arange(k_last - pp + 1, k_last + 1) * T).astype(float)
    if times[0] < max(t_transient, raw.shortcut_time):
        return None
    if not np.any(raw.impacts["t"] >= t_end - pp * T):
        return None
    seg = raw.state_at.segments
    idx = np.searchsorted(seg[:, 0], times, side="right") - 1
    return raw.state_at(times).T.copy(), seg[idx, 5].astype(np.int64), float(times[0])


def settle(p: ModelParams, st: SolverSettings, oscs: Oscillators,
           state0: Sequence[float]) -> EndState:
    """Run ``state0`` = (z_m, z_m', z_b, z_b') at t = 0 and classify its end state."""
    raw, m = run_measured(p, st, state0=tuple(float(v) for v in state0))
    return classify_end(p, st, oscs, raw, m["regime"], float(m["ke_ratio"]),
                        float(m["xmax"]))


def classify_end(p: ModelParams, st: SolverSettings, oscs: Oscillators, raw: RawRun,
                 regime: str, ke_ratio: float = math.nan,
                 xmax: float = math.nan) -> EndState:
    """The end state of a finished run ``raw`` over [., st.t_end] (kinds as above)."""
    base = dict(regime=regime, ke_ratio=ke_ratio, xmax=xmax, status=raw.status,
                final_state=np.asarray(raw.solver_info.get("final_state"), float),
                final_mode=int(raw.solver_info.get("final_mode", 0)))
    if raw.status != "ok":
        return EndState(**(base | {"kind": "unsettled"}))
    orbit = polish_1to1(p, oscs[0], raw.impacts, st.t_end)
    if orbit is not None:
        return EndState(kind="1:1", orbit=orbit, **base)
    if raw.shortcut_period > 0:
        sec = _section(raw, p.period, st.t_end, st.t_transient)
        if sec is not None:
            return EndState(kind="orbit", section=sec[0], modes=sec[1], t_section=sec[2],
                            **base)
    return EndState(kind="motion", **base)


def settle_states(p: ModelParams, st: SolverSettings, states: np.ndarray,
                  n_threads: int | None = None) -> list[EndState]:
    """``settle`` every row of ``states`` (n, 4) on ``n_threads`` threads (default: all
    cores), results in row order."""
    n_threads = check_int("n_threads", n_threads if n_threads is not None
                          else (os.cpu_count() or 1), lo=1)
    oscs = oscillators(p)
    states = np.asarray(states, dtype=float)

    def work(i):
        return settle(p, st, oscs, states[i])

    n = len(states)
    if n_threads == 1 or n <= 1:
        return list(progress.track(map(work, range(n)), n, "census", "states"))
    with ThreadPoolExecutor(max_workers=n_threads) as ex:
        return list(progress.track(ex.map(work, range(n)), n, "census", "states"))
