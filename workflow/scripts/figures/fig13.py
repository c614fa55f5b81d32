"""Fig 13: sections of Fig 12 at the eta values marked in the grids (section_eta, config
key grids.fig12_*.sections): KE ratio (blue stars) and x_max (m, vermillion circles) vs W; rows F,
columns eta."""
import vines.plotting as P
from vines.pipeline.jobs import run_job


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "omega"), fixed=("F",))
                               for p in sm.input.measures], "F")
    etas = P.marked_sections(grids, "eta", "fig12")
    nr, nc = len(grids), etas.size
    fig, axes = P.figure(nr, nc, width=4.4 * nc, height=3.0 * nr)
    for i, ds in enumerate(grids):
        for j, eta in enumerate(etas):
            s = ds.sel(eta=eta).isel(F=0)
            ax = axes[i, j]
            P.twin_measures(ax, s["omega"].values, s["ke_ratio"].values, s["xmax_m"].values,
                            P.LABELS["omega"])
            P.panel_label(ax, i * nc + j, rf"$F$ = {P.fmt(P.fixed_value(ds, 'F'))}, "
                          rf"$\eta$ = {P.fmt(eta)}")
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
