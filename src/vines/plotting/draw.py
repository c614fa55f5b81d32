"""Drawing helpers of the figure scripts: labels and colours, panels, atomic PDF/PNG output."""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402
from matplotlib.colors import BoundaryNorm, ListedColormap, LogNorm  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from ..core.conventions import WALL_L, WALL_R  # noqa: E402
from ..core.params import L_HALF_M  # noqa: E402
from ..data.netcdf import new_file_mode  # noqa: E402
from .checks import FigureInputError  # noqa: E402

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
#: colours of the paper: LO / cavity ends blue, ball red, analytic branch red
C_LO, C_BALL, C_BRANCH = "tab:blue", "tab:red", "tab:red"
#: Fig 16 classes (label, colour) by value of ``cls`` in the stability datasets
CLASSES = {0: ("no admissible 1:1", "0.6"), 1: ("symmetric stable 1:1", "tab:orange"),
           2: ("asymmetric stable 1:1", "black"), 3: ("unstable 1:1", "white")}
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


#: impact markers by phase: (0, pi) LO and ball moving the same way, (pi, 2 pi) opposite
IMPACT_STYLES = ((r"impact, $\varphi_i \in (0, \pi)$", "v", "darkorange"),
                 (r"impact, $\varphi_i \in (\pi, 2\pi)$", "^", "black"))


def point_impacts(ds: xr.Dataset, i: int) -> dict:
    """Impacts of point ``i`` of a time-history dataset: t, dw, phase, wall arrays."""
    edges = np.concatenate([[0], np.cumsum(ds["row_size"].values)])
    return {k: ds[f"impact_{k}"].values[edges[i]:edges[i + 1]]
            for k in ("t", "dw", "phase", "wall")}


def _same_way(phase) -> np.ndarray:
    return np.mod(phase, 2 * np.pi) < np.pi


