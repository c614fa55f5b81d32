"""Shared matplotlib helpers of the figure scripts (workflow/scripts/figures/figNN.py).

Importable without Snakemake. Figures only *read* datasets written by the pipeline
(``results/<run>/{measures,sweeps,branches,stability,timehistories}``); restyling a figure
never reruns a computation. Every reader checks its inputs (expected coordinates, finite
values) and raises :class:`FigureInputError` with a message naming the file, the variable and
the problem, instead of drawing an empty or misleading plot.
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from ..data.netcdf import new_file_mode  # noqa: E402
from ..core.params import L_HALF_M  # noqa: E402

#: axis labels (symbols and units)
LABELS = {
    "eta": r"mass ratio $\eta$",
    "omega": r"frequency ratio $\Omega$",
    "F": r"forcing amplitude $F$",
    "ke_ratio": r"KE ratio $K_b/(K_m+K_b)$",
    "xmax_m": r"$x_m^{\max}$ (m)",
    "dw": r"relative impact velocity $\dot w_i$",
    "abs_lambda": r"$|\lambda|$",
    "t": r"time $\tau$",
}
#: colours of the paper: LO / cavity ends blue, ball red, analytic branch red
C_LO, C_BALL, C_BRANCH = "tab:blue", "tab:red", "tab:red"
#: Fig 16 classes (flag values of ``cls`` in the stability datasets)
CLASSES = {0: ("no admissible 1:1", "0.6"), 1: ("symmetric stable 1:1", "tab:orange"),
           2: ("asymmetric stable 1:1", "black"), 3: ("unstable 1:1", "white")}


class FigureInputError(ValueError):
    """A figure's input dataset is missing, incomplete or not finite."""


# ------------------------------------------------------------------ reading + checks

def load(path) -> xr.Dataset:
    """Open a dataset fully (closed on return); a clear error if it is missing/unreadable."""
    path = Path(path)
    if not path.is_file():
        raise FigureInputError(f"{path}: input dataset does not exist")
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            out = ds.load()
    except Exception as err:  # noqa: BLE001  (any reader error -> one clear message)
        raise FigureInputError(f"{path}: cannot read dataset ({err})") from err
    out.attrs["_path"] = str(path)
    return out


def _where(ds) -> str:
    return ds.attrs.get("_path", "<dataset>")


def require(ds: xr.Dataset, *, coords=(), variables=(), finite=(), allow_nan=None,
            min_size=1) -> xr.Dataset:
    """Check a dataset before drawing it.

    coords: names that must exist as finite, strictly increasing 1-D coordinates with at
    least ``min_size`` values; variables: names that must exist; finite: variables that
    must be finite everywhere except where ``allow_nan[name]`` (a boolean mask) is true.
    Returns ``ds``; raises :class:`FigureInputError` naming the file and the problem.
    """
    allow_nan = allow_nan or {}
    where = _where(ds)
    for c in coords:
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


def marked_sections(grids, dim: str, prefix: str) -> np.ndarray:
    """Values of ``dim`` marked by ``section_<dim>`` in every grid (must be the same, non-empty)."""
    for ds in grids:
        require(ds, variables=(f"section_{dim}",))
    vals = [ds[dim].values[ds[f"section_{dim}"].values.astype(bool)] for ds in grids]
    if not vals or vals[0].size == 0 or not all(np.array_equal(vals[0], v) for v in vals):
        raise FigureInputError(f"the {prefix}_* grids must mark the same, non-empty {dim} "
                               f"sections (section_{dim}), got {[v.tolist() for v in vals]}")
    return vals[0]


def fixed_value(ds: xr.Dataset, dim: str) -> float:
    """The single value of a length-1 grid coordinate (e.g. W of a Fig 7 grid)."""
    v = np.asarray(ds[dim].values, dtype=float)
    if v.size != 1:
        raise FigureInputError(f"{_where(ds)}: coordinate {dim!r} should hold one fixed "
                               f"value, has {v.size}")
    return float(v[0])


def grid2d(ds: xr.Dataset, var: str, x: str, y: str) -> np.ndarray:
    """``var`` of a measures grid as a (len(y), len(x)) array (the fixed dim squeezed)."""
    other = [d for d in ds[var].dims if d not in (x, y)]
    a = ds[var]
    for d in other:
        if a.sizes[d] != 1:
            raise FigureInputError(f"{_where(ds)}: {var!r} varies along {d!r}, a 2-D map "
                                   f"over ({x}, {y}) needs it fixed")
        a = a.isel({d: 0})
    return np.asarray(a.transpose(y, x).values, dtype=float)


