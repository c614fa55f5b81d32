"""Fig 16: the 1:1 orbit over (eta, W), one panel per F (stability maps fig16_*): symmetric
stable (orange), asymmetric stable (black), unstable (white), no admissible 1:1 (grey),
with |lambda_max| = 1 contour and a legend of the four classes."""
import numpy as np
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.patches import Patch

import vines.plotting as P
from vines.plotting import bifurcation as B
from vines.pipeline.jobs import run_job


def main(sm):
    maps = sorted(map(P.stability, sm.input.stability), key=lambda m: float(m.attrs["F"]))
    n = len(maps)
    fig, axes = P.figure(1, n, width=4.0 * n + 1.5, height=3.8)
    keys = sorted(P.CLASSES)
    cmap = ListedColormap([P.CLASSES[k][1] for k in keys])
    norm = BoundaryNorm(np.arange(len(keys) + 1) - 0.5, cmap.N)
    for j, m in enumerate(maps):
        ax = axes[0, j]
        eta, W = m["eta"].values, m["omega"].values
        ax.pcolormesh(eta, W, m["cls"].values.T, cmap=cmap, norm=norm, shading="nearest",
                      rasterized=True)
        ax.set_xlabel(P.LABELS["eta"])
        ax.set_ylabel(P.LABELS["omega"])
        P.panel_label(ax, j, rf"$F$ = {P.fmt(float(m.attrs['F']))}")
        for s in ax.spines.values():
            s.set_edgecolor("black")
        counts = {k: int((m["cls"].values == k).sum()) for k in keys}
        print(f"F = {m.attrs['F']}: class counts {counts}")
    handles = [Patch(facecolor=P.CLASSES[k][1], edgecolor="black",
                     label=P.CLASSES[k][0] + (r" ($|\lambda_{\max}| < 1$)" if k in (1, 2)
                                              else r" ($|\lambda_{\max}| > 1$)" if k == 3
                                              else ""))
               for k in keys]
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False)
    B.draw_on_panels(fig, axes[0], [float(m.attrs["F"]) for m in maps], sm.input.boundaries)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