def time_history(ax_t, ax_p, ds: xr.Dataset, i: int):
    """Cavity ends z_m +- 1 (blue) and ball z_b (red) over the last periods, impacts marked
    by phase; beside it the phase portraits of the last periods (dark) over those of the
    whole measurement window (light, ``window_*`` samples, when the dataset has them)."""
    t, zm = ds["t"].values[i], ds["z_m"].values[i]
    zb = ds["z_b"].values[i]
    ax_t.plot(t, zm + 1, color=C_LO, lw=0.9, label=r"cavity ends $z_m \pm 1$")
    ax_t.plot(t, zm - 1, color=C_LO, lw=0.9)
    ax_t.plot(t, zb, color=C_BALL, lw=0.9, label=r"ball $z_b$")
    imp = point_impacts(ds, i)
    shown = (imp["t"] >= t[0]) & (imp["t"] <= t[-1])
    for same, (lab, mk, col) in zip((True, False), IMPACT_STYLES, strict=False):
        m = shown & (_same_way(imp["phase"]) == same)
        ax_t.plot(imp["t"][m], np.interp(imp["t"][m], t, zb), mk, color=col, ms=4,
                  ls="", label=lab)
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
    window): filled markers at the right end of the cavity (wall R, z_b = z_m + 1, where the
    paper's convention applies: phi_i in (0, pi) LO and ball moving the same way), open ones
    at the left end; (0, pi) shaded. Returns per wall the impacts and those in (0, pi)."""
    imp = point_impacts(ds, i)
    ph = np.mod(imp["phase"], 2 * np.pi)
    ax.axvspan(0, np.pi, color="0.92", lw=0)
    counts = {}
    for wall, name, filled in ((WALL_R, "right end", True), (WALL_L, "left end", False)):
        at = imp["wall"] == wall
        for same, (_, mk, col) in zip((True, False), IMPACT_STYLES, strict=False):
            m = at & (_same_way(ph) == same)
            ax.plot(ph[m], np.abs(imp["dw"][m]), mk, ls="", ms=4.5, alpha=0.7, mec=col,
                    mfc=col if filled else "none", mew=0.8, rasterized=True)
        counts[name] = (int(at.sum()), int((at & _same_way(ph)).sum()))
    ax.axvline(np.pi, color="0.4", lw=0.8, ls=":")
    ax.set_xlim(0, 2 * np.pi)
    if ph.size:
        ax.set_ylim(0, 1.25 * float(np.max(np.abs(imp["dw"]))))
    ax.set_xticks([0, np.pi / 2, np.pi, 1.5 * np.pi, 2 * np.pi],
                  ["0", r"$\pi/2$", r"$\pi$", r"$3\pi/2$", r"$2\pi$"])
    ax.set_xlabel(r"impact phase $\varphi_i$")
    ax.set_ylabel(r"$|\dot w_i|$")
    text = "\n".join(f"{name} (" + ("filled" if name == "right end" else "open")
                      + f"): {n}, {k} in (0, $\\pi$)" for name, (n, k) in counts.items())
    ax.text(0.03, 0.97, text, transform=ax.transAxes, fontsize=6.5, va="top")
    return counts


def bifurcation_dots(ax, x, y, **kw):
    """Small black dots (rasterized) of a bifurcation diagram."""
    kw = {"s": 0.6, "color": "black", "linewidths": 0, "rasterized": True, **kw}
    ax.scatter(x, y, **kw)


def branch_lines(ax, br: xr.Dataset):
    """Analytic 1:1 branch (admissible points): solid stable, dotted unstable, both walls."""
    eta = br["eta"].values
    adm = br["admissible"].values.astype(bool)
    st = br["stable"].values.astype(bool) & adm
    un = (~br["stable"].values.astype(bool)) & adm
    for k, key in enumerate(("dw_L", "dw_R")):
        y = br[key].values
        for mask, ls, lab in ((st, "-", "analytic 1:1, stable"),
                              (un, ":", "analytic 1:1, unstable")):
            ax.plot(eta, np.where(mask, y, np.nan), ls, color=C_BRANCH, lw=1.6,
                    label=lab if k == 0 else None)


def eigenvalue_panel(ax, br: xr.Dataset):
    """|lambda| of the four eigenvalues of J_P2 J_P1 along the branch, |lambda| = 1 dotted."""
    eta = br["eta"].values
    adm = br["admissible"].values.astype(bool)
    ev = np.asarray(br["abs_eigenvalues"].values, dtype=float)
    for j in range(ev.shape[1]):
        ax.plot(eta, np.where(adm, ev[:, j], np.nan), ".", ms=2.5,
                label=rf"$|\lambda_{j + 1}|$")
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
    """x_max (m, red circles, left axis) and KE ratio (blue stars, right axis); returns the
    right axis."""
    ax.plot(x, xmax_m, "o", color="tab:red", ms=3.5, mfc="none", label=r"$x_m^{\max}$")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(LABELS["xmax_m"], color="tab:red")
    ax.tick_params(axis="y", colors="tab:red")
    ax2 = ax.twinx()
    ax2.plot(x, ke, "*", color="tab:blue", ms=4.5, label="KE ratio")
    ax2.set_ylabel(LABELS["ke_ratio"], color="tab:blue")
    ax2.tick_params(axis="y", colors="tab:blue")
    ax2.set_ylim(-0.02, max(1.0, float(np.nanmax(ke)) * 1.05))
    return ax2


def contour_map(fig, ax, x, y, z, *, label, vmin=None, vmax=None, log=False, cells=False):
    """Filled contour (20 levels, jet) with a colour bar; needs at least 2 x 2 points.
    ``log``: levels equally spaced in log10(z) (z > 0), so small values keep their detail
    next to a large resonance peak. ``cells``: one flat cell per grid point in the same 20
    colours instead of contours (coarse grids, where contouring would invent shapes)."""
    if len(x) < 2 or len(y) < 2:
        raise FigureInputError(f"a contour map of {label} needs at least 2 x 2 grid points, "
                               f"got {len(x)} x {len(y)}")
    vmin = float(np.nanmin(z)) if vmin is None else vmin
    vmax = float(np.nanmax(z)) if vmax is None else vmax
    if log and vmin <= 0:
        raise FigureInputError(f"a log colour scale of {label} needs values > 0, "
                               f"minimum {vmin}")
    if vmax <= vmin:
        vmax = vmin * (1 + 1e-9) + 1e-12
    if log:
        levels, norm, ticks = np.geomspace(vmin, vmax, 21), LogNorm(vmin, vmax), None
    else:
        levels, norm, ticks = np.linspace(vmin, vmax, 21), None, MaxNLocator(6)
    if cells:
        cs = ax.pcolormesh(x, y, z, shading="nearest", cmap=plt.get_cmap("jet", 20),
                           norm=norm or BoundaryNorm(levels, 20))
    else:
        cs = ax.contourf(x, y, z, levels=levels, cmap="jet", norm=norm, extend="neither")
    cb = fig.colorbar(cs, ax=ax, shrink=0.9, ticks=ticks)
    if log:
        _log_ticks(cb, vmin, vmax)
    cb.set_label(label + (" (log scale)" if log else ""))


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


def save(fig, pdf, png, dpi=150):
    """Write the figure as PDF and PNG atomically (temp file in the same dir + os.replace)."""
    for path, kw in ((Path(pdf), {}), (Path(png), {"dpi": dpi})):
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix,
                                   dir=path.parent)
        os.close(fd)
        os.chmod(tmp, new_file_mode())
        try:
            fig.savefig(tmp, format=path.suffix.lstrip("."), **kw)
            os.replace(tmp, path)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise
    plt.close(fig)
