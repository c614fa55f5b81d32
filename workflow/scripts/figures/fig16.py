"""Fig 16: the 1:1 orbit over (eta, W), one panel per F (stability maps fig16_*): symmetric
stable (orange), asymmetric stable (black), unstable (white), no admissible 1:1 (grey),
the |lambda_max| = 1 edges interpolated between map points (blue lines) and a legend of the
four classes. A map computed below W = 0.5 (the lower edge of Fig 12) shows the narrow
stable symmetric tongue just below W = 0.5 as what it is; a dashed line marks W = 0.5."""
from matplotlib.lines import Line2D

import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import bifurcation as B

#: lower edge of the paper's Omega range (Figs 12, 16): marked when a map extends below it
OMEGA_PAPER_MIN = 0.5
#: colour of the interpolated |lambda_max| = 1 edges
C_EDGE = "tab:blue"


def main(sm):
    maps = sorted(map(P.stability, sm.input.stability), key=lambda m: float(m.attrs["F"]))
    n = len(maps)
    fig, axes = P.figure(1, n, width=4.0 * n + 1.5, height=3.8)
    keys = sorted(P.CLASSES)
    for j, m in enumerate(maps):
        ax = axes[0, j]
        eta, W = m["eta"].values, m["omega"].values
        P.class_map(ax, eta, W, m["cls"].values.T, P.CLASSES)
        ax.contour(eta, W, P.stability_margin(m), levels=[0.0], colors=C_EDGE, linewidths=0.7)
        if W.min() < OMEGA_PAPER_MIN:
            ax.axhline(OMEGA_PAPER_MIN, color="black", ls="--", lw=0.9)
        ax.set_xlabel(P.LABELS["eta"])
        ax.set_ylabel(P.LABELS["omega"])
        P.panel_label(ax, j, rf"$F$ = {P.fmt(float(m.attrs['F']))}")
        for s in ax.spines.values():
            s.set_edgecolor("black")
        counts = {k: int((m["cls"].values == k).sum()) for k in keys}
        print(f"F = {m.attrs['F']}: class counts {counts}")
    handles = P.class_handles(P.CLASSES, {1: r" ($|\lambda_{\max}| < 1$)",
                                          2: r" ($|\lambda_{\max}| < 1$)",
                                          3: r" ($|\lambda_{\max}| > 1$)"})
    handles.append(Line2D([], [], color=C_EDGE, lw=0.7,
                          label=r"$|\lambda_{\max}| = 1$ (interpolated)"))
    if any(float(m["omega"].min()) < OMEGA_PAPER_MIN for m in maps):
        handles.append(Line2D([], [], color="black", ls="--", lw=0.9,
                              label=rf"$\Omega$ = {P.fmt(OMEGA_PAPER_MIN)} (lower edge of "
                              "Fig. 12)"))
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False)
    B.draw_on_panels(fig, axes[0], [float(m.attrs["F"]) for m in maps], sm.input.boundaries)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
