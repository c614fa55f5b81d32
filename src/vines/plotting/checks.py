"""Reading the figures' input datasets, with checks.

Every reader checks its dataset (expected coordinates and variables, finite values) and
raises :class:`FigureInputError` naming the file, the variable and the problem, instead of
letting a figure draw an empty or misleading plot.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..data.builders import ragged_rows
from ..data.netcdf import read_dataset

#: values of ``cls`` in the stability maps (flag_values of vines.data.schema)
CLASS_VALUES = (0, 1, 2, 3)


class FigureInputError(ValueError):
    """A figure's input dataset is missing, incomplete or not finite."""


def load(path) -> xr.Dataset:
    """Open a dataset fully (closed on return); a clear error if it is missing/unreadable."""
    path = Path(path)
    if not path.is_file():
        raise FigureInputError(f"{path}: input dataset does not exist")
    try:
        out = read_dataset(path)
    except Exception as err:  # noqa: BLE001  (any reader error -> one clear message)
        raise FigureInputError(f"{path}: cannot read dataset ({err})") from err
    out.attrs["_path"] = str(path)
    return out


def _where(ds) -> str:
    return ds.attrs.get("_path", "<dataset>")


def _check_coord(ds, c, min_size):
    where = _where(ds)
    if c not in ds.coords:
        raise FigureInputError(f"{where}: expected coordinate {c!r} is missing "
                               f"(has {sorted(ds.coords)})")
    v = np.asarray(ds[c].values, dtype=float)
    if v.ndim != 1 or v.size < min_size:
        raise FigureInputError(f"{where}: coordinate {c!r} has {v.size} values, "
                               f"at least {min_size} needed")
    if not np.all(np.isfinite(v)):
        raise FigureInputError(f"{where}: coordinate {c!r} has non-finite values")
    if v.size > 1 and not np.all(np.diff(v) > 0):
        raise FigureInputError(f"{where}: coordinate {c!r} is not strictly increasing")


def require(ds: xr.Dataset, *, coords=(), variables=(), finite=(), allow_nan=None,
            min_size=1) -> xr.Dataset:
    """Check ``ds`` before drawing it; returns it.

    coords: finite, strictly increasing 1-D coordinates with at least ``min_size`` values;
    variables: must exist; finite: finite everywhere except where ``allow_nan[name]`` is true.
    """
    allow_nan = allow_nan or {}
    where = _where(ds)
    for c in coords:
        _check_coord(ds, c, min_size)
    for name in list(variables) + [f for f in finite if f not in variables]:
        if name not in ds.variables:
            raise FigureInputError(f"{where}: expected variable {name!r} is missing")
    for name in finite:
        v = np.asarray(ds[name].values, dtype=float)
        if v.size == 0:
            raise FigureInputError(f"{where}: variable {name!r} is empty")
        bad = ~np.isfinite(v)
        if name in allow_nan:
            bad &= ~np.asarray(allow_nan[name], dtype=bool)
        if bad.any():
            raise FigureInputError(f"{where}: variable {name!r} has {int(bad.sum())} "
                                   f"non-finite value(s) of {v.size}")
    return ds


def fixed_value(ds: xr.Dataset, dim: str) -> float:
    """The single value of a length-1 grid coordinate (e.g. omega of a Fig 7 grid)."""
    v = np.asarray(ds[dim].values, dtype=float)
    if v.size != 1:
        raise FigureInputError(f"{_where(ds)}: coordinate {dim!r} should hold one fixed "
                               f"value, has {v.size}")
    return float(v[0])


def sorted_by_fixed(datasets, dim):
    """Datasets (each with one fixed value of ``dim``) in increasing order of that value."""
    return sorted(datasets, key=lambda ds: fixed_value(ds, dim))


def grid2d(ds: xr.Dataset, var: str, x: str, y: str) -> np.ndarray:
    """``var`` of a measures grid as a (len(y), len(x)) array (the fixed dim squeezed)."""
    a = ds[var]
    for d in [d for d in a.dims if d not in (x, y)]:
        if a.sizes[d] != 1:
            raise FigureInputError(f"{_where(ds)}: {var!r} varies along {d!r}, a 2-D map "
                                   f"over ({x}, {y}) needs it fixed")
        a = a.isel({d: 0})
    return np.asarray(a.transpose(y, x).values, dtype=float)


def marked_sections(grids, dim: str, prefix: str) -> np.ndarray:
    """Values of ``dim`` marked by ``section_<dim>`` in every grid (same, non-empty)."""
    for ds in grids:
        require(ds, variables=(f"section_{dim}",))
    vals = [ds[dim].values[ds[f"section_{dim}"].values.astype(bool)] for ds in grids]
    if not vals or vals[0].size == 0 or not all(np.array_equal(vals[0], v) for v in vals):
        raise FigureInputError(f"the {prefix}_* grids must mark the same, non-empty {dim} "
                               f"sections (section_{dim}), got {[v.tolist() for v in vals]}")
    return vals[0]


# ------------------------------------------------------------------ one reader per dataset kind

def measures(path, *, axes, fixed, min_size=2) -> xr.Dataset:
    """A measures grid (extract_measures output): plotted axes, finite measures, fixed dims."""
    ds = load(path)
    require(ds, coords=("eta", "omega", "F"), min_size=1)
    require(ds, coords=axes, min_size=min_size, finite=("ke_ratio", "xmax_m"))
    for d in fixed:
        fixed_value(ds, d)
    return ds


