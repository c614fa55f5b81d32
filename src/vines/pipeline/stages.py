"""The pipeline's compute stages: config entry in, CF dataset out.

One function per stage, named as the rule, the rule file, the workflow script and the
output folder: ``simulate_grid``, ``extract_measures``, ``bifurcation_sweep``,
``lyapunov``, ``map_solve``, ``stability_map``, ``boundaries``, ``timehistory``,
``robust_map``, ``basin_slice``, ``work_precision``, ``convergence``, ``design``,
``design_robust``, ``uncertainty``, ``orbit_atlas``, ``shock``, ``model_ladder``. Each
calls the numerics
(``vines.core``, ``vines.orbits``, ``vines.attractors``, ``vines.studies``), lets
``vines.pipeline.execution`` spread independent tasks over dask, and hands plain arrays to
``vines.data.builders``. Results are assembled by index, so the
numbers do not depend on workers, block size, chunk size or scheduler.
"""
from __future__ import annotations

import numpy as np

from ..core.params import PARAM_NAMES
from ..data import builders
from ..data.netcdf import read_dataset
from ..data.provenance import provenance_attrs
from .axes import axis_values


def compute(tasks: list, n_workers: int, scheduler: str | None, progress: bool) -> list:
    """``execution.compute``, imported on first use: dask costs ~0.3 s of every job that
    imports it, and only the stages with dask tasks need it."""
    from .execution import compute as run
    return run(tasks, n_workers, scheduler, progress)


# ------------------------------------------------------------------ simulate-grid

def _batch_block(eta, omega, F, kw):
    from ..core.simulation import simulate_batch
    return simulate_batch(eta, omega, F, n_threads=1, **kw)


def compute_chunk(chunk: dict, *, model: dict, simulation: dict, n_workers: int = 1,
                  block_size: int = 64, scheduler: str | None = None,
                  progress: bool = False) -> dict:
    """``simulate_batch`` fields of shape (n_eta, n_omega, n_F) for one chunk (sub-grid),
    in dask blocks of ``block_size`` points."""
    import dask

    from ..core.simulation import BATCH_FIELDS
    e, w, f = np.meshgrid(*(np.asarray(chunk[d], dtype=float) for d in PARAM_NAMES), indexing="ij")
    shape = e.shape
    e, w, f = e.ravel(), w.ravel(), f.ravel()
    kw = {**model, **simulation}
    bs = max(1, int(block_size))
    starts = list(range(0, e.size, bs))
    tasks = [dask.delayed(_batch_block, pure=True)(e[i:i + bs], w[i:i + bs], f[i:i + bs], kw)
             for i in starts]
    parts = compute(tasks, max(1, int(n_workers)), scheduler, progress)
    out = {}
    for k, dt in BATCH_FIELDS.items():
        arr = np.empty(e.size, dtype=dt)
        for i, part in zip(starts, parts, strict=False):
            arr[i:i + bs] = part[k]
        out[k] = arr.reshape(shape)
    return out


def simulate_grid(points: dict, *, model: dict, simulation: dict, code: str, title: str,
                  n_workers: int = 1, block_size: int = 64, scheduler: str | None = None):
    """Dataset of one grid chunk: the batch fields at every point."""
    fields = compute_chunk(points, model=model, simulation=simulation, n_workers=n_workers,
                           block_size=block_size, scheduler=scheduler, progress=True)
    subset = {"points": points, "model": model, "simulation": simulation}
    attrs = provenance_attrs(title=title, config_subset=subset,
                             settings={**model, **simulation}, code_version=code)
    return builders.grid_dataset(points, fields, attrs)


# ------------------------------------------------------------------ extract-measures

def _plain(v):
    return v.item() if isinstance(v, np.generic) else v


def _chunk_settings(chunks, paths) -> dict:
    """Solver settings shared by all chunks (attributes ``solver_*``); they must agree."""
    def settings(c):
        return {k[len("solver_"):]: v for k, v in c.attrs.items() if k.startswith("solver_")}
    first = settings(chunks[0])
    for c, p in zip(chunks[1:], list(paths)[1:], strict=False):
        if {k: _plain(v) for k, v in settings(c).items()} != {k: _plain(v) for k, v in first.items()}:
            raise ValueError(f"{p}: solver settings differ from those of {list(paths)[0]}")
    return first


def extract_measures(chunk_paths, *, axes: dict, sections: dict, model: dict, code: str,
                     title: str):
    """Merge a grid's chunk files and add metres, the stuck-linear amplitude, masks and
    section markers."""
    from ..core.measures import derived_measures, section_marks
    chunks = [read_dataset(f) for f in chunk_paths]
    fields = builders.merge_chunks(chunks, axes)
    settings = _chunk_settings(chunks, chunk_paths)
    subset = {"axes": axes, "sections": sections, "model": model,
              "settings": {k: _plain(v) for k, v in settings.items()}}
    attrs = provenance_attrs(title=title, config_subset=subset, settings=settings,
                             code_version=code)
    grid = builders.grid_dataset(axes, fields, attrs)
    derived = derived_measures(fields, axes["eta"], axes["omega"], axes["F"], model["d"])
    marks = {dim: section_marks(axes[dim], vals, dim) for dim, vals in sections.items()}
    return builders.measures_dataset(grid, derived, marks)


# ------------------------------------------------------------------ bifurcation-sweep

def _sweep_line(param, values, fixed, kw):
    from ..core.sweep import bifurcation_sweep as sweep_line
    return sweep_line(param, values, **fixed, **kw)


