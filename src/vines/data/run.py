"""A finished pipeline run as one object: every dataset of ``results/<run>/`` in a DataTree.

The tree mirrors the run's folders: one group per stage folder (``extract_measures``,
``bifurcation_sweep``, ``map_solve``, ...) and below it one group per dataset, named after its file without
``.nc`` (grid chunks one level deeper, ``simulate_grid/<grid>/chunk_<key>``). Each dataset is opened
lazily: opening reads its metadata and coordinates, the values of a variable come from the
file on first access (``.load()``, ``.values``, a plot). Example::

    >>> import vines
    >>> run = vines.open_run("results/smoke")
    >>> run["extract_measures"].children.keys()        # the datasets of one stage
    >>> run["extract_measures/fig2_F0.05"]["ke_ratio"].load()  # one variable, read now
    >>> run.close()                                    # or: with vines.open_run(...) as run:

``print(run)`` is a short summary (stages, datasets per stage, sizes on disk);
``print(run.full_repr())`` is xarray's full tree of every group and variable.
"""
from __future__ import annotations

import os
from pathlib import Path

import xarray as xr

#: dataset names listed per stage in the summary before "..."
SUMMARY_NAMES = 4


class RunTree(xr.DataTree):
    """The DataTree of a run (``open_run``): the run's repr is a summary, its groups' and
    datasets' reprs are xarray's."""

    __slots__ = ()

    def __repr__(self) -> str:
        return run_summary(self) if self.is_root else xr.DataTree.__repr__(self)

    __str__ = __repr__

    def full_repr(self) -> str:
        """xarray's repr: every group, dimension, variable and attribute."""
        return xr.DataTree.__repr__(self)


def _size(nbytes: float) -> str:
    for unit in ("B", "kB", "MB", "GB"):
        if nbytes < 1000 or unit == "GB":
            return f"{nbytes:.0f} {unit}" if unit == "B" else f"{nbytes:.1f} {unit}"
        nbytes /= 1000
    return ""


def _file_size(node) -> int:
    """Bytes on disk of a node's dataset file (its in-memory size if it has no file)."""
    src = node.encoding.get("source")
    return os.path.getsize(src) if src and os.path.isfile(src) else node.nbytes


def run_summary(tree: xr.DataTree) -> str:
    """A few lines: the run, then per stage its number of datasets, their size on disk and
    its first dataset names."""
    stages = sorted(tree.children.values(), key=lambda st: st.name)
    per_stage = [[n for n in st.subtree if n.has_data] for st in stages]
    total = sum(_file_size(n) for nodes in per_stage for n in nodes)
    lines = [f"vines run {tree.attrs.get('run', tree.name)!r}: {len(stages)} stages, "
             f"{sum(map(len, per_stage))} datasets, {_size(total)} on disk (read lazily)"]
    width = max((len(st.name) for st in stages), default=0)
    for st, nodes in zip(stages, per_stage, strict=True):
        names = sorted(st.children)
        more = f", ... (+{len(names) - SUMMARY_NAMES})" if len(names) > SUMMARY_NAMES else ""
        lines.append(f"  {st.name:<{width}}  {len(nodes):>4} dataset{'s' * (len(nodes) != 1)} "
                     f"{_size(sum(map(_file_size, nodes))):>9}  "
                     f"{', '.join(names[:SUMMARY_NAMES])}{more}")
    lines.append("every group and variable: print(run.full_repr()); one dataset: "
                 "run['<stage>/<name>']")
    return "\n".join(lines)


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

    Returns an ``xarray.DataTree`` (a ``RunTree``: its repr is a summary, ``full_repr()``
    the whole tree): groups per stage folder, one child per dataset (see the module
    docstring); the root's attrs hold ``run`` (the directory's name). Close it
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
        tree = RunTree.from_dict(groups)
    except BaseException:
        for ds in opened:
            ds.close()
        raise
    tree.set_close(lambda: [ds.close() for ds in opened])
    return tree
