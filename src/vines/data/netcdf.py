"""NetCDF datasets of the pipeline: CF attributes, provenance, encodings, atomic writes.

Everything here is plain xarray/netCDF4 (no snakemake), so it is importable and tested on
its own. Conventions:

* Dimension coordinates ``eta``, ``omega``, ``F`` (grids), CF-1.10 attributes: ``long_name``
  and ``units`` on every variable (``"1"`` for dimensionless numbers).
* Provenance in global attributes: vines version, git commit of the sources, sha256 of the
  config subset that produced the file, solver settings, code version. No timestamps and no
  host names, so rerunning a job rewrites a byte-identical file.
* zlib compression with explicit chunk sizes; strings stored as char arrays (compressible).
* Files are written to a temporary name in the destination directory, then ``os.replace``d:
  a killed job never leaves a half-written file under the final name.
"""
from __future__ import annotations

import hashlib
import json
import os
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr

from ..core.params import L_HALF_M
from ..core.simulation import BATCH_FIELDS

DIMS = ("eta", "omega", "F")
CONVENTIONS = "CF-1.10"

COORD_ATTRS = {
    "eta": {"long_name": "ball-to-LO mass ratio eta = m/M", "units": "1"},
    "omega": {"long_name": "forcing frequency ratio W = w/w0", "units": "1"},
    "F": {"long_name": "forcing amplitude F = A/L", "units": "1"},
}

#: derived variables added by ``derive_measures``: name -> (long_name, units)
DERIVED_FIELDS = {
    "xmax_m": ("max |x_m| over the window", "m"),
    "xmax_whole_run_m": ("max |x_m| over the whole run", "m"),
    "xmax_stuck_linear": ("steady-state amplitude of the stuck linear system (Eq. 28)", "1"),
    "xmax_stuck_linear_m": ("steady-state amplitude of the stuck linear system (Eq. 28)", "m"),
    "impacting": ("1 where the post-transient motion has impacts", "1"),
    "chatter": ("1 where the post-transient regime is chatter", "1"),
    "failed": ("1 where the run did not finish (status != ok)", "1"),
}

FILL = {"f": np.nan, "i": -1, "U": "", "b": False}


# ------------------------------------------------------------------ provenance

def config_sha256(subset) -> str:
    """sha256 of a JSON-able config subset (keys sorted, floats in repr form)."""
    blob = json.dumps(subset, sort_keys=True, separators=(",", ":"), default=_json_default)
    return hashlib.sha256(blob.encode()).hexdigest()


def _json_default(x):
    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    raise TypeError(f"not JSON-serialisable: {type(x).__name__}")


def git_commit(path=None) -> str:
    """Commit of the git checkout holding ``path`` (default: the vines sources), or 'unknown'.

    A checkout with uncommitted changes to tracked files gets a ``-dirty`` suffix.
    """
    where = Path(path) if path is not None else Path(__file__).resolve().parent
    try:
        head = subprocess.run(["git", "-C", str(where), "rev-parse", "HEAD"], check=True,
                              capture_output=True, text=True, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(where), "status", "--porcelain",
                                "--untracked-files=no", "--", "."], check=True,
                               capture_output=True, text=True, timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return head + ("-dirty" if dirty else "")


def provenance_attrs(*, title: str, config_subset, settings: dict | None = None,
                     code_version: str = "", commit: str | None = None) -> dict:
    """Global attributes: CF conventions and provenance (deterministic: no timestamps)."""
    from .. import __version__
    attrs = {
        "Conventions": CONVENTIONS,
        "title": title,
        "source": f"vines {__version__}",
        "vines_version": __version__,
        "git_commit": git_commit() if commit is None else commit,
        "code_version": code_version,
        "config_sha256": config_sha256(config_subset),
        "config": json.dumps(config_subset, sort_keys=True, default=_json_default),
    }
    for k, v in sorted((settings or {}).items()):
        attrs[f"solver_{k}"] = _attr_value(v)
    return attrs


