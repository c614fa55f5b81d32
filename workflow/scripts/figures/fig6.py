"""Fig 6: zoom of Fig 3 (numerical impacts, black dots) with the analytic 1:1 branch (vermillion,
solid stable, dotted unstable) and the asymmetric branches born on it (blue, an inset when
they are small), and |lambda| of J_P2 J_P1 vs eta with the |lambda| = 1 line; one row per
branch fig6_* (F = 0.05, 0.1 at W = 1), one legend below."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import bifurcation as B


def main(sm):
    P.configure(sm)
    sw = P.sweep(sm.input.sweep[0])
    brs = sorted((P.branch(p) for p in sm.input.branches), key=lambda b: float(b["F"][0]))
    fig = B.branches_figure(sw, brs, outer_dim=sw.attrs.get("outer_parameter", "F"))
    P.save(fig, sm.output.pdf, sm.output.png, dpi=200)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
