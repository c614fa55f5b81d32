"""Robust-TET map beside Fig 12: over (eta, W), one column per F, (a-c) the KE ratio of the
run from rest (Fig 12 (d-f)), (d-f) the basin fraction of efficient motion (attractors with
KE ratio above the map's threshold) and (g-i) the basin fraction of the stable 1:1 orbit,
from a census of Sobol initial states per grid point (robust maps robust_*). On every panel
the white outline is the stable 1:1 region of Fig 16 (|lambda_max| = 1)."""
import matplotlib.pyplot as plt

import vines.plotting as P
from vines.pipeline.jobs import run_job


def outline(ax, smap, eta, W):
    ax.contour(smap["eta"].values, smap["omega"].values, P.stability_margin(smap),
               levels=[0.0], colors="white", linewidths=1.4)
    ax.set_xlim(eta.min(), eta.max())
    ax.set_ylim(W.min(), W.max())


def _by_F(datasets):
    return {round(float(d.attrs["F"]), 9): d for d in datasets}


def main(sm):
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "omega"), fixed=("F",))
                               for p in sm.input.measures], "F")
    maps = _by_F(map(P.stability, sm.input.stability))
    robust = _by_F(map(P.robust_map, sm.input.robust))
    n = len(grids)
    fig, axes = P.figure(3, n, width=4.3 * n, height=10.2)
    for j, ds in enumerate(grids):
        F = P.fixed_value(ds, "F")
        smap, rob = maps.get(round(F, 9)), robust.get(round(F, 9))
        if smap is None or rob is None:
            raise P.FigureInputError(f"no stability map or robust map at F = {F} for "
                                     f"{ds.attrs['_path']} (robust maps at F = {sorted(robust)})")
        thr = float(rob.attrs["threshold"])
        panels = [
            (ds, P.grid2d(ds, "ke_ratio", "eta", "omega"), P.LABELS["ke_ratio"] + " from rest"),
            (rob, P.grid2d(rob, "efficient_fraction", "eta", "omega"),
             f"basin fraction, KE ratio > {P.fmt(thr)}"),
            (rob, P.grid2d(rob, "stable_1to1_fraction", "eta", "omega"),
             "basin fraction of the stable 1:1 orbit"),
        ]
        for i, (src, z, label) in enumerate(panels):
            ax = axes[i, j]
            eta, W = src["eta"].values, src["omega"].values
            # (d-i): a coarse census grid, drawn cell by cell (contours would invent shapes)
            P.contour_map(fig, ax, eta, W, z, label=label, vmin=0.0, vmax=1.0, cells=i > 0)
            outline(ax, smap, eta, W)
            ax.set_xlabel(P.LABELS["eta"])
            ax.set_ylabel(P.LABELS["omega"])
            P.panel_label(ax, i * n + j, rf"$F$ = {P.fmt(F)}")
        print(f"F = {F}: mean efficient basin fraction {float(rob['efficient_fraction'].mean()):.3f}, "
              f"from rest efficient {float(rob['from_rest_efficient'].mean()):.3f} of the points")
    n_states = int(grids and robust[min(robust)].attrs["n_states"])
    fig.legend(handles=[plt.Line2D([], [], color="black", lw=1.4,
                                   label=r"edge of the stable 1:1 region ($|\lambda_{\max}| = 1$, "
                                         "Fig. 16)")],
               loc="outside lower center", fontsize=8, frameon=False,
               title=f"(d-i): {n_states} Sobol initial states per grid point", title_fontsize=8)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