def _sweep_lines(spec: dict) -> list:
    """(outer value, direction, values, fixed) of every sweep line, in dataset order."""
    values = axis_values(spec["values"])
    lines = []
    for ov in axis_values(spec["outer_values"]).tolist():
        for direction in spec["directions"]:
            vals = values if direction == "up" else values[::-1].copy()
            fixed = {**{k: float(v) for k, v in spec["fixed"].items()}, spec["outer"]: ov}
            lines.append((ov, direction, vals, fixed))
    return lines


def compute_sweep(spec: dict, *, model: dict, periodic_shortcut: bool = True,
                  n_workers: int = 1, scheduler: str | None = None,
                  progress: bool = False) -> dict:
    """Bifurcation sweeps of one config entry: every outer value, up and down.

    Returns instance arrays (one entry per (line, direction, value)) and concatenated
    impact arrays, ordered line by line (outer values ascending, 'up' before 'down').
    ``periodic_shortcut``: the config's ``simulation.periodic_shortcut``.
    """
    import dask
    kw = dict(t_settle=spec["t_settle"], t_step=spec["t_step"], n_record=spec["n_record"],
              v_stick=spec["v_stick"], periodic_shortcut=periodic_shortcut, **model)
    lines = _sweep_lines(spec)
    tasks = [dask.delayed(_sweep_line, pure=True)(spec["param"], vals, fixed, kw)
             for (_, _, vals, fixed) in lines]
    res = compute(tasks, max(1, int(n_workers)), scheduler, progress)
    inst = {k: [] for k in ("value", "outer_value", "direction", "line", "phi", "status",
                            "shortcut_time", "row_size")}
    samp = {k: [] for k in ("dw", "phase", "wall")}
    for li, ((ov, direction, _, _), r) in enumerate(zip(lines, res, strict=False)):
        n = r["value"].size
        inst["outer_value"].append(np.full(n, ov))
        inst["direction"].append(np.full(n, 1 if direction == "up" else -1, dtype="i1"))
        inst["line"].append(np.full(n, li, dtype="i4"))
        for k in ("value", "phi", "status", "shortcut_time", "row_size"):
            inst[k].append(r[k])
        for k in samp:
            samp[k].append(r[k])
    cat = {k: np.concatenate(v) for k, v in {**inst, **samp}.items()}
    cat["wall"] = cat["wall"].astype("i1")
    return cat


def bifurcation_sweep(spec: dict, *, model: dict, code: str, title: str, n_workers: int = 1,
                      scheduler: str | None = None, periodic_shortcut: bool = True):
    """Dataset of one sweep entry: impacts of the last ``n_record`` periods per value."""
    sweep = compute_sweep(spec, model=model, periodic_shortcut=periodic_shortcut,
                          n_workers=n_workers, scheduler=scheduler, progress=True)
    settings = {**model, **{k: spec[k] for k in ("t_settle", "t_step", "n_record", "v_stick")},
                "periodic_shortcut": bool(periodic_shortcut)}
    attrs = provenance_attrs(title=title,
                             config_subset={"spec": spec, "model": model,
                                            "periodic_shortcut": bool(periodic_shortcut)},
                             settings=settings, code_version=code)
    attrs.update(swept_parameter=spec["param"], outer_parameter=spec["outer"],
                 fixed=", ".join(f"{k}={v!r}" for k, v in sorted(spec["fixed"].items())))
    return builders.sweep_dataset(sweep, spec["param"], spec["outer"], attrs)


# ------------------------------------------------------------------ lyapunov

def _lyapunov_line(param, values, fixed, kw, window):
    from ..attractors.lyapunov_sweep import sweep_exponents
    from ..core.sweep import SweepLine
    return sweep_exponents(SweepLine(param, values, **fixed, **kw), **window)


def lyapunov_part(spec: dict, sweep: dict, *, model: dict, start: int, stop: int,
                  periodic_shortcut: bool = True, n_workers: int = 1,
                  scheduler: str | None = None) -> list:
    """The exponents along the sweep lines [start, stop) (``_sweep_lines`` order) of
    ``lyapunov``: one result per line (one dask task each)."""
    import dask
    kw = dict(t_settle=sweep["t_settle"], t_step=sweep["t_step"], n_record=sweep["n_record"],
              v_stick=sweep["v_stick"], periodic_shortcut=periodic_shortcut, **model)
    window = dict(t_window=spec["t_window"], n_batches=spec["n_batches"])
    tasks = [dask.delayed(_lyapunov_line, pure=True)(sweep["param"], vals, fixed, kw, window)
             for (_, _, vals, fixed) in _sweep_lines(sweep)[start:stop]]
    return compute(tasks, max(1, int(n_workers)), scheduler, True)


