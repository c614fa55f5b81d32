"""Work-precision: error against cost per run for the exact solver and the RK solvers, one
row per case (work_precision/<case>.nc), columns impact times, KE ratio, x_max."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import studies


def main(sm):
    P.configure(sm)
    cases = [P.load(p) for p in sm.input.cases]
    for ds in cases:
        P.require(ds, variables=studies.VARS, finite=("seconds",))
    P.save(studies.work_precision_figure(cases), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