def _attr_value(v):
    if v is None:
        return "none"
    if isinstance(v, bool):
        return int(v)
    if isinstance(v, (int, float, str, np.generic)):
        return v
    return json.dumps(v, sort_keys=True, default=_json_default)


# ------------------------------------------------------------------ encodings and writing

def _chunks_for(shape, target=65536):
    """Chunk sizes for a variable: whole trailing dims, leading dims cut to ~target elements."""
    if not shape:
        return None
    chunks = list(shape)
    n = int(np.prod(shape)) if shape else 1
    i = 0
    while n > target and i < len(chunks):
        shrink = max(1, int(chunks[i] * target / n))
        n = n // chunks[i] * shrink
        chunks[i] = shrink
        i += 1
    return tuple(max(1, c) for c in chunks)


def default_encoding(ds: xr.Dataset, complevel: int = 4) -> dict:
    """zlib + shuffle + chunksizes for every variable; strings as char arrays."""
    enc = {}
    for name, var in ds.variables.items():
        e: dict = {}
        kind = var.dtype.kind
        if kind in "US":
            e["dtype"] = "S1"
            e["char_dim_name"] = f"{name}_strlen"
            e["_FillValue"] = None
        elif name in ds.dims:
            e["_FillValue"] = None
        elif kind == "f":
            e["_FillValue"] = np.nan
        elif kind in "iub":
            e["_FillValue"] = None
        if var.ndim and var.size:
            e.update(zlib=True, complevel=complevel, shuffle=True)
            if kind not in "US":
                e["chunksizes"] = _chunks_for(var.shape)
        enc[name] = e
    return enc


def new_file_mode() -> int:
    """Permission bits of a newly created file under the current umask (mkstemp uses 0600)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def write_dataset(ds: xr.Dataset, path, encoding: dict | None = None) -> Path:
    """Write ``ds`` to NetCDF-4 at ``path`` atomically (temp file + os.replace, same dir)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    for name, var in ds.variables.items():
        if "long_name" not in var.attrs or "units" not in var.attrs:
            raise ValueError(f"variable {name!r} lacks long_name/units (CF)")
    enc = default_encoding(ds)
    for k, v in (encoding or {}).items():
        enc.setdefault(k, {}).update(v)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    os.chmod(tmp, new_file_mode())
    try:
        ds.to_netcdf(tmp, format="NETCDF4", engine="netcdf4", encoding=enc)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def read_dataset(path) -> xr.Dataset:
    """Open and load a dataset fully (the file is closed on return)."""
    with xr.open_dataset(path, engine="netcdf4") as ds:
        return ds.load()


# ------------------------------------------------------------------ grid datasets

def _coords(axes: dict) -> dict:
    return {d: xr.Variable((d,), np.asarray(axes[d], dtype=float), COORD_ATTRS[d])
            for d in DIMS}


def grid_dataset(axes: dict, fields: dict, attrs: dict) -> xr.Dataset:
    """Dataset over dims (eta, omega, F) holding ``fields`` (BATCH_FIELDS arrays)."""
    coords = _coords(axes)
    data = {}
    for name, arr in fields.items():
        dt, long_name, units = BATCH_FIELDS[name]
        data[name] = xr.Variable(DIMS, np.asarray(arr).astype(dt),
                                 {"long_name": long_name, "units": units})
    return xr.Dataset(data, coords=coords, attrs=attrs)


def merge_chunks(datasets, axes: dict) -> dict:
    """Place chunk datasets (each a sub-grid) into the full grid given by ``axes``.

    Values are matched exactly (chunks are cut from the same axes). Raises ValueError when a
    chunk value is not on an axis or a grid point is missing.
    """
    full = {d: np.asarray(axes[d], dtype=float) for d in DIMS}
    shape = tuple(full[d].size for d in DIMS)
    out = {k: np.full(shape, FILL[np.dtype(dt).kind], dtype=dt)
           for k, (dt, _, _) in BATCH_FIELDS.items()}
    seen = np.zeros(shape, dtype=bool)
    for ds in datasets:
        idx = []
        for d in DIMS:
            v = ds[d].values
            pos = np.searchsorted(full[d], v)
            pos = np.clip(pos, 0, full[d].size - 1)
            if not np.array_equal(full[d][pos], v):
                raise ValueError(f"chunk values of {d} are not on the grid axis")
            idx.append(pos)
        ix = np.ix_(*idx)
        for k in BATCH_FIELDS:
            out[k][ix] = ds[k].values.astype(out[k].dtype)
        seen[ix] = True
    if not seen.all():
        raise ValueError(f"{int((~seen).sum())} grid points missing from the chunks")
    return out


