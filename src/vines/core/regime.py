"""Classification of the post-transient motion (impacts per period, periodicity).

Labels (SPEC 3):
  "no-impact"  no impact in the window (KE ratio 0 if the ball is also at rest)
  "chatter"    the ball sticks at a wall in the window, or a run of CHATTER_RUN or more
               consecutive impacts hits the same wall (accumulating impacts)
  "a:b"        periodic with the forcing period T, a impacts on one wall and b on the
               other per period (a >= b): "1:1" is two alternating impacts per period
  "period-p"   periodic with period p T, p > 1
  "irregular"  no period up to MAX_PERIOD within the tolerance
Periodicity is read off the stroboscopic section x_k = state(t_transient + k T) over the
last periods of the window: period p if max_k |x_(k+p) - x_k| <= PERIOD_TOL * max(1, |x|).
"""
from __future__ import annotations

import math

import numpy as np

from .tally import ImpactTally

CHATTER_RUN = 4
MAX_PERIOD = 16
PERIOD_TOL = 1e-4
N_STROBE = 64


def strobe_times(period: float, t_transient: float, t_end: float, n: int = N_STROBE) -> np.ndarray:
    """The last n stroboscopic times t_transient + k T inside the window."""
    k_max = math.floor((t_end - t_transient) / period + 1e-12)
    if t_transient + k_max * period > t_end:     # a window of whole periods, rounded up
        k_max -= 1
    k = np.arange(max(0, k_max - n + 1), k_max + 1)
    return t_transient + k * period


def detect_period(strobe: np.ndarray, max_period: int = MAX_PERIOD, tol: float = PERIOD_TOL) -> int:
    """Smallest p with strobe[:, k + p] == strobe[:, k] (to tol), or 0 if none."""
    n = strobe.shape[1]
    scale = max(1.0, float(np.abs(strobe).max())) if n else 1.0
    for p in range(1, min(max_period, n // 2) + 1):
        if np.abs(strobe[:, p:] - strobe[:, :-p]).max() <= tol * scale:
            return p
    return 0


def longest_same_wall_run(walls: np.ndarray) -> int:
    if walls.size == 0:
        return 0
    change = np.flatnonzero(np.diff(walls) != 0)
    bounds = np.concatenate(([-1], change, [walls.size - 1]))
    return int(np.max(np.diff(bounds)))


def classify(walls_window: np.ndarray, t_impacts_window: np.ndarray, strobe: np.ndarray,
             strobe_t: np.ndarray, t_stuck_window: float, period: float) -> tuple[str, int]:
    """Regime label and detected period p (0 when not periodic) from the impacts of the
    window (``classify_tally``)."""
    tally = ImpactTally.for_window(-np.inf, strobe_t)
    tally.add(np.asarray(t_impacts_window), np.asarray(walls_window))
    return classify_tally(tally, strobe, strobe_t, t_stuck_window)


def classify_tally(tally: ImpactTally, strobe: np.ndarray, strobe_t: np.ndarray,
                   t_stuck_window: float) -> tuple[str, int]:
    """Regime label and detected period p (0 when not periodic) from the window's impact
    counts (``tally.ImpactTally`` over the stroboscopic span of strobe_t)."""
    p = detect_period(strobe)
    if t_stuck_window > 0.0 or tally.longest_run >= CHATTER_RUN:
        return "chatter", p
    if tally.n_window == 0:
        return "no-impact", p
    if p == 0:
        return "irregular", 0
    if p > 1:
        return f"period-{p}", p
    # impacts per period on each wall over the stroboscopic span
    n_per = strobe_t.size - 1 if strobe_t.size >= 2 else 1
    nL = tally.n_span_L / n_per
    nR = tally.n_span_R / n_per
    if abs(nL - round(nL)) > 1e-9 or abs(nR - round(nR)) > 1e-9:
        return "irregular", 0
    a, b = int(round(max(nL, nR))), int(round(min(nL, nR)))
    return f"{a}:{b}", 1
