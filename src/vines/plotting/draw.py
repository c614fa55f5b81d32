"""Drawing helpers of the figure scripts: labels and colours, panels, atomic PDF/PNG output."""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402
from matplotlib import patheffects  # noqa: E402
from matplotlib.colors import BoundaryNorm, ListedColormap, LogNorm  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402, F401  (re-exported for legends)
from matplotlib.patches import Patch, Rectangle  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, MaxNLocator, NullFormatter  # noqa: E402

from ..core.conventions import WALL_L, WALL_R  # noqa: E402
from ..core.grids import cell_edges  # noqa: E402
from ..core.params import L_HALF_M  # noqa: E402
from ..data.netcdf import temporary_beside  # noqa: E402
from . import palette  # noqa: E402
from .checks import FigureInputError  # noqa: E402
from .impacts import SAME_WAY, TOWARDS, impact_direction, point_impacts  # noqa: E402
from .stable_region import stability_margin  # noqa: E402

#: axis labels (symbols and units)
LABELS = {
    "eta": r"mass ratio $\eta$",
    "omega": r"frequency ratio $\Omega$",
    "F": r"forcing amplitude $F$",
    "ke_ratio": r"KE ratio $K_b/(K_m+K_b)$",
    "xmax_m": r"$x_m^{\max}$ (m)",
    "dw": r"relative impact velocity $\dot w_i$",
    "abs_lambda": r"$|\lambda|$",
    "t": r"time $\tau$",
}
#: colours of the paper: LO / cavity ends blue, ball vermillion, analytic (symmetric) branch vermillion (the paper: red)
C_LO, C_BALL, C_BRANCH = palette.C_LO, palette.C_BALL, palette.C_SYMMETRIC
#: Fig 16 classes (label, colour) by value of ``cls`` in the stability datasets
CLASSES = palette.CLASSES
#: parameter symbols in panel titles
SYMBOLS = {"eta": r"\eta", "omega": r"\Omega", "F": "F"}


def figure(nrows, ncols, *, width=None, height=None, **kw):
    """Figure with a (nrows, ncols) array of axes, constrained layout."""
    width = width or 3.6 * ncols
    height = height or 2.9 * nrows
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, height), squeeze=False,
                             constrained_layout=True, **kw)
    return fig, axes


def panel_label(ax, i, title=None):
    """'(a) title' at the top left of a panel; i is 0-based."""
    text = f"({chr(ord('a') + i)})" + (f" {title}" if title else "")
    ax.set_title(text, loc="left", fontsize=9)


def fmt(v) -> str:
    return f"{v:g}"


def th_title(ds: xr.Dataset, i: int) -> str:
    """'eta = .., Omega = .., F = ..' of point ``i`` of a time-history dataset."""
    return ", ".join(f"${SYMBOLS[k]}$ = {fmt(float(ds[k].values[i]))}"
                     for k in ("eta", "omega", "F"))


def metres(x):
    """Dimensionless displacement (units of L) in metres."""
    return np.asarray(x, dtype=float) * L_HALF_M


#: impact markers by direction of motion just before impact (``vines.plotting.impacts``)
IMPACT_STYLES = {TOWARDS: ("LO and ball moving towards each other", "^", palette.C_TOWARDS),
                 SAME_WAY: ("LO and ball moving the same way", "v", palette.C_SAME_WAY)}
#: walls: filled markers at the right end (wall R, z_b = z_m + 1), open at the left end
WALL_STYLES = ((WALL_R, "right end", True), (WALL_L, "left end", False))


def impact_handles() -> list:
    """Legend entries of the impact markers: the two directions (filled: right end) and the
    open marker of the left end."""
    out = [Line2D([], [], ls="", marker=mk, ms=5, color=col, label=lab + " (filled: right end)")
           for lab, mk, col in IMPACT_STYLES.values()]
    out.append(Line2D([], [], ls="", marker="o", ms=5, mfc="none", mec="0.3",
                      label="open: left end"))
    return out


def _impact_markers(ax, x, y, direction, wall, **kw):
    """Impacts at (x, y) marked by direction (marker, colour) and wall (filled / open); not
    clipped, so a marker on the panel's edge (phase 0 or 2 pi, the last sample's time, a
    zero relative velocity) is drawn whole (the callers give only points inside)."""
    for code, (_, mk, col) in IMPACT_STYLES.items():
        for w, _, filled in WALL_STYLES:
            m = (direction == code) & (wall == w)
            if m.any():
                ax.plot(x[m], y[m], mk, ls="", mec=col, mfc=col if filled else "none",
                        clip_on=False, **kw)


