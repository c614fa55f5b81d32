"""Fig 12: contour maps over (eta, W) of x_max in metres (a-c, log colour scale) and the KE
ratio (d-f), one column per F (grids fig12_*); each row one colour range and one colour
bar. On every panel the dashed line W = 1/sqrt(1+eta); on (d-f) the edge of the stable 1:1
region of the stability map with the same F (stability maps fig16_*, |lambda_max| = 1
interpolated between map points). Points without impacts are a grey class on (d-f)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import maps


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "omega"), fixed=("F",))
                               for p in sm.input.measures], "F")
    smaps = maps.by_F(map(P.stability, sm.input.stability))
    P.save(maps.eta_omega_figure(grids, smaps), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
