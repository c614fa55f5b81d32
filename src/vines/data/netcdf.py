"""NetCDF-4 encoding and atomic reading/writing of datasets.


* zlib compression with explicit chunk sizes; strings stored as char arrays (compressible).
* ``write_dataset`` refuses variables without CF ``long_name``/``units``.
* Files are written to a temporary name in the destination directory, then ``os.replace``d:
  a killed job never leaves a half-written file under the final name.
"""
from __future__ import annotations

import os
import tempfile
import threading
from pathlib import Path

import numpy as np
import xarray as xr


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


def _write_netcdf4(ds: xr.Dataset, path: str, encoding: dict) -> None:
    """``ds.to_netcdf(path, format="NETCDF4", engine="netcdf4")`` with a plain thread lock.

    The datasets are in memory (never dask-chunked), so the scheduler-aware write lock that
    ``to_netcdf`` asks for only costs an import of dask.distributed (~0.3 s per job); the
    bytes written are the same.
    """
    ds = ds.load()      # dask-backed variables would be queued, never written, without it
    store = xr.backends.NetCDF4DataStore.open(path, mode="w", format="NETCDF4",
                                              lock=threading.Lock())
    try:
        ds.dump_to_store(store, encoding=encoding)
    finally:
        store.close()


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
        _write_netcdf4(ds, tmp, enc)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


class UnreadableDatasetError(OSError):
    """A dataset file exists but cannot be read (truncated, corrupted); names the file."""


def read_dataset(path) -> xr.Dataset:
    """Open and load a dataset fully (the file is closed on return).

    Raises UnreadableDatasetError naming ``path`` when the file is damaged.
    """
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            return ds.load()
    except FileNotFoundError:
        raise
    except (OSError, RuntimeError, ValueError, KeyError) as err:
        raise UnreadableDatasetError(f"{path}: cannot be read ({err})") from None


def unreadable_datasets(paths) -> list[tuple[str, str]]:
    """(path, reason) of every existing file in ``paths`` that ``read_dataset`` refuses."""
    bad = []
    for p in paths:
        if Path(p).is_file():
            try:
                read_dataset(p)
            except UnreadableDatasetError as err:
                bad.append((str(p), str(err).split(": cannot be read ", 1)[-1]))
    return bad
