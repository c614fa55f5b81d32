"""Fig 7: contour maps over (eta, F) of the KE ratio (a-c) and x_max in metres (d-f, log
colour scale: the low-x_max valleys stay visible next to the resonance peak), one column
per W (grids fig7_*). Each row compares one quantity: one colour range and one colour bar
per row. Points without impacts are a grey class of their own on (a-c), not KE ratio 0."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import maps


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "F"), fixed=("omega",))
                               for p in sm.input.measures], "omega")
    P.save(maps.eta_F_figure(grids), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
