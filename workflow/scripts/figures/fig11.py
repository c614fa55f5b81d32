"""Fig 11: (a, b) x_max (m, log axis) vs W of the VINES (vermillion, grid fig11_*) and of the stuck
linear system Eq. 28 (black, `vines.core.linear` on a fine omega grid, its exact peak
(closed form, `stuck_peak`) marked and quoted), one panel per eta; (c-e) LO displacement of the
VINES (vermillion) and the steady state of Eq. 28 (black) at the points of timehistories.fig11."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import stuck_linear


def main(sm):
    P.configure(sm)
    ds = P.measures(sm.input.measures[0], axes=("omega",), fixed=("F",), min_size=3)
    P.require(ds, coords=("eta",), finite=("xmax_stuck_linear_m",))
    th = P.timehistory(sm.input.th[0])
    P.save(stuck_linear.stuck_linear_figure(ds, th), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
