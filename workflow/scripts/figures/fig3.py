"""Fig 3: bifurcation diagrams of the relative impact velocity w'_i vs eta at W = 1, one
panel per F (sweep fig3, both sweep directions)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import sweeps


def main(sm):
    P.configure(sm)
    fig = sweeps.diagram_figure(P.sweep(sm.input.sweep[0]))
    P.save(fig, sm.output.pdf, sm.output.png, dpi=200)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
