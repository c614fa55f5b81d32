"""Basin slices: the attractor reached from each initial (z_m(0), z_m'(0)) with the ball at
rest in the middle of the cavity, one panel per slice (basins basin_*), each attractor in
its own colour (legend: regime, KE ratio, share of the slice), the start from rest marked.
Top row: the window view (the attractor the state is on at t_end); with the asymptotic view
in the datasets (config t_max) a second row: the attractor the same state is on at t_max,
in the same colours, the legend giving each attractor's status (persistent / transient /
unresolved) and its regime at t_max (a lasting motion on a torus: quasi-periodic)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import basins


def main(sm):
    P.configure(sm)
    slices = [P.basin_slice(p) for p in sm.input.slices]
    P.save(basins.basin_figure(slices), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
