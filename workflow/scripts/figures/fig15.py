"""Fig 15: zoomed bifurcation diagrams (black dots, sweep fig15) with the analytic 1:1
branch (vermillion, solid stable, dotted unstable) and |lambda| vs eta with the |lambda| = 1 line;
one row per branch fig15_* (F = 0.3077, W = 0.9 and 1.1), with the asymmetric branches born
on it (blue lines, vines.plotting.bifurcation). Dots of swept points that sit on a stable
asymmetric 1:1 orbit (vines.plotting.sweep_regimes) are drawn in blue and labelled."""
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import bifurcation as B

#: colour of the dots on a stable asymmetric 1:1 orbit (that of the asymmetric branches)
C_ASYM = P.palette.C_ASYMMETRIC


def label_asymmetric(ax, sw, outer, codes):
    """Redraw the dots of the points on an asymmetric 1:1 orbit in C_ASYM, with a label."""
    pts = np.flatnonzero(np.isclose(sw["outer_value"].values, outer, rtol=0, atol=1e-9))
    x, y = P.sweep_points(sw, outer)
    c = np.repeat(codes[pts], sw["row_size"].values[pts])
    lo, hi = ax.get_xlim()
    m = (c == P.REGIME_ASYM) & (x >= lo) & (x <= hi)
    if m.any():
        P.bifurcation_dots(ax, x[m], y[m], s=3.0, color=C_ASYM,
                           label="numerical, on a stable asymmetric 1:1 orbit")
        print(f"omega = {outer}: {int(np.unique(x[m]).size)} swept points on an asymmetric "
              f"1:1 orbit, eta {x[m].min():.4g} ... {x[m].max():.4g}")


def main(sm):
    P.configure(sm)
    sw = P.sweep(sm.input.sweep[0])
    brs = sorted((P.branch(p) for p in sm.input.branches),
                 key=lambda b: float(b["omega"][0]))
    outer_dim = sw.attrs.get("outer_parameter", "omega")
    fig = P.zoom_figure(sw, B.continued_branches(brs), outer_dim=outer_dim)
    B.draw_switched(fig, brs, sw, outer_dim)
    codes = P.sweep_regimes(sw)
    for i, br in enumerate(brs):
        label_asymmetric(fig.axes[2 * i], sw, float(br[outer_dim].values[0]), codes)
    P.zoom_legend(fig)
    P.save(fig, sm.output.pdf, sm.output.png, dpi=200)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
