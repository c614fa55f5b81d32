"""Bifurcation structure on the figures: asymmetric 1:1 branches (Figs 6, 15) and boundary
curves of the stability classes (Figs 12, 16).

Reads the datasets of the ``map_solve`` stage (a ragged array of branches: row 0 the
continued branch, then the asymmetric branches born at its symmetry-breaking points) and
of the ``boundaries`` stage (a ragged array of curves in (eta, omega) at one F).
"""
from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib import patheffects
from matplotlib.lines import Line2D
from matplotlib.ticker import MaxNLocator

from ..data.builders import ragged_rows
from . import palette
from .checks import FigureInputError, load, require, sweep_points
from .draw import (
    CLASSES,
    LABELS,
    bifurcation_dots,
    branch_lines,
    class_handles,
    class_map,
    figure,
    fit_y_to_window,
    fmt,
    panel_label,
    stable_edge,
    stable_edge_handle,
)
from .layouts import zoom_figure, zoom_legend
from .stable_region import class_raster, stable_at
from .sweep_regimes import REGIME_ASYM, sweep_regimes

#: colour of the asymmetric 1:1 branches (the symmetric one is C_BRANCH)
C_ASYMMETRIC = palette.C_ASYMMETRIC
#: colour of each boundary curve type, line style of each family (drawn over a thin white
#: halo, so they show on every class colour and colour map)
CURVE_COLOURS = {"fold": palette.OKABE_ITO["blue"], "flip": palette.OKABE_ITO["reddish purple"],
                 "neimark-sacker": palette.OKABE_ITO["bluish green"],
                 "symmetry-breaking": palette.OKABE_ITO["vermillion"],
                 "grazing": "#A6761D"}
FAMILY_STYLES = {"symmetric": "-", "asymmetric": (0, (4, 1.6))}
#: line style of the families beyond 1:1 (``LLRR/1-sym``...; on the orbit atlas, no 1:1
#: curves beside them): solid, the panel names the family
OTHER_FAMILY_STYLE = "-"
#: what a grazing curve is, for captions and legends
GRAZING_NOTE = ("the orbit touches a wall with zero relative velocity;\nbeyond it the ball "
                "would cross the wall:\nno admissible 1:1 orbit there")
HALO = [patheffects.Stroke(linewidth=2.4, foreground="white"), patheffects.Normal()]


# ------------------------------------------------------------------ branches (Figs 6, 15)

def _rows(br: xr.Dataset) -> list[slice]:
    """The point slice of every branch of a branch dataset (one slice if not ragged)."""
    if "row_size" not in br:
        return [slice(0, br.sizes["point"])]
    edges = np.concatenate([[0], np.cumsum(br["row_size"].values)])
    return [slice(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:], strict=False)]


def continued_branches(branches) -> list[xr.Dataset]:
    """The continued branch (row 0) of each branch dataset, as the zoom figures draw it."""
    return [br.isel(point=_rows(br)[0]) for br in branches]


def switched_branches(br: xr.Dataset) -> list[xr.Dataset]:
    """The branches switched onto at symmetry-breaking points (rows 1, 2, ...)."""
    return [br.isel(point=s) for s in _rows(br)[1:] if s.stop > s.start]


def _branch_curves(ax, sub: xr.Dataset, label: bool):
    adm = sub["admissible"].values.astype(bool)
    st = sub["stable"].values.astype(bool) & adm
    eta = sub["eta"].values
    for k, key in enumerate(("dw_L", "dw_R")):
        for mask, ls, lab in ((st, "-", "analytic asymmetric 1:1, stable"),
                              (adm & ~st, ":", "analytic asymmetric 1:1, unstable")):
            ax.plot(eta, np.where(mask, sub[key].values, np.nan), ls, color=C_ASYMMETRIC,
                    lw=1.4, label=lab if (label and k == 0) else None)


