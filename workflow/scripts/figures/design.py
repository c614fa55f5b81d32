"""Design (beyond the paper; docs/design.md): transmissibility x_max/A over the band for
the LO alone (grey), the optimal TMD (blue) and the VI NES design from rest (solid orange)
and over attractors (dashed orange), one panel per base amplitude, the worst value found
from rest marked; and the worst-case ratio from rest of every grid design over
(L, eta) with the chosen design starred."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import design as D


def main(sm):
    P.configure(sm)
    designs = [D.design(p) for p in sm.input.designs]
    P.save(D.design_figure(designs), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
