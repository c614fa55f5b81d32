"""Fig 8: sections of Fig 7 at the F values marked in the grids (section_F, config key
grids.fig7_*.sections): KE ratio (blue stars) and x_max (m, red circles) vs eta; rows F,
columns W."""
import _common
import numpy as np

from vines import plotting as P


def main(sm):
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "F"), fixed=("omega",))
                               for p in sm.input.measures], "omega")
    for ds in grids:
        P.require(ds, variables=("section_F",))
    Fs = [ds["F"].values[ds["section_F"].values.astype(bool)] for ds in grids]
    if not all(np.array_equal(Fs[0], f) for f in Fs) or Fs[0].size == 0:
        raise P.FigureInputError("the fig7_* grids must mark the same, non-empty F sections "
                                 f"(section_F), got {[f.tolist() for f in Fs]}")
    nr, nc = Fs[0].size, len(grids)
    fig, axes = P.figure(nr, nc, width=4.4 * nc, height=3.2 * nr)
    for i, F in enumerate(Fs[0]):
        for j, ds in enumerate(grids):
            s = ds.sel(F=F).isel(omega=0)
            ax = axes[i, j]
            P.twin_measures(ax, s["eta"].values, s["ke_ratio"].values, s["xmax_m"].values,
                            P.LABELS["eta"])
            P.panel_label(ax, i * nc + j, rf"$F$ = {P.fmt(F)}, "
                          rf"$\Omega$ = {P.fmt(P.fixed_value(ds, 'omega'))}")
    P.save(fig, sm.output.pdf, sm.output.png)


_common.run(snakemake, main)  # noqa: F821  (injected by Snakemake)
