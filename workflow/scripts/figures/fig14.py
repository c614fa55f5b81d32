"""Fig 14: 3-D bifurcation diagrams of w'_i over (eta, W), one panel per F (sweeps fig14_*),
each over the whole W range (the paper's (a, b), (c, d), (e, f) split at W = 1 is one panel
here). The impacts of each swept point are coloured by the
point's regime (vines.plotting.sweep_regimes): 1:1 points large and opaque, the others
small and faint, so the 1:1 windows stand out; the companion figure fig14_regimes shows the
same regimes flat over (eta, W). The legend lists the regimes drawn (a point without
impacts draws nothing)."""
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import MaxNLocator

import vines.plotting as P
from vines.pipeline.jobs import run_job

#: impacts drawn per swept point (the last ones recorded), keeps the 3-D scatter readable
MAX_PER_POINT = 12
#: marker size and opacity: 1:1 points (emphasised) and all other points
STYLE_1TO1 = {"s": 2.5, "alpha": 0.9}
STYLE_OTHER = {"s": 0.5, "alpha": 0.35}
#: view (elevation, azimuth): eta across, W into depth, seen from low and from the side of
#: small W, so that the two branches (w' > 0 and w' < 0) of consecutive W rows separate
VIEW = (14, -52)
#: figure width and height per panel (inches): a 3-D box of this aspect seen from VIEW
#: fills a panel about 1.9 times as wide as it is high, so the page holds no empty margins
#: and the 8-9 pt labels read at their size
FIG_SIZE = (6.0, 3.2)


def panel(ax, s, W_sel, codes) -> set:
    """The impacts of the sweep points at the omega values W_sel, coloured by regime;
    returns the regime codes drawn (a point without impacts draws nothing)."""
    drawn = set()
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
                drawn.add(code)
    return drawn


def main(sm):
    P.configure(sm)
    sweeps = [P.sweep(p) for p in sm.input.sweeps]
    for s, p in zip(sweeps, sm.input.sweeps, strict=False):
        if s.attrs.get("swept_parameter") != "eta" or s.attrs.get("outer_parameter") != "omega":
            raise P.FigureInputError(f"{p}: Fig 14 needs eta sweeps at several W, got "
                                     f"{s.attrs.get('swept_parameter')!r} over "
                                     f"{s.attrs.get('outer_parameter')!r}")
    Fs = [P.sweep_fixed(s, "F") for s in sweeps]
    n, drawn = len(sweeps), set()
    fig = plt.figure(figsize=(FIG_SIZE[0], FIG_SIZE[1] * n), constrained_layout=True)
    for r, k in enumerate(np.argsort(Fs)):
        s, codes = sweeps[k], P.sweep_regimes(sweeps[k])
        W = np.unique(s["outer_value"].values)
        ax = fig.add_subplot(n, 1, r + 1, projection="3d")
        drawn |= panel(ax, s, W, codes)
        ax.set_ylim(W.min(), W.max())
        ax.set_xlabel(P.LABELS["eta"], fontsize=9)
        ax.set_ylabel(r"$\Omega$", fontsize=9)
        ax.set_zlabel(r"$\dot w_i$", fontsize=9)
        ax.tick_params(labelsize=8, pad=1)
        ax.yaxis.set_major_locator(MaxNLocator(4))      # Omega ticks that do not touch
        ax.zaxis.set_major_locator(MaxNLocator(5))
        ax.view_init(*VIEW)
        ax.set_box_aspect((1.7, 1.0, 0.75), zoom=1.4)
        P.panel_label(ax, r, rf"$F$ = {P.fmt(Fs[k])}")
    handles = [plt.Line2D([], [], ls="", marker="o", ms=5, color=col, label=lab)
               for code, (lab, col) in P.REGIMES.items() if code in drawn]
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=8,
               frameon=False, title="regime of the swept point (from its recorded impacts)",
               title_fontsize=8)
    P.save(fig, sm.output.pdf, sm.output.png, dpi=170)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
