"""Robust-TET map beside Fig 12: over (eta, W), one column per F, (a-c) the KE ratio of the
run from rest (Fig 12 (d-f); points without impacts a grey class, no data left blank),
(d-f) the basin fraction of efficient motion (attractors with KE ratio above the map's
threshold) and (g-i) the basin fraction of the stable 1:1 orbit, from a census of Sobol
initial states per grid point (robust maps robust_*), one cell per census point (whole
cells drawn), hatched where the 95 % Wilson interval of the fraction is wider than 0.2;
(g-i) drawn finer than the census grid: the cell's value only where the Fig 16 map has a
stable 1:1 orbit, 0 elsewhere (no orbit, no basin), so that the W = 0.5 row, which samples
the narrow stable tongue just below W = 0.5001, shows as that tongue and not as a band half
a cell high. When the robust maps carry the asymptotic view (config t_max), (j-l) the
efficient basin fraction of the same states at t_max, a cross where it differs from the
window fraction (d-f). Each row one colour bar. On every panel the edge of the stable 1:1
region of Fig 16 (|lambda_max| = 1)."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import maps


def main(sm):
    P.configure(sm)
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "omega"), fixed=("F",))
                               for p in sm.input.measures], "F")
    smaps = maps.by_F(map(P.stability, sm.input.stability))
    robust = maps.by_F(map(P.robust_map, sm.input.robust))
    P.save(maps.robust_tet_figure(grids, smaps, robust), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
