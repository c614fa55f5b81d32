"""The regime of each point of a bifurcation sweep, read off its recorded impacts (Figs 14, 15).

A sweep stores, per swept point, the impacts of its last ``n_record`` forcing periods
(relative velocity ``dw``, phase, wall). From them (same rules as ``vines.core.regime``,
which classifies the grid runs from their stroboscopic section):

  no impact      no impact recorded
  chatter        CHATTER_RUN or more consecutive impacts on the same wall
  1:1 symmetric  two alternating impacts per forcing period, repeating every period, the
                 second half a period after the first (phases differ by pi, to ``SYM_TOL``)
  1:1 asymmetric the same with phases not half a period apart (|dw| is the same on both
                 walls for every 1:1 orbit: the ball's velocity changes at the two impacts
                 cancel over a period, so |dw| cannot tell the two apart)
  other periodic the impact sequence repeats after k impacts (to ``PERIOD_TOL``), at least
                 twice in the record, and is not 1:1 (a:b with a != b, period-p)
  irregular      none of these

With a ``lyapunov`` dataset of the same sweep (``regime_grid(..., lyapunov=...)``), irregular
points are split by their leading exponent lambda_1 and its 95 % interval: chaotic (the
interval above 0), quasi-periodic (the interval contains 0: motion on a torus) and
irregular (below 0: a long period or a motion still settling) (``palette.REGIMES_SPLIT``).
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ..core.regime import CHATTER_RUN, longest_same_wall_run
from ..data.builders import ragged_rows
from . import palette

#: regime codes -> (label, colour): the one regime palette (``vines.plotting.palette``)
REGIMES = palette.REGIMES
(REGIME_NONE, REGIME_SYM, REGIME_ASYM, REGIME_PERIODIC, REGIME_IRREGULAR,
 REGIME_CHATTER, REGIME_CHAOTIC, REGIME_QUASIPERIODIC) = range(8)
#: relative tolerance of a repeating impact sequence (dw and phase, scaled by max(1, |dw|))
PERIOD_TOL = 1e-3
#: tolerance (rad) of the half-period phase difference of a symmetric 1:1 orbit
SYM_TOL = 1e-3


def _repeat_length(dw, phase, wall) -> int:
    """Smallest k with the sequence equal to itself shifted by k (to PERIOD_TOL), seen at
    least twice (k <= n/2); 0 when none."""
    n = dw.size
    scale = max(1.0, float(np.max(np.abs(dw))))
    for k in range(1, n // 2 + 1):
        dph = np.angle(np.exp(1j * (phase[k:] - phase[:-k])))
        if (np.array_equal(wall[k:], wall[:-k])
                and np.max(np.abs(dw[k:] - dw[:-k])) <= PERIOD_TOL * scale
                and np.max(np.abs(dph)) <= PERIOD_TOL * scale):
            return k
    return 0


def point_regime(dw, phase, wall, n_record: int) -> int:
    """Regime code (``REGIMES``) of one swept point from its recorded impacts."""
    dw, phase, wall = (np.asarray(a) for a in (dw, phase, wall))
    if dw.size == 0:
        return REGIME_NONE
    if longest_same_wall_run(wall) >= CHATTER_RUN:
        return REGIME_CHATTER
    k = _repeat_length(dw, phase, wall)
    if k == 0:
        return REGIME_IRREGULAR
    periods = k * n_record / dw.size          # forcing periods per repeat
    if k == 2 and abs(periods - 1.0) < 0.25 and wall[0] != wall[1]:
        half = abs(np.angle(np.exp(1j * (phase[1] - phase[0] - np.pi))))
        return REGIME_SYM if half <= SYM_TOL else REGIME_ASYM
    return REGIME_PERIODIC


def sweep_regimes(ds: xr.Dataset) -> np.ndarray:
    """Regime code of every point of a sweep dataset (needs the attribute solver_n_record)."""
    n_record = int(ds.attrs["solver_n_record"])
    rows = [ragged_rows(ds, k) for k in ("dw", "phase", "wall")]
    return np.array([point_regime(d, p, w, n_record) for d, p, w in zip(*rows, strict=False)], dtype=int)


def split_irregular(codes: np.ndarray, ly: xr.Dataset) -> np.ndarray:
    """``codes`` of a sweep's points with irregular split by the exponents of ``ly`` (a
    lyapunov dataset of the same sweep, same points in the same order)."""
    ci = ly["exponents_ci"].values[:, 0, :]
    out = codes.copy()
    irregular = codes == REGIME_IRREGULAR
    out[irregular & (ci[:, 0] > 0.0)] = REGIME_CHAOTIC
    out[irregular & (ci[:, 0] <= 0.0) & (ci[:, 1] >= 0.0)] = REGIME_QUASIPERIODIC
    return out


def _same_points(ds: xr.Dataset, ly: xr.Dataset) -> bool:
    return all(ds[k].shape == ly[k].shape and np.array_equal(ds[k].values, ly[k].values)
               for k in ("value", "outer_value", "direction", "phi"))


def regime_grid(ds: xr.Dataset, direction: int, lyapunov: xr.Dataset | None = None):
    """(values, outer values, codes (len(outer), len(values))) of the points of one sweep
    direction (+1 up, -1 down); -1 where a (value, outer) pair has no point. With
    ``lyapunov`` (the same sweep's exponents) irregular is split (``split_irregular``)."""
    sel = ds["direction"].values == direction
    val, out = ds["value"].values[sel], ds["outer_value"].values[sel]
    codes = sweep_regimes(ds)
    if lyapunov is not None:
        if not _same_points(ds, lyapunov):
            raise ValueError("the lyapunov dataset's points (value, outer_value, direction, "
                             "phi) differ from the sweep's")
        codes = split_irregular(codes, lyapunov)
    codes = codes[sel]
    xs, ys = np.unique(val), np.unique(out)
    grid = np.full((ys.size, xs.size), -1, dtype=int)
    grid[np.searchsorted(ys, out), np.searchsorted(xs, val)] = codes
    return xs, ys, grid
