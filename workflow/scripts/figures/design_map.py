"""Design map (beyond the paper; docs/design.md, "Who wins where"): per ``design_maps``
entry and amplitude span the VI NES's worst case over the TMD's of the same mass, free and
at equal travel, over mass ratio and band; the frontier, the cells checked exactly
(vines.plotting.design_map)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import design_map as D


def main(sm):
    P.configure(sm)
    maps = [D.design_map(p) for p in sm.input.maps]
    P.save(D.design_map_figure(maps), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
