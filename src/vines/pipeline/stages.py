"""Helpers of the Snakemake pipeline (importable and tested without snakemake).

* config validation with defaults (jsonschema), errors naming the offending key
* grid axes and their split into chunks keyed by the chunk's parameter values
* code version: sha256 of the vines sources the computations use
* the computations of each stage, parallel with dask (threaded scheduler by default, a
  dask.distributed scheduler when an address is given); every point / sweep line is computed
  independently and the results are assembled by index, so the numbers do not depend on the
  number of workers, the block size, the chunk size or the scheduler.
"""
from __future__ import annotations

import hashlib
import math
from pathlib import Path

import numpy as np

DIMS = ("eta", "omega", "F")

#: sources that do not affect any computed number (CLI, reference RK solver, file layout)
NON_COMPUTE_SOURCES = ("__main__.py", "cli.py", "reference.py", "io.py", "pipeline.py",
                       "plotting.py", "_numba_cache.py")
#: sources used only by the solver studies (work-precision, convergence): their code version
#: also covers reference.py, and the study stages' own changes rerun nothing else
STUDY_SOURCES = ("hiprec.py", "workprecision.py", "convergence.py")


class ConfigError(ValueError):
    """Invalid pipeline config; ``str(err)`` names the key path."""

    def __init__(self, key: str, message: str):
        self.key = key
        super().__init__(f"invalid config key '{key}': {message}")


# ------------------------------------------------------------------ config

def _with_defaults(validator_class):
    validate_properties = validator_class.VALIDATORS["properties"]

    def set_defaults(validator, properties, instance, schema):
        if isinstance(instance, dict):
            for prop, sub in properties.items():
                if "default" in sub and prop not in instance:
                    import copy
                    instance[prop] = copy.deepcopy(sub["default"])
        yield from validate_properties(validator, properties, instance, schema)

    import jsonschema
    return jsonschema.validators.extend(validator_class, {"properties": set_defaults})


def load_schema(path) -> dict:
    import yaml
    with open(path) as fh:
        return yaml.safe_load(fh)


def validate_config(config: dict, schema: dict) -> dict:
    """Validate ``config`` in place (filling defaults) and check cross-key rules.

    Raises ConfigError naming the first offending key (dotted path).
    """
    import jsonschema
    cls = _with_defaults(jsonschema.validators.validator_for(schema))
    errors = sorted(cls(schema).iter_errors(config), key=lambda e: list(e.absolute_path))
    if errors:
        err = min(errors, key=lambda e: -len(e.absolute_path))
        key = ".".join(str(p) for p in err.absolute_path) or "<top level>"
        raise ConfigError(key, err.message)
    sim = config["simulation"]
    if sim["t_transient"] >= sim["t_end"]:
        raise ConfigError("simulation.t_transient",
                          f"{sim['t_transient']} must be < simulation.t_end = {sim['t_end']}")
    for name, grid in config["grids"].items():
        axes = grid_axes(grid, key=f"grids.{name}")
        for dim, vals in grid.get("sections", {}).items():
            missing = [v for v in vals if float(v) not in set(axes[dim].tolist())]
            if missing:
                raise ConfigError(f"grids.{name}.sections.{dim}",
                                  f"{missing} not on the {dim} axis (add them with 'include')")
    for name, sw in config["sweeps"].items():
        if sw["outer"] == sw["param"]:
            raise ConfigError(f"sweeps.{name}.outer", "must differ from param")
        need = set(DIMS) - {sw["param"], sw["outer"]}
        if set(sw["fixed"]) != need:
            raise ConfigError(f"sweeps.{name}.fixed", f"must give exactly {sorted(need)}")
        axis_values(sw["values"], key=f"sweeps.{name}.values")
        axis_values(sw["outer_values"], key=f"sweeps.{name}.outer_values")
    for name, br in config["branches"].items():
        need = set(DIMS) - {br["param"]}
        if set(br["fixed"]) != need:
            raise ConfigError(f"branches.{name}.fixed", f"must give exactly {sorted(need)}")
    for name, case in config["work_precision"]["cases"].items():
        if case["t_transient"] >= case["t_end"]:
            raise ConfigError(f"work_precision.cases.{name}.t_transient",
                              f"{case['t_transient']} must be < t_end = {case['t_end']}")
    for name, sm in config["stability_maps"].items():
        axis_values(sm["eta"], key=f"stability_maps.{name}.eta")
        axis_values(sm["omega"], key=f"stability_maps.{name}.omega")
    return config