def lyapunov(spec: dict, sweep: dict, *, model: dict, code: str, title: str,
             periodic_shortcut: bool = True, n_workers: int = 1, scheduler: str | None = None,
             parts: list | None = None):
    """Dataset of the Lyapunov exponents along the sweep entry ``sweep`` (the config's
    ``sweeps[spec['sweep']]``, with defaults): every line (outer value, direction), every
    point, over the last ``spec['t_window']`` of the point's run (one dask task per line).
    ``parts``: the ``lyapunov_part`` results covering every line in order (else computed
    here)."""
    lines = _sweep_lines(sweep)
    if parts is None:
        parts = [lyapunov_part(spec, sweep, model=model, start=0, stop=len(lines),
                               periodic_shortcut=periodic_shortcut, n_workers=n_workers,
                               scheduler=scheduler)]
    res = [r for part in parts for r in part]
    if len(res) != len(lines):
        raise ValueError(f"parts hold {len(res)} sweep lines, the sweep {len(lines)}")
    cat = {k: np.concatenate([r[k] for r in res]) for k in res[0]}
    cat["outer_value"] = np.concatenate([np.full(r["value"].size, ov)
                                         for (ov, _, _, _), r in zip(lines, res, strict=True)])
    cat["direction"] = np.concatenate([np.full(r["value"].size, 1 if dr == "up" else -1, "i1")
                                       for (_, dr, _, _), r in zip(lines, res, strict=True)])
    cat["line"] = np.concatenate([np.full(r["value"].size, i, "i4")
                                  for i, r in enumerate(res)])
    settings = {**model, **{k: sweep[k] for k in ("t_settle", "t_step", "n_record", "v_stick")},
                "periodic_shortcut": bool(periodic_shortcut), "t_window": spec["t_window"],
                "n_batches": spec["n_batches"]}
    attrs = provenance_attrs(title=title, config_subset={"spec": spec, "sweep": sweep,
                                                         "model": model,
                                                         "periodic_shortcut": bool(periodic_shortcut)},
                             settings=settings, code_version=code)
    attrs.update(swept_parameter=sweep["param"], outer_parameter=sweep["outer"],
                 sweep=spec["sweep"],
                 fixed=", ".join(f"{k}={v!r}" for k, v in sorted(sweep["fixed"].items())),
                 window=f"last t_window = {spec['t_window']:g} of each point's run "
                        "(finite-time exponents)")
    return builders.lyapunov_sweep_dataset(cat, sweep["param"], sweep["outer"], attrs)


# ------------------------------------------------------------------ map-solve, stability-map

#: parameter tolerance of the events of a stored branch (the smallest continue_branch
#: accepts): a symmetry-breaking event then coincides with the exactly solved start of the
#: asymmetric branch switched onto there
BRANCH_EVENT_TOL = 1e-12


def switch_start(branch, start: float):
    """Parameter value and orbit where the switching run along ``branch`` (a natural run
    from ``start``) starts: ``(start, None)`` (the preferred orbit there) if the branch's
    first point is admissible or none is, else its first admissible point and orbit."""
    admissible = np.asarray(branch.admissible, dtype=bool)
    if admissible.size == 0 or admissible[0] or not admissible.any():
        return start, None
    first = int(np.argmax(admissible))
    return float(branch.values[first]), branch.orbits[first]


def map_solve(spec: dict, *, model: dict, code: str, title: str):
    """Dataset of one 1:1 branch continued in ``spec['param']`` with stability and events,
    and (``spec['switch']``, default true) the asymmetric branches born at its
    symmetry-breaking points.

    The branch itself is continued in natural-parameter steps over the whole interval
    [start, stop], as the paper draws it (admissible or not at every step); the asymmetric
    branches are those a pseudo-arclength run of the same branch switches onto. That run
    starts at the branch's first admissible point (a run started on a non-admissible
    stretch stops there and never meets the symmetry-breaking points beyond it) and may end
    before ``stop``, e.g. after a long non-admissible stretch."""
    from ..orbits.continuation.one_to_one import continue_branch
    fixed = {k: float(v) for k, v in spec["fixed"].items()}
    args = (spec["param"], spec["start"], spec["stop"], spec["step"], fixed)
    br = continue_branch(*args, r=model["r"], d=model["d"], method="natural",
                         event_tol=BRANCH_EVENT_TOL)
    if bool(spec.get("switch", True)):
        start, orbit = switch_start(br, spec["start"])
        br.switched = continue_branch(spec["param"], start, *args[2:], orbit=orbit,
                                      r=model["r"], d=model["d"], method="arclength",
                                      switch=True).switched
    attrs = provenance_attrs(title=title, config_subset={"spec": spec, "model": model},
                             settings=model, code_version=code)
    attrs.update(continued_parameter=spec["param"], stopped=str(br.stopped))
    return builders.branch_dataset(br, attrs)


def boundaries(spec: dict, *, model: dict, code: str, title: str, stability_path=None):
    """Dataset of the boundary curves (fold, flip, Neimark-Sacker, symmetry-breaking,
    grazing) of 1:1 orbits (or of ``spec['walls']``/``spec['periods']``) in the box ``spec['eta_range']`` x ``spec['omega_range']`` at
    ``spec['F']``; the class changes of the stability map at ``stability_path`` (a
    ``stability_map`` dataset at this F), if given, seed the curves no scan line meets."""
    from ..orbits.curves.boundaries import boundaries as curves_at
    kw = {k: spec[k] for k in ("n_scan", "step", "max_points", "n_map", "walls", "periods")
          if k in spec}
    if stability_path is not None:
        smap = read_dataset(stability_path)
        if float(smap.attrs["F"]) != float(spec["F"]):
            raise ValueError(f"{stability_path}: stability map at F = {smap.attrs['F']}, "
                             f"boundaries at F = {spec['F']}")
        kw["class_map"] = (smap["eta"].values, smap["omega"].values, smap["cls"].values)
    res = curves_at(float(spec["F"]), spec["eta_range"], spec["omega_range"],
                    r=model["r"], d=model["d"], **kw)
    attrs = provenance_attrs(title=title, config_subset={"spec": spec, "model": model},
                             settings=model, code_version=code)
    attrs.update(eta_range=list(res.eta_range), omega_range=list(res.omega_range))
    from ..orbits.family.family import Family
    family = Family(res.walls, res.periods)
    keys = family.engine.output_keys(family)        # 1:1: none, the dataset it always was
    attrs.update(keys)
    return builders.boundaries_dataset(res.curves, res.F, attrs, named_family=bool(keys))


