"""Bifurcation sweeps on figures: the diagrams of w'_i against eta (Fig 3, with the leading
Lyapunov exponent under them: fig3_lyapunov), the 3-D diagrams over (eta, W) coloured by
regime (Fig 14) and the regimes flat over (eta, W) (fig14_regimes)."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.ticker import MaxNLocator

from . import palette
from .checks import FigureInputError, load, require, sweep_fixed, sweep_points
from .draw import (
    LABELS,
    SYMBOLS,
    bifurcation_dots,
    class_handles,
    class_map,
    figure,
    fmt,
    panel_label,
)
from .sweep_regimes import REGIME_ASYM, REGIME_SYM, REGIMES, regime_grid, sweep_regimes

#: Lyapunov exponents of the two sweep directions: (label, colour, marker)
DIRECTIONS = {1: ("up", palette.C_TOWARDS, "o"), -1: ("down", palette.C_SAME_WAY, "s")}
#: Fig 14: impacts drawn per swept point (the last ones recorded), keeps the 3-D scatter
#: readable
MAX_PER_POINT = 12
#: Fig 14: marker size and opacity: 1:1 points (emphasised) and all other points
STYLE_1TO1 = {"s": 2.5, "alpha": 0.9}
STYLE_OTHER = {"s": 0.5, "alpha": 0.35}
#: Fig 14: view (elevation, azimuth): eta across, W into depth, seen from low and from the
#: side of small W, so that the two branches (w' > 0 and w' < 0) of consecutive W rows
#: separate
VIEW = (14, -52)
#: Fig 14: figure width and height per panel (inches): a 3-D box of this aspect seen from
#: VIEW fills a panel about 1.9 times as wide as it is high, so the page holds no empty
#: margins and the 8-9 pt labels read at their size
FIG_SIZE = (6.0, 3.2)
#: fig14_regimes: the frequency ratio whose 1:1 window the text discusses
OMEGA_TEXT = 1.0


# ------------------------------------------------------------------ Fig 3, fig3_lyapunov

def _eta_sweep(sw):
    """The outer parameter's name and values of an eta sweep (else FigureInputError)."""
    if sw.attrs.get("swept_parameter") != "eta":
        raise FigureInputError(f"{sw.attrs.get('_path')}: Fig 3 sweeps eta, the dataset "
                               f"sweeps {sw.attrs.get('swept_parameter')!r}")
    return sw.attrs.get("outer_parameter", "F"), np.unique(sw["outer_value"].values)


def _diagram_panel(ax, sw, outer_name, o, i):
    """The impacts of the sweep at outer value ``o`` as black dots, panel (i)."""
    x, y = sweep_points(sw, o)
    bifurcation_dots(ax, x, y, s=1.0)
    ax.axhline(0, color="0.7", lw=0.5)
    ax.set_ylabel(LABELS["dw"])
    title = rf"${SYMBOLS[outer_name]}$ = {fmt(o)}, {sw.attrs.get('fixed', '')}"
    panel_label(ax, i, title.replace("omega=", r"$\Omega$ = "))


def diagram_figure(sw):
    """Fig 3: w'_i against eta, one panel per outer value of the sweep ``sw``."""
    outer_name, outers = _eta_sweep(sw)
    fig, axes = figure(1, len(outers), width=5.0 * len(outers), height=3.6)
    for i, o in enumerate(outers):
        axes[0, i].set_xlabel(LABELS["eta"])
        _diagram_panel(axes[0, i], sw, outer_name, o, i)
    return fig


def lyapunov(path):
    """A Lyapunov dataset of a sweep (stage ``lyapunov``), checked."""
    ds = load(path)
    require(ds, variables=("value", "outer_value", "direction", "lambda_1", "exponents_ci"),
            finite=("value", "outer_value"))
    return ds