# ------------------------------------------------------------------ axes, grids, chunks

def axis_values(spec, key: str = "axis") -> np.ndarray:
    """1-D float axis from a number, a list, {values: [...]} or {start, stop, num[, include]}.

    ``include`` adds exact values (e.g. F = 0.3077) to a linspace; the result is sorted and
    unique.
    """
    if isinstance(spec, (int, float)) and not isinstance(spec, bool):
        vals = np.array([float(spec)])
    elif isinstance(spec, list):
        vals = np.asarray(spec, dtype=float)
    elif isinstance(spec, dict):
        if "values" in spec:
            vals = np.asarray(spec["values"], dtype=float)
        else:
            vals = np.linspace(float(spec["start"]), float(spec["stop"]), int(spec["num"]))
        if spec.get("include"):
            vals = np.concatenate([vals, np.asarray(spec["include"], dtype=float)])
    else:
        raise ConfigError(key, f"cannot read an axis from {spec!r}")
    vals = np.unique(vals)
    if vals.size == 0 or not np.all(np.isfinite(vals)):
        raise ConfigError(key, "axis must hold at least one finite value")
    return vals


def grid_axes(grid: dict, key: str = "grid") -> dict:
    """Axes of a grid config: swept ``axes`` and ``fixed`` values -> {dim: 1-D array}."""
    axes = {}
    for d in DIMS:
        in_axes, in_fixed = d in grid.get("axes", {}), d in grid.get("fixed", {})
        if in_axes == in_fixed:
            raise ConfigError(f"{key}.{'axes' if in_fixed else 'fixed'}.{d}",
                              f"{d} must be given exactly once, in axes or in fixed")
        spec = grid["axes"][d] if in_axes else float(grid["fixed"][d])
        axes[d] = axis_values(spec, key=f"{key}.axes.{d}")
        if d in ("eta", "omega") and axes[d][0] <= 0 or axes[d][0] < 0:
            raise ConfigError(f"{key}.axes.{d}", f"{d} must be positive")
    return axes