def draw_switched(fig, branches, sweep=None, outer_dim=None):
    """Add the asymmetric branches of each branch dataset to a zoom figure (row i of
    ``fig``: bifurcation panel, |lambda| panel): impact velocities (solid stable, dotted
    unstable) and lambda_max. The x-limits are kept, the bifurcation panel's y range is
    fitted to what it shows (``fit_y_to_window``). Where the asymmetric branches span less
    than ``INSET_BELOW`` of the panel's eta range, an inset zooms on them (with the swept
    points of ``sweep`` at the row's ``outer_dim`` value when given)."""
    axes = fig.axes
    for i, br in enumerate(branches):
        ax, axl = axes[2 * i], axes[2 * i + 1]
        subs = switched_branches(br)
        lims = ax.get_xlim(), ax.get_ylim(), axl.get_xlim(), axl.get_ylim()
        for j, sub in enumerate(subs):
            _branch_curves(ax, sub, label=j == 0)
            adm = sub["admissible"].values.astype(bool)
            axl.plot(sub["eta"].values, np.where(adm, sub["lambda_max"].values, np.nan), "-",
                     color=C_ASYMMETRIC, lw=1.2,
                     label=r"$|\lambda_{\max}|$ asymmetric" if j == 0 else None)
        ax.set_xlim(lims[0])
        fit_y_to_window(ax)
        axl.set_xlim(lims[2])
        axl.set_ylim(lims[3])
        if subs:
            _inset(ax, br, subs, sweep, outer_dim)


#: an inset zooms on the asymmetric branches when they span less than this fraction of the
#: panel's eta range
INSET_BELOW = 0.15


#: inset size (axes fraction: width, height), the smallest fraction of it an inset may be
#: scaled down to where the full size finds no empty place, and the margins kept free
#: around it: its tick labels below and left
INSET_SIZE = (0.36, 0.34)
INSET_MIN_SCALE = 0.6
INSET_MARGIN = {"left": 0.07, "right": 0.02, "below": 0.08, "above": 0.02}


def _drawn_points(ax) -> np.ndarray:
    """Every drawn point of ``ax`` in axes fraction (lines sampled along their segments)."""
    pts = [np.asarray(c.get_offsets(), float).reshape(-1, 2) for c in ax.collections]
    for ln in ax.lines:
        xy = np.asarray(ln.get_xydata(), float).reshape(-1, 2)
        if len(xy) > 1:
            t = np.linspace(0.0, 1.0, 20)[:, None, None]
            xy = (xy[:-1] + t * (xy[1:] - xy[:-1])).reshape(-1, 2)
        pts.append(xy)
    xy = np.concatenate(pts or [np.empty((0, 2))])
    xy = xy[np.all(np.isfinite(xy), axis=1)]
    frac = (ax.transData + ax.transAxes.inverted()).transform(xy) if xy.size else xy
    return frac[(frac[:, 0] >= 0) & (frac[:, 0] <= 1) & (frac[:, 1] >= 0) & (frac[:, 1] <= 1)]


def _covered(frac, box) -> int:
    """Drawn points (axes fraction) inside ``box`` with its margins."""
    m = INSET_MARGIN
    return int(np.sum((frac[:, 0] >= box[0] - m["left"]) & (frac[:, 0] <= box[0] + box[2] + m["right"])
                      & (frac[:, 1] >= box[1] - m["below"])
                      & (frac[:, 1] <= box[1] + box[3] + m["above"])))


def _empty_box(frac, w, h):
    """The first box of size (w, h) (axes fraction) on a grid of positions, upper right
    first, that covers no point of ``frac`` with its margins; None if there is none."""
    m = INSET_MARGIN
    for y0 in np.linspace(1 - m["above"] - h, m["below"], 25):
        for x0 in np.linspace(1 - m["right"] - w, m["left"], 25):
            if _covered(frac, [x0, y0, w, h]) == 0:
                return [float(x0), float(y0), w, h]
    return None


def _outline(ax, rect) -> np.ndarray:
    """Points along the outline of ``rect`` = (x0, x1, y0, y1) (data) in axes fraction."""
    x0, x1, y0, y1 = rect
    t = np.linspace(0.0, 1.0, 50)
    xy = np.concatenate([np.c_[x0 + t * (x1 - x0), np.full_like(t, y)] for y in (y0, y1)]
                        + [np.c_[np.full_like(t, x), y0 + t * (y1 - y0)] for x in (x0, x1)])
    return (ax.transData + ax.transAxes.inverted()).transform(xy)


