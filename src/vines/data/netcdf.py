"""NetCDF-4 encoding and atomic reading/writing of datasets.


* zlib compression with explicit chunk sizes; strings stored as char arrays (compressible).
* ``write_dataset`` refuses variables without CF ``long_name``/``units``.
* Files are written to a temporary name in the destination directory, then ``os.replace``d:
  a killed job never leaves a half-written file under the final name.
"""
from __future__ import annotations

import contextlib
import glob
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


def temporary_beside(path: Path, suffix: str) -> str:
    """A new temporary file ``.<name>.<random><suffix>`` beside ``path`` (mode as a new file),
    to be renamed onto ``path`` once written. Temporaries of ``path`` left by a writer that
    was killed (SIGKILL leaves no chance to clean up) are removed first: no two writers of
    one output run at once (Snakemake's jobs own their outputs)."""
    for stale in path.parent.glob(f".{glob.escape(path.name)}.*{suffix}"):
        with contextlib.suppress(FileNotFoundError):
            stale.unlink()
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=suffix, dir=path.parent)
    os.close(fd)
    os.chmod(tmp, new_file_mode())
    return tmp


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
    return write_atomically(path, lambda tmp: _write_netcdf4(ds, tmp, enc))


def write_atomically(path: Path, write) -> Path:
    """``write(tmp)`` a temporary file beside ``path``, then rename it onto ``path``; the
    temporary is removed if writing fails (a killed write leaves no partial ``path``)."""
    tmp = temporary_beside(path, ".tmp")
    try:
        write(tmp)
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


#: the HDF5 format signature that starts a NetCDF-4 file (at offset 0, 512, 1024, ...)
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
#: the signatures of the classic NetCDF formats (CDF-1, CDF-2, CDF-5)
CLASSIC_SIGNATURES = (b"CDF\x01", b"CDF\x02", b"CDF\x05")
_UNDEFINED_ADDRESS = 2**64 - 1


def _hdf5_end(head: bytes, at: int) -> int | None:
    """File size an HDF5 superblock starting at ``head[at]`` records (base + end-of-file
    address, bytes), or None if the superblock does not say (undefined address)."""
    version = head[at + 8]
    if version in (2, 3):       # signature, version, offset/length sizes, flags, addresses
        base, _, eof = (int.from_bytes(head[at + 12 + 8 * i:at + 20 + 8 * i], "little")
                        for i in range(3))
    elif version in (0, 1):     # 16 bytes of versions and sizes, then base, free-space, eof
        first = at + 24 + (4 if version == 1 else 0)
        base, _, eof = (int.from_bytes(head[first + 8 * i:first + 8 + 8 * i], "little")
                        for i in range(3))
    else:
        return None
    return None if _UNDEFINED_ADDRESS in (base, eof) else base + eof


def dataset_damage(path) -> str | None:
    """Why the NetCDF file ``path`` cannot be complete, from its header and size alone
    (microseconds, nothing decoded): empty, not NetCDF, or shorter than its HDF5 superblock
    records (a truncated copy or write). None if the header and size agree. A file damaged
    inside (bytes flipped, same size) passes; ``read_dataset`` finds that."""
    size = os.path.getsize(path)
    if size == 0:
        return "empty file"
    with open(path, "rb") as fh:
        head = fh.read(64)
        if head.startswith(CLASSIC_SIGNATURES):
            return None
        at = 0
        while not head.startswith(HDF5_SIGNATURE):   # a user block of 512 * 2**k bytes
            at = 512 if at == 0 else 2 * at
            if at + 64 > size:
                return "not a NetCDF file (no NetCDF or HDF5 signature)"
            fh.seek(at)
            head = fh.read(64)
    if len(head) < 56:
        return f"truncated: {size} bytes, shorter than its header"
    end = _hdf5_end(head, 0)
    if end is not None and end > size:
        return f"truncated: {size} of {end} bytes"
    return None


def unreadable_datasets(paths) -> list[tuple[str, str]]:
    """(path, reason) of every existing file in ``paths`` whose header or size shows it is
    damaged (``dataset_damage``): a check of milliseconds for a whole results tree, run by
    every parse of the workflow. ``reason`` is in parentheses."""
    bad = []
    for p in paths:
        if Path(p).is_file():
            reason = dataset_damage(p)
            if reason is not None:
                bad.append((str(p), f"({reason})"))
    return bad


def unwritable_folder(path) -> str | None:
    """Why datasets cannot be written under the folder ``path`` (created when missing), or
    None: its nearest existing ancestor, and every folder already in it, must be a writable
    folder. Cheap (``os.access``, no file written): run by every parse of the workflow."""
    path = Path(path).absolute()
    existing = path
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        return f"{existing} is a file, not a folder"
    folders = [Path(d) for d, _, _ in os.walk(path)] if existing == path else [existing]
    for folder in folders:
        if not os.access(folder, os.W_OK | os.X_OK):
            return f"{folder} is not writable"
    return None
