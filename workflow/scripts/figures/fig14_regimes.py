"""Companion of Fig 14 (not in the paper): the regime of every swept point over (eta, W),
one panel per F, from the same sweeps (fig14_*) and the same classification
(vines.plotting.sweep_regimes). Cells: the upward sweep in eta; a white dot where the
downward sweep ends in another regime (hysteresis). Irregular points are split by their
leading Lyapunov exponent (lyapunov datasets fig14_*, same sweeps): chaotic, quasi-periodic,
or irregular with lambda_1 < 0. The eta range of the 1:1 window at W = 1 is written in each
panel."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import sweeps


def main(sm):
    P.configure(sm)
    sws = sorted((P.sweep(p) for p in sm.input.sweeps), key=lambda s: P.sweep_fixed(s, "F"))
    exponents = {}
    for path in sm.input.lyapunov:
        ly = P.load(path)
        exponents[ly.attrs["sweep"]] = ly
    P.save(sweeps.regimes_figure(sws, exponents), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
