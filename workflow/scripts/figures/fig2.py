"""Fig 2: x_max of the LO (m, vermillion circles) and KE ratio (blue stars) vs eta at W = 1, one
panel per F (grids fig2_*): the KE ratio peaks where x_max is smallest."""
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta",), fixed=("omega", "F"))
                               for p in sm.input.measures], "F")
    fig, axes = P.figure(1, len(grids), width=5.0 * len(grids), height=3.6)
    for i, ds in enumerate(grids):
        ax = axes[0, i]
        eta = ds["eta"].values
        ke = ds["ke_ratio"].values.ravel()
        xm = ds["xmax_m"].values.ravel()
        ax2 = P.twin_measures(ax, eta, ke, xm, P.LABELS["eta"])
        k = int(np.argmax(ke))
        ax.axvline(eta[k], color="0.6", lw=0.8, ls="--")
        P.panel_label(ax, i, rf"$F$ = {P.fmt(P.fixed_value(ds, 'F'))}, "
                             rf"$\Omega$ = {P.fmt(P.fixed_value(ds, 'omega'))}")
        h1, l1 = ax.get_legend_handles_labels()
        h2, l2 = ax2.get_legend_handles_labels()
        ax.legend(h1 + h2, l1 + l2, fontsize=7, loc="upper right")
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
