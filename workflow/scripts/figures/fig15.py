"""Fig 15: zoomed bifurcation diagrams (black dots, sweep fig15) with the analytic 1:1
branch (vermillion, solid stable, dotted unstable) and |lambda| vs eta with the |lambda| = 1 line;
one row per branch fig15_* (F = 0.3077, W = 0.9 and 1.1), with the asymmetric branches born
on it (blue lines, vines.plotting.bifurcation). Dots of swept points that sit on a stable
asymmetric 1:1 orbit (vines.plotting.sweep_regimes) are drawn in blue and labelled."""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import bifurcation as B


def main(sm):
    P.configure(sm)
    sw = P.sweep(sm.input.sweep[0])
    brs = sorted((P.branch(p) for p in sm.input.branches),
                 key=lambda b: float(b["omega"][0]))
    fig = B.branches_figure(sw, brs, outer_dim=sw.attrs.get("outer_parameter", "omega"),
                            mark_asymmetric=True)
    P.save(fig, sm.output.pdf, sm.output.png, dpi=200)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