def _exponent_panel(ax, ly, outer):
    at = np.isclose(ly["outer_value"].values, outer, rtol=0, atol=1e-9)
    if not at.any():
        raise FigureInputError(f"{ly.attrs['_path']}: no exponents at outer value {outer}")
    for code, (label, colour, marker) in DIRECTIONS.items():
        sel = at & (ly["direction"].values == code)
        x, lam = ly["value"].values[sel], ly["lambda_1"].values[sel]
        ci = ly["exponents_ci"].values[sel, 0, :]
        err = np.abs(np.vstack([lam - ci[:, 0], ci[:, 1] - lam]))
        ax.errorbar(x, lam, yerr=err, fmt=marker, ms=2.5, lw=0.6, color=colour,
                    mfc="none" if code < 0 else colour, label=f"sweep {label}")
    ax.axhline(0, color="0.4", lw=0.6)
    ax.set_xlabel(LABELS["eta"])
    ax.set_ylabel(r"$\lambda_1$ (per unit time)")


def diagram_lyapunov_figure(sw, ly):
    """fig3_lyapunov: Fig 3's panels and under each the leading Lyapunov exponent of every
    sweep point (``ly``) with its 95 % batch-means interval, up and down sweeps apart."""
    outer_name, outers = _eta_sweep(sw)
    fig, axes = figure(2, len(outers), width=5.0 * len(outers), height=6.0,
                       sharex="col", gridspec_kw={"height_ratios": [3, 2]})
    t_window = ly.attrs.get("window", "")
    for i, o in enumerate(outers):
        _diagram_panel(axes[0, i], sw, outer_name, o, i)
        _exponent_panel(axes[1, i], ly, o)
        panel_label(axes[1, i], len(outers) + i,
                    r"leading Lyapunov exponent $\lambda_1$ (finite time)")
    axes[1, -1].legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7,
                       frameon=False)
    fig.supxlabel(f"exponents over the {t_window}; intervals: 95 % batch means",
                  fontsize=7)
    return fig


# ------------------------------------------------------------------ Fig 14

def _regime_scatter(ax, s, W_sel, codes) -> set:
    """The impacts of the sweep points at the omega values W_sel, coloured by regime;
    returns the regime codes drawn (a point without impacts draws nothing)."""
    drawn = set()
    W_pt = s["outer_value"].values
    for w in W_sel:
        pts = np.flatnonzero(np.isclose(W_pt, w, rtol=0, atol=1e-9))
        x, y = sweep_points(s, w, max_per_point=MAX_PER_POINT)
        # the regime of each impact's point (sweep_points keeps the points' order)
        n_kept = [min(int(s["row_size"].values[i]), MAX_PER_POINT) for i in pts]
        c = np.repeat(codes[pts], n_kept)
        for code, (_, colour) in REGIMES.items():
            m = c == code
            if m.any():
                style = STYLE_1TO1 if code in (REGIME_SYM, REGIME_ASYM) else STYLE_OTHER
                ax.scatter(x[m], np.full(m.sum(), w), y[m], c=colour, linewidths=0,
                           depthshade=False, rasterized=True, **style)
                drawn.add(code)
    return drawn


def diagram_3d_figure(sweeps):
    """Fig 14: per sweep (eta sweeps at several W, stacked by F) a 3-D scatter of the last
    impacts of every point over (eta, W), coloured by the point's regime; one legend of the
    regimes drawn."""
    for s in sweeps:
        if s.attrs.get("swept_parameter") != "eta" or s.attrs.get("outer_parameter") != "omega":
            raise FigureInputError(f"{s.attrs.get('_path')}: Fig 14 needs eta sweeps at "
                                   f"several W, got {s.attrs.get('swept_parameter')!r} over "
                                   f"{s.attrs.get('outer_parameter')!r}")
    Fs = [sweep_fixed(s, "F") for s in sweeps]
    n, drawn = len(sweeps), set()
    fig = plt.figure(figsize=(FIG_SIZE[0], FIG_SIZE[1] * n), constrained_layout=True)
    for r, k in enumerate(np.argsort(Fs)):
        s, codes = sweeps[k], sweep_regimes(sweeps[k])
        W = np.unique(s["outer_value"].values)
        ax = fig.add_subplot(n, 1, r + 1, projection="3d")
        drawn |= _regime_scatter(ax, s, W, codes)
        ax.set_ylim(W.min(), W.max())
        ax.set_xlabel(LABELS["eta"], fontsize=9)
        ax.set_ylabel(r"$\Omega$", fontsize=9)
        ax.set_zlabel(r"$\dot w_i$", fontsize=9)
        ax.tick_params(labelsize=8, pad=1)
        ax.yaxis.set_major_locator(MaxNLocator(4))      # Omega ticks that do not touch
        ax.zaxis.set_major_locator(MaxNLocator(5))
        ax.view_init(*VIEW)
        ax.set_box_aspect((1.7, 1.0, 0.75), zoom=1.4)
        panel_label(ax, r, rf"$F$ = {fmt(Fs[k])}")
    handles = [plt.Line2D([], [], ls="", marker="o", ms=5, color=col, label=lab)
               for code, (lab, col) in REGIMES.items() if code in drawn]
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=8,
               frameon=False, title="regime of the swept point (from its recorded impacts)",
               title_fontsize=8)
    return fig


