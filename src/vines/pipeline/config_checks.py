"""Physical checks of a validated config, with the API's own validators.

The schema checks types and shapes; here every parameter value of every section goes
through ``ModelParams`` / ``SolverSettings`` (the validators of the Python API), every
number must be finite, and the sizes a config asks for stay below the ``limits`` section
(grid points, run length, branch points). Each failure is one ``ConfigError`` naming the
key path, the value and what is allowed, raised before any job runs.
"""
from __future__ import annotations

import math

import numpy as np

from ..core.params import (
    PARAM_NAMES,
    STATE_MAX,
    T_END_MAX,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_int,
)
from ..orbits.family.family import Family
from .axes import ConfigError, axis_values


def _walk_finite(node, path=""):
    """Refuse NaN and infinities anywhere (YAML .nan / .inf pass a schema's minimum)."""
    if isinstance(node, dict):
        for k, v in node.items():
            _walk_finite(v, f"{path}.{k}" if path else str(k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            _walk_finite(v, f"{path}[{i}]")
    elif isinstance(node, float) and not math.isfinite(node):
        raise ConfigError(path, f"{node!r} is not a finite number")


def _check_param(key: str, name: str, value, model: dict) -> None:
    """``value`` of parameter ``name`` must be accepted by ModelParams (with ``model``)."""
    kw = {"eta": 0.1, "omega": 1.0, "F": 0.0, "r": model["r"], "d": model["d"], name: value}
    try:
        ModelParams(**kw)
    except ParameterError as err:
        raise ConfigError(key, f"{value!r}: {name} {err.allowed}") from None


def axis_size(spec) -> int:
    """Number of values an axis spec asks for (without building it)."""
    if isinstance(spec, dict) and "num" in spec:
        return int(spec["num"]) + len(spec.get("include", []))
    if isinstance(spec, dict):
        return len(spec["values"]) + len(spec.get("include", []))
    return len(spec) if isinstance(spec, list) else 1


def _check_axis(key: str, name: str, spec, model: dict) -> int:
    n = axis_size(spec)
    if n > 10_000_000:
        raise ConfigError(key, f"{n} values on one axis (at most 10000000)")
    for v in (axis_values(spec, key=key)[[0, -1]] if n else []):
        _check_param(key, name, float(v), model)
    return n


def _check_size(key: str, n: int, limits: dict, what: str = "points") -> None:
    cap = limits["max_grid_points"]
    if n > cap:
        raise ConfigError(key, f"{n} {what} exceed limits.max_grid_points = {cap} "
                               "(raise it in the config's 'limits' section if this is intended)")


def _check_t_end(key: str, t_end, limits: dict, what: str = "") -> None:
    cap = limits["max_t_end"]
    if t_end > cap:
        total = f"{what} = {t_end!r}" if what else repr(t_end)
        raise ConfigError(key, f"{total} exceeds limits.max_t_end = {cap!r} "
                               "(raise it in the config's 'limits' section if this is intended)")


def _slowest_period(sw: dict, dim_key: str) -> float:
    """Longest forcing period 2 pi / omega over a sweep's values (omega swept, outer or fixed)."""
    if sw["param"] == "omega":
        omegas = axis_values(sw["values"])
    elif sw["outer"] == "omega":
        omegas = axis_values(sw["outer_values"])
    else:
        omegas = np.array([float(sw["fixed"]["omega"])])
    return 2.0 * math.pi / float(np.min(omegas))


def _check_recorded_periods(key: str, sw: dict) -> None:
    """The last n_record periods are recorded at every value: they must fit in the run of
    one value (t_step after the first, t_settle at the first)."""
    t_record = sw["n_record"] * _slowest_period(sw, key)
    t_run = min(sw["t_settle"], sw["t_step"])
    if t_record >= t_run:
        raise ConfigError(f"{key}.n_record", f"{sw['n_record']} periods (up to {t_record:.4g} "
                          f"time units) do not fit in min(t_settle, t_step) = {t_run:g}")


def _check_settings(key: str, settings: dict, limits: dict) -> None:
    _check_t_end(f"{key}.t_end", settings["t_end"], limits)
    try:
        SolverSettings(**settings)
    except ParameterError as err:
        raise ConfigError(f"{key}.{err.name}", f"{err.value!r}: {err.allowed}") from None


def _check_point(key: str, point: dict, model: dict) -> None:
    for name in PARAM_NAMES:
        _check_param(f"{key}.{name}", name, point[name], model)


def check_grids(config: dict, model: dict, limits: dict) -> None:
    for name, grid in config["grids"].items():
        n = 1
        for dim, spec in grid.get("axes", {}).items():
            n *= _check_axis(f"grids.{name}.axes.{dim}", dim, spec, model)
        for dim, v in grid.get("fixed", {}).items():
            _check_param(f"grids.{name}.fixed.{dim}", dim, v, model)
        _check_size(f"grids.{name}", n, limits)


def check_sweeps(config: dict, model: dict, limits: dict) -> None:
    for name, sw in config["sweeps"].items():
        key = f"sweeps.{name}"
        n = _check_axis(f"{key}.values", sw["param"], sw["values"], model)
        n_lines = _check_axis(f"{key}.outer_values", sw["outer"], sw["outer_values"], model)
        for dim, v in sw["fixed"].items():
            _check_param(f"{key}.fixed.{dim}", dim, v, model)
        _check_size(key, n * n_lines, limits, "sweep points")
        _check_t_end(f"{key}.t_settle" if sw["t_settle"] > limits["max_t_end"] else f"{key}.t_step",
                     sw["t_settle"] + n * sw["t_step"], limits,
                     what=f"t_settle + {n} values x t_step")
        _check_recorded_periods(key, sw)


def check_lyapunov_sweeps(config: dict, model: dict, limits: dict) -> None:
    """Each lyapunov_sweeps entry names a sweeps entry, and its window fits in the shortest
    run of a point (t_step; the first point runs t_settle + the recorded periods)."""
    for name, ly in config["lyapunov_sweeps"].items():
        key = f"lyapunov_sweeps.{name}"
        sw = config["sweeps"].get(ly["sweep"])
        if sw is None:
            raise ConfigError(f"{key}.sweep", f"{ly['sweep']!r} is not a sweeps entry "
                              f"({sorted(config['sweeps'])})")
        shortest = min(sw["t_step"], sw["t_settle"])
        if ly["t_window"] > shortest:
            raise ConfigError(f"{key}.t_window", f"{ly['t_window']:g} must not exceed the "
                              f"shortest run of a point of sweep {ly['sweep']!r} "
                              f"(min(t_settle, t_step) = {shortest:g})")


def check_branches(config: dict, model: dict, limits: dict) -> None:
    for name, br in config["branches"].items():
        key = f"branches.{name}"
        for end in ("start", "stop"):
            _check_param(f"{key}.{end}", br["param"], br[end], model)
        for dim, v in br["fixed"].items():
            _check_param(f"{key}.fixed.{dim}", dim, v, model)
        n = abs(br["stop"] - br["start"]) / br["step"]
        if n > limits["max_branch_points"]:
            raise ConfigError(f"{key}.step", f"{br['step']!r} needs {n:.3g} points from start to "
                              f"stop (limits.max_branch_points = {limits['max_branch_points']})")


def check_maps_and_points(config: dict, model: dict, limits: dict) -> None:
    for name, sm in config["stability_maps"].items():
        key = f"stability_maps.{name}"
        n = _check_axis(f"{key}.eta", "eta", sm["eta"], model)
        n *= _check_axis(f"{key}.omega", "omega", sm["omega"], model)
        _check_param(f"{key}.F", "F", sm["F"], model)
        _check_size(key, n, limits)
    for name, th in config["timehistories"].items():
        for i, p in enumerate(th["points"]):
            _check_point(f"timehistories.{name}.points[{i}]", p, model)
        _check_timehistory(f"timehistories.{name}", th, config["simulation"], limits)


def _check_timehistory(key: str, th: dict, simulation: dict, limits: dict) -> None:
    """The densely sampled last periods lie inside the run; the samples of all points stay
    within limits.max_samples."""
    t_end, t_tr = simulation["t_end"], simulation["t_transient"]
    slowest = min(p["omega"] for p in th["points"])
    span = th["n_periods"] * 2.0 * math.pi / slowest
    if span > t_end:
        raise ConfigError(f"{key}.n_periods", f"{th['n_periods']} periods ({span:.4g} time "
                          f"units at omega = {slowest:g}) exceed the run (t_end = {t_end:g})")
    dense = th["n_periods"] * th["samples_per_period"] + 1
    most = max((t_end - t_tr) * p["omega"] / (2.0 * math.pi) for p in th["points"])
    window = math.ceil(most) * th["window_samples_per_period"] + 1
    total = len(th["points"]) * (dense + window)
    cap = limits["max_samples"]
    if total > cap:
        which = ("window_samples_per_period" if window > dense else "samples_per_period")
        raise ConfigError(f"{key}.{which}", f"{total:.3g} samples in all exceed "
                          f"limits.max_samples = {cap} (raise it in the config's 'limits' "
                          "section if this is intended)")


def _check_t_max(key: str, t_max, simulation: dict) -> None:
    """The asymptotic view's horizon lies beyond the window view's end."""
    if t_max is not None and not simulation["t_end"] < t_max <= T_END_MAX:
        raise ConfigError(key, f"{t_max:g} must be > simulation.t_end = "
                          f"{simulation['t_end']:g} and <= {T_END_MAX:g}")


def check_attractor_maps(config: dict, model: dict, limits: dict) -> None:
    """Robust-TET maps and basin slices: parameters the model accepts, sizes (grid points
    times initial states) within limits.max_grid_points, slice states within the bound of
    an initial state (|z_m(0)|, |z_m'(0)| <= STATE_MAX)."""
    for section in ("robust_maps", "basin_slices"):
        for name, entry in config[section].items():
            _check_t_max(f"{section}.{name}.t_max", entry.get("t_max"), config["simulation"])
    for name, rm in config["robust_maps"].items():
        key = f"robust_maps.{name}"
        n = _check_axis(f"{key}.eta", "eta", rm["eta"], model)
        n *= _check_axis(f"{key}.omega", "omega", rm["omega"], model)
        _check_param(f"{key}.F", "F", rm["F"], model)
        _check_size(key, n * rm["n"], limits, "runs (grid points x n)")
    for name, bs in config["basin_slices"].items():
        key = f"basin_slices.{name}"
        _check_point(key, bs, model)
        n = 1
        for dim in ("z_m0", "v_m0"):
            vals = axis_values(bs[dim], key=f"{key}.{dim}")
            n *= vals.size
            if np.any(np.abs(vals) > STATE_MAX):
                raise ConfigError(f"{key}.{dim}", f"values must lie in [-{STATE_MAX:g}, {STATE_MAX:g}]")
        _check_size(key, n, limits, "slice points")


def boundary_family(entry: dict) -> Family:
    """The family whose curves a ``boundaries`` entry traces (without walls/periods: the
    1:1 orbits)."""
    return Family(str(entry.get("walls", "LR")).upper(), int(entry.get("periods", 1)))


def check_boundaries(config: dict, model: dict, limits: dict) -> None:
    """Ranges and F of every boundaries entry are parameters the model accepts."""
    for name, bd in config["boundaries"].items():
        key = f"boundaries.{name}"
        for dim in ("eta", "omega"):
            lo, hi = bd[f"{dim}_range"]
            for v in (lo, hi):
                _check_param(f"{key}.{dim}_range", dim, v, model)
            if not lo < hi:
                raise ConfigError(f"{key}.{dim}_range", f"{[lo, hi]} must be [lo, hi], lo < hi")
        _check_param(f"{key}.F", "F", bd["F"], model)
        name_map = bd.get("stability_map")
        family = boundary_family(bd)
        if name_map is not None and not family.engine.class_map_seeds:
            raise ConfigError(f"{key}.stability_map", f"{name_map!r} seeds 1:1 curves only, "
                              f"not those of walls {family.walls}, periods {family.periods} (drop "
                              "the key)")
        if name_map is not None:
            if name_map not in config["stability_maps"]:
                raise ConfigError(f"{key}.stability_map", f"{name_map!r} is not a "
                                  f"stability_maps entry ({sorted(config['stability_maps'])})")
            sm = config["stability_maps"][name_map]
            if float(sm["F"]) != float(bd["F"]):
                raise ConfigError(f"{key}.stability_map", f"{name_map!r} has F = "
                                  f"{sm['F']}, not {bd['F']}")
            for dim in ("eta", "omega"):
                axis = axis_values(sm[dim])
                lo, hi = bd[f"{dim}_range"]
                if lo < axis[0] or hi > axis[-1]:
                    raise ConfigError(f"{key}.{dim}_range", f"{[lo, hi]} reaches outside the "
                                      f"{dim} axis of stability map {name_map!r} "
                                      f"[{axis[0]:g}, {axis[-1]:g}] that seeds the curves")


def check_studies(config: dict, model: dict, limits: dict) -> None:
    wp = config["work_precision"]
    for name, case in wp["cases"].items():
        key = f"work_precision.cases.{name}"
        _check_point(key, case, model)
        _check_settings(key, {"t_end": case["t_end"], "t_transient": case["t_transient"]},
                        limits)
    conv = config["convergence"]
    for study in ("window", "vstick"):
        for i, p in enumerate(conv.get(study, {}).get("points", [])):
            _check_point(f"convergence.{study}.points[{i}]", p, model)
    window = conv.get("window", {})
    for i, t in enumerate(window.get("t_ends", [])):
        _check_t_end(f"convergence.window.t_ends[{i}]", t, limits)
    if window:
        shortest = min(window["t_ends"])
        for i, length in enumerate(window["window_lengths"]):
            if length >= shortest:
                raise ConfigError(f"convergence.window.window_lengths[{i}]", f"{length:g} "
                                  f"must be shorter than every run (t_ends down to {shortest:g})")
    grid = conv.get("grid")
    if grid:
        for dim, rng in (("eta", grid["eta_range"]), ("omega", grid["omega_range"])):
            for v in rng:
                _check_param(f"convergence.grid.{dim}_range", dim, v, model)
            if not rng[0] < rng[1]:
                raise ConfigError(f"convergence.grid.{dim}_range",
                                  f"{list(rng)} must be [lo, hi], lo < hi")
        _check_param("convergence.grid.F", "F", grid["F"], model)
        _check_nested(grid["resolutions"])
        _check_size("convergence.grid.resolutions", max(grid["resolutions"]) ** 2, limits)


def _check_nested(resolutions) -> None:
    """Grid resolutions increase and nest: every coarser grid's nodes lie on the finer
    grid ((n_fine - 1) a multiple of (n_coarse - 1)), so contours compare node by node."""
    for a, b in zip(resolutions[:-1], resolutions[1:], strict=True):
        if not (b > a and (b - 1) % (a - 1) == 0):
            raise ConfigError("convergence.grid.resolutions", f"{list(resolutions)}: each "
                              "must exceed the one before and nest in it ((n - 1) a multiple "
                              "of the previous n - 1, e.g. 11, 21, 41, 81)")


#: design keywords of ``vines.design`` -> config key, where the API's ParameterError names
#: the argument differently
_DESIGN_KEYS = {"amplitude": "amplitudes_m", "M": "M_kg", "k": "k_N_per_m",
                "c": "c_Ns_per_m", "clearance": "clearance_m",
                "clearance_range": "clearance_range_m"}


def _check_design(key: str, ds: dict, model: dict, simulation: dict, limits: dict) -> None:
    """One ``designs`` entry through the validators of ``vines.design`` (without running)."""
    from ..studies import design as dz
    from ..studies import design_checks as chk
    try:
        chk.check_mode(ds.get("eta"), ds.get("clearance_m"), ds.get("eta_max"),
                       ds.get("clearance_range_m"))
        chk.check_band(ds["omega_band"])
        chk.check_count("n_omega", ds["n_omega"], 2, dz.N_OMEGA_MAX)
        amps = chk.check_amplitudes(ds["amplitudes_m"], dz.AMPLITUDE_MAX_M,
                                    dz.N_AMPLITUDES_MAX)
        chk.check_structure(ds["M_kg"], ds["k_N_per_m"], ds["c_Ns_per_m"], ds["d"])
        if ds.get("eta_max") is None:
            chk.check_eta("eta", ds["eta"])
            chk.check_clearance("clearance", ds["clearance_m"], amps)
        else:
            chk.check_eta("eta_max", ds["eta_max"])
            chk.check_clearance_range(ds.get("clearance_range_m"), amps,
                                      dz.CLEARANCE_RANGE_FACTORS)
            chk.check_count("n_eta", ds["n_eta"], 1, dz.N_GRID_MAX)
            chk.check_count("n_clearance", ds["n_clearance"], 2, dz.N_GRID_MAX)
    except ParameterError as err:
        sub = _DESIGN_KEYS.get(err.name, err.name)
        raise ConfigError(f"{key}.{sub}", f"{err.value!r}: {err.allowed}") from None
    _check_settings(key, {"t_end": ds["t_end"], "t_transient": ds["t_transient"],
                          **{k: simulation[k] for k in ("v_stick", "max_impacts", "root_tol")}},
                    limits)
    n_designs = ds["n_eta"] * ds["n_clearance"] if ds.get("eta_max") is not None else 1
    n_runs = ds["n_omega"] * len(ds["amplitudes_m"]) * (n_designs + ds["census_n"])
    _check_size(key, n_runs, limits, "runs (omega x amplitudes x (grid designs + census_n))")


def check_designs(config: dict, model: dict, limits: dict) -> None:
    for name, ds in config["designs"].items():
        _check_design(f"designs.{name}", ds, model, config["simulation"], limits)


#: shock keywords of ``studies.shock`` -> config key, where the API names them differently
_SHOCK_KEYS = {"M": "M_kg", "k": "k_N_per_m", "c": "c_Ns_per_m", "clearance": "clearance_m",
               "energy_range": "energy_range_J"}


def _check_shock(key: str, sh: dict, limits: dict) -> None:
    """One ``shocks`` entry through the validators of ``studies.shock`` (without running):
    the design, the structure, the window, every energy; its runs within the limits."""
    from ..studies import shock as sk
    try:
        inp = sk.check_inputs(eta=sh["eta"], clearance_m=sh["clearance_m"],
                              periods=sh["periods"], M_kg=sh["M_kg"],
                              k_N_per_m=sh["k_N_per_m"], c_Ns_per_m=sh["c_Ns_per_m"],
                              d=sh["d"], omega_band=sh["omega_band"])
        n = check_int("n_energies", sh["n_energies"], lo=2, hi=sk.N_ENERGIES_MAX)
        lo, hi = sh["energy_range_J"]
        sk.check_energy_range((lo, hi, n), inp["M_kg"], inp["v_unit"])
    except ParameterError as err:
        sub = _SHOCK_KEYS.get(err.name, err.name)
        raise ConfigError(f"{key}.{sub}", f"{err.value!r}: {err.allowed}") from None
    for i, E in enumerate(sh["history_energies_J"]):
        try:
            sk.check_energy("energy", E, inp["M_kg"], inp["v_unit"])
        except ParameterError as err:
            raise ConfigError(f"{key}.history_energies_J[{i}]",
                              f"{err.value!r}: {err.allowed}") from None
    _check_t_end(f"{key}.periods", 2.0 * math.pi * sh["periods"], limits,
                 "2 pi periods")
    _check_size(key, sh["n_energies"] * (1 + sh["starts"]) + len(sh["history_energies_J"]),
                limits, "runs (n_energies (1 + starts) + history_energies_J)")


def check_shocks(config: dict, model: dict, limits: dict) -> None:
    for name, sh in config["shocks"].items():
        _check_shock(f"shocks.{name}", sh, limits)


def _check_model_ladder(key: str, ml: dict, model: dict, limits: dict) -> None:
    """One ``model_ladders`` entry through ``studies.model_ladder.check_inputs`` (the
    validators of the slow flow and of the exact solver), its grids within the limits."""
    from ..studies.model_ladder import check_inputs
    try:
        check_inputs(**{k: v for k, v in ml.items() if k != "description"}, r=model["r"],
                     d=model["d"])
    except ParameterError as err:
        sub = "etas" if err.name == "eta" else err.name
        raise ConfigError(f"{key}.{sub}", f"{err.value!r}: {err.allowed}") from None
    _check_t_end(f"{key}.t_end", ml["t_end"], limits)
    _check_size(key, len(ml["etas"]) * max(ml["n_omega"], ml["n_dense"]), limits,
                "frequencies (etas x max(n_omega, n_dense))")


def check_model_ladders(config: dict, model: dict, limits: dict) -> None:
    for name, ml in config["model_ladders"].items():
        _check_model_ladder(f"model_ladders.{name}", ml, model, limits)


def check_design_maps(config: dict, model: dict, limits: dict) -> None:
    """Each ``design_maps`` entry through ``studies.design_map.check_map`` (as the stage
    builds it, without running), its run length within the limits."""
    from ..studies.design_map import from_entry
    sim = {k: config["simulation"][k] for k in ("v_stick", "max_impacts", "root_tol")}
    for name, e in config["design_maps"].items():
        key = f"design_maps.{name}"
        try:
            from_entry(e, d=model["d"], **sim)
        except ParameterError as err:
            sub = err.name if err.name in e else ""
            raise ConfigError(f"{key}.{sub}" if sub else key,
                              f"{err.value!r}: {err.allowed}") from None
        _check_t_end(f"{key}.t_end", e["t_end"], limits)


def check_design_robust(config: dict, model: dict, limits: dict) -> None:
    """A ``design_robust`` entry: its design keys as a ``designs`` entry's (an
    optimisation), its mistuning keys through ``studies.mistuning.check_mistuning``, and
    the runs of the nominal and the robust search (n_search host frequencies) within
    limits.max_grid_points."""
    from ..studies.mistuning import check_mistuning
    for name, ds in config["design_robust"].items():
        key = f"design_robust.{name}"
        design = {k: v for k, v in ds.items() if k not in ("mistuning", "n_delta", "n_search")}
        _check_design(key, design, model, config["simulation"], limits)
        try:
            check_mistuning(ds["mistuning"], ds["n_delta"], ds["n_search"])
        except ParameterError as err:
            raise ConfigError(f"{key}.{err.name}", f"{err.value!r}: {err.allowed}") from None
        n_runs = (ds["n_omega"] * len(ds["amplitudes_m"])
                  * (ds["n_eta"] * ds["n_clearance"] + ds["census_n"]) * (1 + ds["n_search"]))
        _check_size(key, n_runs, limits, "runs (omega x amplitudes x (grid designs + "
                    "census_n) x (1 + n_search))")


def check_uncertainty(config: dict, model: dict, limits: dict) -> None:
    """Each ``uncertainty`` entry: its design as a ``designs`` entry, its parameters and
    samples through the validators of ``studies.uncertainty_checks``, its runs (points x
    the design's runs from rest) within limits.max_grid_points."""
    from ..studies import uncertainty_checks as chk
    from ..studies.design import N_REFINE
    for name, entry in config["uncertainty"].items():
        key, ds = f"uncertainty.{name}", entry["design"]
        _check_design(f"{key}.design", {**ds, "census_n": 0}, model, config["simulation"],
                      limits)
        where = "parameters"
        try:
            chk.check_parameters(entry["parameters"], amplitudes_m=ds["amplitudes_m"],
                                 clearance_m=ds.get("clearance_m"), eta=ds.get("eta"))
            where = "samples"
            n = chk.check_samples(entry["samples"])
        except ParameterError as err:
            raise ConfigError(f"{key}.{where}", f"{err.value!r}: {err.allowed}") from None
        n_points = n * (len(entry["parameters"]) + 2)
        runs = len(ds["amplitudes_m"]) * (ds["n_omega"] + 2 * N_REFINE + 1)
        _check_size(key, n_points * runs, limits,
                    "runs (samples x (parameters + 2) x the design's runs from rest)")


def atlas_grid(config: dict, name: str) -> dict:
    """The (eta, omega, F) of ``orbit_atlases[name]``: its own, or its stability map's."""
    oa = config["orbit_atlases"][name]
    ref = oa.get("stability_map")
    src = config["stability_maps"][ref] if ref is not None else oa
    return {k: src[k] for k in ("eta", "omega", "F")}


def check_orbit_atlases(config: dict, model: dict, limits: dict) -> None:
    """An atlas names a stability map or gives eta, omega and F (not both); its grid
    passes the model's checks and limits.max_grid_points."""
    for name, oa in config["orbit_atlases"].items():
        key = f"orbit_atlases.{name}"
        own = [k for k in ("eta", "omega", "F") if k in oa]
        ref = oa.get("stability_map")
        if ref is not None:
            if own:
                raise ConfigError(f"{key}.{own[0]}", "give stability_map or the grid "
                                  "(eta, omega, F), not both")
            if ref not in config["stability_maps"]:
                raise ConfigError(f"{key}.stability_map", f"{ref!r} is not a "
                                  f"stability_maps entry ({sorted(config['stability_maps'])})")
        elif len(own) < 3:
            missing = next(k for k in ("eta", "omega", "F") if k not in oa)
            raise ConfigError(f"{key}.{missing}", "missing: give stability_map or all of "
                              "eta, omega and F")
        grid = atlas_grid(config, name)
        where = {dim: f"{key}.stability_map" if ref is not None else f"{key}.{dim}"
                 for dim in ("eta", "omega", "F")}
        n = _check_axis(where["eta"], "eta", grid["eta"], model)
        n *= _check_axis(where["omega"], "omega", grid["omega"], model)
        _check_param(where["F"], "F", grid["F"], model)
        _check_size(key, n, limits)
        _check_t_end(f"{key}.sim_t_end", oa["sim_t_end"], limits)


def check_physical(config: dict) -> None:
    """Every check of this module, in config order; raises the first ConfigError."""
    _walk_finite(config)
    m = config["model"]
    try:
        ModelParams(eta=0.1, omega=1.0, F=0.0, r=m["r"], d=0.0 if m["d"] is None else m["d"])
    except ParameterError as err:
        raise ConfigError(f"model.{err.name}", f"{err.value!r}: {err.allowed}") from None
    model = {"r": m["r"], "d": 0.0 if m["d"] is None else m["d"]}
    limits = config["limits"]
    _check_settings("simulation", {k: config["simulation"][k] for k in
                                   ("t_end", "t_transient", "v_stick", "max_impacts",
                                    "root_tol")}, limits)
    for check in (check_grids, check_sweeps, check_lyapunov_sweeps, check_branches,
                  check_maps_and_points, check_attractor_maps, check_boundaries, check_studies,
                  check_designs, check_orbit_atlases, check_shocks,
                  check_model_ladders, check_design_robust, check_uncertainty,
                  check_design_maps):
        check(config, model, limits)