def stability_map(spec: dict, *, model: dict, code: str, title: str, n_workers: int = 1):
    """Dataset of one stability map over (eta, omega) at ``spec['F']``."""
    from ..orbits.atlas.stability_map import stability_map as solve_map
    eta, omega = axis_values(spec["eta"]), axis_values(spec["omega"])
    res = solve_map(eta, omega, float(spec["F"]), r=model["r"], d=model["d"],
                    n_threads=n_workers)
    attrs = provenance_attrs(title=title, config_subset={"spec": spec, "model": model},
                             settings=model, code_version=code)
    attrs["F"] = float(spec["F"])
    return builders.stability_dataset(eta, omega, res, attrs)


# ------------------------------------------------------------------ timehistory

def timehistory(spec: dict, *, model: dict, simulation: dict, code: str, title: str):
    """Dataset of the time histories of one figure's points."""
    from ..core.measures import WINDOW_SAMPLES_PER_PERIOD, time_histories
    points = [dict(p) for p in spec["points"]]
    th = time_histories(points, model=model, simulation=simulation,
                        n_periods=spec["n_periods"],
                        samples_per_period=spec["samples_per_period"],
                        window_samples_per_period=spec.get("window_samples_per_period",
                                                           WINDOW_SAMPLES_PER_PERIOD))
    attrs = provenance_attrs(title=title, config_subset={"spec": spec, "model": model,
                                                         "simulation": simulation},
                             settings={**model, **simulation}, code_version=code)
    return builders.timehistory_dataset(points, th, attrs)


# ------------------------------------------------------------------ robust-map, basin-slice

#: census settings taken from the ``simulation`` section (the shortcut is always on)
CENSUS_SETTINGS = ("t_end", "t_transient", "v_stick", "max_impacts", "root_tol")


def _census_kw(model: dict, simulation: dict) -> dict:
    return {"r": model["r"], "d": model["d"],
            **{k: simulation[k] for k in CENSUS_SETTINGS if k in simulation}}


def _views(spec: dict) -> dict:
    """Global attributes naming the views a census dataset holds."""
    if spec.get("t_max") is None:
        return {"views": "window (state at t_end)"}
    return {"views": "window (state at t_end) and asymptotic (*_asymptotic: state at t_max)",
            "t_max": float(spec["t_max"])}


def _robust_block(points, F, kw):
    from ..attractors.census_maps import robust_point
    return [robust_point(e, w, F, n_threads=1, **kw) for e, w in points]


def _robust_points(spec: dict) -> tuple:
    """eta, omega axes of a robust map and its points (eta slowest)."""
    eta, omega = axis_values(spec["eta"]), axis_values(spec["omega"])
    return eta, omega, [(e, w) for e in eta for w in omega]


def robust_map_part(spec: dict, *, model: dict, simulation: dict, start: int, stop: int,
                    n_workers: int = 1, block_size: int = 4,
                    scheduler: str | None = None) -> list:
    """The census rows of the robust map's points [start, stop) (eta slowest), in dask
    blocks: every point's census of the same ``spec['n']`` Sobol states (seed
    ``spec['seed']``)."""
    import dask
    points = _robust_points(spec)[2][start:stop]
    kw = {**_census_kw(model, simulation), "n": spec["n"], "seed": spec["seed"],
          "threshold": spec["threshold"], "t_max": spec.get("t_max")}
    bs = max(1, int(block_size))
    tasks = [dask.delayed(_robust_block, pure=True)(points[i:i + bs], float(spec["F"]), kw)
             for i in range(0, len(points), bs)]
    return [r for part in compute(tasks, max(1, int(n_workers)), scheduler, True) for r in part]


def robust_map(spec: dict, *, model: dict, simulation: dict, code: str, title: str,
               n_workers: int = 1, block_size: int = 4, scheduler: str | None = None,
               parts: list | None = None):
    """Dataset of one robust-TET map over (eta, omega) at ``spec['F']``: a census of
    ``spec['n']`` Sobol states (seed ``spec['seed']``) per point, in dask blocks.
    ``parts``: the ``robust_map_part`` results covering every point in order (else
    computed here)."""
    from ..attractors.census_maps import ROBUST_ASYMPTOTIC_FIELDS, ROBUST_FIELDS
    eta, omega, points = _robust_points(spec)
    if parts is None:
        parts = [robust_map_part(spec, model=model, simulation=simulation, start=0,
                                 stop=len(points), n_workers=n_workers,
                                 block_size=block_size, scheduler=scheduler)]
    rows = [r for part in parts for r in part]
    if len(rows) != len(points):
        raise ValueError(f"parts hold {len(rows)} points, the map {len(points)}")
    kw = {"t_max": spec.get("t_max")}
    names = ROBUST_FIELDS + (ROBUST_ASYMPTOTIC_FIELDS if kw["t_max"] is not None else ())
    fields = {k: np.array([r[k] for r in rows]).reshape(len(eta), len(omega)) for k in names}
    attrs = provenance_attrs(title=title, config_subset={"spec": spec, "model": model,
                                                         "simulation": simulation},
                             settings={**model, **simulation}, code_version=code)
    attrs.update(F=float(spec["F"]), threshold=float(spec["threshold"]),
                 n_states=int(spec["n"]), seed=int(spec["seed"]), **_views(spec))
    return builders.robust_dataset(eta, omega, fields, attrs)


def basin_slice_part(spec: dict, *, model: dict, simulation: dict, start: int, stop: int,
                     n_workers: int = 1) -> dict:
    """The runs of the slice's initial states [start, stop) (z_m0 slowest) of
    ``basin_slice``."""
    from ..attractors.census_maps import basin_slice_part as runs
    return runs(spec["eta"], spec["omega"], spec["F"], axis_values(spec["z_m0"]),
                axis_values(spec["v_m0"]), start, stop, n_threads=max(1, int(n_workers)),
                t_max=spec.get("t_max"), **_census_kw(model, simulation))


