"""Model ladder (beyond the paper; docs/performance.md): per ``model_ladders`` entry two
rows, one column per eta: the frequency response by the averaged slow flow, the exact 1:1
orbits (map solve and continuation) and the simulation from rest; under it the slow flow's
amplitude error against the exact orbits and each model's wall time
(vines.plotting.model_ladder)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import model_ladder as M


def main(sm):
    P.configure(sm)
    ladders = [M.model_ladder(p) for p in sm.input.ladders]
    P.save(M.ladder_figure(ladders), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
