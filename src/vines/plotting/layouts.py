"""Multi-panel layouts shared by several figures (Figs 4, 5, 9, 10 and Figs 6, 15)."""
from __future__ import annotations

import numpy as np
import xarray as xr

from .checks import sweep_points
from .draw import (
    LABELS,
    SYMBOLS,
    bifurcation_dots,
    branch_lines,
    eigenvalue_panel,
    figure,
    fit_y_to_window,
    fmt,
    impact_handles,
    impact_phase_panel,
    panel_label,
    th_title,
    time_history,
)

#: a zoom window is the stable 1:1 interval widened by this fraction of its width each side
ZOOM_PAD = 0.6


def time_history_figure(ds: xr.Dataset):
    """Figs 4, 5, 9, 10: one row per point: time history of the last periods with the
    impacts marked by direction of motion and wall (a, c), phase portraits over those periods (dark) and the whole
    measurement window (light) (b, d), |w'_i| against the impact phase of every impact of
    the window (third column, titled after the row's time history)."""
    n = ds.sizes["point"]
    fig, axes = figure(n, 3, width=12.0, height=2.9 * n,
                       gridspec_kw={"width_ratios": [1.8, 1, 0.9]})
    window = _window_text(ds)
    for i in range(n):
        time_history(axes[i, 0], axes[i, 1], ds, i)
        impact_phase_panel(axes[i, 2], ds, i)
        panel_label(axes[i, 0], 2 * i, th_title(ds, i))
        panel_label(axes[i, 1], 2 * i + 1, f"light: {window}, dark: as ({chr(97 + 2 * i)})"
                    if "window_t" in ds.variables else None)
        axes[i, 2].set_title(f"impacts of ({chr(ord('a') + 2 * i)}), {window}", loc="left",
                             fontsize=9)
    lines = axes[0, 0].get_legend_handles_labels()[0]     # same colours in (b, d)
    fig.legend(handles=lines + impact_handles(), loc="outside lower center", ncol=3,
               fontsize=7.5, frameon=False, title="impacts: direction of motion just before "
               "impact", title_fontsize=7.5)
    return fig


def _window_text(ds: xr.Dataset) -> str:
    """'tau in [a, b]' of the whole-window samples (or of the impacts when none)."""
    t = ds["window_t"].values if "window_t" in ds.variables else ds["impact_t"].values
    if t.size == 0:
        return ""
    return rf"$\tau \in$ [{np.min(t):.0f}, {np.max(t):.0f}]"


def zoom_range(br: xr.Dataset):
    """The eta window of a zoom: the stable 1:1 interval (else the admissible one) widened
    by ``ZOOM_PAD`` times its width on each side, within the branch's range."""
    adm = br["admissible"].values.astype(bool)
    st = br["stable"].values.astype(bool) & adm
    eta = br["eta"].values
    sel = st if st.any() else adm
    if not sel.any():
        return float(eta.min()), float(eta.max())
    a, b = float(eta[sel].min()), float(eta[sel].max())
    w = max(b - a, 0.02 * float(eta.max() - eta.min()))
    return max(float(eta.min()), a - ZOOM_PAD * w), min(float(eta.max()), b + ZOOM_PAD * w)


def zoom_figure(sw: xr.Dataset, branches, outer_dim: str):
    """Figs 6, 15: per branch a row of (zoomed bifurcation + analytic 1:1, |lambda|), the
    bifurcation panel's y range fitted to what it shows of the zoom window; the legend below
    the figure (``zoom_legend``, once every curve is drawn)."""
    n = len(branches)
    fig, axes = figure(n, 2, width=10.0, height=3.2 * n + 0.8)
    for i, br in enumerate(branches):
        outer = float(br[outer_dim].values[0])
        ax, axl = axes[i]
        x, y = sweep_points(sw, outer)
        lo, hi = zoom_range(br)
        sel = (x >= lo) & (x <= hi)
        bifurcation_dots(ax, x[sel], y[sel], s=1.5, label="numerical")
        branch_lines(ax, br)
        ax.set_xlim(lo, hi)
        fit_y_to_window(ax)
        ax.set_xlabel(LABELS["eta"])
        ax.set_ylabel(LABELS["dw"])
        others = ", ".join(f"${SYMBOLS[k]}$ = {fmt(float(br[k].values[0]))}"
                           for k in ("F", "omega"))
        panel_label(ax, 2 * i, others)
        eigenvalue_panel(axl, br)
        axl.set_xlim(lo, hi)
        panel_label(axl, 2 * i + 1, others)
    return fig


def zoom_legend(fig):
    """One legend below a zoom figure: every label drawn on its panels, once."""
    seen = {}
    for ax in fig.axes:
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            seen.setdefault(lab, h)
    fig.legend(list(seen.values()), list(seen), loc="outside lower center", ncol=4,
               fontsize=7.5, frameon=False, markerscale=3)