def measures(path, *, axes, fixed, min_size=2) -> xr.Dataset:
    """A measures grid (extract_measures output) with the checks every figure needs."""
    ds = load(path)
    require(ds, coords=("eta", "omega", "F"), min_size=1)
    require(ds, coords=axes, min_size=min_size, finite=("ke_ratio", "xmax_m"))
    for d in fixed:
        fixed_value(ds, d)
    return ds


def sorted_by_fixed(datasets, dim):
    """Datasets (each with one fixed value of ``dim``) in increasing order of that value."""
    return sorted(datasets, key=lambda ds: fixed_value(ds, dim))


def sweep(path) -> xr.Dataset:
    """A bifurcation sweep (contiguous ragged array of impacts) with its checks."""
    ds = load(path)
    require(ds, variables=("value", "outer_value", "direction", "row_size", "dw"),
            finite=("value", "outer_value", "dw"))
    rs = np.asarray(ds["row_size"].values)
    if rs.sum() != ds.sizes.get("impact", 0):
        raise FigureInputError(f"{_where(ds)}: row_size sums to {rs.sum()}, "
                               f"{ds.sizes.get('impact', 0)} impacts stored")
    if rs.sum() == 0:
        raise FigureInputError(f"{_where(ds)}: the sweep recorded no impact at all")
    return ds


def sweep_points(ds: xr.Dataset, outer: float | None = None, max_per_point=None):
    """(value, dw) arrays of the impacts of a sweep, optionally for one outer value only
    and keeping at most the last ``max_per_point`` impacts of each point."""
    rs = np.asarray(ds["row_size"].values)
    edges = np.concatenate([[0], np.cumsum(rs)])
    keep = np.ones(rs.size, bool)
    if outer is not None:
        keep &= np.isclose(ds["outer_value"].values, outer, rtol=0, atol=1e-9)
        if not keep.any():
            raise FigureInputError(f"{_where(ds)}: no sweep at outer value {outer}")
    xs, ys = [], []
    dw, val = ds["dw"].values, ds["value"].values
    for i in np.flatnonzero(keep):
        a, b = edges[i], edges[i + 1]
        if max_per_point is not None:
            a = max(a, b - max_per_point)
        xs.append(np.full(b - a, val[i]))
        ys.append(dw[a:b])
    return np.concatenate(xs), np.concatenate(ys)


def branch(path) -> xr.Dataset:
    """A 1:1 branch (map_solve output) with its checks."""
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
    """A stability map over (eta, omega) with its checks (lambda_max NaN only for cls 0)."""
    ds = load(path)
    require(ds, coords=("eta", "omega"), min_size=2, variables=("cls",))
    cls = ds["cls"].values
    if not np.isin(cls, list(CLASSES)).all():
        raise FigureInputError(f"{_where(ds)}: 'cls' has values outside {sorted(CLASSES)}")
    require(ds, finite=("lambda_max",), allow_nan={"lambda_max": cls == 0})
    if "F" not in ds.attrs:
        raise FigureInputError(f"{_where(ds)}: global attribute 'F' is missing")
    return ds


def timehistory(path, n_points=None) -> xr.Dataset:
    """Time histories of single runs with their checks."""
    ds = load(path)
    require(ds, variables=("t", "z_m", "v_m", "z_b", "v_b", "row_size"),
            finite=("eta", "omega", "F", "t", "z_m", "v_m", "z_b", "v_b"))
    n = ds.sizes.get("point", 0)
    if n_points is not None and n != n_points:
        raise FigureInputError(f"{_where(ds)}: {n} time histories, the figure shows "
                               f"{n_points}")
    if ds.sizes.get("sample", 0) < 2:
        raise FigureInputError(f"{_where(ds)}: time histories have no samples")
    return ds


# ------------------------------------------------------------------ drawing helpers

def figure(nrows, ncols, *, width=None, height=None, **kw):
    width = width or 3.6 * ncols
    height = height or 2.9 * nrows
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, height), squeeze=False,
                             constrained_layout=True, **kw)
    return fig, axes


