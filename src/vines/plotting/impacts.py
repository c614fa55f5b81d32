"""Impacts of a time-history dataset and the direction of motion just before each (Figs 4,
5, 9, 10).

The dataset stores per impact its time, wall and relative velocity w'_i = v_m- - v_b-, not
the two velocities. Between impacts the ball flies freely (constant velocity) or sticks to
the LO (v_b = v_m), so the ball's velocity just before impact i is its sampled velocity at
the last sample after impact i-1 and before impact i; when no sample lies between two
impacts it is carried over the impact by the impact law (momentum v_m + eta v_b kept,
coefficient of restitution r): v_b+ = v_b- + (1 + r) w'/(1 + eta). Then v_m- = v_b- + w'.
Impacts before the first sample have no known direction (``UNKNOWN``; the time-history
datasets sample the whole window, so there are none there).
"""
from __future__ import annotations

import numpy as np
import xarray as xr

#: the LO and the ball move towards each other (v_m v_b < 0) / the same way (> 0) before
#: impact (a velocity exactly zero counts as "towards each other")
TOWARDS, SAME_WAY, UNKNOWN = 0, 1, -1


def point_impacts(ds: xr.Dataset, i: int) -> dict:
    """Impacts of point ``i`` of a time-history dataset: t, dw, phase, wall arrays."""
    edges = np.concatenate([[0], np.cumsum(ds["row_size"].values)])
    return {k: ds[f"impact_{k}"].values[edges[i]:edges[i + 1]]
            for k in ("t", "dw", "phase", "wall")}


def _samples(ds: xr.Dataset, i: int):
    """All samples (t, v_b) of point ``i`` (last periods and whole window), time-sorted."""
    parts = [("t", "v_b")] + ([("window_t", "window_v_b")] if "window_t" in ds.variables
                              else [])
    t = np.concatenate([np.asarray(ds[a].values[i], float) for a, _ in parts])
    v = np.concatenate([np.asarray(ds[b].values[i], float) for _, b in parts])
    order = np.argsort(t, kind="stable")
    return t[order], v[order]


def pre_impact_velocities(ds: xr.Dataset, i: int) -> tuple[np.ndarray, np.ndarray]:
    """(v_m-, v_b-) just before every impact of point ``i`` (see the module docstring);
    needs the dataset attributes ``solver_r`` and the point's ``eta``."""
    imp = point_impacts(ds, i)
    t_imp, dw = imp["t"], imp["dw"]
    n = t_imp.size
    vb = np.full(n, np.nan)
    if n == 0:
        return vb, vb
    ts, vs = _samples(ds, i)
    prev = np.concatenate([[-np.inf], t_imp[:-1]])
    k = np.searchsorted(ts, t_imp, side="left") - 1           # last sample before impact
    ok = (k >= 0) & (ts[np.maximum(k, 0)] > prev)
    vb[ok] = vs[k[ok]]
    if np.isnan(vb[1:]).any():                                 # carried over impacts
        jump = (1.0 + float(ds.attrs["solver_r"])) * dw / (1.0 + float(ds["eta"].values[i]))
        for j in range(1, n):
            if np.isnan(vb[j]) and not np.isnan(vb[j - 1]):
                vb[j] = vb[j - 1] + jump[j - 1]
    return vb + dw, vb


def impact_direction(ds: xr.Dataset, i: int) -> np.ndarray:
    """``TOWARDS``, ``SAME_WAY`` (sign of v_m- v_b-) or ``UNKNOWN`` for every impact of
    point ``i``."""
    vm, vb = pre_impact_velocities(ds, i)
    return np.where(np.isnan(vb), UNKNOWN, np.where(vm * vb > 0, SAME_WAY, TOWARDS))
