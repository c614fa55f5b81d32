"""Fig 14: 3-D bifurcation diagrams of w'_i over (eta, W), one panel per F (sweeps fig14_*),
each over the whole W range (the paper's (a, b), (c, d), (e, f) split at W = 1 is one panel
here). The impacts of each swept point are coloured by the
point's regime (vines.plotting.sweep_regimes): 1:1 points large and opaque, the others
small and faint, so the 1:1 windows stand out; the companion figure fig14_regimes shows the
same regimes flat over (eta, W). The legend lists the regimes drawn (a point without
impacts draws nothing)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import sweeps


def main(sm):
    P.configure(sm)
    fig = sweeps.diagram_3d_figure([P.sweep(p) for p in sm.input.sweeps])
    P.save(fig, sm.output.pdf, sm.output.png, dpi=170)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