def _inset_box(ax, zoomed=None):
    """An inset box (axes fraction) that covers no drawn point of ``ax`` nor the outline
    of the ``zoomed`` rectangle (x0, x1, y0, y1; data) marked on the panel: the largest
    empty one from ``INSET_SIZE`` down to ``INSET_MIN_SCALE`` of it; when there is none,
    the panel's y range is extended upwards until a band at the top holds the inset (the
    data keep their place, the panel gains headroom)."""
    w, h = INSET_SIZE
    m = INSET_MARGIN
    frac = _drawn_points(ax)
    avoid = frac if zoomed is None else np.concatenate([frac, _outline(ax, zoomed)])
    for scale in np.linspace(1.0, INSET_MIN_SCALE, 9):
        box = _empty_box(avoid, w * scale, h * scale)
        if box is not None:
            return box
    lo, hi = ax.get_ylim()
    top = lo + (hi - lo) * float(frac[:, 1].max()) if frac.size else lo
    if zoomed is not None:
        top = max(top, zoomed[3])
    band = h + m["above"] + m["below"] + 0.02        # + a gap between data and labels
    ax.set_ylim(lo, (top - band * lo) / (1 - band))
    return [float(1 - m["right"] - w), float(1 - m["above"] - h), w, h]


def _inset(ax, br, subs, sweep, outer_dim):
    """Inset on the admissible part of the asymmetric branches ``subs`` of ``br``."""
    eta = np.concatenate([s["eta"].values[s["admissible"].values.astype(bool)] for s in subs])
    if eta.size == 0:
        return
    lo, hi = ax.get_xlim()
    a, b = float(eta.min()), float(eta.max())
    if b - a >= INSET_BELOW * (hi - lo):
        return
    pad = max(0.5 * (b - a), 1e-3 * (hi - lo))
    a, b = a - pad, b + pad
    ys, dots = [], None
    if sweep is not None:
        x, y = sweep_points(sweep, float(br[outer_dim].values[0]))
        m = (x >= a) & (x <= b)
        dots = x[m], y[m]
        ys.append(y[m])
    for sub in [br.isel(point=_rows(br)[0])] + subs:
        adm = sub["admissible"].values.astype(bool)
        m = adm & (sub["eta"].values >= a) & (sub["eta"].values <= b)
        ys += [sub[k].values[m] for k in ("dw_L", "dw_R")]
    y = np.concatenate(ys) if ys else np.array([])
    y = y[np.isfinite(y)]
    top = 1.1 * float(np.max(np.abs(y))) if y.size else float(np.max(np.abs(ax.get_ylim())))
    ins = ax.inset_axes(_inset_box(ax, zoomed=(a, b, -top, top)))
    if dots is not None:
        ins.scatter(*dots, s=2.0, color="black", linewidths=0, rasterized=True)
    branch_lines(ins, br.isel(point=_rows(br)[0]), label=False)
    for sub in subs:
        _branch_curves(ins, sub, label=False)
    ins.set_xlim(a, b)
    ins.set_ylim(-top, top)
    ins.tick_params(labelsize=6, pad=1.5)
    ins.xaxis.set_major_locator(MaxNLocator(nbins=3, min_n_ticks=2))
    ins.yaxis.set_major_locator(MaxNLocator(nbins=4, min_n_ticks=2))
    ax.indicate_inset_zoom(ins, edgecolor="0.3")


# ------------------------------------------------------------------ boundary curves (Figs 12, 16)

def boundaries(path) -> xr.Dataset:
    """Boundary curves of one F (``boundaries`` stage output)."""
    ds = load(path)
    require(ds, variables=("curve_type", "family", "row_size"), finite=("eta", "omega"))
    if "F" not in ds.attrs:
        raise FigureInputError(f"{path}: global attribute 'F' is missing")
    unknown = set(ds["curve_type"].values.tolist()) - set(CURVE_COLOURS)
    if unknown:
        raise FigureInputError(f"{path}: unknown curve types {sorted(unknown)}")
    return ds


