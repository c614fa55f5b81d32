"""Fig 7: contour maps over (eta, F) of the KE ratio (a-c) and x_max in metres (d-f, log
colour scale: the low-x_max valleys stay visible next to the resonance peak), one column
per W (grids fig7_*). Each row compares one quantity: one colour range and one colour bar
per row. Points without impacts are a grey class of their own on (a-c), not KE ratio 0."""
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "F"), fixed=("omega",))
                               for p in sm.input.measures], "omega")
    n = len(grids)
    fig, axes = P.figure(2, n, width=4.0 * n + 1.0, height=7.0)
    xmax_range = P.common_range([P.grid2d(ds, "xmax_m", "eta", "F") for ds in grids], log=True)
    rows = (("ke_ratio", P.LABELS["ke_ratio"], {"vmin": 0.0, "vmax": 1.0}),
            ("xmax_m", P.LABELS["xmax_m"], {"log": True, "vmin": xmax_range[0],
                                              "vmax": xmax_range[1]}))
    any_silent = False
    for i, (var, lab, kw) in enumerate(rows):
        for j, ds in enumerate(grids):
            eta, F = ds["eta"].values, ds["F"].values
            ax = axes[i, j]
            silent = P.grid2d(ds, "n_impacts", "eta", "F") == 0 if var == "ke_ratio" else None
            any_silent |= bool(np.any(silent)) if silent is not None else False
            cs = P.contour_map(fig, ax, eta, F, P.grid2d(ds, var, "eta", "F"),
                               P.MapStyle(lab, colorbar=False, **kw), no_impact=silent)
            ax.set_xlabel(P.LABELS["eta"])
            ax.set_ylabel(P.LABELS["F"])
            P.panel_label(ax, i * n + j, rf"$\Omega$ = {P.fmt(P.fixed_value(ds, 'omega'))}")
        P.shared_colorbar(fig, cs, axes[i, :], shrink=0.85)
    if any_silent:
        fig.legend(handles=[P.no_impact_handle()], loc="outside lower center", fontsize=8,
                   frameon=False)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