def time_history(ax_t, ax_p, ds: xr.Dataset, i: int):
    """Cavity ends z_m +- 1 (blue) and ball z_b (vermillion) over the last periods, impacts marked
    by direction and wall (``IMPACT_STYLES``, ``WALL_STYLES``); beside it the phase portraits of the last periods (dark) over those of the
    whole measurement window (light, ``window_*`` samples, when the dataset has them)."""
    t, zm = ds["t"].values[i], ds["z_m"].values[i]
    zb = ds["z_b"].values[i]
    ax_t.plot(t, zm + 1, color=C_LO, lw=0.9, label=r"cavity ends $z_m \pm 1$")
    ax_t.plot(t, zm - 1, color=C_LO, lw=0.9)
    ax_t.plot(t, zb, color=C_BALL, lw=0.9, label=r"ball $z_b$")
    imp = point_impacts(ds, i)
    shown = (imp["t"] >= t[0]) & (imp["t"] <= t[-1])
    _impact_markers(ax_t, imp["t"][shown], np.interp(imp["t"][shown], t, zb),
                    impact_direction(ds, i)[shown], imp["wall"][shown], ms=4.5, mew=0.9)
    ax_t.set_xlim(t[0], t[-1])
    ax_t.set_xlabel(LABELS["t"])
    ax_t.set_ylabel(r"displacement $z$ (units of $L$)")
    if "window_t" in ds.variables:       # the whole window, light, broken at the impacts
        tw = ds["window_t"].values[i]
        for k, col in (("m", C_LO), ("b", C_BALL)):
            z, v = (_broken(tw, ds[f"window_{q}_{k}"].values[i], imp["t"]) for q in ("z", "v"))
            ax_p.plot(z, v, color=col, lw=0.25, alpha=0.35, rasterized=True)
    ax_p.plot(zm, ds["v_m"].values[i], color=C_LO, lw=0.8, label="LO")
    ax_p.plot(zb, ds["v_b"].values[i], color=C_BALL, lw=0.8, label="ball")
    ax_p.set_xlabel(r"displacement $z$")
    ax_p.set_ylabel(r"velocity $\dot z$")


def _broken(t, y, t_impacts):
    """``y`` with NaN inserted between two samples that have an impact between them (the
    velocity jump is not drawn as a slanted line)."""
    j = np.unique(np.searchsorted(t, t_impacts[(t_impacts > t[0]) & (t_impacts < t[-1])]))
    return np.insert(np.asarray(y, dtype=float), j, np.nan)


def impact_phase_panel(ax, ds: xr.Dataset, i: int) -> dict:
    """|w'_i| against the impact phase of every impact of the dataset (the whole measurement
    window), marked by direction and wall (filled: right end, where the paper's phase
    convention applies; open: left end); (0, pi) shaded. Returns per wall the number of
    impacts and of those with the LO and the ball moving the same way."""
    imp = point_impacts(ds, i)
    ph = np.mod(imp["phase"], 2 * np.pi)
    direction = impact_direction(ds, i)
    ax.axvspan(0, np.pi, color="0.93", lw=0)
    _impact_markers(ax, ph, np.abs(imp["dw"]), direction, imp["wall"], ms=4.5, alpha=0.75,
                    mew=0.8, rasterized=True)
    counts = {name: (int((imp["wall"] == w).sum()),
                     int(((imp["wall"] == w) & (direction == SAME_WAY)).sum()))
              for w, name, _ in WALL_STYLES}
    ax.axvline(np.pi, color="0.4", lw=0.8, ls=":")
    ax.set_xlim(0, 2 * np.pi)
    if ph.size:
        ax.set_ylim(0, 1.3 * float(np.max(np.abs(imp["dw"]))))
    ax.set_xticks([0, np.pi / 2, np.pi, 1.5 * np.pi, 2 * np.pi],
                  ["0", r"$\pi/2$", r"$\pi$", r"$3\pi/2$", r"$2\pi$"])
    ax.set_xlabel(r"impact phase $\varphi_i$")
    ax.set_ylabel(r"$|\dot w_i|$")
    text = "\n".join(f"{name}: {n} impacts, {k} same way" for name, (n, k) in counts.items())
    ax.text(0.03, 0.97, text, transform=ax.transAxes, fontsize=6.5, va="top",
            bbox={"facecolor": "white", "alpha": 0.85, "lw": 0, "pad": 1.5})
    return counts