def panel_label(ax, i, title=None, *, three_d=False):
    """'(a) title' at the top left of a panel; i is 0-based."""
    text = f"({chr(ord('a') + i)})" + (f" {title}" if title else "")
    if three_d:
        ax.set_title(text, loc="left", fontsize=9)
    else:
        ax.set_title(text, loc="left", fontsize=9)


def fmt(v) -> str:
    return f"{v:g}"


def time_history(ax_t, ax_p, ds: xr.Dataset, i: int):
    """Cavity ends z_m +- 1 (blue) and ball z_b (red) vs time; phase portraits beside."""
    t, zm, vm = ds["t"].values[i], ds["z_m"].values[i], ds["v_m"].values[i]
    zb, vb = ds["z_b"].values[i], ds["v_b"].values[i]
    ax_t.plot(t, zm + 1, color=C_LO, lw=0.9, label=r"cavity ends $z_m \pm 1$")
    ax_t.plot(t, zm - 1, color=C_LO, lw=0.9)
    ax_t.plot(t, zb, color=C_BALL, lw=0.9, label=r"ball $z_b$")
    ax_t.set_xlim(t[0], t[-1])
    ax_t.set_xlabel(LABELS["t"])
    ax_t.set_ylabel(r"displacement $z$ (units of $L$)")
    ax_p.plot(zm, vm, color=C_LO, lw=0.8, label="LO")
    ax_p.plot(zb, vb, color=C_BALL, lw=0.8, label="ball")
    ax_p.set_xlabel(r"displacement $z$")
    ax_p.set_ylabel(r"velocity $\dot z$")


def th_title(ds, i, keys=("eta", "omega", "F")) -> str:
    sym = {"eta": r"\eta", "omega": r"\Omega", "F": "F"}
    return ", ".join(f"${sym[k]}$ = {fmt(float(ds[k].values[i]))}" for k in keys)


def time_history_figure(ds: xr.Dataset, title_keys=("eta", "omega", "F")):
    """Figs 4, 5, 9, 10: one row per point, time history (a, c) and phase portrait (b, d)."""
    n = ds.sizes["point"]
    fig, axes = figure(n, 2, width=9.0, height=2.8 * n,
                       gridspec_kw={"width_ratios": [1.8, 1]})
    for i in range(n):
        time_history(axes[i, 0], axes[i, 1], ds, i)
        panel_label(axes[i, 0], 2 * i, th_title(ds, i, title_keys))
        panel_label(axes[i, 1], 2 * i + 1)
    axes[0, 0].legend(fontsize=7, loc="upper right")
    axes[0, 1].legend(fontsize=7, loc="upper right")
    return fig


def bifurcation_dots(ax, x, y, **kw):
    kw = {"s": 0.6, "color": "black", "linewidths": 0, "rasterized": True, **kw}
    ax.scatter(x, y, **kw)


def branch_lines(ax, br: xr.Dataset, *, with_label=True):
    """Analytic 1:1 branch (admissible points): solid stable, dotted unstable, both walls."""
    eta = br["eta"].values
    adm = br["admissible"].values.astype(bool)
    st = br["stable"].values.astype(bool) & adm
    un = (~br["stable"].values.astype(bool)) & adm
    for k, key in enumerate(("dw_L", "dw_R")):
        y = br[key].values
        for mask, ls, lab in ((st, "-", "analytic 1:1, stable"),
                              (un, ":", "analytic 1:1, unstable")):
            ax.plot(eta, np.where(mask, y, np.nan), ls, color=C_BRANCH, lw=1.6,
                    label=lab if (with_label and k == 0) else None)


def eigenvalue_panel(ax, br: xr.Dataset):
    """|lambda| of the four eigenvalues of J_P2 J_P1 along the branch, |lambda| = 1 dotted."""
    eta = br["eta"].values
    adm = br["admissible"].values.astype(bool)
    ev = np.asarray(br["abs_eigenvalues"].values, dtype=float)
    for j in range(ev.shape[1]):
        ax.plot(eta, np.where(adm, ev[:, j], np.nan), ".", ms=2.5,
                label=rf"$|\lambda_{j + 1}|$")
    ax.axhline(1.0, color="black", ls=":", lw=1.0)
    ax.set_xlabel(LABELS["eta"])
    ax.set_ylabel(LABELS["abs_lambda"])
    top = np.nanmax(np.where(adm[:, None], ev, np.nan)) if adm.any() else 2.0
    ax.set_ylim(0, min(max(1.5, 1.05 * top), 3.0))