def draw_curves(ax, ds: xr.Dataset, lw: float = 1.2) -> set:
    """Draw every curve of ``ds`` on ``ax`` (axis limits kept): colour by curve type, line
    style by family, width ``lw`` (a white halo around it); returns the (type, family)
    pairs drawn."""
    xlim, ylim = ax.get_xlim(), ax.get_ylim()
    etas, omegas = ragged_rows(ds, "eta"), ragged_rows(ds, "omega")
    kinds = list(zip(ds["curve_type"].values.tolist(), ds["family"].values.tolist(),
                     strict=True))
    for (typ, fam), e, w in zip(kinds, etas, omegas, strict=False):
        ax.plot(e, w, color=CURVE_COLOURS[typ], ls=FAMILY_STYLES.get(fam, OTHER_FAMILY_STYLE),
                lw=lw, path_effects=HALO if lw <= 1.2 else
                [patheffects.Stroke(linewidth=lw + 1.6, foreground="white"),
                 patheffects.Normal()])
    ax.set_xlim(xlim)
    ax.set_ylim(ylim)
    return set(kinds)


def curve_handles(drawn, note=True) -> list:
    """Legend entries of the curve types drawn (colours) and of the 1:1 families (line
    styles; a panel with other families' curves names them itself); ``note``: the grazing
    entry says what grazing is (for the 1:1 family)."""
    types = {t for t, _ in drawn}
    fams = {f for _, f in drawn}
    out = [Line2D([], [], color=CURVE_COLOURS[t], lw=1.6, label=t.replace("-", " ") + " curve"
                  + (f" ({GRAZING_NOTE})" if t == "grazing" and note else ""))
           for t in CURVE_COLOURS if t in types]
    out += [Line2D([], [], color="0.2", ls=FAMILY_STYLES[f], lw=1.2, label=f"{f} 1:1 family")
            for f in FAMILY_STYLES if f in fams]
    return out


def draw_on_panels(fig, axes, F_values, paths, legend=True) -> list:
    """Boundary curves on panels: ``axes[j]`` gets the curves computed at ``F_values[j]``
    (from the boundaries datasets ``paths``). Returns the legend handles of the curve types
    drawn; ``legend``: also draw them as one legend below the figure."""
    by_F = {round(float(ds.attrs["F"]), 9): ds for ds in map(boundaries, paths)}
    drawn = set()
    for ax, F in zip(axes, F_values, strict=False):
        ds = by_F.get(round(float(F), 9))
        if ds is None:
            raise FigureInputError(f"no boundary curves at F = {F} (curves at F = {sorted(by_F)})")
        drawn |= draw_curves(ax, ds)
    handles = curve_handles(drawn)
    if handles and legend:
        fig.legend(handles=handles, loc="outside lower center", ncol=len(handles), fontsize=8,
                   frameon=False, title=f"boundaries in ({LABELS['eta'].split()[-1]}, "
                                        f"{LABELS['omega'].split()[-1]})", title_fontsize=8)
    return handles


# ------------------------------------------------------------------ the figures

#: Fig 16: lower edge of the paper's Omega range (Figs 12, 16), marked when a map extends
#: below it
OMEGA_PAPER_MIN = 0.5
#: Fig 16: W range of the zoom row on the tongue below OMEGA_PAPER_MIN
TONGUE_ZOOM = (0.45, 0.53)


def branches_figure(sw: xr.Dataset, branches, outer_dim: str, mark_asymmetric=False):
    """Figs 6, 15: per branch dataset (one row each) the sweep ``sw`` zoomed with the
    analytic 1:1 branch and the asymmetric branches born on it, and |lambda|; with
    ``mark_asymmetric`` the dots of swept points on a stable asymmetric 1:1 orbit in
    ``C_ASYMMETRIC``, labelled. One legend below."""
    fig = zoom_figure(sw, continued_branches(branches), outer_dim=outer_dim)
    draw_switched(fig, branches, sw, outer_dim)
    if mark_asymmetric:
        codes = sweep_regimes(sw)
        for i, br in enumerate(branches):
            _mark_asymmetric(fig.axes[2 * i], sw, float(br[outer_dim].values[0]), codes)
    zoom_legend(fig)
    return fig


