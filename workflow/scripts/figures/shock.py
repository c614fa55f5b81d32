"""Shock (beyond the paper; docs/design.md): one row per ``shocks`` entry, the fraction of
a shock's energy dissipated within the window against the initial energy, and the energy
left in time at a few initial energies, for the VI NES, the equal-mass TMD and the LO
alone (vines.plotting.shock)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import shock as S


def main(sm):
    P.configure(sm)
    rows = [S.shock(p) for p in sm.input.shocks]
    fig, axes = P.figure(len(rows), 2, width=10.0, height=3.9 * len(rows) + 0.7)
    for i, ds in enumerate(rows):
        S.curve_panel(axes[i, 0], ds)
        S.decay_panel(axes[i, 1], ds)
        where = rf"$\eta$ = {ds.attrs['eta']:g}, $L$ = {ds.attrs['clearance_m'] * 1e3:.3g} mm"
        P.panel_label(axes[i, 0], 2 * i, f"dissipated against initial energy ({where})")
        P.panel_label(axes[i, 1], 2 * i + 1, f"energy left in time ({where})")
        axes[i, 1].legend(fontsize=7, loc="lower left", frameon=False)
        print(S.summary(ds))
    fig.legend(handles=axes[0, 0].get_legend_handles_labels()[0], loc="outside lower center",
               ncol=3, fontsize=8, frameon=False)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
