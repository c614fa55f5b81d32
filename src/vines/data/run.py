"""A finished pipeline run as one object: every dataset of ``results/<run>/`` in a DataTree.

The tree mirrors the run's folders: one group per stage folder (``measures``, ``sweeps``,
``branches``, ...) and below it one group per dataset, named after its file without
``.nc`` (grid chunks one level deeper, ``grid/<grid>/chunk_<key>``). Each dataset is opened
lazily: opening reads its metadata and coordinates, the values of a variable come from the
file on first access (``.load()``, ``.values``, a plot). Example::

    >>> import vines
    >>> run = vines.open_run("results/smoke")
    >>> run["measures"].children.keys()                # the datasets of one stage
    >>> run["measures/fig2_F0.05"]["ke_ratio"].load()  # one variable, read now
    >>> run.close()                                    # or: with vines.open_run(...) as run:
"""
from __future__ import annotations

from pathlib import Path

import xarray as xr


def run_datasets(path) -> dict[str, Path]:
    """{group path: file} of every dataset (``*.nc``) under the run directory ``path``.

    The group path is the file's path relative to ``path`` without ``.nc``; hidden files
    (``.name.nc.tmp`` of a write in progress, dot folders) are left out.
    """
    root = Path(path)
    found = {}
    for f in sorted(root.rglob("*.nc")):
        rel = f.relative_to(root)
        if any(part.startswith(".") for part in rel.parts) or not f.is_file():
            continue
        found[rel.with_suffix("").as_posix()] = f
    return found


def open_run(path) -> xr.DataTree:
    """Open every dataset of the run directory ``path`` (e.g. ``results/smoke``) lazily.

    Returns an ``xarray.DataTree``: groups per stage folder, one child per dataset (see the
    module docstring); the root's attrs hold ``run`` (the directory's name). Close it
    (``tree.close()`` or a ``with`` block) to release the files. Raises
    ``FileNotFoundError`` if ``path`` is not a directory and ``ValueError`` if it holds no
    dataset.
    """
    root = Path(path)
    if not root.is_dir():
        raise FileNotFoundError(f"open_run: {path}: no such run directory")
    files = run_datasets(root)
    if not files:
        raise ValueError(f"open_run: {path}: no dataset (*.nc) in this directory")
    opened: list[xr.Dataset] = []
    try:
        for f in files.values():
            opened.append(xr.open_dataset(f, engine="netcdf4"))
        groups = {"/": xr.Dataset(attrs={"run": root.resolve().name})}
        groups.update(zip(files, opened, strict=True))
        tree = xr.DataTree.from_dict(groups)
    except BaseException:
        for ds in opened:
            ds.close()
        raise
    tree.set_close(lambda: [ds.close() for ds in opened])
    return tree
