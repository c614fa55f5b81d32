"""The measures against one parameter (Figs 2, 8, 13): x_max (m, vermillion circles, left
axis) and the KE ratio (blue stars, right axis) of measures grids, along a grid's only
axis (Fig 2) or on sections of two-parameter grids at marked values (Figs 8, 13)."""
from __future__ import annotations

import numpy as np

from .checks import fixed_value, marked_sections
from .draw import LABELS, SYMBOLS, figure, fmt, panel_label, twin_measures


def along_eta_figure(grids):
    """Fig 2: one panel per grid (sorted), measures against eta with a dashed line at the
    KE-ratio peak and one legend per panel."""
    fig, axes = figure(1, len(grids), width=5.0 * len(grids), height=3.6)
    for i, ds in enumerate(grids):
        ax = axes[0, i]
        eta = ds["eta"].values
        ke = ds["ke_ratio"].values.ravel()
        xm = ds["xmax_m"].values.ravel()
        ax2 = twin_measures(ax, eta, ke, xm, LABELS["eta"])
        k = int(np.argmax(ke))
        ax.axvline(eta[k], color="0.6", lw=0.8, ls="--")
        panel_label(ax, i, rf"$F$ = {fmt(fixed_value(ds, 'F'))}, "
                           rf"$\Omega$ = {fmt(fixed_value(ds, 'omega'))}")
        h1, l1 = ax.get_legend_handles_labels()
        h2, l2 = ax2.get_legend_handles_labels()
        ax.legend(h1 + h2, l1 + l2, fontsize=7, loc="upper right")
    return fig


def sections_figure(grids, cut: str, along: str, prefix: str, panel_height: float):
    """Figs 8 (``cut`` F ``along`` eta, grids over (eta, F) at one omega each) and 13
    (``cut`` eta ``along`` omega, grids over (eta, omega) at one F each): the measures
    against ``along`` on the sections at the ``cut`` values marked in the grids (``section_<cut>``, the same in all
    ``prefix``_* grids); rows F, columns the other parameter (omega or eta), each panel
    titled by its F and that parameter."""
    values = marked_sections(grids, cut, prefix)
    fixed = next(d for d in ("eta", "omega", "F") if d not in (cut, along))
    cells = [[(ds, v) for ds in grids] for v in values]
    if cut != "F":              # rows F: the grids' fixed F, columns the cut values
        cells = [list(col) for col in zip(*cells, strict=True)]
    nr, nc = len(cells), len(cells[0])
    fig, axes = figure(nr, nc, width=4.4 * nc, height=panel_height * nr)
    for i, row in enumerate(cells):
        for j, (ds, v) in enumerate(row):
            s = ds.sel({cut: v}).isel({fixed: 0})
            ax = axes[i, j]
            twin_measures(ax, s[along].values, s["ke_ratio"].values, s["xmax_m"].values,
                          LABELS[along])
            at = {cut: v, fixed: fixed_value(ds, fixed)}
            other = fixed if cut == "F" else cut
            panel_label(ax, i * nc + j, rf"$F$ = {fmt(at['F'])}, "
                                        rf"${SYMBOLS[other]}$ = {fmt(at[other])}")
    return fig
