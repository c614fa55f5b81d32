"""Figs 4, 5, 9, 10 (one script, one rule per figure): time histories of the cavity ends
z_m +- 1 (blue) and the ball z_b (vermillion), phase portraits beside them, one row per point of
the figure's time-history dataset (timehistories.figN)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job


def main(sm):
    P.configure(sm)
    ds = P.timehistory(sm.input.th[0])
    fig = P.time_history_figure(ds)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
