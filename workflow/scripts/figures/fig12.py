"""Fig 12: contour maps over (eta, W) of x_max in metres (a-c, log colour scale) and the KE
ratio (d-f), one column per F (grids fig12_*); each row one colour range and one colour
bar. On every panel the dashed line W = 1/sqrt(1+eta); on (d-f) the edge of the stable 1:1
region of the stability map with the same F (stability maps fig16_*, |lambda_max| = 1
interpolated between map points). Points without impacts are a grey class on (d-f)."""
import numpy as np
from matplotlib import patheffects

import vines.plotting as P
from vines.pipeline.jobs import run_job

#: the line W = 1/sqrt(1 + eta) (the paper's dashed pink line)
RIDGE = {"color": P.palette.OKABE_ITO["reddish purple"], "ls": "--", "lw": 1.6,
         "path_effects": [patheffects.Stroke(linewidth=2.8, foreground="white"),
                          patheffects.Normal()]}


def stable_edge(ax, grid, smap, F):
    """Stable 1:1 outline, a note on the stable tongue below the plotted range when its edge
    runs along the bottom."""
    eta, W = grid["eta"].values, grid["omega"].values
    P.stable_edge(ax, smap)
    ax.set_xlim(eta.min(), eta.max())
    ax.set_ylim(W.min(), W.max())
    if P.stable_at(smap, eta, W[:1]).mean() > 0.5:
        ax.text(0.5, 0.015, r"stable tongue below $\Omega$ = "
                f"{P.fmt(W.min())} (Fig. 16)", transform=ax.transAxes, ha="center",
                va="bottom", fontsize=6.5, bbox={"facecolor": "white", "alpha": 0.8, "lw": 0,
                                                  "pad": 1})
    counts = P.region_counts(grid, smap)
    print(f"F = {F}: grid points in the stable 1:1 region {counts['stable']}, reached from "
          f"rest {counts['reached']}, KE ratio 0 {counts['ke_zero']}")


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "omega"), fixed=("F",))
                               for p in sm.input.measures], "F")
    maps = {round(float(m.attrs["F"]), 9): m for m in map(P.stability, sm.input.stability)}
    n = len(grids)
    fig, axes = P.figure(2, n, width=4.0 * n + 1.0, height=7.6)
    lo, hi = P.common_range([P.grid2d(ds, "xmax_m", "eta", "omega") for ds in grids], log=True)
    for j, ds in enumerate(grids):
        F = P.fixed_value(ds, "F")
        smap = maps.get(round(F, 9))
        if smap is None:
            raise P.FigureInputError(f"no stability map at F = {F} for {ds.attrs['_path']} "
                                     f"(stability maps at F = {sorted(maps)})")
        eta, W = ds["eta"].values, ds["omega"].values
        top = P.contour_map(fig, axes[0, j], eta, W, P.grid2d(ds, "xmax_m", "eta", "omega"),
                            P.MapStyle(P.LABELS["xmax_m"], lo, hi, log=True, colorbar=False))
        silent = P.grid2d(ds, "n_impacts", "eta", "omega") == 0
        bottom = P.contour_map(fig, axes[1, j], eta, W, P.grid2d(ds, "ke_ratio", "eta", "omega"),
                               P.MapStyle(P.LABELS["ke_ratio"], 0.0, 1.0, colorbar=False),
                               no_impact=silent)
        stable_edge(axes[1, j], ds, smap, F)
        e = np.linspace(eta.min(), eta.max(), 200)
        for i in range(2):
            axes[i, j].plot(e, 1 / np.sqrt(1 + e), **RIDGE)
            axes[i, j].set_ylim(W.min(), W.max())
            axes[i, j].set_xlabel(P.LABELS["eta"])
            axes[i, j].set_ylabel(P.LABELS["omega"])
            P.panel_label(axes[i, j], i * n + j, rf"$F$ = {P.fmt(F)}")
    P.shared_colorbar(fig, top, axes[0, :], shrink=0.85)
    P.shared_colorbar(fig, bottom, axes[1, :], shrink=0.85)
    handles = [P.Line2D([], [], label=r"$\Omega = 1/\sqrt{1+\eta}$", **RIDGE),
               P.stable_edge_handle(r"(d-f) edge of the stable 1:1 region "
                                    r"($|\lambda_{\max}| = 1$, Fig. 16)"),
               P.no_impact_handle("(d-f) no impact (the LO never reaches a wall)")]
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=8,
               frameon=False, facecolor="0.9")
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
