"""Fig 16: the 1:1 orbit over (eta, W), one column per F (stability maps fig16_*):
symmetric stable (orange), asymmetric stable (black), unstable (white), no admissible 1:1
(grey), drawn finer than the map so that the stable / unstable split follows the
|lambda_max| = 1 edge of the stable region (interpolated between map points, the style of
Figs 12 and robust_tet; vines.plotting.class_raster) and the boundary curves (boundaries fig16_*: colour by
type, line style by family). Top row the whole map; bottom row a zoom on the narrow stable
symmetric tongue just below W = 0.5 (the lower edge of Fig 12, dashed) when the map
extends below it."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import bifurcation as B


def main(sm):
    P.configure(sm)
    maps = sorted(map(P.stability, sm.input.stability), key=lambda m: float(m.attrs["F"]))
    curves = {round(float(b.attrs["F"]), 9): b for b in map(B.boundaries, sm.input.boundaries)}
    P.save(B.class_figure(maps, curves), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
