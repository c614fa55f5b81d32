"""Fig 14: 3-D bifurcation diagrams of w'_i over (eta, W), one row per F (sweeps fig14_*),
W <= 1 (a, c, e) and W >= 1 (b, d, f). The impacts of each swept point are coloured by the
point's regime (vines.plotting.sweep_regimes): 1:1 points large and opaque, the others
small and faint, so the 1:1 windows stand out; the companion figure fig14_regimes shows the
same regimes flat over (eta, W)."""
import matplotlib.pyplot as plt
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job

#: impacts drawn per swept point (the last ones recorded), keeps the 3-D scatter readable
MAX_PER_POINT = 12
#: marker size and opacity: 1:1 points (emphasised) and all other points
STYLE_1TO1 = {"s": 1.2, "alpha": 0.9}
STYLE_OTHER = {"s": 0.25, "alpha": 0.35}
#: view (elevation, azimuth): eta across, W into depth; the W <= 1 panels have their W axis
#: reversed, so that W = 1 (the 1:1 windows the text discusses) is the front row of both
VIEW = (22, -68)


def panel(ax, s, W_sel, codes):
    """The impacts of the sweep points at the omega values W_sel, coloured by regime."""
    W_pt = s["outer_value"].values
    for w in W_sel:
        pts = np.flatnonzero(np.isclose(W_pt, w, rtol=0, atol=1e-9))
        x, y = P.sweep_points(s, w, max_per_point=MAX_PER_POINT)
        # the regime of each impact's point (sweep_points keeps the points' order)
        n_kept = [min(int(s["row_size"].values[i]), MAX_PER_POINT) for i in pts]
        c = np.repeat(codes[pts], n_kept)
        for code, (_, colour) in P.REGIMES.items():
            m = c == code
            if m.any():
                style = STYLE_1TO1 if code in (P.REGIME_SYM, P.REGIME_ASYM) else STYLE_OTHER
                ax.scatter(x[m], np.full(m.sum(), w), y[m], c=colour, linewidths=0,
                           depthshade=False, rasterized=True, **style)


def main(sm):
    sweeps = [P.sweep(p) for p in sm.input.sweeps]
    for s, p in zip(sweeps, sm.input.sweeps, strict=False):
        if s.attrs.get("swept_parameter") != "eta" or s.attrs.get("outer_parameter") != "omega":
            raise P.FigureInputError(f"{p}: Fig 14 needs eta sweeps at several W, got "
                                     f"{s.attrs.get('swept_parameter')!r} over "
                                     f"{s.attrs.get('outer_parameter')!r}")
    Fs = [P.sweep_fixed(s, "F") for s in sweeps]
    n = len(sweeps)
    fig = plt.figure(figsize=(11.0, 4.2 * n), constrained_layout=True)
    for r, k in enumerate(np.argsort(Fs)):
        s, codes = sweeps[k], P.sweep_regimes(sweeps[k])
        W = np.unique(s["outer_value"].values)
        for c, (sel, side) in enumerate(((W <= 1 + 1e-12, r"$\Omega \leq 1$"),
                                         (W >= 1 - 1e-12, r"$\Omega \geq 1$"))):
            ax = fig.add_subplot(n, 2, 2 * r + c + 1, projection="3d")
            if not sel.any():
                raise P.FigureInputError(f"{sm.input.sweeps[k]}: no sweep with {side}")
            panel(ax, s, W[sel], codes)
            lim = (W[sel].min(), W[sel].max())
            ax.set_ylim(lim[::-1] if c == 0 else lim)
            ax.set_xlabel(P.LABELS["eta"], fontsize=8)
            ax.set_ylabel(r"$\Omega$", fontsize=8)
            ax.set_zlabel(r"$\dot w_i$", fontsize=8)
            ax.tick_params(labelsize=7)
            ax.view_init(*VIEW)
            P.panel_label(ax, 2 * r + c, rf"$F$ = {P.fmt(Fs[k])}, {side}")
    handles = [plt.Line2D([], [], ls="", marker="o", ms=5, color=col, label=lab)
               for lab, col in P.REGIMES.values()]
    fig.legend(handles=handles, loc="outside lower center", ncol=len(handles), fontsize=8,
               frameon=False, title="regime of the swept point (from its recorded impacts)",
               title_fontsize=8)
    P.save(fig, sm.output.pdf, sm.output.png, dpi=170)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