def grid_chunks(axes: dict, chunk_size: int) -> list[dict]:
    """Cut the grid into sub-grids (cartesian products) of at most ``chunk_size`` points.

    Cuts go along the slowest axis in (eta, omega, F) order that has several values: groups
    of whole "rows" (all values of the faster axes), or, if one row alone is too big, the
    row is cut recursively along the next axis. Appending values to the slowest axis, or
    refining nothing but adding another grid, leaves existing chunks (and their files)
    unchanged.
    """
    chunk_size = max(1, int(chunk_size))
    out: list[dict] = []

    def rec(prefix: dict, rest: list):
        n = int(np.prod([axes[d].size for d in rest])) if rest else 1
        if n <= chunk_size:
            out.append({**prefix, **{d: axes[d].tolist() for d in rest}})
            return
        d, faster = rest[0], rest[1:]
        row = int(np.prod([axes[x].size for x in faster])) if faster else 1
        vals = axes[d].tolist()
        if row <= chunk_size:
            k = max(1, chunk_size // row)
            for i in range(0, len(vals), k):
                out.append({**prefix, d: vals[i:i + k], **{x: axes[x].tolist() for x in faster}})
        else:
            for v in vals:
                rec({**prefix, d: [v]}, faster)

    rec({}, list(DIMS))
    return [{d: c[d] for d in DIMS} for c in out]


def chunk_key(chunk: dict) -> str:
    """Name of a chunk: sha256 (16 hex digits) of its parameter values (exact float64)."""
    h = hashlib.sha256()
    for d in DIMS:
        a = np.ascontiguousarray(np.asarray(chunk[d], dtype="<f8"))
        h.update(d.encode() + b":" + str(a.size).encode() + b":" + a.tobytes())
    return h.hexdigest()[:16]


def chunk_map(axes: dict, chunk_size: int) -> dict:
    """{chunk_key: chunk} in grid order."""
    return {chunk_key(c): c for c in grid_chunks(axes, chunk_size)}


def code_version(src_dir=None, exclude=NON_COMPUTE_SOURCES) -> str:
    """sha256 over the vines sources that computations use (names and contents).

    Passed as a Snakemake param so a change of the numerics reruns the computing jobs
    (Snakemake does not track imported modules) while figure-only edits do not.
    """
    src = Path(src_dir) if src_dir is not None else Path(__file__).resolve().parent
    h = hashlib.sha256()
    for f in sorted(src.glob("*.py")):
        if f.name in exclude:
            continue
        h.update(f.name.encode() + b"\0" + f.read_bytes() + b"\0")
    return h.hexdigest()[:16]


# ------------------------------------------------------------------ dask execution

def _compute(tasks: list, n_workers: int, scheduler: str | None, progress: bool):
    """Compute dask.delayed ``tasks`` in order; threaded, or on a distributed scheduler."""
    import dask
    if scheduler:
        from dask.distributed import Client, progress as dprogress
        with Client(scheduler) as client:
            futs = client.compute(tasks)
            if progress:
                dprogress(futs)
            return client.gather(futs)
    if progress:
        with _LineProgress(len(tasks)):
            return list(dask.compute(*tasks, scheduler="threads", num_workers=n_workers))
    return list(dask.compute(*tasks, scheduler="threads", num_workers=n_workers))


def _progress_callback_class():
    from dask.callbacks import Callback

    class LineProgress(Callback):
        """Progress of a dask computation as plain lines (for job logs): every 10 %."""

        def __init__(self, n_tasks, stream=None):
            super().__init__()
            self.n, self.done, self.next = n_tasks, 0, 0.1
            self.stream = stream
            self.lock = __import__("threading").Lock()

        def _start(self, dsk):
            import time
            self.t0 = time.perf_counter()

        def _posttask(self, key, result, dsk, state, worker_id):
            import sys
            import time
            name = key[0] if isinstance(key, tuple) else key
            if not str(name).startswith(("_batch_block", "_sweep_line")):
                return
            with self.lock:
                self.done += 1
                frac = self.done / max(1, self.n)
                if frac >= self.next or self.done == self.n:
                    while self.next <= frac:
                        self.next += 0.1
                    print(f"[{time.perf_counter() - self.t0:8.1f} s] {self.done}/{self.n} tasks "
                          f"({100 * frac:.0f} %)", file=self.stream or sys.stdout, flush=True)

    return LineProgress


def _LineProgress(n_tasks, stream=None):
    return _progress_callback_class()(n_tasks, stream)


def _batch_block(eta, omega, F, kw):
    from ..core.simulation import simulate_batch
    return simulate_batch(eta, omega, F, n_threads=1, **kw)


def compute_chunk(chunk: dict, *, model: dict, simulation: dict, n_workers: int = 1,
                  block_size: int = 64, scheduler: str | None = None,
                  progress: bool = False) -> dict:
    """BATCH_FIELDS arrays of shape (n_eta, n_omega, n_F) for one chunk (sub-grid)."""
    import dask
    from ..core.simulation import BATCH_FIELDS
    e, w, f = np.meshgrid(*(np.asarray(chunk[d], dtype=float) for d in DIMS), indexing="ij")
    shape = e.shape
    e, w, f = e.ravel(), w.ravel(), f.ravel()
    kw = {**model, **simulation}
    bs = max(1, int(block_size))
    starts = list(range(0, e.size, bs))
    tasks = [dask.delayed(_batch_block, pure=True)(e[i:i + bs], w[i:i + bs], f[i:i + bs], kw)
             for i in starts]
    parts = _compute(tasks, max(1, int(n_workers)), scheduler, progress)
    out = {}
    for k, (dt, _, _) in BATCH_FIELDS.items():
        arr = np.empty(e.size, dtype=dt)
        for i, part in zip(starts, parts):
            arr[i:i + bs] = part[k]
        out[k] = arr.reshape(shape)
    return out


def _sweep_line(param, values, fixed, kw):
    from ..core.sweep import bifurcation_sweep
    return bifurcation_sweep(param, values, **fixed, **kw)


def compute_sweep(spec: dict, *, model: dict, n_workers: int = 1,
                  scheduler: str | None = None, progress: bool = False) -> dict:
    """Bifurcation sweeps of one config entry: every outer value, up and down.

    Returns instance arrays (one entry per (line, direction, value)) and concatenated
    impact arrays, ordered line by line (outer values ascending, 'up' before 'down').
    """
    import dask
    values = axis_values(spec["values"])
    outer_values = axis_values(spec["outer_values"])
    kw = dict(t_settle=spec["t_settle"], t_step=spec["t_step"], n_record=spec["n_record"],
              v_stick=spec["v_stick"], **model)
    lines = []
    for ov in outer_values.tolist():
        for direction in spec["directions"]:
            vals = values if direction == "up" else values[::-1].copy()
            fixed = {**{k: float(v) for k, v in spec["fixed"].items()}, spec["outer"]: ov}
            lines.append((ov, direction, vals, fixed))
    tasks = [dask.delayed(_sweep_line, pure=True)(spec["param"], vals, fixed, kw)
             for (_, _, vals, fixed) in lines]
    res = _compute(tasks, max(1, int(n_workers)), scheduler, progress)
    inst = {k: [] for k in ("value", "outer_value", "direction", "line", "phi", "status",
                            "row_size")}
    samp = {k: [] for k in ("dw", "phase", "wall")}
    for li, ((ov, direction, vals, _), r) in enumerate(zip(lines, res)):
        n = r["value"].size
        inst["value"].append(r["value"])
        inst["outer_value"].append(np.full(n, ov))
        inst["direction"].append(np.full(n, 1 if direction == "up" else -1, dtype="i1"))
        inst["line"].append(np.full(n, li, dtype="i4"))
        inst["phi"].append(r["phi"])
        inst["status"].append(r["status"])
        inst["row_size"].append(r["row_size"])
        for k in samp:
            samp[k].append(r[k])
    cat = {k: np.concatenate(v) for k, v in {**inst, **samp}.items()}
    cat["wall"] = cat["wall"].astype("i1")
    return cat


def compute_timehistory(points: list[dict], *, model: dict, simulation: dict,
                        n_periods: int, samples_per_period: int) -> dict:
    """Single runs at ``points``: the last ``n_periods`` densely sampled, their impacts,
    and the scalar measures of each run."""
    from ..core.simulation import simulate
    n_s = int(n_periods) * int(samples_per_period) + 1
    P = len(points)
    out = {"t": np.empty((P, n_s)), "z_m": np.empty((P, n_s)), "v_m": np.empty((P, n_s)),
           "z_b": np.empty((P, n_s)), "v_b": np.empty((P, n_s)), "ke_ratio": np.empty(P),
           "xmax": np.empty(P), "regime": np.empty(P, dtype="U16"),
           "status": np.empty(P, dtype="U16")}
    imp_t, imp_dw, imp_phase, imp_wall, row_size = [], [], [], [], np.zeros(P, dtype=np.int64)
    for i, pt in enumerate(points):
        res = simulate(pt["eta"], pt["omega"], pt["F"], **model, **simulation)
        T = 2 * math.pi / pt["omega"]
        t1 = res.t_last
        t0 = max(0.0, t1 - n_periods * T)
        ts = np.linspace(t0, t1, n_s)
        st = res.state_at(ts)
        out["t"][i] = ts
        for j, k in enumerate(("z_m", "v_m", "z_b", "v_b")):
            out[k][i] = st[j]
        out["ke_ratio"][i] = res.ke_ratio
        out["xmax"][i] = res.xmax
        out["regime"][i] = res.regime
        out["status"][i] = res.status
        sel = res.impacts["t"] >= t0
        imp_t.append(res.impacts["t"][sel])
        imp_dw.append(res.impact_dw[sel])
        imp_phase.append(res.impact_phase[sel])
        imp_wall.append(res.impacts["wall"][sel].astype("i1"))
        row_size[i] = int(sel.sum())
    out.update(impact_t=np.concatenate(imp_t), impact_dw=np.concatenate(imp_dw),
               impact_phase=np.concatenate(imp_phase), impact_wall=np.concatenate(imp_wall),
               row_size=row_size)
    return out