def bifurcation_dots(ax, x, y, **kw):
    """Small black dots (rasterized) of a bifurcation diagram."""
    kw = {"s": 0.6, "color": "black", "linewidths": 0, "rasterized": True, **kw}
    ax.scatter(x, y, **kw)


def fit_y_to_window(ax, pad=0.05):
    """y-limits of ``ax`` to what is drawn inside its x-limits (scatter points and line
    vertices), widened by ``pad`` of the range each side: a line drawn over a wider eta
    range than the panel's does not stretch the panel."""
    lo, hi = ax.get_xlim()
    xy = [np.asarray(c.get_offsets(), float).reshape(-1, 2) for c in ax.collections]
    xy += [np.asarray(ln.get_xydata(), float).reshape(-1, 2) for ln in ax.lines]
    xy = np.concatenate(xy or [np.empty((0, 2))])
    y = xy[(xy[:, 0] >= lo) & (xy[:, 0] <= hi), 1]
    y = y[np.isfinite(y)]
    if y.size:
        a, b = float(y.min()), float(y.max())
        d = pad * (b - a) if b > a else 1.0
        ax.set_ylim(a - d, b + d)


def branch_lines(ax, br: xr.Dataset, label=True):
    """Analytic 1:1 branch (admissible points): solid stable, dotted unstable, both walls."""
    eta = br["eta"].values
    adm = br["admissible"].values.astype(bool)
    st = br["stable"].values.astype(bool) & adm
    un = (~br["stable"].values.astype(bool)) & adm
    for k, key in enumerate(("dw_L", "dw_R")):
        y = br[key].values
        for mask, ls, lab in ((st, "-", "analytic symmetric 1:1, stable"),
                              (un, ":", "analytic symmetric 1:1, unstable")):
            ax.plot(eta, np.where(mask, y, np.nan), ls, color=C_BRANCH, lw=1.6,
                    label=lab if (k == 0 and label) else None)


#: markers and greys of the four |lambda| (colours are kept for the branches)
EIGEN_STYLES = (("o", "black"), ("s", "0.45"), ("^", "0.25"), ("D", "0.6"))


def eigenvalue_panel(ax, br: xr.Dataset):
    """|lambda| of the four eigenvalues of J_P2 J_P1 along the branch, |lambda| = 1 dotted."""
    eta = br["eta"].values
    adm = br["admissible"].values.astype(bool)
    ev = np.asarray(br["abs_eigenvalues"].values, dtype=float)
    for j in range(ev.shape[1]):
        mk, col = EIGEN_STYLES[j % len(EIGEN_STYLES)]
        ax.plot(eta, np.where(adm, ev[:, j], np.nan), mk, ms=2.5, color=col, mfc="none",
                mew=0.6, label=rf"$|\lambda_{j + 1}|$")
    ax.axhline(1.0, color="black", ls=":", lw=1.0)
    ax.set_xlabel(LABELS["eta"])
    ax.set_ylabel(LABELS["abs_lambda"])
    top = np.nanmax(np.where(adm[:, None], ev, np.nan)) if adm.any() else 2.0
    ax.set_ylim(0, min(max(1.5, 1.05 * top), 3.0))


def class_map(ax, x, y, codes, classes: dict):
    """Categorical map: ``codes`` (len(y), len(x)) drawn in the colours of ``classes``
    (code -> (label, colour)), one cell per point; negative codes are left blank."""
    keys = sorted(classes)
    cmap = ListedColormap([classes[k][1] for k in keys])
    norm = BoundaryNorm(np.arange(len(keys) + 1) - 0.5, cmap.N)
    idx = np.searchsorted(keys, np.asarray(codes))
    ax.pcolormesh(x, y, np.ma.masked_where(np.asarray(codes) < 0, idx), cmap=cmap, norm=norm,
                  shading="nearest", rasterized=True)


def class_handles(classes: dict, suffix=None) -> list:
    """Legend patches of ``classes`` (code -> (label, colour)); ``suffix``: code -> text."""
    suffix = suffix or {}
    return [Patch(facecolor=classes[k][1], edgecolor="black",
                  label=classes[k][0] + suffix.get(k, "")) for k in sorted(classes)]


