"""Design (beyond the paper; docs/design.md): transmissibility x_max/A over the band for
the LO alone (grey), the optimal TMD (blue) and the VI NES design from rest (solid orange)
and over attractors (dashed orange), one panel per base amplitude, the worst value found
from rest marked; and the worst-case ratio from rest of every grid design over
(L, eta) with the chosen design starred."""
import numpy as np
from matplotlib.colors import LogNorm
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

import vines.plotting as P
from vines.pipeline.jobs import run_job

C_LO_ALONE, C_TMD, C_VINES = "0.45", P.palette.OKABE_ITO["blue"], P.palette.OKABE_ITO["orange"]


def design(path):
    ds = P.load(path)
    P.require(ds, coords=("omega", "amplitude"), min_size=1,
              finite=("lo_alone_ratio", "tmd_ratio", "vines_ratio", "F"))
    return ds


def curve_panel(ax, ds, j, k):
    W = ds["omega"].values
    ax.plot(W, ds["lo_alone_ratio"].values, color=C_LO_ALONE, lw=1.6, label="LO alone")
    ax.plot(W, ds["tmd_ratio"].values, color=C_TMD, lw=1.6,
            label=rf"optimal TMD ($\eta$ = {P.fmt(float(ds['tmd_eta']))})")
    ax.plot(W, ds["vines_ratio"].values[j], "o-", color=C_VINES, ms=3, lw=1.4,
            label="VI NES, from rest")
    if "vines_ratio_any_attractor" in ds:
        ax.plot(W, ds["vines_ratio_any_attractor"].values[j], "--", color=C_VINES, lw=1.4,
                label="VI NES, worst attractor")
    ax.plot(float(ds["vines_peak_omega"][j]), float(ds["vines_peak_ratio"][j]), "v",
            color="black", ms=6, label="VI NES worst from rest (refined)")
    ax.set_yscale("log")
    _plain_log_ticks(ax.yaxis)
    ax.set_xlabel(P.LABELS["omega"])
    ax.set_ylabel(r"$x_{\max}/A$")
    A, F = float(ds["amplitude"][j]), float(ds["F"][j])
    P.panel_label(ax, k, rf"$A$ = {P.fmt(A * 1e3)} mm, $F$ = {F:.3g}")


def _plain_log_ticks(axis):
    """Plain numbers at 1, 2, 5 x 10^k on a log axis (the default labels every minor tick
    of a short range, and they overlap)."""
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


def _log_edges(v):
    """Cell edges half-way in log between values (one-value axes: a factor 1.2 around)."""
    lv = np.log10(v)
    mid = (lv[1:] + lv[:-1]) / 2 if lv.size > 1 else np.array([])
    lo = 2 * lv[0] - mid[0] if mid.size else lv[0] - 0.08
    hi = 2 * lv[-1] - mid[-1] if mid.size else lv[-1] + 0.08
    return 10.0 ** np.concatenate([[lo], mid, [hi]])


def _lin_edges(v):
    mid = (v[1:] + v[:-1]) / 2 if v.size > 1 else np.array([])
    step = (v[-1] - v[0]) / (v.size - 1) if v.size > 1 else 0.1 * v[0]
    return np.concatenate([[v[0] - (v[1] - v[0]) / 2 if mid.size else v[0] - step / 2], mid,
                           [v[-1] + (v[-1] - v[-2]) / 2 if mid.size else v[-1] + step / 2]])


def search_panel(fig, ax, ds, i):
    """One cell per search-grid design over (L, eta): L logarithmic, cells halfway in log."""
    L = ds["search_clearance"].values * 1e3
    eta = ds["search_eta"].values
    z = ds["search_worst_ratio"].values
    norm = LogNorm(np.nanmin(z), np.nanmax(z)) if np.nanmin(z) > 0 else None
    mesh = ax.pcolormesh(_log_edges(L), _lin_edges(eta), z, cmap=P.palette.colormap(),
                         norm=norm, rasterized=True)
    fig.colorbar(mesh, ax=ax, label=r"worst $x_{\max}/A$ from rest (log scale)")
    ax.set_xscale("log")
    _plain_log_ticks(ax.xaxis)
    ax.plot(float(ds["vines_clearance"]) * 1e3, float(ds["vines_eta"]), "*", color="white",
            mec="black", ms=16)
    ax.set_xlabel(r"clearance $L$ (mm)")
    ax.set_ylabel(P.LABELS["eta"])
    P.panel_label(ax, i, "search grid, star: chosen design")


def _ratio_range(ds):
    """y range (log) of a row's curve panels holding every curve of every amplitude (the
    shared axis would otherwise keep the first panel's range and clip the others)."""
    names = ("lo_alone_ratio", "tmd_ratio", "vines_ratio", "vines_ratio_any_attractor",
             "vines_peak_ratio")
    vals = np.concatenate([np.ravel(ds[v].values) for v in names if v in ds])
    vals = vals[np.isfinite(vals) & (vals > 0)]
    return 0.8 * float(vals.min()), 1.25 * float(vals.max())


def summary(ds) -> str:
    any_ = float(ds["vines_worst_ratio_any_attractor"])
    return (f"worst x_max/A: LO alone {float(ds['lo_alone_worst_ratio']):.3g}, TMD "
            f"{float(ds['tmd_worst_ratio']):.3g}, VI NES from rest "
            f"{float(ds['vines_worst_ratio']):.3g}"
            + ("" if np.isnan(any_) else f", over attractors {any_:.3g}")
            + f" (eta = {float(ds['vines_eta']):.3g}, L = "
              f"{float(ds['vines_clearance']) * 1e3:.3g} mm)")


def main(sm):
    P.configure(sm)
    designs = [design(p) for p in sm.input.designs]
    rows = [(ds, ds.sizes["amplitude"], "search_worst_ratio" in ds) for ds in designs]
    n = max(n_amp + int(search) for _, n_amp, search in rows)
    fig, axes = P.figure(len(rows), n, width=3.6 * n + 0.8, height=3.9 * len(rows))
    k = 0
    for i, (ds, n_amp, search) in enumerate(rows):
        for j in range(n_amp):
            curve_panel(axes[i, j], ds, j, k)
            axes[i, j].sharey(axes[i, 0])
            k += 1
        axes[i, 0].set_ylim(*_ratio_range(ds))
        if search:
            search_panel(fig, axes[i, n - 1], ds, k)
            k += 1
        for j in range(n_amp, n - int(search)):
            axes[i, j].set_visible(False)
        print(summary(ds))
    fig.suptitle("\n".join(summary(ds) for ds in designs), fontsize=9)
    fig.legend(handles=axes[0, 0].get_legend_handles_labels()[0], loc="outside lower center",
               ncol=5, fontsize=8, frameon=False)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
