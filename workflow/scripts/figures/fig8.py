"""Fig 8: sections of Fig 7 at the F values marked in the grids (section_F, config key
grids.fig7_*.sections): KE ratio (blue stars) and x_max (m, vermillion circles) vs eta; rows F,
columns W."""
import vines.plotting as P
from vines.pipeline.jobs import run_job


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "F"), fixed=("omega",))
                               for p in sm.input.measures], "omega")
    Fs = P.marked_sections(grids, "F", "fig7")
    nr, nc = Fs.size, len(grids)
    fig, axes = P.figure(nr, nc, width=4.4 * nc, height=3.2 * nr)
    for i, F in enumerate(Fs):
        for j, ds in enumerate(grids):
            s = ds.sel(F=F).isel(omega=0)
            ax = axes[i, j]
            P.twin_measures(ax, s["eta"].values, s["ke_ratio"].values, s["xmax_m"].values,
                            P.LABELS["eta"])
            P.panel_label(ax, i * nc + j, rf"$F$ = {P.fmt(F)}, "
                          rf"$\Omega$ = {P.fmt(P.fixed_value(ds, 'omega'))}")
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
