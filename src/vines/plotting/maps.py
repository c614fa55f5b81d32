"""Colour maps of the measures over parameter planes: Fig 7 over (eta, F), Fig 12 over
(eta, omega) with the stable 1:1 region of Fig 16, and the robust-TET map beside Fig 12
(basin fractions of a census of initial states per grid point)."""
from __future__ import annotations

import numpy as np
from matplotlib import patheffects
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..core.grids import cell_edges
from . import palette
from .checks import FigureInputError, fixed_value, grid2d
from .draw import (
    LABELS,
    MapStyle,
    common_range,
    contour_map,
    figure,
    fmt,
    hatch_cells,
    hatch_region,
    no_impact_handle,
    panel_label,
    shared_colorbar,
    stable_edge,
    stable_edge_handle,
)
from .stable_region import region_counts, stable_at, stable_orbit_share
from .uncertainty import WIDE_INTERVAL, wilson_width

#: the line W = 1/sqrt(1 + eta) (the paper's dashed pink line)
RIDGE = {"color": palette.OKABE_ITO["reddish purple"], "ls": "--", "lw": 1.6,
         "path_effects": [patheffects.Stroke(linewidth=2.8, foreground="white"),
                          patheffects.Normal()]}
#: the asymptotic view's variable of the robust maps (config t_max)
ASYMPTOTIC = "efficient_fraction_asymptotic"


def by_F(datasets) -> dict:
    """Datasets by their global attribute F (rounded to 9 digits)."""
    return {round(float(d.attrs["F"]), 9): d for d in datasets}


# ------------------------------------------------------------------ Fig 7

def eta_F_figure(grids):
    """Fig 7: KE ratio (top row; no-impact points a grey class) and x_max (bottom row, log
    colour scale) over (eta, F), one column per grid (W); one colour range per row."""
    n = len(grids)
    fig, axes = figure(2, n, width=4.0 * n + 1.0, height=7.0)
    xmax_range = common_range([grid2d(ds, "xmax_m", "eta", "F") for ds in grids], log=True)
    rows = (("ke_ratio", LABELS["ke_ratio"], {"vmin": 0.0, "vmax": 1.0}),
            ("xmax_m", LABELS["xmax_m"], {"log": True, "vmin": xmax_range[0],
                                            "vmax": xmax_range[1]}))
    any_silent = False
    for i, (var, lab, kw) in enumerate(rows):
        for j, ds in enumerate(grids):
            eta, F = ds["eta"].values, ds["F"].values
            ax = axes[i, j]
            silent = grid2d(ds, "n_impacts", "eta", "F") == 0 if var == "ke_ratio" else None
            any_silent |= bool(np.any(silent)) if silent is not None else False
            cs = contour_map(fig, ax, eta, F, grid2d(ds, var, "eta", "F"),
                             MapStyle(lab, colorbar=False, **kw), no_impact=silent)
            ax.set_xlabel(LABELS["eta"])
            ax.set_ylabel(LABELS["F"])
            panel_label(ax, i * n + j, rf"$\Omega$ = {fmt(fixed_value(ds, 'omega'))}")
        shared_colorbar(fig, cs, axes[i, :], shrink=0.85)
    if any_silent:
        fig.legend(handles=[no_impact_handle()], loc="outside lower center", fontsize=8,
                   frameon=False)
    return fig


# ------------------------------------------------------------------ Fig 12

def _outline(ax, grid, smap, F):
    """Stable 1:1 outline, a note on the stable tongue below the plotted range when its edge
    runs along the bottom."""
    eta, W = grid["eta"].values, grid["omega"].values
    stable_edge(ax, smap)
    ax.set_xlim(eta.min(), eta.max())
    ax.set_ylim(W.min(), W.max())
    if stable_at(smap, eta, W[:1]).mean() > 0.5:
        ax.text(0.5, 0.015, r"stable tongue below $\Omega$ = "
                f"{fmt(W.min())} (Fig. 16)", transform=ax.transAxes, ha="center",
                va="bottom", fontsize=6.5, bbox={"facecolor": "white", "alpha": 0.8, "lw": 0,
                                                  "pad": 1})
    counts = region_counts(grid, smap)
    print(f"F = {F}: grid points in the stable 1:1 region {counts['stable']}, reached from "
          f"rest {counts['reached']}, KE ratio 0 {counts['ke_zero']}")