def basin_slice(spec: dict, *, model: dict, simulation: dict, code: str, title: str,
                n_workers: int = 1, parts: list | None = None):
    """Dataset of one basin slice: the attractor reached from each (z_m(0), z_m'(0)) with
    the ball at rest in the middle of the cavity, at ``spec``'s (eta, omega, F).
    ``parts``: the ``basin_slice_part`` results covering every state in order (else the
    states are run here)."""
    from ..attractors.census_maps import basin_slice as solve_slice
    from ..attractors.census_maps import basin_slice_of_parts
    z_m0, v_m0 = axis_values(spec["z_m0"]), axis_values(spec["v_m0"])
    kw = dict(n_threads=max(1, int(n_workers)), t_max=spec.get("t_max"),
              **_census_kw(model, simulation))
    point = (spec["eta"], spec["omega"], spec["F"], z_m0, v_m0)
    res = (solve_slice(*point, **kw) if parts is None
           else basin_slice_of_parts(*point, parts, **kw))
    attrs = provenance_attrs(title=title, config_subset={"spec": spec, "model": model,
                                                         "simulation": simulation},
                             settings={**model, **simulation}, code_version=code)
    attrs.update(eta=float(spec["eta"]), omega=float(spec["omega"]), F=float(spec["F"]),
                 **_views(spec))
    return builders.basin_slice_dataset(z_m0, v_m0, res, attrs)


# ------------------------------------------------------------------ work-precision, convergence

def work_precision(case: dict, *, settings: dict, model: dict, v_stick: float, code: str,
                   title: str, progress=None):
    """Dataset of one work-precision case: error and cost of every solver setting against
    the 40-digit reference (``settings``: the ``work_precision`` section but its cases)."""
    from ..studies.workprecision import work_precision as study
    result = study(case["eta"], case["omega"], case["F"], t_end=case["t_end"],
                   t_transient=case["t_transient"], r=model["r"], d=model["d"],
                   v_stick=v_stick, v_sticks=case.get("v_sticks", []),
                   root_tols=settings["root_tols"], rk_methods=settings["rk_methods"],
                   rtols=settings["rtols"], dps=settings["dps"],
                   h_sample=settings["h_sample"], v_visible=settings["v_visible"],
                   min_time=settings["min_time"], progress=progress)
    attrs = provenance_attrs(
        title=title,
        config_subset={"case": case, "settings": settings, "model": model, "v_stick": v_stick},
        settings=model, code_version=code)
    return builders.work_precision_dataset(result, attrs)


def convergence_part(study: str, spec: dict, *, model: dict, simulation: dict, start: int,
                     stop: int, n_workers: int = 1) -> dict:
    """The runs of the grid study's finest-grid eta rows [start, stop) (``study`` must be
    ``grid``: the one study split into chunk jobs)."""
    from ..studies.convergence import grid_convergence_part
    if study != "grid":
        raise ValueError(f"convergence study {study!r} is not split into parts")
    return grid_convergence_part(start, stop, **spec, **simulation, **model,
                                 n_threads=n_workers)


def convergence(study: str, spec: dict, *, model: dict, simulation: dict, code: str,
                title: str, n_workers: int = 1, parts: list | None = None):
    """Dataset of one convergence study (``study``: window, vstick or grid). ``parts``
    (grid only): the ``convergence_part`` results covering the finest grid's rows in
    order (else run here)."""
    from ..studies.convergence import STUDIES, grid_convergence_of_parts
    if parts:
        result = grid_convergence_of_parts(parts, **spec, **simulation, **model,
                                           n_threads=n_workers)
    else:
        result = STUDIES[study](**spec, **simulation, **model, n_threads=n_workers)
    attrs = provenance_attrs(
        title=title,
        config_subset={"spec": spec, "model": model, "simulation": simulation},
        settings={**model, **simulation}, code_version=code)
    return builders.convergence_dataset(study, result, attrs)


# ------------------------------------------------------------------ design

#: solver settings of the design runs taken from the ``simulation`` section (run length and
#: window are the entry's own t_end, t_transient)
DESIGN_SETTINGS = ("v_stick", "max_impacts", "root_tol")


def _design_kw(spec: dict, model: dict, simulation: dict, skip=()) -> tuple[dict, dict]:
    """``vines.design``'s keywords of a ``designs`` entry (but ``skip``), and the solver
    settings of it taken from the simulation section."""
    kw = {k: v for k, v in spec.items()
          if k not in ("description", *skip) and v is not None}
    settings = {k: simulation[k] for k in DESIGN_SETTINGS}
    return {**kw, "r": model["r"], **settings}, settings


def design_part(spec: dict, *, model: dict, simulation: dict, start: int, stop: int,
                n_workers: int = 1) -> dict:
    """The responses from rest of the search grid's designs [start, stop) of ``design``
    (``studies.design.grid_responses``)."""
    from ..studies.design import grid_responses
    kw, _ = _design_kw(spec, model, simulation)
    return grid_responses(start, stop, **kw, n_threads=max(1, int(n_workers)))


