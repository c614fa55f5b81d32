"""The model-ladder figure's panels (datasets of the stage ``model_ladder``): per eta the
frequency response by the slow flow, the exact 1:1 orbits (map solve, continuation) and the
simulation from rest, the slow flow's amplitude error against the exact orbits, and each
model's cost."""
from __future__ import annotations

import numpy as np
import xarray as xr

from . import palette
from .checks import load, require
from .draw import figure, panel_label

C_SLOW = palette.OKABE_ITO["orange"]
C_EXACT = "black"
C_SIM = palette.OKABE_ITO["blue"]
#: the tolerance lines and bands of the error panel (tolerance -> colour)
C_BAND = {0.01: palette.OKABE_ITO["bluish green"], 0.05: "0.75"}
#: model names in the cost line
COST_NAMES = {"slowflow": "slow flow", "map_solve": "map solve",
              "continuation": "continuation", "simulation": "simulation"}


def model_ladder(path) -> xr.Dataset:
    """A model-ladder dataset, checked."""
    ds = load(path)
    return require(ds, coords=("eta", "sigma", "sigma_dense", "tolerance"), min_size=1,
                   variables=("slowflow_amplitude", "exact_amplitude", "continuation_omega",
                              "dense_amplitude", "slowflow_error", "model"),
                   finite=("omega", "omega_dense", "simulation_xmax", "seconds", "xi_min"))


def _split(x, y, mask):
    """y where mask, NaN elsewhere (a line broken where the mask changes)."""
    return x, np.where(mask, y, np.nan)


def frc_panel(ax, ds: xr.Dataset, k: int) -> None:
    """Amplitude max |z_m|/L against omega at eta[k]: slow flow (dots: stable dark,
    unstable light), exact branches (continuation: stable solid, unstable dashed), exact
    orbits at the grid frequencies (circles: filled stable), simulation from rest (x)."""
    p = ds.isel(eta=k)
    Wd = p["omega_dense"].values
    amp, st = p["dense_amplitude"].values, p["dense_stable"].values.astype(bool)
    for j in range(amp.shape[1]):
        ax.plot(Wd[st[:, j]], amp[st[:, j], j], ".", color=C_SLOW, ms=2.2,
                label="slow flow, stable" if j == 0 else None)
        ax.plot(Wd[~st[:, j]], amp[~st[:, j], j], ".", color=C_SLOW, ms=1.0, alpha=0.45,
                label="slow flow, unstable" if j == 0 else None)
    cw, ca = p["continuation_omega"].values, p["continuation_amplitude"].values
    cs = p["continuation_stable"].values.astype(bool)
    for c in range(cw.shape[0]):
        ax.plot(*_split(cw[c], ca[c], cs[c]), "-", color=C_EXACT, lw=1.0,
                label="exact branch, stable" if c == 0 else None)
        ax.plot(*_split(cw[c], ca[c], ~cs[c]), "--", color=C_EXACT, lw=0.7, alpha=0.6,
                label="exact branch, unstable" if c == 0 else None)
    W = p["omega"].values
    ex, es = p["exact_amplitude"].values, p["exact_stable"].values.astype(bool)
    for j in range(ex.shape[1]):
        ax.plot(W[es[:, j]], ex[es[:, j], j], "o", color=C_EXACT, ms=3.2,
                label="exact orbit (map solve), stable" if j == 0 else None)
        ax.plot(W[~es[:, j]], ex[~es[:, j], j], "o", mfc="white", mec=C_EXACT, ms=3.2,
                mew=0.7, label="exact orbit (map solve), unstable" if j == 0 else None)
    ax.plot(W, p["simulation_xmax"].values, "x", color=C_SIM, ms=4, mew=1.0,
            label="simulation from rest (window)")
    ax.axhline(float(p["xi_min"]), color="0.5", ls=":", lw=0.9,
               label=r"activation $\xi_{\min}$ (fold of the SIM)")
    # up to the largest orbit found at a grid frequency or simulated (the unstable branches
    # climb far higher near resonance and would flatten the rest)
    top = np.nanmax(np.concatenate([np.ravel(ex), p["simulation_xmax"].values, [1.0]]))
    ax.set_ylim(0.0, 1.1 * top)
    ax.set_xlim(W[0], W[-1])
    ax.set_xlabel(r"frequency ratio $\Omega$")
    ax.set_ylabel(r"LO amplitude $\max|z_m|/L$")


def _band(p: xr.Dataset, j: int) -> tuple[float, float]:
    """(lo, hi) of the widest band at the j-th tolerance (``DataArray.sel`` takes
    ``tolerance`` as its own argument, hence positions)."""
    return float(p["band_lo"][j]), float(p["band_hi"][j])