def eta_omega_figure(grids, maps: dict):
    """Fig 12: x_max (top row, log colour scale) and KE ratio (bottom row, no-impact points
    a grey class, the edge of the stable 1:1 region of the stability map ``maps[F]``) over
    (eta, omega), one column per grid (F); the line W = 1/sqrt(1+eta) on every panel."""
    n = len(grids)
    fig, axes = figure(2, n, width=4.0 * n + 1.0, height=7.6)
    lo, hi = common_range([grid2d(ds, "xmax_m", "eta", "omega") for ds in grids], log=True)
    for j, ds in enumerate(grids):
        F = fixed_value(ds, "F")
        smap = maps.get(round(F, 9))
        if smap is None:
            raise FigureInputError(f"no stability map at F = {F} for {ds.attrs['_path']} "
                                   f"(stability maps at F = {sorted(maps)})")
        eta, W = ds["eta"].values, ds["omega"].values
        top = contour_map(fig, axes[0, j], eta, W, grid2d(ds, "xmax_m", "eta", "omega"),
                          MapStyle(LABELS["xmax_m"], lo, hi, log=True, colorbar=False))
        silent = grid2d(ds, "n_impacts", "eta", "omega") == 0
        bottom = contour_map(fig, axes[1, j], eta, W, grid2d(ds, "ke_ratio", "eta", "omega"),
                             MapStyle(LABELS["ke_ratio"], 0.0, 1.0, colorbar=False),
                             no_impact=silent)
        _outline(axes[1, j], ds, smap, F)
        e = np.linspace(eta.min(), eta.max(), 200)
        for i in range(2):
            axes[i, j].plot(e, 1 / np.sqrt(1 + e), **RIDGE)
            axes[i, j].set_ylim(W.min(), W.max())
            axes[i, j].set_xlabel(LABELS["eta"])
            axes[i, j].set_ylabel(LABELS["omega"])
            panel_label(axes[i, j], i * n + j, rf"$F$ = {fmt(F)}")
    shared_colorbar(fig, top, axes[0, :], shrink=0.85)
    shared_colorbar(fig, bottom, axes[1, :], shrink=0.85)
    handles = [Line2D([], [], label=r"$\Omega = 1/\sqrt{1+\eta}$", **RIDGE),
               stable_edge_handle(r"(d-f) edge of the stable 1:1 region "
                                  r"($|\lambda_{\max}| = 1$, Fig. 16)"),
               no_impact_handle("(d-f) no impact (the LO never reaches a wall)")]
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=8,
               frameon=False, facecolor="0.9")
    return fig


# ------------------------------------------------------------------ robust TET

def _robust_rows(ds, rob, thr):
    """(source, values, label, no-impact mask) of the rows at one F (three, or four with
    the asymptotic view)."""
    silent = grid2d(ds, "n_impacts", "eta", "omega") == 0
    asymptotic = []
    if ASYMPTOTIC in rob:
        asymptotic = [(rob, grid2d(rob, ASYMPTOTIC, "eta", "omega"),
                       f"basin fraction, KE ratio > {fmt(thr)}, at t_max", None)]
    return [
        (ds, grid2d(ds, "ke_ratio", "eta", "omega"), LABELS["ke_ratio"] + " from rest",
         silent),
        (rob, grid2d(rob, "efficient_fraction", "eta", "omega"),
         f"basin fraction, KE ratio > {fmt(thr)}", None),
        (rob, grid2d(rob, "stable_1to1_fraction", "eta", "omega"),
         "basin fraction of the stable 1:1 orbit", None),
    ] + asymptotic


def _mark_changed(ax, rob):
    """A cross on every cell whose efficient fraction at t_max differs from the window's."""
    window = grid2d(rob, "efficient_fraction", "eta", "omega")
    late = grid2d(rob, ASYMPTOTIC, "eta", "omega")
    e, w = np.meshgrid(rob["eta"].values, rob["omega"].values)   # as grid2d: (omega, eta)
    changed = np.abs(late - window) > 1e-12
    ax.plot(e[changed], w[changed], "x", color="black", ms=5, mew=1.6)
    ax.plot(e[changed], w[changed], "x", color="white", ms=4, mew=0.7)
    return int(changed.sum())


