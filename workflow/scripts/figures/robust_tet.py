"""Robust-TET map beside Fig 12: over (eta, W), one column per F, (a-c) the KE ratio of the
run from rest (Fig 12 (d-f); points without impacts a grey class, no data left blank),
(d-f) the basin fraction of efficient motion (attractors with KE ratio above the map's
threshold) and (g-i) the basin fraction of the stable 1:1 orbit, from a census of Sobol
initial states per grid point (robust maps robust_*), one cell per census point (whole
cells drawn), hatched where the 95 % Wilson interval of the fraction is wider than 0.2;
(g-i) drawn finer than the census grid: the cell's value only where the Fig 16 map has a
stable 1:1 orbit, 0 elsewhere (no orbit, no basin), so that the W = 0.5 row, which samples
the narrow stable tongue just below W = 0.5001, shows as that tongue and not as a band half
a cell high. When the robust maps carry the asymptotic view (config t_max), (j-l) the
efficient basin fraction of the same states at t_max, a cross where it differs from the
window fraction (d-f). Each row one colour bar. On every panel the edge of the stable 1:1
region of Fig 16 (|lambda_max| = 1)."""
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting.uncertainty import WIDE_INTERVAL, wilson_width


def _by_F(datasets):
    return {round(float(d.attrs["F"]), 9): d for d in datasets}


ASYMPTOTIC = "efficient_fraction_asymptotic"


def panels(ds, rob, thr):
    """(source, values, label, no-impact mask) of the rows at one F (three, or four with
    the asymptotic view)."""
    silent = P.grid2d(ds, "n_impacts", "eta", "omega") == 0
    asymptotic = []
    if ASYMPTOTIC in rob:
        asymptotic = [(rob, P.grid2d(rob, ASYMPTOTIC, "eta", "omega"),
                       f"basin fraction, KE ratio > {P.fmt(thr)}, at t_max", None)]
    return [
        (ds, P.grid2d(ds, "ke_ratio", "eta", "omega"), P.LABELS["ke_ratio"] + " from rest",
         silent),
        (rob, P.grid2d(rob, "efficient_fraction", "eta", "omega"),
         f"basin fraction, KE ratio > {P.fmt(thr)}", None),
        (rob, P.grid2d(rob, "stable_1to1_fraction", "eta", "omega"),
         "basin fraction of the stable 1:1 orbit", None),
    ] + asymptotic


def mark_changed(ax, rob):
    """A cross on every cell whose efficient fraction at t_max differs from the window's."""
    window = P.grid2d(rob, "efficient_fraction", "eta", "omega")
    late = P.grid2d(rob, ASYMPTOTIC, "eta", "omega")
    e, w = np.meshgrid(rob["eta"].values, rob["omega"].values)   # as grid2d: (omega, eta)
    changed = np.abs(late - window) > 1e-12
    ax.plot(e[changed], w[changed], "x", color="black", ms=5, mew=1.6)
    ax.plot(e[changed], w[changed], "x", color="white", ms=4, mew=0.7)
    return int(changed.sum())


