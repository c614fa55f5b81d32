"""Uncertain parts (beyond the paper; docs/design.md): per ``uncertainty`` entry, the
distribution of the worst ratio x_max/A over the Sobol points for the VI NES (orange) and
the TMD (blue) with their nominal values (dashed) and 95 % quantiles (dotted); the
first-order and total Sobol indices of each with 95 % bootstrap intervals (unreliable ones
hatched); the regime of the VI NES at its worst point, share of the points."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import design as D


def main(sm):
    P.configure(sm)
    studies = [D.study(p) for p in sm.input.studies]
    P.save(D.uncertainty_figure(studies), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
