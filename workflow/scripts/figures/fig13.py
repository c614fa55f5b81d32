"""Fig 13: sections of Fig 12 at the eta values marked in the grids (section_eta, config
key grids.fig12_*.sections): KE ratio (blue stars) and x_max (m, red circles) vs W; rows F,
columns eta."""
import _common
import numpy as np

from vines import plotting as P


def main(sm):
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "omega"), fixed=("F",))
                               for p in sm.input.measures], "F")
    for ds in grids:
        P.require(ds, variables=("section_eta",))
    etas = [ds["eta"].values[ds["section_eta"].values.astype(bool)] for ds in grids]
    if not all(np.array_equal(etas[0], e) for e in etas) or etas[0].size == 0:
        raise P.FigureInputError("the fig12_* grids must mark the same, non-empty eta "
                                 f"sections (section_eta), got {[e.tolist() for e in etas]}")
    nr, nc = len(grids), etas[0].size
    fig, axes = P.figure(nr, nc, width=4.4 * nc, height=3.0 * nr)
    for i, ds in enumerate(grids):
        for j, eta in enumerate(etas[0]):
            s = ds.sel(eta=eta).isel(F=0)
            ax = axes[i, j]
            P.twin_measures(ax, s["omega"].values, s["ke_ratio"].values, s["xmax_m"].values,
                            P.LABELS["omega"])
            P.panel_label(ax, i * nc + j, rf"$F$ = {P.fmt(P.fixed_value(ds, 'F'))}, "
                          rf"$\eta$ = {P.fmt(eta)}")
    P.save(fig, sm.output.pdf, sm.output.png)


_common.run(snakemake, main)  # noqa: F821  (injected by Snakemake)
