"""Geometry of the grids of parameter values (numbers only): the cells that grid points
stand for, as maps draw them and as rasters finer than a grid subdivide them."""
from __future__ import annotations

import numpy as np


def cell_edges(v, single=None) -> np.ndarray:
    """Edges of the cells of the grid points ``v`` (increasing): half-way between points,
    the end cells symmetric about their point. A single point needs ``single``, the width
    of its cell (centred on it)."""
    v = np.asarray(v, float)
    if v.size == 1:
        if single is None:
            raise ValueError("the cell of a single grid point needs its width")
        return np.array([v[0] - single / 2, v[0] + single / 2])
    mid = (v[1:] + v[:-1]) / 2
    return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])


def log_cell_edges(v, single=0.16) -> np.ndarray:
    """``cell_edges`` of the logarithms of ``v`` (> 0), back in ``v``'s units: edges at the
    geometric means of neighbours; a single point's cell spans ``single`` decades."""
    return 10.0 ** cell_edges(np.log10(np.asarray(v, float)), single)
