"""Chunk jobs of the chunked stages: which items each job computes, and its part file.

A chunked stage (``robust_map``, ``orbit_atlas``, ``basin_slice``, ``lyapunov``,
``design``, ``convergence``) lists the independent items of one config entry (points,
eta rows, sweep lines, search designs) in dataset order; ``item_ranges`` cuts them into
runs of whole items of about ``points`` points each (the config's ``chunks`` section),
one job per run. A job writes its results as a part file (``write_part``: a pickle,
written atomically beside its path); the gather job reads the parts in order
(``read_parts``) and builds the same dataset as one job computing every item would: each
item's numbers depend on the item alone, never on the run it is computed in.
"""
from __future__ import annotations

import math
import os
import pickle
from pathlib import Path

#: the stages split into chunk jobs (config ``chunks`` keys besides ``simulate_grid``)
CHUNKED_STAGES = ("robust_map", "orbit_atlas", "basin_slice", "lyapunov", "design",
                  "convergence")


def item_ranges(n_items: int, points_per_item: int, points: int) -> list[tuple[int, int]]:
    """[(start, stop)] cutting ``n_items`` items of ``points_per_item`` points each into
    runs of at most ``points`` points (at least one item a run), as even as they go."""
    n_items = int(n_items)
    per = max(1, int(points) // max(1, int(points_per_item)))
    n_runs = max(1, math.ceil(n_items / per))
    bounds = [round(k * n_items / n_runs) for k in range(n_runs + 1)]
    return [(a, b) for a, b in zip(bounds[:-1], bounds[1:], strict=True) if b > a]


def write_part(obj, path) -> Path:
    """Pickle ``obj`` to ``path`` atomically (temporary beside it, then renamed)."""
    from ..data.netcdf import temporary_beside
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temporary_beside(path, ".tmp")
    try:
        with open(tmp, "wb") as fh:
            pickle.dump(obj, fh, protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def read_parts(paths) -> list:
    """The objects of the part files ``paths``, in order (files this workflow wrote)."""
    out = []
    for p in paths:
        with open(p, "rb") as fh:
            out.append(pickle.load(fh))  # noqa: S301 (the workflow's own temporary files)
    return out