def design(spec: dict, *, model: dict, simulation: dict, code: str, title: str,
           n_workers: int = 1, parts: list | None = None):
    """Dataset of one ``designs`` entry: ``vines.design`` with the entry's keywords, the
    model's r and the simulation section's v_stick, max_impacts, root_tol (the structure's
    damping is the entry's: M, k, c or d, Table 1 by default). ``parts``: ``design_part``
    results for parts of the search grid (not run again; the same dataset)."""
    from ..studies.design import complete
    from ..studies.design import design as solve_design
    kw, settings = _design_kw(spec, model, simulation)
    n = max(1, int(n_workers))
    if parts:
        known = {"responses": {k: v for p in parts for k, v in p["responses"].items()},
                 "n_runs": sum(p["n_runs"] for p in parts)}
        res = complete(known, **kw, n_threads=n)
    else:
        res = solve_design(**kw, n_threads=n)
    cost = res.cost
    print(f"design: {cost['n_designs']} designs, {cost['n_runs_from_rest']} runs from rest, "
          f"{cost['n_runs_census']} census runs; wall {cost['wall_s']:.1f} s "
          f"(search {cost['search_s']:.1f} s, census {cost['census_s']:.1f} s), "
          f"CPU {cost['cpu_s']:.1f} s")
    return builders.design_dataset(res, _design_attrs(spec, model, settings, code, title))


def _design_attrs(spec, model, settings, code, title) -> dict:
    """The provenance attributes of a design entry's dataset."""
    return provenance_attrs(title=title, config_subset={"spec": spec, "model": model,
                                                         "settings": settings},
                            settings={"r": model["r"], **settings}, code_version=code)


def _solved_design(spec, model, simulation, code, title, n_workers, skip=()) -> tuple:
    """(``vines.design`` of an entry's keywords but ``skip``, the dataset's provenance)."""
    from ..studies.design import design as solve_design
    kw, settings = _design_kw(spec, model, simulation, skip)
    res = solve_design(**kw, n_threads=max(1, int(n_workers)))
    return res, _design_attrs(spec, model, settings, code, title)


# ------------------------------------------------------------------ design_robust

#: keys of a ``design_robust`` entry that are not ``vines.design`` keywords
MISTUNING_KEYS = ("mistuning", "n_delta", "n_search")


def design_robust_part(spec: dict, *, model: dict, simulation: dict, start: int, stop: int,
                       n_workers: int = 1) -> dict:
    """The responses of the search-grid designs [start, stop) on the hosts of the nominal
    and the robust search (``studies.mistuning.search_part``)."""
    from ..studies.design import prepared
    from ..studies.mistuning import search_part
    kw, _ = _design_kw(spec, model, simulation, skip=MISTUNING_KEYS)
    problem, search = prepared(**kw)
    return search_part(problem, search, spec["mistuning"], spec["n_search"], start, stop,
                       n_threads=max(1, int(n_workers)))


def design_robust(spec: dict, *, model: dict, simulation: dict, code: str, title: str,
                  n_workers: int = 1, parts: list | None = None):
    """Dataset of one ``design_robust`` entry: the design optimised as ``design`` does,
    its designs over the host's drift delta in [-mistuning, mistuning], and the robust
    VI NES and re-tuned TMD (``studies.mistuning.mistuning`` with robust=True).
    ``parts``: ``design_robust_part`` results (their designs not run again; the same
    dataset)."""
    from ..studies.design import complete
    from ..studies.mistuning import merged_parts, mistuning
    known = merged_parts(parts or ())
    if 0.0 in known:
        kw, settings = _design_kw(spec, model, simulation, MISTUNING_KEYS)
        res = complete(known[0.0], **kw, n_threads=max(1, int(n_workers)))
        attrs = _design_attrs(spec, model, settings, code, title)
    else:
        res, attrs = _solved_design(spec, model, simulation, code, title, n_workers,
                                    skip=MISTUNING_KEYS)
    mis = mistuning(res, spec["mistuning"], n_delta=spec["n_delta"], robust=True,
                    n_search=spec["n_search"], n_threads=res.cost["n_threads"], known=known)
    rob = mis["robust"]
    print(f"design_robust: nominal design {res.cost['cpu_s']:.1f} s CPU; mistuning and "
          f"robust designs {mis['cost']['cpu_s']:.1f} s CPU ({rob['search']['n_designs']} "
          f"designs, {rob['search']['n_runs']} runs in the robust search; search grids "
          f"from {len(parts or ())} chunk parts); worst over delta: "
          f"TMD {mis['worst']['tmd']:.3g} -> {rob['worst']['tmd']:.3g}, VI NES "
          f"{mis['worst']['vines']:.3g} -> {rob['worst']['vines']:.3g}")
    return builders.design_robust_dataset(res, mis, attrs)


# ------------------------------------------------------------------ uncertainty

def _uncertain_design(spec: dict, model: dict, simulation: dict, n: int) -> tuple:
    """(the design of an ``uncertainty`` entry's ``design`` keywords, as a ``designs``
    entry from rest: census_n = 0; its solver settings)."""
    from ..studies.design import design as solve_design
    kw, settings = _design_kw(spec["design"], model, simulation)
    return solve_design(**{**kw, "census_n": 0}, n_threads=n), settings


def uncertainty_part(spec: dict, *, model: dict, simulation: dict, start: int, stop: int,
                     n_workers: int = 1) -> dict:
    """The rows of the sample points [start, stop) of ``uncertainty``
    (``studies.uncertainty.uncertainty_part``); each job builds the entry's design first
    (a design that is optimised, not evaluated, is searched again in every job)."""
    from ..studies.uncertainty import uncertainty_part as rows
    n = max(1, int(n_workers))
    res, _ = _uncertain_design(spec, model, simulation, n)
    return rows(res, spec["parameters"], start, stop, samples=spec["samples"],
                seed=spec["seed"], n_threads=n)