def twin_measures(ax, x, ke, xmax_m, xlabel):
    """x_max (m, vermillion circles, left axis) and KE ratio (blue stars, right axis); returns the
    right axis."""
    red, blue = palette.OKABE_ITO["vermillion"], palette.OKABE_ITO["blue"]
    ax.plot(x, xmax_m, "o", color=red, ms=3.5, mfc="none", label=r"$x_m^{\max}$")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(LABELS["xmax_m"], color=red)
    ax.tick_params(axis="y", colors=red)
    ax2 = ax.twinx()
    ax2.plot(x, ke, "*", color=blue, ms=4.5, label="KE ratio")
    ax2.set_ylabel(LABELS["ke_ratio"], color=blue)
    ax2.tick_params(axis="y", colors=blue)
    ax2.set_ylim(-0.02, max(1.0, float(np.nanmax(ke)) * 1.05))
    return ax2


@dataclass(frozen=True)
class MapStyle:
    """How ``contour_map`` draws one quantity: ``label`` of its colour bar (symbol and
    unit), colour range ``vmin``..``vmax`` (None: the data's), ``log``: levels equally
    spaced in log10 (values > 0, so small values keep their detail next to a large
    resonance peak), ``cells``: one flat cell per grid point in the same 20 colours instead
    of contours (coarse grids, where contouring would invent shapes), ``colorbar=False``:
    none on this panel (panels comparing one quantity share one, ``shared_colorbar``)."""

    label: str
    vmin: float | None = None
    vmax: float | None = None
    log: bool = False
    cells: bool = False
    colorbar: bool = True


def contour_map(fig, ax, x, y, z, style: MapStyle, *, no_impact=None):
    """Filled contour (20 levels of the configured colour map, ``palette.colormap``) of
    ``z`` (len(y), len(x)) drawn as ``style`` says; needs at least 2 x 2 points.
    ``no_impact``: mask of the points without impacts, not drawn as data but as the grey
    class ``palette.NO_IMPACT`` (around them with contours). NaN points are left blank (no
    data). Returns the mappable."""
    label, vmin, vmax, log = style.label, style.vmin, style.vmax, style.log
    if len(x) < 2 or len(y) < 2:
        raise FigureInputError(f"a contour map of {label} needs at least 2 x 2 grid points, "
                               f"got {len(x)} x {len(y)}")
    z = np.ma.masked_invalid(np.asarray(z, dtype=float))
    if no_impact is not None and np.any(no_impact):
        z = np.ma.masked_where(np.asarray(no_impact, bool), z)
        ax.set_facecolor(palette.NO_IMPACT)
    vmin = float(z.min()) if vmin is None else vmin
    vmax = float(z.max()) if vmax is None else vmax
    if log and vmin <= 0:
        raise FigureInputError(f"a log colour scale of {label} needs values > 0, "
                               f"minimum {vmin}")
    if vmax <= vmin:
        vmax = vmin * (1 + 1e-9) + 1e-12
    if log:
        levels, norm, ticks = np.geomspace(vmin, vmax, 21), LogNorm(vmin, vmax), None
    else:
        levels, norm, ticks = np.linspace(vmin, vmax, 21), None, MaxNLocator(6)
    if style.cells:
        cs = ax.pcolormesh(x, y, z, shading="nearest", cmap=palette.colormap(20),
                           norm=norm or BoundaryNorm(levels, 20), rasterized=True)
    else:
        cs = ax.contourf(x, y, z, levels=levels, cmap=palette.colormap(), norm=norm,
                         extend="neither")
    cs.vines_scale = (label, log, vmin, vmax, ticks)
    if style.colorbar:
        shared_colorbar(fig, cs, ax)
    return cs


def shared_colorbar(fig, mappable, axes, **kw):
    """One colour bar for ``axes`` (one axes or several comparing one quantity, drawn with
    the same range) from a mappable of ``contour_map``."""
    label, log, vmin, vmax, ticks = mappable.vines_scale
    cb = fig.colorbar(mappable, ax=axes, shrink=kw.pop("shrink", 0.9), ticks=ticks, **kw)
    if log:
        _log_ticks(cb, vmin, vmax)
    cb.set_label(label + (" (log scale)" if log else ""))
    return cb


def common_range(arrays, log=False):
    """(vmin, vmax) over several panels of one quantity (positive values only if ``log``)."""
    vals = np.concatenate([np.asarray(a, float).ravel() for a in arrays])
    vals = vals[np.isfinite(vals) & ((vals > 0) if log else True)]
    return float(vals.min()), float(vals.max())


#: edge of the stable 1:1 region on colour maps: white over a thin black halo
STABLE_EDGE = {"color": "white", "lw": 1.5}
_EDGE_HALO = [patheffects.Stroke(linewidth=2.7, foreground="black"), patheffects.Normal()]


