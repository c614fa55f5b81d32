"""Model ladder (beyond the paper; docs/performance.md): per ``model_ladders`` entry two
rows, one column per eta: the frequency response by the averaged slow flow, the exact 1:1
orbits (map solve and continuation) and the simulation from rest; under it the slow flow's
amplitude error against the exact orbits and each model's wall time
(vines.plotting.model_ladder)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import model_ladder as M


def main(sm):
    P.configure(sm)
    ladders = [M.model_ladder(p) for p in sm.input.ladders]
    n = max(ds.sizes["eta"] for ds in ladders)
    fig, axes = P.figure(2 * len(ladders), n, width=3.7 * n + 0.4,
                         height=7.0 * len(ladders) + 1.4)
    for row, ds in enumerate(ladders):
        top, bottom = axes[2 * row], axes[2 * row + 1]
        for k in range(ds.sizes["eta"]):
            M.frc_panel(top[k], ds, k)
            M.error_panel(bottom[k], ds, k)
            eta, F = float(ds["eta"][k]), float(ds["F"][k])
            P.panel_label(top[k], 2 * row * n + k, rf"$\eta$ = {eta:g}, $F$ = {F:g}")
            P.panel_label(bottom[k], (2 * row + 1) * n + k, "slow flow against the exact orbits")
            bottom[k].text(0.02, 0.02, M.cost_line(ds, k).replace(", ", "\n"),
                           transform=bottom[k].transAxes, fontsize=6.5, va="bottom")
            print(M.summary(ds, k))
        for k in range(ds.sizes["eta"], n):
            top[k].set_visible(False)
            bottom[k].set_visible(False)
    handles = {}
    for ax in axes.ravel():
        for h, label in zip(*ax.get_legend_handles_labels(), strict=True):
            handles.setdefault(label, h)
    fig.legend(handles=list(handles.values()), labels=list(handles), loc="outside lower center",
               ncol=4 if n > 2 else 2, fontsize=7.5, frameon=False)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
