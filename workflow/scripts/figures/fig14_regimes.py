"""Companion of Fig 14 (not in the paper): the regime of every swept point over (eta, W),
one panel per F, from the same sweeps (fig14_*) and the same classification
(vines.plotting.sweep_regimes). Cells: the upward sweep in eta; a white dot where the
downward sweep ends in another regime (hysteresis). Irregular points are split by their
leading Lyapunov exponent (lyapunov datasets fig14_*, same sweeps): chaotic, quasi-periodic,
or irregular with lambda_1 < 0. The eta range of the 1:1 window at W = 1 is written in each
panel."""
from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D

import vines.plotting as P
from vines.pipeline.jobs import run_job

#: the frequency ratio whose 1:1 window the text discusses
OMEGA_TEXT = 1.0


def window_text(xs, ys, grid) -> str:
    """'1:1 at W = 1: eta in [a, b]' (or 'none') from the regime grid of one sweep."""
    j = np.flatnonzero(np.isclose(ys, OMEGA_TEXT, rtol=0, atol=1e-9))
    if j.size == 0:
        return ""
    one = np.isin(grid[j[0]], (P.REGIME_SYM, P.REGIME_ASYM))
    if not one.any():
        return r"1:1 at $\Omega$ = 1: none"
    return (rf"1:1 at $\Omega$ = 1: $\eta \in$ [{xs[one].min():.3g}, {xs[one].max():.3g}]"
            f" ({int(one.sum())} points)")


def main(sm):
    P.configure(sm)
    sweeps = sorted((P.sweep(p) for p in sm.input.sweeps), key=lambda s: P.sweep_fixed(s, "F"))
    exponents = {}
    for path in sm.input.lyapunov:
        ly = P.load(path)
        exponents[ly.attrs["sweep"]] = ly
    n = len(sweeps)
    fig, axes = P.figure(1, n, width=4.2 * n + 2.4, height=4.2)
    regimes = P.palette.REGIMES_SPLIT
    keys = sorted(regimes)
    for j, s in enumerate(sweeps):
        ax = axes[0, j]
        name = Path(s.attrs["_path"]).stem
        ly = exponents.get(name)
        if ly is None:
            raise P.FigureInputError(f"no lyapunov dataset of sweep {name!r} "
                                     f"(have {sorted(exponents)})")
        xs, ys, up = P.regime_grid(s, +1, lyapunov=ly)
        P.class_map(ax, xs, ys, up, regimes)
        xd, yd, down = P.regime_grid(s, -1, lyapunov=ly)
        if down.shape == up.shape and np.allclose(xd, xs) and np.allclose(yd, ys):
            jj, ii = np.nonzero((down != up) & (down >= 0) & (up >= 0))
            ax.plot(xs[ii], ys[jj], ".", color="white", ms=1.5, mec="none")
        ax.axhline(OMEGA_TEXT, color="red", lw=0.8, ls="--")
        ax.set_xlabel(P.LABELS["eta"])
        ax.set_ylabel(P.LABELS["omega"])
        P.panel_label(ax, j, rf"$F$ = {P.fmt(P.sweep_fixed(s, 'F'))}")
        ax.text(0.02, 0.02, window_text(xs, ys, up), transform=ax.transAxes, fontsize=7,
                color="black", bbox={"facecolor": "white", "alpha": 0.8, "lw": 0})
        print(f"{s.attrs.get('fixed')}: {window_text(xs, ys, up)}; up-sweep regime counts "
              f"{ {regimes[k][0]: int((up == k).sum()) for k in keys} }")
    handles = P.class_handles(regimes) + [Line2D([], [], ls="", marker="o", ms=3, mfc="white", mec="0.5",
                       label="down sweep differs"),
                Line2D([], [], color="red", ls="--", lw=0.8, label=r"$\Omega$ = 1")]
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
