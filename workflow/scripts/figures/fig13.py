"""Fig 13: sections of Fig 12 at the eta values marked in the grids (section_eta, config
key grids.fig12_*.sections): KE ratio (blue stars) and x_max (m, vermillion circles) vs W; rows F,
columns eta (vines.plotting.sections)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import sections


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "omega"), fixed=("F",))
                               for p in sm.input.measures], "F")
    fig = sections.sections_figure(grids, "eta", "omega", "fig12", panel_height=3.0)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
