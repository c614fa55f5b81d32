"""Fig 7: contour maps over (eta, F) of the KE ratio (a-c) and x_max in metres (d-f, log
colour scale: the low-x_max valleys stay visible next to the resonance peak), one column
per W (grids fig7_*), each with its colour bar."""
import vines.plotting as P
from vines.pipeline.jobs import run_job


def main(sm):
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "F"), fixed=("omega",))
                               for p in sm.input.measures], "omega")
    n = len(grids)
    fig, axes = P.figure(2, n, width=4.2 * n, height=7.0)
    for j, ds in enumerate(grids):
        eta, F = ds["eta"].values, ds["F"].values
        W = P.fmt(P.fixed_value(ds, "omega"))
        for i, (var, lab, kw) in enumerate((("ke_ratio", P.LABELS["ke_ratio"],
                                             {"vmin": 0.0, "vmax": 1.0}),
                                            ("xmax_m", P.LABELS["xmax_m"], {"log": True}))):
            ax = axes[i, j]
            P.contour_map(fig, ax, eta, F, P.grid2d(ds, var, "eta", "F"), label=lab, **kw)
            ax.set_xlabel(P.LABELS["eta"])
            ax.set_ylabel(P.LABELS["F"])
            P.panel_label(ax, i * n + j, rf"$\Omega$ = {W}")
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
