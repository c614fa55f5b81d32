"""Fig 3: bifurcation diagrams of the relative impact velocity w'_i vs eta at W = 1, one
panel per F (sweep fig3, both sweep directions)."""
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job


def main(sm):
    P.configure(sm)
    sw = P.sweep(sm.input.sweep[0])
    if sw.attrs.get("swept_parameter") != "eta":
        raise P.FigureInputError(f"{sm.input.sweep[0]}: Fig 3 sweeps eta, the dataset "
                                 f"sweeps {sw.attrs.get('swept_parameter')!r}")
    outer_name = sw.attrs.get("outer_parameter", "F")
    outers = np.unique(sw["outer_value"].values)
    fig, axes = P.figure(1, len(outers), width=5.0 * len(outers), height=3.6)
    for i, o in enumerate(outers):
        ax = axes[0, i]
        x, y = P.sweep_points(sw, o)
        P.bifurcation_dots(ax, x, y, s=1.0)
        ax.axhline(0, color="0.7", lw=0.5)
        ax.set_xlabel(P.LABELS["eta"])
        ax.set_ylabel(P.LABELS["dw"])
        title = rf"${P.SYMBOLS[outer_name]}$ = {P.fmt(o)}, {sw.attrs.get('fixed', '')}"
        P.panel_label(ax, i, title.replace("omega=", r"$\Omega$ = "))
    P.save(fig, sm.output.pdf, sm.output.png, dpi=200)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
