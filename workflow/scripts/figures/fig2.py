"""Fig 2: x_max of the LO (m, vermillion circles) and KE ratio (blue stars) vs eta at W = 1, one
panel per F (grids fig2_*): the KE ratio peaks where x_max is smallest
(vines.plotting.sections)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import sections


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta",), fixed=("omega", "F"))
                               for p in sm.input.measures], "F")
    P.save(sections.along_eta_figure(grids), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
