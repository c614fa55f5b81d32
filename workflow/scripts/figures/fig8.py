"""Fig 8: sections of Fig 7 at the F values marked in the grids (section_F, config key
grids.fig7_*.sections): KE ratio (blue stars) and x_max (m, vermillion circles) vs eta; rows F,
columns W (vines.plotting.sections)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import sections


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "F"), fixed=("omega",))
                               for p in sm.input.measures], "omega")
    fig = sections.sections_figure(grids, "F", "eta", "fig7", panel_height=3.2)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