def census_cells(fig, ax, grid, style, wide, smap, F):
    """A census row (d-l): one cell per census point, edges half-way between points (the
    panel shows the whole cells: each is the census at its centre), hatched where ``wide``
    (the Wilson interval); the stable 1:1 share (``smap`` given) finer, only where Fig. 16's
    map has a stable 1:1 orbit (``P.stable_orbit_share``), hatched where it is drawn."""
    eta, W, z = grid
    if smap is None:
        cs = P.contour_map(fig, ax, eta, W, z, style)
        P.hatch_cells(ax, eta, W, wide)
    else:
        eta_r, W_r, z_r, kept = P.stable_orbit_share(eta, W, z, smap)
        print(f"F = {F}: stable 1:1 share drawn where Fig. 16 has a stable 1:1 orbit; "
              f"{kept} cells with a share > 0 and no stable point kept whole")
        cs = P.contour_map(fig, ax, eta_r, W_r, z_r, style)
        cell = np.ix_(np.searchsorted(P.cell_edges(W)[1:-1], W_r),
                      np.searchsorted(P.cell_edges(eta)[1:-1], eta_r))
        # a measured share > 0: hatched where drawn; a measured 0: the whole cell, as (d-f)
        P.hatch_region(ax, eta_r, W_r, wide[cell] & ((z_r > 0) | (z[cell] == 0)))
    for v, set_lim in ((eta, ax.set_xlim), (W, ax.set_ylim)):     # eta, W > 0
        lo, hi = P.cell_edges(v)[[0, -1]]
        set_lim(max(lo, 0.0), hi)
    return cs


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "omega"), fixed=("F",))
                               for p in sm.input.measures], "F")
    maps = _by_F(map(P.stability, sm.input.stability))
    robust = _by_F(map(P.robust_map, sm.input.robust))
    n = len(grids)
    n_rows = 4 if all(ASYMPTOTIC in r for r in robust.values()) else 3
    fig, axes = P.figure(n_rows, n, width=4.0 * n + 1.0, height=3.47 * n_rows)
    mappables = [None] * n_rows
    for j, ds in enumerate(grids):
        F = P.fixed_value(ds, "F")
        smap, rob = maps.get(round(F, 9)), robust.get(round(F, 9))
        if smap is None or rob is None:
            raise P.FigureInputError(f"no stability map or robust map at F = {F} for "
                                     f"{ds.attrs['_path']} (robust maps at F = {sorted(robust)})")
        n_states = int(rob.attrs["n_states"])
        for i, (src, z, label, silent) in enumerate(panels(ds, rob, float(rob.attrs["threshold"]))):
            ax = axes[i, j]
            eta, W = src["eta"].values, src["omega"].values
            style = P.MapStyle(label, 0.0, 1.0, cells=i > 0, colorbar=False)
            if i == 0:
                mappables[i] = P.contour_map(fig, ax, eta, W, z, style, no_impact=silent)
                # only the computed grid: no data is not zero
                ax.set_xlim(eta.min(), eta.max())
                ax.set_ylim(W.min(), W.max())
            else:
                wide = wilson_width(z, n_states) > WIDE_INTERVAL
                mappables[i] = census_cells(fig, ax, (eta, W, z), style, wide,
                                            smap if i == 2 else None, F)
            if i == 3:
                print(f"F = {F}: efficient fraction at t_max differs at "
                      f"{mark_changed(ax, rob)} of {z.size} points")
            P.stable_edge(ax, smap)
            ax.set_xlabel(P.LABELS["eta"])
            ax.set_ylabel(P.LABELS["omega"])
            P.panel_label(ax, i * n + j, rf"$F$ = {P.fmt(F)}")
        print(f"F = {F}: mean efficient basin fraction {float(rob['efficient_fraction'].mean()):.3f}, "
              f"from rest efficient {float(rob['from_rest_efficient'].mean()):.3f} of the points")
    for i, m in enumerate(mappables):
        P.shared_colorbar(fig, m, axes[i, :], shrink=0.85)
    n_states = int(robust[min(robust)].attrs["n_states"])
    handles = [P.stable_edge_handle(), P.no_impact_handle("(a-c) no impact from rest"),
               P.Patch(facecolor="0.55", edgecolor="white", hatch="////",
                       label=f"(d-{'l' if n_rows == 4 else 'i'}) 95 % Wilson interval wider "
                             f"than {P.fmt(WIDE_INTERVAL)} ({n_states} states)")]
    title = f"(d-i): {n_states} Sobol initial states per grid point, state at t_end (window view)"
    if n_rows == 4:
        t_max = float(robust[min(robust)].attrs["t_max"])
        handles.append(P.Line2D([], [], ls="none", marker="x", color="black", ms=5, mew=1.6,
                                label="(j-l) differs from the window fraction (d-f)"))
        title += f"; (j-l): the same states at t_max = {P.fmt(t_max)} (asymptotic view)"
    fig.legend(handles=handles, loc="outside lower center", ncol=2, fontsize=8, frameon=False,
               title=title, title_fontsize=8)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