def error_panel(ax, ds: xr.Dataset, k: int) -> None:
    """Relative amplitude error of each slow-flow fixed point against the nearest exact
    orbit (log; filled: stable), the tolerance lines and the widest band within each;
    triangles on top: frequencies where the two models find different numbers of orbits."""
    p = ds.isel(eta=k)
    W = p["omega"].values
    err, st = p["slowflow_error"].values, p["slowflow_stable"].values.astype(bool)
    floor = 1e-5
    for j, tol in enumerate(ds["tolerance"].values):
        col = C_BAND.get(float(tol), "0.6")
        ax.axhline(float(tol), color=col, lw=0.8)
        lo, hi = _band(p, j)
        if np.isfinite(lo):      # a thick stretch of the tolerance's own line: no overlap
            half = 0.5 * (W[1] - W[0])      # the grid cells of the band's frequencies
            ax.hlines(float(tol), lo - half, hi + half, color=col, lw=6, alpha=0.7,
                      label=f"widest band within {float(tol):.0%}")
    for j in range(err.shape[1]):     # the colours of the panel above: light = unstable
        e = np.maximum(err[:, j], floor)
        ax.semilogy(W[st[:, j]], e[st[:, j]], "o", color=C_SLOW, ms=3.4)
        ax.semilogy(W[~st[:, j]], e[~st[:, j]], "o", color=C_SLOW, ms=3.4, alpha=0.4)
    differ = p["n_slowflow"].values != p["n_exact"].values
    if differ.any():
        ax.plot(W[differ], np.full(differ.sum(), 0.6), "v", color="0.35", ms=4,
                label="numbers of orbits differ")
    ax.set_ylim(floor, 1.0)
    ax.set_xlim(W[0], W[-1])
    ax.set_xlabel(r"frequency ratio $\Omega$")
    ax.set_ylabel("slow flow: relative amplitude error")


def cost_line(ds: xr.Dataset, k: int) -> str:
    """Wall time of each model at eta[k], and the exact models' cost in slow-flow calls
    ("(30x)": 30 times the slow flow's time)."""
    sec = ds["seconds"].isel(eta=k)
    base = float(sec.sel(model="slowflow"))
    parts = []
    for m in ds["model"].values:
        s = float(sec.sel(model=m))
        t = f"{s * 1e3:.2g} ms" if s < 0.1 else f"{s:.2g} s"
        parts.append(f"{COST_NAMES.get(str(m), str(m))} {t}" +
                     ("" if m == "slowflow" else f" ({s / base:.0f}x)"))
    return ", ".join(parts)


def summary(ds: xr.Dataset, k: int) -> str:
    """One line per eta: the bands within each tolerance and the costs."""
    p = ds.isel(eta=k)
    bands = []
    for j, tol in enumerate(ds["tolerance"].values):
        lo, hi = _band(p, j)
        share = float(p["share_within"][j])
        where = "none" if not np.isfinite(lo) else f"omega {lo:.4g}-{hi:.4g}"
        bands.append(f"within {float(tol):.0%}: {where} ({share:.0%} of the grid)")
    return f"eta = {float(p['eta']):g}, F = {float(p['F']):g}: " + "; ".join(bands) + \
        "; cost " + cost_line(ds, k)


def ladder_figure(ladders):
    """Per ladder two rows, one column per eta: ``frc_panel`` over ``error_panel`` with the
    models' cost; one legend of every entry below."""
    n = max(ds.sizes["eta"] for ds in ladders)
    fig, axes = figure(2 * len(ladders), n, width=3.7 * n + 0.4,
                       height=7.0 * len(ladders) + 1.4)
    for row, ds in enumerate(ladders):
        top, bottom = axes[2 * row], axes[2 * row + 1]
        for k in range(ds.sizes["eta"]):
            frc_panel(top[k], ds, k)
            error_panel(bottom[k], ds, k)
            eta, F = float(ds["eta"][k]), float(ds["F"][k])
            panel_label(top[k], 2 * row * n + k, rf"$\eta$ = {eta:g}, $F$ = {F:g}")
            panel_label(bottom[k], (2 * row + 1) * n + k,
                        "slow flow's error against the exact orbits")
            bottom[k].text(0.02, 0.02, "wall time (x: times the slow flow's)\n"
                           + cost_line(ds, k).replace(", ", "\n"),
                           transform=bottom[k].transAxes, fontsize=6.5, va="bottom")
            print(summary(ds, k))
        for k in range(ds.sizes["eta"], n):
            top[k].set_visible(False)
            bottom[k].set_visible(False)
    handles = {}
    for ax in axes.ravel():
        for h, label in zip(*ax.get_legend_handles_labels(), strict=True):
            handles.setdefault(label, h)
    fig.legend(handles=list(handles.values()), labels=list(handles), loc="outside lower center",
               ncol=4 if n > 2 else 2, fontsize=7.5, frameon=False)
    return fig