def sweep(path) -> xr.Dataset:
    """A bifurcation sweep (contiguous ragged array of impacts)."""
    ds = load(path)
    require(ds, variables=("value", "outer_value", "direction", "row_size", "dw"),
            finite=("value", "outer_value", "dw"))
    n, stored = int(ds["row_size"].values.sum()), ds.sizes.get("impact", 0)
    if n != stored:
        raise FigureInputError(f"{_where(ds)}: row_size sums to {n}, {stored} impacts stored")
    if n == 0:
        raise FigureInputError(f"{_where(ds)}: the sweep recorded no impact at all")
    return ds


def sweep_fixed(ds: xr.Dataset, name: str) -> float:
    """The value of a parameter held fixed along a sweep (global attribute 'fixed',
    'F=0.2,omega=1')."""
    fx = dict(kv.split("=") for kv in ds.attrs.get("fixed", "").split(",") if "=" in kv)
    if name not in fx:
        raise FigureInputError(f"{_where(ds)}: global attribute 'fixed' does not give {name}")
    return float(fx[name])


def sweep_points(ds: xr.Dataset, outer: float | None = None, max_per_point=None):
    """(value, dw) of a sweep's impacts: optionally at one outer value only and the last
    ``max_per_point`` impacts of each point."""
    keep = np.ones(ds["row_size"].size, bool)
    if outer is not None:
        keep &= np.isclose(ds["outer_value"].values, outer, rtol=0, atol=1e-9)
        if not keep.any():
            raise FigureInputError(f"{_where(ds)}: no sweep at outer value {outer}")
    rows, val = ragged_rows(ds, "dw"), ds["value"].values
    xs, ys = [], []
    for i in np.flatnonzero(keep):
        y = rows[i]
        if max_per_point is not None:
            y = y[max(0, y.size - max_per_point):]
        xs.append(np.full(y.size, val[i]))
        ys.append(y)
    return np.concatenate(xs), np.concatenate(ys)


def branch(path) -> xr.Dataset:
    """A 1:1 branch (map_solve output); values may be NaN at non-admissible points only."""
    ds = load(path)
    require(ds, variables=("stable", "admissible", "abs_eigenvalues", "dw_L", "dw_R"),
            finite=("eta", "omega", "F"))
    if ds.sizes.get("point", 0) < 1:
        raise FigureInputError(f"{_where(ds)}: the branch has no point")
    adm = ds["admissible"].values.astype(bool)
    require(ds, finite=("dw_L", "dw_R", "lambda_max"),
            allow_nan={k: ~adm for k in ("dw_L", "dw_R", "lambda_max")})
    return ds


def stability(path) -> xr.Dataset:
    """A stability map over (eta, omega) (lambda_max NaN only for cls 0)."""
    ds = load(path)
    require(ds, coords=("eta", "omega"), min_size=2, variables=("cls",))
    cls = ds["cls"].values
    if not np.isin(cls, CLASS_VALUES).all():
        raise FigureInputError(f"{_where(ds)}: 'cls' has values outside {list(CLASS_VALUES)}")
    require(ds, finite=("lambda_max",), allow_nan={"lambda_max": cls == 0})
    if "F" not in ds.attrs:
        raise FigureInputError(f"{_where(ds)}: global attribute 'F' is missing")
    return ds


def robust_map(path) -> xr.Dataset:
    """A robust-TET map over (eta, omega): basin fractions in [0, 1], attributes F and
    threshold."""
    ds = load(path)
    require(ds, coords=("eta", "omega"), min_size=2,
            finite=("efficient_fraction", "stable_1to1_fraction"))
    for k in ("F", "threshold", "n_states"):
        if k not in ds.attrs:
            raise FigureInputError(f"{_where(ds)}: global attribute {k!r} is missing")
    return ds


def basin_slice(path) -> xr.Dataset:
    """A basin slice: attractor index over (z_m0, v_m0) within the attractor table."""
    ds = load(path)
    require(ds, coords=("z_m0", "v_m0"), min_size=2, variables=("attractor", "regime"),
            finite=("ke_ratio",))
    idx = ds["attractor"].values
    if idx.min() < -1 or idx.max() >= ds.sizes["attractor_index"]:
        raise FigureInputError(f"{_where(ds)}: 'attractor' indexes outside the table")
    return ds


def timehistory(path) -> xr.Dataset:
    """Time histories of single runs (at least 2 samples per point), their impacts and, if
    stored, the samples of the whole measurement window (``window_*``); the attribute
    ``solver_r`` (impact directions, ``vines.plotting.impacts``)."""
    ds = load(path)
    impacts = ("impact_t", "impact_dw", "impact_phase")
    require(ds, variables=("t", "z_m", "v_m", "z_b", "v_b", "row_size") + impacts,
            finite=("eta", "omega", "F", "t", "z_m", "v_m", "z_b", "v_b") + impacts)
    if ds.sizes.get("sample", 0) < 2:
        raise FigureInputError(f"{_where(ds)}: time histories have no samples")
    n, stored = int(ds["row_size"].values.sum()), ds.sizes.get("impact", 0)
    if n != stored:
        raise FigureInputError(f"{_where(ds)}: row_size sums to {n}, {stored} impacts stored")
    if "window_t" in ds.variables:
        require(ds, finite=tuple(f"window_{k}" for k in ("t", "z_m", "v_m", "z_b", "v_b")))
    if "solver_r" not in ds.attrs:     # the impact law carries v_b over sample-less gaps
        raise FigureInputError(f"{_where(ds)}: global attribute 'solver_r' (coefficient of "
                               f"restitution) is missing")
    return ds
