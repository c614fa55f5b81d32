"""Fig 16: the 1:1 orbit over (eta, W), one column per F (stability maps fig16_*):
symmetric stable (orange), asymmetric stable (black), unstable (white), no admissible 1:1
(grey), drawn finer than the map so that the stable / unstable split follows the
|lambda_max| = 1 edge of the stable region (interpolated between map points, the style of
Figs 12 and robust_tet; vines.plotting.class_raster) and the boundary curves (boundaries fig16_*: colour by
type, line style by family). Top row the whole map; bottom row a zoom on the narrow stable
symmetric tongue just below W = 0.5 (the lower edge of Fig 12, dashed) when the map
extends below it."""
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import bifurcation as B

#: lower edge of the paper's Omega range (Figs 12, 16): marked when a map extends below it
OMEGA_PAPER_MIN = 0.5
#: W range of the zoom row on the tongue below OMEGA_PAPER_MIN
TONGUE_ZOOM = (0.45, 0.53)


def class_panel(ax, m, boundaries):
    eta, W = m["eta"].values, m["omega"].values
    P.class_map(ax, *P.class_raster(m), P.CLASSES)
    P.stable_edge(ax, m)
    if W.min() < OMEGA_PAPER_MIN:
        ax.axhline(OMEGA_PAPER_MIN, color="black", ls="--", lw=0.9)
    ax.set_xlim(eta.min(), eta.max())
    ax.set_ylim(W.min(), W.max())
    ax.set_xlabel(P.LABELS["eta"])
    ax.set_ylabel(P.LABELS["omega"])
    for s in ax.spines.values():
        s.set_edgecolor("black")
    return B.draw_curves(ax, boundaries)


def main(sm):
    P.configure(sm)
    maps = sorted(map(P.stability, sm.input.stability), key=lambda m: float(m.attrs["F"]))
    curves = {round(float(b.attrs["F"]), 9): b for b in map(B.boundaries, sm.input.boundaries)}
    n = len(maps)
    zoom = any(float(m["omega"].min()) < OMEGA_PAPER_MIN for m in maps)
    fig, axes = P.figure(2 if zoom else 1, n, width=4.0 * n + 2.2, height=6.4 if zoom else 3.9,
                         gridspec_kw={"height_ratios": [2.2, 1]} if zoom else {})
    drawn = set()
    for j, m in enumerate(maps):
        F = float(m.attrs["F"])
        if round(F, 9) not in curves:
            raise P.FigureInputError(f"no boundary curves at F = {F} (curves at F = "
                                     f"{sorted(curves)})")
        for i in range(axes.shape[0]):
            drawn |= class_panel(axes[i, j], m, curves[round(F, 9)])
        P.panel_label(axes[0, j], j, rf"$F$ = {P.fmt(F)}")
        if zoom:
            W = m["omega"].values
            axes[1, j].set_ylim(max(TONGUE_ZOOM[0], W.min()), TONGUE_ZOOM[1])
            P.panel_label(axes[1, j], n + j, rf"$F$ = {P.fmt(F)}, zoom: tongue below "
                                             rf"$\Omega$ = {P.fmt(OMEGA_PAPER_MIN)}")
            axes[0, j].axhspan(*axes[1, j].get_ylim(), fill=False, ec="0.3", lw=0.7, ls=":")
        keys = sorted(P.CLASSES)
        counts = {k: int((m["cls"].values == k).sum()) for k in keys}
        stable_05 = P.stable_at(m, m["eta"].values, np.array([OMEGA_PAPER_MIN]))
        print(f"F = {F}: class counts {counts}; stable at W = {OMEGA_PAPER_MIN} for "
              f"{int(stable_05.sum())} of {stable_05.size} eta values")
    handles = P.class_handles(P.CLASSES, {1: r" ($|\lambda_{\max}| < 1$)",
                                          2: r" ($|\lambda_{\max}| < 1$)",
                                          3: r" ($|\lambda_{\max}| > 1$)"})
    handles.append(P.stable_edge_handle(r"$|\lambda_{\max}| = 1$ (interpolated)"))
    if zoom:
        handles.append(P.Line2D([], [], color="black", ls="--", lw=0.9,
                                label=rf"$\Omega$ = {P.fmt(OMEGA_PAPER_MIN)} (lower edge of "
                                      "Fig. 12)"))
    handles += B.curve_handles(drawn)
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