def uncertainty(spec: dict, *, model: dict, simulation: dict, code: str, title: str,
                n_workers: int = 1, parts: list | None = None):
    """Dataset of one ``uncertainty`` entry: the design of its ``design`` keywords (as a
    ``designs`` entry, from rest: census_n = 0), then ``studies.uncertainty`` with its
    ``parameters``, ``samples`` and ``seed``. ``parts``: ``uncertainty_part`` results
    (their points not run again; the same dataset)."""
    from ..studies.uncertainty import uncertainty as solve
    n = max(1, int(n_workers))
    res, settings = _uncertain_design(spec, model, simulation, n)
    known = {k: v for p in parts or () for k, v in p.items()}
    unc = solve(res, spec["parameters"], samples=spec["samples"], seed=spec["seed"],
                n_threads=n, known=known)
    cost = unc.cost
    print(f"uncertainty: design eta {res.eta:.4g}, L {res.clearance_m:.4g} m; "
          f"{cost['n_distinct_points']} points ({len(known)} from {len(parts or ())} chunk "
          f"parts), wall {cost['wall_s']:.1f} s, CPU {cost['cpu_s']:.1f} s")
    return builders.uncertainty_dataset(unc, _design_attrs(spec, model, settings, code,
                                                           title))


# ------------------------------------------------------------------ orbit-atlas

def _atlas_rows(eta, omega, F, kw):
    from ..orbits.atlas.atlas import atlas_arrays
    return atlas_arrays(eta, omega, F, **kw)


def _atlas_kw(sim_t_end: float, model: dict) -> dict:
    """``atlas_arrays``'s keywords: r, d, and the simulation check (sim_t_end 0: none)."""
    from ..orbits.family.sequence import SIM_T_END
    return {"r": model["r"], "d": model["d"], "simulation": sim_t_end > 0,
            "sim_t_end": sim_t_end if sim_t_end > 0 else SIM_T_END}


def orbit_atlas_part(grid: dict, *, sim_t_end: float, model: dict, start: int, stop: int,
                     n_workers: int = 1, rows_per_task: int = 1,
                     scheduler: str | None = None) -> dict:
    """The atlas arrays of the eta rows [start, stop) of ``orbit_atlas`` (whole rows: each
    is swept in omega from omega[0]), in dask tasks of ``rows_per_task`` rows."""
    import dask
    eta, omega = axis_values(grid["eta"])[start:stop], axis_values(grid["omega"])
    kw = _atlas_kw(sim_t_end, model)
    n = max(1, int(rows_per_task))
    tasks = [dask.delayed(_atlas_rows, pure=True)(eta[i:i + n], omega, float(grid["F"]), kw)
             for i in range(0, eta.size, n)]
    parts = compute(tasks, max(1, int(n_workers)), scheduler, True)
    return {k: np.concatenate([p[k] for p in parts], axis=0) for k in parts[0]}


def orbit_atlas(grid: dict, *, sim_t_end: float, model: dict, code: str, title: str,
                n_workers: int = 1, rows_per_task: int = 1, scheduler: str | None = None,
                parts: list | None = None):
    """Dataset of one orbit atlas over ``grid``'s (eta, omega) at its F: every family of
    ``orbits.atlas.atlas.FAMILIES`` found / admissible / stable at each point. Each eta row is
    swept in omega from omega[0], seeded by the previous omega (``atlas_arrays``), so tasks
    and parts hold whole rows (``rows_per_task`` of them a task): the numbers do not
    depend on workers, task size, parts or scheduler. ``parts``: the ``orbit_atlas_part``
    results covering every row in order (else computed here)."""
    from ..orbits.atlas.atlas import FAMILIES, PAPER_LABELS
    eta, omega = axis_values(grid["eta"]), axis_values(grid["omega"])
    F = float(grid["F"])
    if parts is None:
        parts = [orbit_atlas_part(grid, sim_t_end=sim_t_end, model=model, start=0,
                                  stop=eta.size, n_workers=n_workers,
                                  rows_per_task=rows_per_task, scheduler=scheduler)]
    arrays = {k: np.concatenate([p[k] for p in parts], axis=0) for k in parts[0]}
    if next(iter(arrays.values())).shape[0] != eta.size:
        raise ValueError(f"parts hold {next(iter(arrays.values())).shape[0]} eta rows, "
                         f"the atlas {eta.size}")
    families = {k: (f.walls, f.periods, PAPER_LABELS[k]) for k, f in FAMILIES.items()}
    attrs = provenance_attrs(title=title, config_subset={"grid": grid, "sim_t_end": sim_t_end,
                                                         "model": model},
                             settings=model, code_version=code)
    attrs.update(F=F, sim_t_end=float(sim_t_end))
    return builders.atlas_dataset(eta, omega, families, arrays, attrs)


# ------------------------------------------------------------------ shock

#: keys of a ``shocks`` entry passed to ``studies.shock.shock`` as they are
SHOCK_KEYS = ("eta", "clearance_m", "periods", "omega_band", "M_kg", "k_N_per_m",
              "c_Ns_per_m", "d")


