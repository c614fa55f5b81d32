"""Orbit atlas (beyond the paper; docs/bifurcation.md): per F a row, (left) the periodic
family group that is stable and admissible at each (eta, W) (orbit_atlas atlas_*; the
group of the smallest lambda_max where several are stable, hatched there), dark grey where only
unstable or non-admissible orbits were found, white where no seed reached any family;
with the boundary curves of the families beyond 1:1 computed at that F (boundaries
entries with walls, e.g. llrr_F0.4: fold, symmetry-breaking, grazing of LLRR/1-sym;
coloured by curve type as on Fig 16) where configured;
(right) the regime the simulation from rest settles on (Fig 12's grid at the same F,
grids.fig12_*): its periodic families in the atlas's colours, the other regimes in the
regime colours of every regime figure (palette.REGIMES). One legend of exactly the
classes drawn. The atlas is a finite search: absent means that no seed reached a family,
not that none exists."""

import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import atlas as A
from vines.plotting import bifurcation as B


def main(sm):
    P.configure(sm)
    atlases = sorted(map(A.atlas, sm.input.atlases), key=lambda d: float(d.attrs["F"]))
    grids = {round(P.fixed_value(g, "F"), 9): g
             for g in (P.load(p) for p in sm.input.measures)}
    curves = [B.boundaries(p) for p in getattr(sm.input, "boundaries", [])]
    P.save(A.atlas_figure(atlases, grids, curves), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
