"""Design over a drifting host (beyond the paper; docs/design.md, "Mistuning"): the worst
x_max/A over band and amplitudes against the host's frequency drift delta (natural
frequency (1 + delta) w0) for the LO alone (grey), the TMD (blue) and the VI NES from rest
(orange; dotted: over attractors), the designs chosen at delta = 0 (solid) and those
optimised for the worst case over the drift (dashed), one panel per entry."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import design as D


def main(sm):
    P.configure(sm)
    entries = [D.robust(p) for p in sm.input.robust]
    P.save(D.robust_figure(entries), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