def zoom_range(br: xr.Dataset, pad=0.6):
    """The eta window of a zoom: the stable 1:1 interval (else the admissible one) widened
    by ``pad`` times its width on each side, within the branch's range."""
    adm = br["admissible"].values.astype(bool)
    st = br["stable"].values.astype(bool) & adm
    eta = br["eta"].values
    sel = st if st.any() else adm
    if not sel.any():
        return float(eta.min()), float(eta.max())
    a, b = float(eta[sel].min()), float(eta[sel].max())
    w = max(b - a, 0.02 * float(eta.max() - eta.min()))
    return max(float(eta.min()), a - pad * w), min(float(eta.max()), b + pad * w)


def zoom_figure(sw: xr.Dataset, branches, outer_dim: str):
    """Figs 6, 15: per branch a row of (zoomed bifurcation + analytic 1:1, |lambda|)."""
    n = len(branches)
    fig, axes = figure(n, 2, width=9.0, height=3.0 * n)
    sym = {"omega": r"\Omega", "F": "F"}
    for i, br in enumerate(branches):
        outer = float(br[outer_dim].values[0])
        ax, axl = axes[i]
        x, y = sweep_points(sw, outer)
        lo, hi = zoom_range(br)
        sel = (x >= lo) & (x <= hi)
        bifurcation_dots(ax, x[sel], y[sel], s=1.5, label="numerical")
        branch_lines(ax, br)
        ax.set_xlim(lo, hi)
        ax.set_xlabel(LABELS["eta"])
        ax.set_ylabel(LABELS["dw"])
        others = ", ".join(f"${sym[k]}$ = {fmt(float(br[k].values[0]))}"
                           for k in ("F", "omega"))
        panel_label(ax, 2 * i, others)
        ax.legend(fontsize=7, loc="best", markerscale=4)
        eigenvalue_panel(axl, br)
        axl.set_xlim(lo, hi)
        panel_label(axl, 2 * i + 1, others)
        axl.legend(fontsize=7, loc="best", ncol=2)
    return fig


def twin_measures(ax, x, ke, xmax_m, xlabel):
    """Fig 2 style: x_max (m, red circles, left axis) and KE ratio (blue stars, right axis)."""
    ax.plot(x, xmax_m, "o", color="tab:red", ms=3.5, mfc="none", label=r"$x_m^{\max}$")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(LABELS["xmax_m"], color="tab:red")
    ax.tick_params(axis="y", colors="tab:red")
    ax2 = ax.twinx()
    ax2.plot(x, ke, "*", color="tab:blue", ms=4.5, label="KE ratio")
    ax2.set_ylabel(LABELS["ke_ratio"], color="tab:blue")
    ax2.tick_params(axis="y", colors="tab:blue")
    ax2.set_ylim(-0.02, max(1.0, float(np.nanmax(ke)) * 1.05))
    return ax2


def contour_map(fig, ax, x, y, z, *, label, levels=20, cmap="jet", vmin=None, vmax=None):
    """Filled contour with a colour bar; needs at least 2 x 2 points."""
    if len(x) < 2 or len(y) < 2:
        raise FigureInputError(f"a contour map of {label} needs at least 2 x 2 grid points, "
                               f"got {len(x)} x {len(y)}")
    vmin = float(np.nanmin(z)) if vmin is None else vmin
    vmax = float(np.nanmax(z)) if vmax is None else vmax
    if vmax <= vmin:
        vmax = vmin + 1e-12
    cs = ax.contourf(x, y, z, levels=np.linspace(vmin, vmax, levels + 1), cmap=cmap,
                     extend="neither")
    cb = fig.colorbar(cs, ax=ax, shrink=0.9, ticks=MaxNLocator(6))
    cb.set_label(label)
    return cs


def save(fig, pdf, png, dpi=150):
    """Write the figure as PDF and PNG atomically (temp file in the same dir + os.replace)."""
    for path, kw in ((Path(pdf), {}), (Path(png), {"dpi": dpi})):
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix,
                                   dir=path.parent)
        os.close(fd)
        os.chmod(tmp, new_file_mode())
        try:
            fig.savefig(tmp, format=path.suffix.lstrip("."), **kw)
            os.replace(tmp, path)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise
    plt.close(fig)


def metres(x):
    """Dimensionless displacement (units of L) in metres."""
    return np.asarray(x, dtype=float) * L_HALF_M
