"""Fig 4: time histories of the cavity ends z_m +- 1 (blue) and the ball z_b (red), phase
portraits beside them, one row per point of timehistories.fig4."""
import _common

from vines.plotting import draw as P


def main(sm):
    ds = P.timehistory(sm.input.th[0])
    fig = P.time_history_figure(ds)
    P.save(fig, sm.output.pdf, sm.output.png)


_common.run(snakemake, main)  # noqa: F821  (injected by Snakemake)
