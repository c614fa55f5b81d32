"""Shock (beyond the paper; docs/design.md): one row per ``shocks`` entry, the fraction of
a shock's energy dissipated within the window against the initial energy, and the energy
left in time at a few initial energies, for the VI NES, the equal-mass TMD and the LO
alone (vines.plotting.shock)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import shock as S


def main(sm):
    P.configure(sm)
    rows = [S.shock(p) for p in sm.input.shocks]
    P.save(S.shock_figure(rows), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