def _mark_asymmetric(ax, sw, outer, codes):
    """Redraw the dots of the points on an asymmetric 1:1 orbit in C_ASYMMETRIC, with a
    label."""
    pts = np.flatnonzero(np.isclose(sw["outer_value"].values, outer, rtol=0, atol=1e-9))
    x, y = sweep_points(sw, outer)
    c = np.repeat(codes[pts], sw["row_size"].values[pts])
    lo, hi = ax.get_xlim()
    m = (c == REGIME_ASYM) & (x >= lo) & (x <= hi)
    if m.any():
        bifurcation_dots(ax, x[m], y[m], s=3.0, color=C_ASYMMETRIC,
                         label="numerical, on a stable asymmetric 1:1 orbit")
        print(f"omega = {outer}: {int(np.unique(x[m]).size)} swept points on an asymmetric "
              f"1:1 orbit, eta {x[m].min():.4g} ... {x[m].max():.4g}")


def _class_panel(ax, m, curves):
    """The classes of the stability map ``m`` (finer than the map, ``class_raster``), its
    stable edge and the boundary curves ``curves``; returns the (type, family) drawn."""
    eta, W = m["eta"].values, m["omega"].values
    class_map(ax, *class_raster(m), CLASSES)
    stable_edge(ax, m)
    if W.min() < OMEGA_PAPER_MIN:
        ax.axhline(OMEGA_PAPER_MIN, color="black", ls="--", lw=0.9)
    ax.set_xlim(eta.min(), eta.max())
    ax.set_ylim(W.min(), W.max())
    ax.set_xlabel(LABELS["eta"])
    ax.set_ylabel(LABELS["omega"])
    for s in ax.spines.values():
        s.set_edgecolor("black")
    return draw_curves(ax, curves)


def class_figure(maps, curves: dict):
    """Fig 16: per stability map (one column each, sorted by F) its classes over (eta, W)
    with the boundary curves ``curves[F]``; a zoom row on the tongue below
    ``OMEGA_PAPER_MIN`` when a map extends below it; one legend on the right."""
    n = len(maps)
    zoom = any(float(m["omega"].min()) < OMEGA_PAPER_MIN for m in maps)
    fig, axes = figure(2 if zoom else 1, n, width=4.0 * n + 2.2, height=6.4 if zoom else 3.9,
                       gridspec_kw={"height_ratios": [2.2, 1]} if zoom else {})
    drawn = set()
    for j, m in enumerate(maps):
        F = float(m.attrs["F"])
        if round(F, 9) not in curves:
            raise FigureInputError(f"no boundary curves at F = {F} (curves at F = "
                                   f"{sorted(curves)})")
        for i in range(axes.shape[0]):
            drawn |= _class_panel(axes[i, j], m, curves[round(F, 9)])
        panel_label(axes[0, j], j, rf"$F$ = {fmt(F)}")
        if zoom:
            W = m["omega"].values
            axes[1, j].set_ylim(max(TONGUE_ZOOM[0], W.min()), TONGUE_ZOOM[1])
            panel_label(axes[1, j], n + j, rf"$F$ = {fmt(F)}, zoom: tongue below "
                                           rf"$\Omega$ = {fmt(OMEGA_PAPER_MIN)}")
            axes[0, j].axhspan(*axes[1, j].get_ylim(), fill=False, ec="0.3", lw=0.7, ls=":")
        keys = sorted(CLASSES)
        counts = {k: int((m["cls"].values == k).sum()) for k in keys}
        stable_05 = stable_at(m, m["eta"].values, np.array([OMEGA_PAPER_MIN]))
        print(f"F = {F}: class counts {counts}; stable at W = {OMEGA_PAPER_MIN} for "
              f"{int(stable_05.sum())} of {stable_05.size} eta values")
    handles = class_handles(CLASSES, {1: r" ($|\lambda_{\max}| < 1$)",
                                      2: r" ($|\lambda_{\max}| < 1$)",
                                      3: r" ($|\lambda_{\max}| > 1$)"})
    handles.append(stable_edge_handle(r"$|\lambda_{\max}| = 1$ (interpolated)"))
    if zoom:
        handles.append(Line2D([], [], color="black", ls="--", lw=0.9,
                              label=rf"$\Omega$ = {fmt(OMEGA_PAPER_MIN)} (lower edge of "
                                    "Fig. 12)"))
    handles += curve_handles(drawn)
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False)
    return fig