# ------------------------------------------------------------------ fig14_regimes

def window_text(xs, ys, grid) -> str:
    """'1:1 at W = 1: eta in [a, b]' (or 'none') from the regime grid of one sweep."""
    j = np.flatnonzero(np.isclose(ys, OMEGA_TEXT, rtol=0, atol=1e-9))
    if j.size == 0:
        return ""
    one = np.isin(grid[j[0]], (REGIME_SYM, REGIME_ASYM))
    if not one.any():
        return r"1:1 at $\Omega$ = 1: none"
    return (rf"1:1 at $\Omega$ = 1: $\eta \in$ [{xs[one].min():.3g}, {xs[one].max():.3g}]"
            f" ({int(one.sum())} points)")


def regimes_figure(sweeps, exponents: dict):
    """fig14_regimes: per sweep (sorted by F) the regime of every point over (eta, W), the
    up sweep as cells, a white dot where the down sweep differs; irregular points split by
    the leading Lyapunov exponent of ``exponents[<sweep name>]``."""
    n = len(sweeps)
    fig, axes = figure(1, n, width=4.2 * n + 2.4, height=4.2)
    regimes = palette.REGIMES_SPLIT
    keys = sorted(regimes)
    for j, s in enumerate(sweeps):
        ax = axes[0, j]
        name = Path(s.attrs["_path"]).stem
        ly = exponents.get(name)
        if ly is None:
            raise FigureInputError(f"no lyapunov dataset of sweep {name!r} "
                                   f"(have {sorted(exponents)})")
        xs, ys, up = regime_grid(s, +1, lyapunov=ly)
        class_map(ax, xs, ys, up, regimes)
        xd, yd, down = regime_grid(s, -1, lyapunov=ly)
        if down.shape == up.shape and np.allclose(xd, xs) and np.allclose(yd, ys):
            jj, ii = np.nonzero((down != up) & (down >= 0) & (up >= 0))
            ax.plot(xs[ii], ys[jj], ".", color="white", ms=1.5, mec="none")
        ax.axhline(OMEGA_TEXT, color="red", lw=0.8, ls="--")
        ax.set_xlabel(LABELS["eta"])
        ax.set_ylabel(LABELS["omega"])
        panel_label(ax, j, rf"$F$ = {fmt(sweep_fixed(s, 'F'))}")
        ax.text(0.02, 0.02, window_text(xs, ys, up), transform=ax.transAxes, fontsize=7,
                color="black", bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
        print(f"{s.attrs.get('fixed')}: {window_text(xs, ys, up)}; up-sweep regime counts "
              f"{ {regimes[k][0]: int((up == k).sum()) for k in keys} }")
    handles = class_handles(regimes) + [
        Line2D([], [], ls="", marker="o", ms=3, mfc="white", mec="0.5",
               label="down sweep differs"),
        Line2D([], [], color="red", ls="--", lw=0.8, label=r"$\Omega$ = 1")]
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False)
    return fig
