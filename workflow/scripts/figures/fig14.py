"""Fig 14: 3-D bifurcation diagrams of w'_i over (eta, W), one row per F (sweeps fig14_*),
W <= 1 (a, c, e) and W >= 1 (b, d, f)."""
import matplotlib.pyplot as plt
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job

#: impacts drawn per swept point (the last ones recorded), keeps the 3-D scatter readable
MAX_PER_POINT = 20


def main(sm):
    sweeps = [P.sweep(p) for p in sm.input.sweeps]
    for s, p in zip(sweeps, sm.input.sweeps):
        if s.attrs.get("swept_parameter") != "eta" or s.attrs.get("outer_parameter") != "omega":
            raise P.FigureInputError(f"{p}: Fig 14 needs eta sweeps at several W, got "
                                     f"{s.attrs.get('swept_parameter')!r} over "
                                     f"{s.attrs.get('outer_parameter')!r}")
    Fs = []
    for s, p in zip(sweeps, sm.input.sweeps):
        fx = dict(kv.split("=") for kv in s.attrs.get("fixed", "").split(",") if "=" in kv)
        if "F" not in fx:
            raise P.FigureInputError(f"{p}: global attribute 'fixed' does not give F")
        Fs.append(float(fx["F"]))
    order = np.argsort(Fs)
    n = len(sweeps)
    fig = plt.figure(figsize=(10.0, 3.9 * n), constrained_layout=True)
    for r, k in enumerate(order):
        s = sweeps[k]
        W = np.unique(s["outer_value"].values)
        for c, (sel, side) in enumerate(((W <= 1 + 1e-12, r"$\Omega \leq 1$"),
                                         (W >= 1 - 1e-12, r"$\Omega \geq 1$"))):
            ax = fig.add_subplot(n, 2, 2 * r + c + 1, projection="3d")
            if not sel.any():
                raise P.FigureInputError(f"{sm.input.sweeps[k]}: no sweep with {side}")
            for w in W[sel]:
                x, y = P.sweep_points(s, w, max_per_point=MAX_PER_POINT)
                ax.scatter(x, np.full_like(x, w), y, s=0.3, c="black", linewidths=0,
                           depthshade=False, rasterized=True)
            ax.set_ylim(W[sel].min(), W[sel].max())
            ax.set_xlabel(P.LABELS["eta"], fontsize=8)
            ax.set_ylabel(r"$\Omega$", fontsize=8)
            ax.set_zlabel(r"$\dot w_i$", fontsize=8)
            ax.tick_params(labelsize=7)
            ax.view_init(elev=25, azim=-60 if c == 0 else -120)
            P.panel_label(ax, 2 * r + c, rf"$F$ = {P.fmt(Fs[k])}, {side}")
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
