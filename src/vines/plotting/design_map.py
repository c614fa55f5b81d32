"""The design map's figure (datasets of the stage ``design_map``): who wins where, the VI
NES's worst case over the TMD's of the same mass, free and at equal travel, over mass ratio
and band, one row per amplitude span."""
from __future__ import annotations

import matplotlib.colors as mcolors
import numpy as np
import xarray as xr
from matplotlib.lines import Line2D

from ..core.grids import cell_edges, log_cell_edges
from .checks import load, require
from .draw import figure, panel_label

#: diverging map of log2 of the ratio VI NES / TMD: blue where the VI NES wins, red the TMD
CMAP = "RdBu_r"
#: markers of the exact check (``confirm``: 1 frontier, 2 sample) and of a changed verdict
MARK = {1: ("o", "near the frontier, checked exactly"), 2: ("s", "sampled, checked exactly")}
COLUMNS = (("verdict_ratio", "ratio", "TMD free", "verdict_differs"),
           ("verdict_ratio_equal_travel", "ratio_equal_travel", "TMD at equal travel",
            "verdict_differs_equal_travel"))


def design_map(path) -> xr.Dataset:
    """A design-map dataset, checked."""
    ds = load(path)
    return require(ds, coords=("eta", "half_width", "span"), min_size=1,
                   variables=("verdict_ratio", "verdict_ratio_equal_travel", "ratio",
                              "ratio_equal_travel", "confirm", "verdict_differs",
                              "verdict_differs_equal_travel"),
                   finite=("ratio", "ratio_equal_travel"))


def _norm(maps: list) -> mcolors.Normalize:
    """One colour scale of log2(ratio) for every panel, symmetric about 0 (ratio 1)."""
    top = max(float(np.nanmax(np.abs(np.log2(m[c].values)))) for m in maps
              for c, *_ in COLUMNS)
    top = max(1.0, np.ceil(top))
    return mcolors.Normalize(-top, top)


def ratio_panel(ax, ds: xr.Dataset, k: int, column: int, norm) -> object:
    """log2 of the verdict ratio over (eta, half width) at span[k] (colour; the number in
    each cell), the slow flow's frontier (ratio 1, black line), the cells checked exactly
    (markers) and those whose verdict changed (crossed)."""
    verdict, slow, _, flag = COLUMNS[column]
    p = ds.isel(span=k)
    eta, h = ds["eta"].values, ds["half_width"].values
    z = np.log2(p[verdict].values.T)
    mesh = ax.pcolormesh(log_cell_edges(eta), cell_edges(h, 0.1), z, cmap=CMAP, norm=norm)
    if eta.size > 1 and h.size > 1:
        ax.contour(eta, h, np.log2(p[slow].values.T), levels=[0.0], colors="black",
                   linewidths=1.2)
    conf, differs = p["confirm"].values, p[flag].values.astype(bool)
    for code, (marker, _) in MARK.items():
        i, j = np.nonzero(conf == code)
        ax.plot(eta[i], h[j], marker, ms=6, mfc="none", mec="0.15", mew=0.8)
    i, j = np.nonzero(differs)
    ax.plot(eta[i], h[j], "x", ms=7, color="black", mew=1.2)
    ratio = p[verdict].values
    for i in range(eta.size):
        for j in range(h.size):
            ax.annotate(f"{ratio[i, j]:.2g}", (eta[i], h[j]), xytext=(0, 6),
                        textcoords="offset points", ha="center", va="bottom", fontsize=7)
    ax.set_xscale("log")
    ax.set_xlabel(r"mass ratio $\eta$ (VI NES and TMD)")
    ax.set_ylabel("band half width h")
    span = float(ds["span"].values[k])
    panel_label(ax, 2 * k + column, f"VI NES / {COLUMNS[column][2]}, span "
                                    f"$A_{{max}}/A_{{min}}$ = {span:g}")
    return mesh


def design_map_figure(maps: list):
    """One design map per dataset: a row per amplitude span, the free and equal-travel TMD
    side by side; one colour bar (log2 scale, labelled in ratios) and a legend."""
    rows = [(ds, k) for ds in maps for k in range(ds.sizes["span"])]
    fig, axes = figure(len(rows), 2, width=10.0, height=3.3 * len(rows) + 0.6)
    norm = _norm(maps)
    mesh = None
    for r, (ds, k) in enumerate(rows):
        for c in range(2):
            mesh = ratio_panel(axes[r, c], ds, k, c, norm)
    ticks = np.arange(norm.vmin, norm.vmax + 1)
    cb = fig.colorbar(mesh, ax=axes, shrink=0.8, ticks=ticks)
    cb.ax.set_yticklabels([f"{2.0 ** t:g}" for t in ticks])
    cb.set_label("worst x_max/A: VI NES over TMD (< 1: the VI NES wins)")
    handles = [Line2D([], [], color="black", lw=1.2, label="frontier (slow flow: ratio 1)")]
    handles += [Line2D([], [], marker=m, ls="none", mfc="none", mec="0.15", label=t)
                for m, t in MARK.values()]
    handles.append(Line2D([], [], marker="x", ls="none", color="black",
                          label="exact and slow flow name opposite winners (beyond 5 %)"))
    fig.legend(handles=handles, loc="outside lower center", ncol=2, fontsize=8,
               frameon=False)
    return fig