def derive_measures(ds: xr.Dataset, r: float, d: float, sections: dict | None = None) -> xr.Dataset:
    """Add metres, the stuck-linear reference amplitude, masks and section markers."""
    from ..core.linear import stuck_amplitude
    ds = ds.copy()
    L = L_HALF_M

    def put(name, arr, dims=DIMS, dtype=None):
        long_name, units = DERIVED_FIELDS[name]
        a = np.asarray(arr)
        ds[name] = xr.Variable(dims, a if dtype is None else a.astype(dtype),
                               {"long_name": long_name, "units": units})

    put("xmax_m", ds["xmax"].values * L)
    put("xmax_whole_run_m", ds["xmax_whole_run"].values * L)
    e, w, f = np.meshgrid(ds["eta"].values, ds["omega"].values, ds["F"].values, indexing="ij")
    amp = stuck_amplitude(e, w, f, d)
    put("xmax_stuck_linear", amp)
    put("xmax_stuck_linear_m", amp * L)
    put("impacting", ds["impacts_per_period"].values > 0, dtype="i1")
    put("chatter", ds["regime"].values == "chatter", dtype="i1")
    put("failed", ds["status"].values != "ok", dtype="i1")
    for dim, values in (sections or {}).items():
        mark = np.isin(ds[dim].values, np.asarray(values, dtype=float))
        missing = set(map(float, values)) - set(ds[dim].values[mark].tolist())
        if missing:
            raise ValueError(f"section {dim} = {sorted(missing)} is not on the grid axis")
        ds[f"section_{dim}"] = xr.Variable(
            (dim,), mark.astype("i1"),
            {"long_name": f"1 where {dim} is one of the requested sections", "units": "1",
             "flag_values": np.array([0, 1], dtype="i1"),
             "flag_meanings": "not_section section"})
    return ds


# ------------------------------------------------------------------ ragged (sweeps)

def ragged_dataset(instances: dict, samples: dict, row_size, *, instance_dim: str,
                   sample_dim: str, attrs: dict) -> xr.Dataset:
    """CF contiguous ragged array: ``row_size`` samples per instance, one after another.

    ``instances`` / ``samples``: name -> (array, long_name, units).
    """
    data = {}
    for name, (arr, ln, un) in instances.items():
        data[name] = xr.Variable((instance_dim,), np.asarray(arr), {"long_name": ln, "units": un})
    for name, (arr, ln, un) in samples.items():
        data[name] = xr.Variable((sample_dim,), np.asarray(arr), {"long_name": ln, "units": un})
    rs = np.asarray(row_size, dtype=np.int64)
    n = int(rs.sum())
    for name, (arr, _, _) in samples.items():
        if np.asarray(arr).shape[0] != n:
            raise ValueError(f"{name}: {np.asarray(arr).shape[0]} samples, row_size sums to {n}")
    data["row_size"] = xr.Variable((instance_dim,), rs, {
        "long_name": f"number of {sample_dim}s of each {instance_dim}", "units": "1",
        "sample_dimension": sample_dim})
    return xr.Dataset(data, attrs=attrs)


def ragged_rows(ds: xr.Dataset, name: str, row_size: str = "row_size") -> list[np.ndarray]:
    """Split a contiguous ragged sample variable into one array per instance."""
    rs = ds[row_size].values
    edges = np.concatenate([[0], np.cumsum(rs)])
    v = ds[name].values
    return [v[edges[i]:edges[i + 1]] for i in range(rs.size)]