def stable_edge(ax, smap: xr.Dataset):
    """The |lambda_max| = 1 edge of the stable 1:1 region of the stability map ``smap``
    (interpolated between map points, ``stable_region.stability_margin``)."""
    cs = ax.contour(smap["eta"].values, smap["omega"].values, stability_margin(smap),
                    levels=[0.0], colors=STABLE_EDGE["color"], linewidths=STABLE_EDGE["lw"])
    cs.set_path_effects(_EDGE_HALO)
    return cs


def stable_edge_handle(label=r"edge of the stable 1:1 region ($|\lambda_{\max}| = 1$, Fig. 16)"):
    """Legend entry drawn as the edge is."""
    return Line2D([], [], label=label, path_effects=_EDGE_HALO, **STABLE_EDGE)


def hatch_cells(ax, x, y, mask, hatch="////", color="white"):
    """Hatch the cells (one per grid point, edges half-way between points) where ``mask``
    (len(y), len(x)) is True."""
    ex, ey = cell_edges(x), cell_edges(y)
    for j, i in zip(*np.nonzero(mask), strict=True):
        ax.add_patch(Rectangle((ex[i], ey[j]), ex[i + 1] - ex[i], ey[j + 1] - ey[j],
                               fill=False, hatch=hatch, edgecolor=color, lw=0))


def hatch_region(ax, x, y, mask, hatch="////", color="white"):
    """Hatch where ``mask`` (len(y), len(x)) on a fine raster is True, as one artist (its
    edge follows the raster; ``hatch_cells`` draws one patch per cell of a coarse grid)."""
    if not np.any(mask):
        return None
    cs = ax.contourf(x, y, np.asarray(mask, float), levels=[0.5, 1.5], colors="none",
                     hatches=[hatch])
    cs.set_hatchcolor(color)
    cs.set_linewidth(0)
    return cs


def no_impact_handle(what="no impact (the LO never reaches a wall)"):
    """Legend patch of the no-impact class of KE-ratio maps."""
    return Patch(facecolor=palette.NO_IMPACT, edgecolor="0.3", lw=0.5, label=what)


def plain_log_ticks(axis, subs=(1.0, 2.0, 5.0)):
    """Plain numbers at ``subs`` x 10^k on a log axis (the default labels every minor tick
    of a short range, and they overlap)."""
    axis.set_major_locator(LogLocator(base=10, subs=subs))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


def summary_and_legend(fig, summaries, legend_ax=None, ncol=3):
    """The tail of the design figures: each summary line printed (to the job's log) and all
    as the figure's title; below the panels one legend of ``legend_ax``'s entries."""
    for line in summaries:
        print(line)
    if summaries:
        fig.suptitle("\n".join(summaries), fontsize=9)
    if legend_ax is not None:
        fig.legend(handles=legend_ax.get_legend_handles_labels()[0],
                   loc="outside lower center", ncol=ncol, fontsize=8, frameon=False)


def _log_ticks(cb, vmin, vmax):
    """Colour bar ticks at 1, 2, 5 x 10^k inside [vmin, vmax] (and the two ends)."""
    k = np.arange(np.floor(np.log10(vmin)), np.ceil(np.log10(vmax)) + 1)
    cand = np.sort(np.concatenate([m * 10.0 ** k for m in (1, 2, 5)]))
    ticks = cand[(cand >= vmin) & (cand <= vmax)]
    if ticks.size < 3:
        ticks = np.geomspace(vmin, vmax, 4)
    cb.set_ticks(ticks)
    cb.set_ticklabels([f"{v:.3g}" for v in ticks])
    cb.ax.minorticks_off()


#: file metadata without a creation date (or a version string), so that the same data give
#: the same bytes
METADATA = {"pdf": {"CreationDate": None, "Producer": None, "Creator": None},
            "png": {"Software": None}}


def save(fig, pdf, png, dpi=150):
    """Write the figure as PNG and PDF atomically (temp file in the same dir + os.replace),
    without a creation date: rendering the same data twice gives identical bytes. The
    layout (constrained layout: ~0.5 s a figure) is computed once, for the PNG."""
    for path, kw in ((Path(png), {"dpi": dpi}), (Path(pdf), {})):
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = temporary_beside(path, path.suffix)
        try:
            fmt_ = path.suffix.lstrip(".")
            fig.savefig(tmp, format=fmt_, metadata=METADATA.get(fmt_), **kw)
            os.replace(tmp, path)
            fig.set_layout_engine("none")      # keep the positions just computed
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise
    plt.close(fig)