def _census_cells(fig, ax, grid, style, wide, smap, F):
    """A census row (d-l): one cell per census point, edges half-way between points (the
    panel shows the whole cells: each is the census at its centre), hatched where ``wide``
    (the Wilson interval); the stable 1:1 share (``smap`` given) finer, only where Fig. 16's
    map has a stable 1:1 orbit (``stable_orbit_share``), hatched where it is drawn."""
    eta, W, z = grid
    if smap is None:
        cs = contour_map(fig, ax, eta, W, z, style)
        hatch_cells(ax, eta, W, wide)
    else:
        eta_r, W_r, z_r, kept = stable_orbit_share(eta, W, z, smap)
        print(f"F = {F}: stable 1:1 share drawn where Fig. 16 has a stable 1:1 orbit; "
              f"{kept} cells with a share > 0 and no stable point kept whole")
        cs = contour_map(fig, ax, eta_r, W_r, z_r, style)
        cell = np.ix_(np.searchsorted(cell_edges(W)[1:-1], W_r),
                      np.searchsorted(cell_edges(eta)[1:-1], eta_r))
        # a measured share > 0: hatched where drawn; a measured 0: the whole cell, as (d-f)
        hatch_region(ax, eta_r, W_r, wide[cell] & ((z_r > 0) | (z[cell] == 0)))
    for v, set_lim in ((eta, ax.set_xlim), (W, ax.set_ylim)):     # eta, W > 0
        lo, hi = cell_edges(v)[[0, -1]]
        set_lim(max(lo, 0.0), hi)
    return cs


def robust_tet_figure(grids, maps: dict, robust: dict):
    """The robust-TET map: per grid (F) a column of the KE ratio from rest, the basin
    fractions of efficient motion and of the stable 1:1 orbit (and, with the asymptotic
    view, the efficient fraction at t_max) of the robust map ``robust[F]``, the edge of the
    stable region of ``maps[F]`` on every panel; one colour bar per row."""
    n = len(grids)
    n_rows = 4 if all(ASYMPTOTIC in r for r in robust.values()) else 3
    fig, axes = figure(n_rows, n, width=4.0 * n + 1.0, height=3.47 * n_rows)
    mappables = [None] * n_rows
    for j, ds in enumerate(grids):
        F = fixed_value(ds, "F")
        smap, rob = maps.get(round(F, 9)), robust.get(round(F, 9))
        if smap is None or rob is None:
            raise FigureInputError(f"no stability map or robust map at F = {F} for "
                                   f"{ds.attrs['_path']} (robust maps at F = {sorted(robust)})")
        n_states = int(rob.attrs["n_states"])
        for i, (src, z, label, silent) in enumerate(_robust_rows(ds, rob,
                                                                 float(rob.attrs["threshold"]))):
            ax = axes[i, j]
            eta, W = src["eta"].values, src["omega"].values
            style = MapStyle(label, 0.0, 1.0, cells=i > 0, colorbar=False)
            if i == 0:
                mappables[i] = contour_map(fig, ax, eta, W, z, style, no_impact=silent)
                # only the computed grid: no data is not zero
                ax.set_xlim(eta.min(), eta.max())
                ax.set_ylim(W.min(), W.max())
            else:
                wide = wilson_width(z, n_states) > WIDE_INTERVAL
                mappables[i] = _census_cells(fig, ax, (eta, W, z), style, wide,
                                             smap if i == 2 else None, F)
            if i == 3:
                print(f"F = {F}: efficient fraction at t_max differs at "
                      f"{_mark_changed(ax, rob)} of {z.size} points")
            stable_edge(ax, smap)
            ax.set_xlabel(LABELS["eta"])
            ax.set_ylabel(LABELS["omega"])
            panel_label(ax, i * n + j, rf"$F$ = {fmt(F)}")
        print(f"F = {F}: mean efficient basin fraction {float(rob['efficient_fraction'].mean()):.3f}, "
              f"from rest efficient {float(rob['from_rest_efficient'].mean()):.3f} of the points")
    for i, m in enumerate(mappables):
        shared_colorbar(fig, m, axes[i, :], shrink=0.85)
    _robust_legend(fig, robust[min(robust)], n_rows)
    return fig


def _robust_legend(fig, rob, n_rows):
    """The legend below the robust-TET map: edge, no impact, wide intervals (and the
    asymptotic view's crosses), titled by the census of ``rob``."""
    n_states = int(rob.attrs["n_states"])
    handles = [stable_edge_handle(), no_impact_handle("(a-c) no impact from rest"),
               Patch(facecolor="0.55", edgecolor="white", hatch="////",
                     label=f"(d-{'l' if n_rows == 4 else 'i'}) 95 % Wilson interval wider "
                           f"than {fmt(WIDE_INTERVAL)} ({n_states} states)")]
    title = f"(d-i): {n_states} Sobol initial states per grid point, state at t_end (window view)"
    if n_rows == 4:
        t_max = float(rob.attrs["t_max"])
        handles.append(Line2D([], [], ls="none", marker="x", color="black", ms=5, mew=1.6,
                              label="(j-l) differs from the window fraction (d-f)"))
        title += f"; (j-l): the same states at t_max = {fmt(t_max)} (asymptotic view)"
    fig.legend(handles=handles, loc="outside lower center", ncol=2, fontsize=8, frameon=False,
               title=title, title_fontsize=8)

