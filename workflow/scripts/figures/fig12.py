"""Fig 12: contour maps over (eta, W) of x_max in metres (a-c, dashed W = 1/sqrt(1+eta))
and the KE ratio (d-f, stable 1:1 region of the stability map with the same F outlined and
hatched in white), one column per F (grids fig12_*, stability maps fig16_*)."""
import matplotlib.pyplot as plt
import numpy as np

import vines.plotting as P
from vines.plotting import bifurcation as B
from vines.pipeline.jobs import run_job


def main(sm):
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "omega"), fixed=("F",))
                               for p in sm.input.measures], "F")
    maps = {round(float(m.attrs["F"]), 9): m for m in map(P.stability, sm.input.stability)}
    n = len(grids)
    fig, axes = P.figure(2, n, width=4.3 * n, height=7.0)
    for j, ds in enumerate(grids):
        F = P.fixed_value(ds, "F")
        sm_ = maps.get(round(F, 9))
        if sm_ is None:
            raise P.FigureInputError(f"no stability map at F = {F} for {ds.attrs['_path']} "
                                     f"(stability maps at F = {sorted(maps)})")
        eta, W = ds["eta"].values, ds["omega"].values
        ax = axes[0, j]
        P.contour_map(fig, ax, eta, W, P.grid2d(ds, "xmax_m", "eta", "omega"),
                      label=P.LABELS["xmax_m"])
        e = np.linspace(eta.min(), eta.max(), 200)
        ax.plot(e, 1 / np.sqrt(1 + e), "--", color="magenta", lw=1.5,
                label=r"$\Omega = 1/\sqrt{1+\eta}$")
        ax.set_ylim(W.min(), W.max())
        ax.legend(fontsize=7, loc="upper right")
        ax = axes[1, j]
        P.contour_map(fig, ax, eta, W, P.grid2d(ds, "ke_ratio", "eta", "omega"),
                      label=P.LABELS["ke_ratio"], vmin=0.0, vmax=1.0)
        stable = np.isin(sm_["cls"].values, (1, 2)).astype(float).T   # (omega, eta)
        se, sW = sm_["eta"].values, sm_["omega"].values
        if stable.any():
            with plt.rc_context({"hatch.color": "white", "hatch.linewidth": 0.8}):
                ax.contourf(se, sW, stable, levels=[0.5, 1.5], colors="none",
                            hatches=["////"])
            ax.contour(se, sW, stable, levels=[0.5], colors="white", linewidths=1.4)
        ax.plot([], [], color="white", lw=1.4, label="stable 1:1 (Fig. 16)")
        leg = ax.legend(fontsize=7, loc="upper right", facecolor="0.3", labelcolor="white")
        leg.get_frame().set_alpha(0.7)
        for i in range(2):
            axes[i, j].set_xlabel(P.LABELS["eta"])
            axes[i, j].set_ylabel(P.LABELS["omega"])
            P.panel_label(axes[i, j], i * n + j, rf"$F$ = {P.fmt(F)}")
    B.draw_on_panels(fig, axes[1], [P.fixed_value(g, "F") for g in grids], sm.input.boundaries)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