def shock(spec: dict, *, model: dict, code: str, title: str):
    """Dataset of one ``shocks`` entry: ``studies.shock.shock`` over the entry's energy range
    (the curve) and at each of its history energies (the decays in time), with the model's
    r (the structure's damping is the entry's: M, k, c or d, Table 1 by default)."""
    import math

    from ..studies.shock import report_times
    from ..studies.shock import shock as free_decay
    kw = {k: spec[k] for k in SHOCK_KEYS if spec.get(k) is not None}
    lo, hi = spec["energy_range_J"]
    curve = free_decay(**kw, r=model["r"], energy_range=(lo, hi, spec["n_energies"]),
                       starts=spec.get("starts", 0), seed=spec.get("seed", 0))
    histories = [free_decay(**kw, r=model["r"], energy_J=E)
                 for E in spec["history_energies_J"]]
    opt = curve["optimal"]
    print(f"shock: {spec['n_energies'] + len(histories)} exact runs; VI NES best "
          f"{opt['dissipated_fraction']:.4f} at {opt['energy_J']:.4g} J, TMD "
          f"{curve['tmd']['dissipated_fraction']:.4f}, LO alone "
          f"{curve['lo_alone']['dissipated_fraction']:.4f} within {spec['periods']:g} periods")
    attrs = provenance_attrs(title=title, config_subset={"spec": spec, "model": model},
                             settings={"r": model["r"]}, code_version=code)
    periods = report_times(curve["inputs"]["periods"]) / (2.0 * math.pi)
    return builders.shock_dataset(curve, histories, spec["history_energies_J"], periods, attrs)


# ------------------------------------------------------------------ model ladder

def model_ladder(spec: dict, *, model: dict, code: str, title: str):
    """Dataset of one ``model_ladders`` entry: per eta the band omega = 1 + sigma eta at
    F = f eta by the slow flow, the exact orbits (map solve, continuation) and the
    simulation from rest (``studies.model_ladder.ladder``), the slow flow's error, its bands
    within each of ``TOLERANCES`` and every model's wall time (model's r and d)."""
    from ..studies import model_ladder as ml
    kw = {k: v for k, v in spec.items() if k != "description"}
    panels_in = ml.check_inputs(**kw, r=model["r"], d=model["d"])
    ml.warm_up(model["r"], model["d"])
    panels, bands = [], []
    for eta, F, W in panels_in:
        lad = ml.ladder(eta, F, W, r=model["r"], d=model["d"], t_end=spec["t_end"],
                        t_transient=spec["t_transient"], n_dense=spec["n_dense"],
                        continuation_step=spec["continuation_step"])
        panels.append(lad)
        bands.append([ml.band(W, lad.error_max, tol) for tol in ml.TOLERANCES])
        sec = lad.seconds
        print(f"model_ladder: eta {eta:g}: slow flow {sec['slowflow'] * 1e3:.3g} ms, map solve "
              f"{sec['map_solve']:.3g} s, continuation {sec['continuation']:.3g} s, "
              f"simulation {sec['simulation']:.3g} s; within 1 % on "
              f"{bands[-1][0][2]:.0%} of the grid, 5 % on {bands[-1][1][2]:.0%}")
    lo, hi = spec["sigma_range"]
    sigma = np.linspace(lo, hi, spec["n_omega"])
    sigma_dense = np.linspace(lo, hi, spec["n_dense"])
    attrs = provenance_attrs(title=title, config_subset={"spec": spec, "model": model},
                             settings=model, code_version=code)
    attrs.update(f=float(spec["f"]), r=float(model["r"]), d=float(model["d"]),
                 t_end=float(spec["t_end"]), t_transient=float(spec["t_transient"]),
                 continuation_step=float(spec["continuation_step"]))
    return builders.model_ladder_dataset(panels, sigma, sigma_dense, ml.TOLERANCES, bands,
                                         attrs)


# ------------------------------------------------------------------ design map

def design_map_spec(spec: dict, model: dict, simulation: dict):
    """The ``MapSpec`` of a ``design_maps`` entry (``studies.design_map.from_entry``): its
    own keys, the model's d, the simulation's v_stick, max_impacts, root_tol (restitution
    is the entry's grid, not the model's r)."""
    from ..studies.design_map import from_entry
    return from_entry(spec, d=model["d"], **{k: simulation[k] for k in DESIGN_SETTINGS})


def design_map_part(spec: dict, *, model: dict, simulation: dict, start: int, stop: int,
                    n_workers: int = 1) -> list:
    """The cells [start, stop) of a ``design_maps`` entry (``studies.design_map.map_cells``;
    each cell's numbers depend on the cell alone). One process: a job's script cannot be
    the main module of spawned workers, and the chunk jobs run side by side anyway
    (n_workers is accepted and does not change a number)."""
    from ..studies.design_map import map_cells
    return map_cells(design_map_spec(spec, model, simulation), start, stop)


def design_map(spec: dict, *, model: dict, simulation: dict, code: str, title: str,
               n_workers: int = 1, parts: list | None = None):
    """Dataset of one ``design_maps`` entry: every cell (``design_map_part``, here or from
    ``parts`` in cell order), assembled (``studies.design_map.assemble``) with its counts."""
    import time

    from ..studies.design_map import assemble, summary
    t0 = time.process_time()
    m = design_map_spec(spec, model, simulation)
    cells = ([c for p in parts for c in p] if parts is not None else
             design_map_part(spec, model=model, simulation=simulation, start=0,
                             stop=m.n_cells))
    arrays = assemble(m, cells)
    counts = summary(m, arrays)
    print(f"design_map: {counts['n_cells']} cells, {counts['n_frontier']} near the frontier "
          f"and {counts['n_sample']} sampled checked exactly ({counts['n_exact_runs']} runs); "
          f"VI NES wins {counts['vines_wins']} against the free TMD, "
          f"{counts['vines_wins_equal_travel']} at equal travel (by more than 5 %); the models "
          f"name opposite winners at {counts['verdict_differs']} and "
          f"{counts['verdict_differs_equal_travel']}; gather CPU "
          f"{time.process_time() - t0:.1f} s")
    attrs = provenance_attrs(title=title, config_subset={"spec": spec, "model": model},
                             settings={"d": model["d"]}, code_version=code)
    return builders.design_map_dataset(m.to_dict(), arrays, counts, attrs)
