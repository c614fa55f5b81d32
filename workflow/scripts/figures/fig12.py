"""Fig 12: contour maps over (eta, W) of x_max in metres (a-c, log colour scale, dashed
W = 1/sqrt(1+eta)) and the KE ratio (d-f), one column per F (grids fig12_*, stability maps
fig16_*). On (d-f): the stable 1:1 region of the stability map with the same F (white
outline at |lambda_max| = 1, interpolated between map points), hatched where the grid's
from-rest run reaches the 1:1 orbit, the dotted lines W = 1 +- F outside which the LO
started from rest never reaches the cavity wall, and the boundary curves of the same F
(boundaries fig16_*, vines.plotting.bifurcation)."""
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Patch

import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import bifurcation as B


def overlay(ax, grid, smap, F):
    """Stable 1:1 outline (white), hatching where the run reaches it, W = 1 +- F lines, a
    note on the stable tongue below the plotted range when its edge runs along the bottom."""
    eta, W = grid["eta"].values, grid["omega"].values
    reached = P.stable_at(smap, eta, W) & P.reaches_1to1(grid)
    if reached.any():
        with plt.rc_context({"hatch.color": "white", "hatch.linewidth": 0.8}):
            ax.contourf(eta, W, reached.astype(float), levels=[0.5, 1.5], colors="none",
                        hatches=["////"])
    ax.contour(smap["eta"].values, smap["omega"].values, P.stability_margin(smap),
               levels=[0.0], colors="white", linewidths=1.4)
    for w in (1 - F, 1 + F):
        ax.axhline(w, color="white", ls=":", lw=1.0)
    ax.set_xlim(eta.min(), eta.max())
    ax.set_ylim(W.min(), W.max())
    if P.stable_at(smap, eta, W[:1]).mean() > 0.5:
        ax.text(0.5, 0.012, r"edge of the stable tongue below $\Omega$ = "
                f"{P.fmt(W.min())} (Fig. 16)", transform=ax.transAxes, ha="center",
                va="bottom", fontsize=6.5, color="white")
    counts = P.region_counts(grid, smap)
    print(f"F = {F}: grid points in the stable 1:1 region {counts['stable']}, reached from "
          f"rest {counts['reached']}, KE ratio 0 {counts['ke_zero']}")


#: legend of the overlay on (d-f), once below the figure
OVERLAY_HANDLES = [
    plt.Line2D([], [], color="black", lw=1.4, label="(d-f) edge of the stable 1:1 region "
               r"($|\lambda_{\max}| = 1$, Fig. 16)"),
    Patch(facecolor="none", edgecolor="black", hatch="////",
          label="(d-f) the run from rest reaches the 1:1 orbit"),
    plt.Line2D([], [], color="black", ls=":", lw=1.0,
               label=r"(d-f) $\Omega = 1 \pm F$: first impact from rest"),
    plt.Line2D([], [], color="magenta", ls="--", lw=1.5,
               label=r"(a-c) $\Omega = 1/\sqrt{1+\eta}$")]


def main(sm):
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "omega"), fixed=("F",))
                               for p in sm.input.measures], "F")
    maps = {round(float(m.attrs["F"]), 9): m for m in map(P.stability, sm.input.stability)}
    n = len(grids)
    fig, axes = P.figure(2, n, width=4.3 * n, height=7.6)
    for j, ds in enumerate(grids):
        F = P.fixed_value(ds, "F")
        smap = maps.get(round(F, 9))
        if smap is None:
            raise P.FigureInputError(f"no stability map at F = {F} for {ds.attrs['_path']} "
                                     f"(stability maps at F = {sorted(maps)})")
        P.require(ds, variables=("regime",))
        eta, W = ds["eta"].values, ds["omega"].values
        ax = axes[0, j]
        P.contour_map(fig, ax, eta, W, P.grid2d(ds, "xmax_m", "eta", "omega"),
                      label=P.LABELS["xmax_m"], log=True)
        e = np.linspace(eta.min(), eta.max(), 200)
        ax.plot(e, 1 / np.sqrt(1 + e), "--", color="magenta", lw=1.5)
        ax.set_ylim(W.min(), W.max())
        P.contour_map(fig, axes[1, j], eta, W, P.grid2d(ds, "ke_ratio", "eta", "omega"),
                      label=P.LABELS["ke_ratio"], vmin=0.0, vmax=1.0)
        overlay(axes[1, j], ds, smap, F)
        for i in range(2):
            axes[i, j].set_xlabel(P.LABELS["eta"])
            axes[i, j].set_ylabel(P.LABELS["omega"])
            P.panel_label(axes[i, j], i * n + j, rf"$F$ = {P.fmt(F)}")
    curve_handles = B.draw_on_panels(fig, axes[1], [P.fixed_value(g, "F") for g in grids],
                                     sm.input.boundaries, legend=False)
    fig.legend(handles=OVERLAY_HANDLES + curve_handles, loc="outside lower center", ncol=3,
               fontsize=8, frameon=False)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
