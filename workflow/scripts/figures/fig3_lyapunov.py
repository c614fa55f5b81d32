"""Fig 3 with its leading Lyapunov exponent (beyond the paper): the bifurcation diagrams of
w'_i vs eta at W = 1 (sweep fig3, both directions) and, under each, lambda_1 of every sweep
point over the last t_window of its run (lyapunov dataset fig3), up and down sweeps apart,
with the 95 % batch-means intervals."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import sweeps


def main(sm):
    P.configure(sm)
    sw = P.sweep(sm.input.sweep[0])
    ly = sweeps.lyapunov(sm.input.lyapunov[0])
    P.save(sweeps.diagram_lyapunov_figure(sw, ly), sm.output.pdf, sm.output.png, dpi=200)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
