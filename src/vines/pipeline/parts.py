"""Chunk jobs of the chunked stages: which items each job computes, and its part file.

A chunked stage (``robust_map``, ``orbit_atlas``, ``basin_slice``, ``lyapunov``,
``design``, ``convergence``, ``uncertainty``, ``design_robust``, ``design_map``) lists the
independent items of one config entry (points, eta rows, sweep lines, search designs, sample
points, search designs on each host, map cells) in dataset order; ``item_ranges`` cuts them into
runs of whole items of about ``points`` points each (the config's ``chunks`` section),
one job per run. A job writes its results as a part file (``write_part``: a pickle,
written atomically beside its path); the gather job reads the parts in order
(``read_parts``) and builds the same dataset as one job computing every item would: each
item's numbers depend on the item alone, never on the run it is computed in.
"""
from __future__ import annotations

import math
import pickle
from pathlib import Path

#: the stages split into chunk jobs (config ``chunks`` keys besides ``simulate_grid``) ->
#: the config section of their entries
CHUNKED_STAGES = {"robust_map": "robust_maps", "orbit_atlas": "orbit_atlases",
                  "basin_slice": "basin_slices", "lyapunov": "lyapunov_sweeps",
                  "design": "designs", "convergence": "convergence",
                  "uncertainty": "uncertainty", "design_robust": "design_robust",
                  "design_map": "design_maps"}


def item_ranges(n_items: int, points_per_item: int, points: int) -> list[tuple[int, int]]:
    """[(start, stop)] cutting ``n_items`` items of ``points_per_item`` points each into
    runs of at most ``points`` points (at least one item a run), as even as they go."""
    n_items = int(n_items)
    per = max(1, int(points) // max(1, int(points_per_item)))
    n_runs = max(1, math.ceil(n_items / per))
    bounds = [round(k * n_items / n_runs) for k in range(n_runs + 1)]
    return [(a, b) for a, b in zip(bounds[:-1], bounds[1:], strict=True) if b > a]


def stage_items(stage: str, name: str, config: dict) -> tuple[int, int]:
    """(items, points per item) of the entry ``name`` of a chunked stage in a validated
    ``config``: robust_map and basin_slice points (states), orbit_atlas eta rows,
    lyapunov sweep lines, design search-grid designs (runs from rest each: omega values x
    amplitudes), uncertainty sample points, design_robust search-grid designs per host, design_map cells,
    convergence finest-grid eta rows of the ``grid`` study (the other studies
    and a design that is evaluated, not searched: no items, one job)."""
    from .axes import axis_values
    from .config_checks import atlas_grid
    if stage == "robust_map":
        e = config["robust_maps"][name]
        return axis_values(e["eta"]).size * axis_values(e["omega"]).size, 1
    if stage == "basin_slice":
        e = config["basin_slices"][name]
        return axis_values(e["z_m0"]).size * axis_values(e["v_m0"]).size, 1
    if stage == "orbit_atlas":
        g = atlas_grid(config, name)
        return axis_values(g["eta"]).size, axis_values(g["omega"]).size
    if stage == "lyapunov":
        sw = config["sweeps"][config["lyapunov_sweeps"][name]["sweep"]]
        lines = axis_values(sw["outer_values"]).size * len(sw["directions"])
        return lines, axis_values(sw["values"]).size
    if stage == "design":
        return _design_items(config["designs"][name])
    if stage == "uncertainty":
        return _uncertainty_items(config["uncertainty"][name])
    if stage == "design_robust":
        return _design_robust_items(config["design_robust"][name])
    if stage == "design_map":
        return _design_map_cells(config, name), 1
    if stage == "convergence":
        if name != "grid":
            return 0, 1
        rows = int(max(config["convergence"]["grid"]["resolutions"]))
        return rows, rows
    raise ValueError(f"{stage} is not a chunked stage ({', '.join(CHUNKED_STAGES)})")


def _design_items(entry: dict) -> tuple[int, int]:
    """(search-grid designs, runs from rest per design) of a ``designs`` entry."""
    from ..studies import design_checks as dc
    if entry.get("eta_max") is None:
        return 0, 1
    n = entry.get("n_eta", dc.N_ETA_DEFAULT) * entry.get("n_clearance", dc.N_CLEARANCE_DEFAULT)
    amps = entry.get("amplitudes_m", dc.DEFAULT_AMPLITUDES_M)
    amps = [amps] if isinstance(amps, (int, float)) else amps
    return n, entry.get("n_omega", dc.DEFAULT_N_OMEGA) * len(amps)


def _uncertainty_items(entry: dict) -> tuple[int, int]:
    """(sample points n (k + 2), runs from rest per point: omega values x amplitudes) of
    an ``uncertainty`` entry."""
    n, k = int(entry["samples"]), len(entry["parameters"])
    return n * (k + 2), _design_items(entry["design"] | {"eta_max": 1.0})[1]


def _design_robust_items(entry: dict) -> tuple[int, int]:
    """(search-grid designs on each distinct host of the searches: the nominal one and
    the robust search's n_search drifts, delta = 0 once; runs per design) of a
    ``design_robust`` entry (``studies.mistuning.search_hosts``)."""
    from ..studies.mistuning import search_hosts
    n, per = _design_items(entry)
    return n * len(search_hosts(entry["mistuning"], entry["n_search"])), per


def _design_map_cells(config: dict, name: str) -> int:
    """Cells (eta x half_width x span) of a ``design_maps`` entry."""
    e = config["design_maps"][name]
    eta = e["eta"]
    n_eta = int(eta["num"]) if isinstance(eta, dict) else axis_size(eta)
    return n_eta * axis_size(e["half_width"]) * axis_size(e["span"])


def axis_size(values) -> int:
    return 1 if isinstance(values, (int, float)) else len(values)


def chunk_plan(stage: str, name: str, config: dict) -> list[tuple[int, int]]:
    """The item ranges of the chunk jobs of one entry (``config['chunks'][stage]`` points
    a job); [] when the entry has no items to split (its gather job computes it)."""
    n, per = stage_items(stage, name, config)
    return item_ranges(n, per, config["chunks"][stage])


def write_part(obj, path) -> Path:
    """Pickle ``obj`` to ``path`` atomically (temporary beside it, then renamed)."""
    from ..data.netcdf import write_atomically

    def dump(tmp):
        with open(tmp, "wb") as fh:
            pickle.dump(obj, fh, protocol=pickle.HIGHEST_PROTOCOL)

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    return write_atomically(path, dump)


def read_parts(paths) -> list:
    """The objects of the part files ``paths``, in order (files this workflow wrote)."""
    out = []
    for p in paths:
        with open(p, "rb") as fh:
            out.append(pickle.load(fh))  # noqa: S301 (the workflow's own temporary files)
    return out
