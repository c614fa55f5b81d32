"""The absorber design figures (docs/design.md): transmissibility over the band and the
search grid (``design``), the worst case over a drifting host (``design_robust``) and the
design with uncertain parts (``uncertainty``), for the LO alone (grey), the TMD (blue) and
the VI NES (orange)."""
from __future__ import annotations

import numpy as np
from matplotlib.colors import LogNorm
from matplotlib.patches import Patch

from ..core.grids import cell_edges, log_cell_edges
from . import palette
from .checks import load, require
from .draw import LABELS, figure, fmt, panel_label, plain_log_ticks, summary_and_legend

C_LO_ALONE, C_TMD, C_VINES = "0.45", palette.OKABE_ITO["blue"], palette.OKABE_ITO["orange"]
#: uncertainty: regime groups -> colour (the regime figures' colours)
REGIME_COLOURS = {"no-impact": palette.REGIMES[0][1], "1:1": palette.REGIMES[1][1],
                  "other periodic": palette.REGIMES[3][1],
                  "irregular": palette.REGIMES[4][1], "chatter": palette.REGIMES[5][1]}
#: uncertainty: the two systems compared (variable prefix, label, colour)
SYSTEMS = (("vines", "VI NES", C_VINES), ("tmd", "TMD", C_TMD))


# ------------------------------------------------------------------ design

def design(path):
    """A design dataset (stage ``design``), checked."""
    ds = load(path)
    require(ds, coords=("omega", "amplitude"), min_size=1,
            finite=("lo_alone_ratio", "tmd_ratio", "vines_ratio", "F"))
    return ds


def _curve_panel(ax, ds, j, k):
    W = ds["omega"].values
    ax.plot(W, ds["lo_alone_ratio"].values, color=C_LO_ALONE, lw=1.6, label="LO alone")
    ax.plot(W, ds["tmd_ratio"].values, color=C_TMD, lw=1.6,
            label=rf"optimal TMD ($\eta$ = {fmt(float(ds['tmd_eta']))})")
    if "tmd_equal_travel_ratio" in ds:
        ax.plot(W, ds["tmd_equal_travel_ratio"].values, ":", color=C_TMD, lw=1.8,
                label=r"TMD with stroke $\leq L$ at the largest $A$")
    ax.plot(W, ds["vines_ratio"].values[j], "o-", color=C_VINES, ms=3, lw=1.4,
            label="VI NES, from rest")
    if "vines_ratio_any_attractor" in ds:
        ax.plot(W, ds["vines_ratio_any_attractor"].values[j], "--", color=C_VINES, lw=1.4,
                label="VI NES, worst attractor")
    ax.plot(float(ds["vines_peak_omega"][j]), float(ds["vines_peak_ratio"][j]), "v",
            color="black", ms=6, label="VI NES worst from rest (refined)")
    ax.set_yscale("log")
    plain_log_ticks(ax.yaxis)
    ax.set_xlabel(LABELS["omega"])
    ax.set_ylabel(r"$x_{\max}/A$")
    A, F = float(ds["amplitude"][j]), float(ds["F"][j])
    panel_label(ax, k, rf"$A$ = {fmt(A * 1e3)} mm, $F$ = {F:.3g}")
    if "tmd_worst_travel" in ds:
        ax.text(0.02, 0.02, _travel_note(ds, A), transform=ax.transAxes, fontsize=7,
                va="bottom", bbox=dict(facecolor="white", alpha=0.8, lw=0))


def _travel_note(ds, A) -> str:
    """Each absorber's stroke relative to the LO at amplitude A."""
    L = 1e3 * float(ds["vines_stroke"])
    note = (f"stroke at this A: TMD {1e3 * A * float(ds['tmd_worst_travel']):.3g} mm, "
            rf"VI NES ball $\pm L$ = {L:.3g} mm")
    return note


def _search_panel(fig, ax, ds, i):
    """One cell per search-grid design over (L, eta): L logarithmic, cells halfway in log."""
    L = ds["search_clearance"].values * 1e3
    eta = ds["search_eta"].values
    z = ds["search_worst_ratio"].values
    norm = LogNorm(np.nanmin(z), np.nanmax(z)) if np.nanmin(z) > 0 else None
    mesh = ax.pcolormesh(log_cell_edges(L), cell_edges(eta, single=0.1 * eta[0]), z,
                         cmap=palette.colormap(), norm=norm, rasterized=True)
    fig.colorbar(mesh, ax=ax, label=r"worst $x_{\max}/A$ from rest (log scale)")
    ax.set_xscale("log")
    plain_log_ticks(ax.xaxis)
    ax.plot(float(ds["vines_clearance"]) * 1e3, float(ds["vines_eta"]), "*", color="white",
            mec="black", ms=16)
    ax.set_xlabel(r"clearance $L$ (mm)")
    ax.set_ylabel(LABELS["eta"])
    panel_label(ax, i, "search grid, star: chosen design" + _edge_note(ds))


def _edge_note(ds) -> str:
    """What edge of the search grid the chosen design lies on (a bound of the search,
    not an interior optimum), or nothing."""
    eta, L = float(ds["vines_eta"]), float(ds["vines_clearance"])
    etas, Ls = ds["search_eta"].values, ds["search_clearance"].values
    edges = []
    if eta >= etas.max() * (1 - 1e-12):
        edges.append(r"$\eta = \eta_{\max}$")
    lo, hi = float(Ls.min()) * (1 + 1e-12), float(Ls.max()) * (1 - 1e-12)
    if not lo < L < hi:
        edges.append("an end of the $L$ range")
    return "" if not edges else "\n(on the edge of the search: " + ", ".join(edges) + ")"


def _ratio_range(ds):
    """y range (log) of a row's curve panels holding every curve of every amplitude (the
    shared axis would otherwise keep the first panel's range and clip the others)."""
    names = ("lo_alone_ratio", "tmd_ratio", "vines_ratio", "vines_ratio_any_attractor",
             "vines_peak_ratio", "tmd_equal_travel_ratio")
    vals = np.concatenate([np.ravel(ds[v].values) for v in names if v in ds])
    vals = vals[np.isfinite(vals) & (vals > 0)]
    return 0.8 * float(vals.min()), 1.25 * float(vals.max())


def design_summary(ds) -> str:
    any_ = float(ds["vines_worst_ratio_any_attractor"])
    equal = ("" if "tmd_equal_travel_worst_ratio" not in ds else
             f", TMD with stroke <= L {float(ds['tmd_equal_travel_worst_ratio']):.3g}")
    stroke = ("" if "tmd_stroke" not in ds else
              f"\nstrokes at the largest A: TMD {1e3 * float(ds['tmd_stroke']):.3g} mm, "
              f"VI NES +-L {1e3 * float(ds['vines_stroke']):.3g} mm")
    return (f"worst x_max/A: LO alone {float(ds['lo_alone_worst_ratio']):.3g}, TMD "
            f"{float(ds['tmd_worst_ratio']):.3g}{equal}, VI NES from rest "
            f"{float(ds['vines_worst_ratio']):.3g}"
            + ("" if np.isnan(any_) else f", over attractors {any_:.3g}")
            + f" (eta = {float(ds['vines_eta']):.3g}, L = "
              f"{float(ds['vines_clearance']) * 1e3:.3g} mm){stroke}")


def design_figure(designs):
    """Per design a row: x_max/A over the band, one panel per base amplitude, and the
    worst ratio of every search-grid design over (L, eta) with the chosen one starred."""
    rows = [(ds, ds.sizes["amplitude"], "search_worst_ratio" in ds) for ds in designs]
    n = max(n_amp + int(search) for _, n_amp, search in rows)
    fig, axes = figure(len(rows), n, width=3.6 * n + 0.8, height=3.9 * len(rows))
    k = 0
    for i, (ds, n_amp, search) in enumerate(rows):
        for j in range(n_amp):
            _curve_panel(axes[i, j], ds, j, k)
            axes[i, j].sharey(axes[i, 0])
            k += 1
        axes[i, 0].set_ylim(*_ratio_range(ds))
        if search:
            _search_panel(fig, axes[i, n - 1], ds, k)
            k += 1
        for j in range(n_amp, n - int(search)):
            axes[i, j].set_visible(False)
    summary_and_legend(fig, [design_summary(ds) for ds in designs], axes[0, 0], ncol=5)
    return fig


# ------------------------------------------------------------------ design_robust

def robust(path):
    """A design-over-drift dataset (stage ``design_robust``), checked."""
    ds = load(path)
    require(ds, coords=("delta", "robust_delta"), min_size=1,
            finite=("lo_alone", "tmd", "vines", "robust_tmd", "robust_vines"))
    return ds


def _drift_panel(ax, ds, k):
    x, xr = ds["delta"].values, ds["robust_delta"].values
    ax.plot(x, ds["lo_alone"].values, color=C_LO_ALONE, lw=1.6, label="LO alone")
    ax.plot(x, ds["tmd"].values, color=C_TMD, lw=1.6, label=r"TMD tuned at $\delta$ = 0")
    ax.plot(xr, ds["robust_tmd"].values, "--", color=C_TMD, lw=1.6,
            label="TMD re-tuned for the drift")
    ax.plot(x, ds["vines"].values, "o-", color=C_VINES, ms=3, lw=1.4,
            label=r"VI NES designed at $\delta$ = 0, from rest")
    if "vines_any_attractor" in ds:
        ax.plot(x, ds["vines_any_attractor"].values, ":", color=C_VINES, lw=1.4,
                label=r"VI NES designed at $\delta$ = 0, worst of its attractors (census)")
    ax.plot(xr, ds["robust_vines"].values, "s--", color=C_VINES, ms=3, lw=1.4,
            label="VI NES optimised for the drift, from rest")
    ax.set_yscale("log")
    plain_log_ticks(ax.yaxis)
    ax.set_xlabel(r"host frequency drift $\delta$ (natural frequency $(1+\delta)\,\omega_0$)")
    ax.set_ylabel(r"worst $x_{\max}/A$ over band and amplitudes")
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    title = _drift_designs(ds)
    if k is None:                 # the only panel: no letter
        ax.set_title(title, loc="left", fontsize=9)
    else:
        panel_label(ax, k, title)


def _drift_designs(ds) -> str:
    """The designs at delta = 0 and those optimised for the drift, in the axes' symbols."""
    def v(name):
        return float(ds[name])
    arrow = r"$\rightarrow$"
    return (rf"at $\delta$ = 0 {arrow} for the drift: TMD "
            rf"$f$ {v('tmd_frequency_ratio'):.3f} {arrow} {v('robust_tmd_frequency_ratio'):.3f}; "
            rf"VI NES $\eta$ {v('vines_eta'):.3g}, $L$ {1e3 * v('vines_clearance'):.3g} mm "
            rf"{arrow} $\eta$ {v('robust_vines_eta'):.3g}, "
            rf"$L$ {1e3 * v('robust_vines_clearance'):.3g} mm")


def robust_summary(ds) -> str:
    def w(name):
        x = float(ds[name])
        return "n/a" if np.isnan(x) else f"{x:.3g}"
    return (rf"$|\delta| \leq$ {float(ds.attrs['mistuning']):g}, worst over the drift: LO alone "
            f"{w('worst_lo_alone')}; TMD {w('worst_tmd')} (re-tuned {w('robust_worst_tmd')}); "
            f"VI NES {w('worst_vines')} (optimised for the drift {w('robust_worst_vines')})")


def robust_figure(entries):
    """One panel per entry: the worst x_max/A against the host's drift delta, the designs
    chosen at delta = 0 (solid) and those optimised for the drift (dashed)."""
    fig, axes = figure(len(entries), 1, width=8.0, height=4.6 * len(entries))
    for i, ds in enumerate(entries):
        _drift_panel(axes[i, 0], ds, i if len(entries) > 1 else None)
    summary_and_legend(fig, [robust_summary(ds) for ds in entries], axes[0, 0], ncol=3)
    return fig


# ------------------------------------------------------------------ uncertainty

def study(path):
    """An uncertainty dataset (stage ``uncertainty``), checked."""
    ds = load(path)
    require(ds, variables=("parameter", "regime_group", "vines_first_order",
                           "vines_total_order", "tmd_first_order", "tmd_total_order"),
            finite=("vines_worst_ratio", "tmd_worst_ratio", "regime_share", "vines_mean",
                    "vines_q95", "vines_nominal", "tmd_mean", "tmd_q95", "tmd_nominal"))
    return ds


def _distribution_panel(ax, ds, k):
    vals = [ds[f"{key}_worst_ratio"].values for key, _, _ in SYSTEMS]
    lo, hi = min(v.min() for v in vals), max(v.max() for v in vals)
    bins = np.geomspace(0.95 * lo, 1.05 * hi, 60)
    for (key, label, colour), v in zip(SYSTEMS, vals, strict=True):
        ax.hist(v, bins=bins, color=colour, alpha=0.75,
                label=f"{label}: mean {float(ds[f'{key}_mean']):.3g}, "
                      f"95 % {float(ds[f'{key}_q95']):.3g}")
        ax.axvline(float(ds[f"{key}_nominal"]), color=colour, ls="--", lw=1.4)
        ax.axvline(float(ds[f"{key}_q95"]), color=colour, ls=":", lw=1.6)
    ax.set_xscale("log")
    plain_log_ticks(ax.xaxis)
    ax.set_xlabel(r"worst $x_{\max}/A$ over the band and amplitudes")
    ax.set_ylabel("points")
    ax.legend(fontsize=7, loc="upper center", frameon=False)
    panel_label(ax, k, f"{ds.sizes['point']} points, dashed: exact parts, dotted: 95 %")


def _indices_panel(ax, ds, k):
    names = list(ds["parameter"].values)
    x = np.arange(len(names))
    width = 0.2
    for s, (key, _, colour) in enumerate(SYSTEMS):
        reliable = ds[f"{key}_index_reliable"].values.astype(bool)
        for o, order in enumerate(("first_order", "total_order")):
            v = ds[f"{key}_{order}"].values
            ci = ds[f"{key}_{order}_ci"].values
            pos = x + (2 * s + o - 1.5) * width
            err = np.abs(np.stack([v - ci[:, 0], ci[:, 1] - v]))
            bars = ax.bar(pos, np.nan_to_num(v), width, color=colour,
                          alpha=1.0 if o else 0.55, edgecolor="black", lw=0.5,
                          yerr=np.nan_to_num(err), capsize=2, error_kw={"lw": 0.8})
            for b, ok, val in zip(bars, reliable, v, strict=True):
                if not ok:
                    b.set_hatch("////")
                if val == 0.0:          # a part without any effect: exactly 0
                    ax.text(b.get_x() + b.get_width() / 2, 0.02, "0", ha="center",
                            va="bottom", fontsize=7, color=colour)
    ax.axhline(0, color="black", lw=0.6)
    top = max(1.0, float(np.nanmax([ds[f"{key}_{o}_ci"].values for key, _, _ in SYSTEMS
                                    for o in ("first_order", "total_order")])))
    ax.set_ylim(top=1.45 * top)
    ax.set_xticks(x, names)
    ax.set_ylabel("Sobol index")
    handles = [Patch(color=C_VINES, alpha=0.55, label="VI NES first order"),
               Patch(color=C_VINES, label="VI NES total"),
               Patch(color=C_TMD, alpha=0.55, label="TMD first order"),
               Patch(color=C_TMD, label="TMD total"),
               Patch(facecolor="white", edgecolor="black", hatch="////",
                     label="unreliable (wide interval)")]
    ax.legend(handles=handles, fontsize=7, frameon=False, loc="upper center", ncol=3)
    panel_label(ax, k, "Sobol indices, 95 % bootstrap intervals")


def _regime_panel(ax, ds, k):
    groups = list(ds["regime_group"].values)
    shares = ds["regime_share"].values
    ax.bar(range(len(groups)), shares, color=[REGIME_COLOURS[g] for g in groups],
           edgecolor="black", lw=0.5)
    for i, v in enumerate(shares):
        ax.text(i, v + 0.02, f"{v:.0%}", ha="center", fontsize=8)
    ax.set_xticks(range(len(groups)), groups, rotation=20)
    ax.set_ylim(0, 1.12)
    ax.set_ylabel("share of the points")
    panel_label(ax, k, "VI NES regime at its worst point")


def uncertainty_summary(ds) -> str:
    """Two lines: the designs' mean worst ratio (exact parts), then how often the VI NES
    wins and is in its efficient regime."""
    return (rf"VI NES ($\eta$ {float(ds['vines_eta']):.3g}, $L$ "
            rf"{float(ds['vines_clearance']) * 1e3:.3g} mm): mean worst $x_{{\max}}/A$ "
            f"{float(ds['vines_mean']):.3g} (exact parts {float(ds['vines_nominal']):.3g}); "
            f"TMD {float(ds['tmd_mean']):.3g} ({float(ds['tmd_nominal']):.3g})\n"
            f"VI NES better at {float(ds['vines_better_probability']):.0%} of the points, "
            f"in 1:1 at its worst point at {float(ds['efficient_probability']):.0%}")


def _distribution_spec(ds, name: str) -> tuple[str, float, float] | None:
    """(kind, a, b) of the attribute ``distribution_<name>`` ("uniform:a:b (...)",
    "normal:mean:sd (...)"); None when absent or of another form."""
    spec = str(ds.attrs.get(f"distribution_{name}", "")).split(" ")[0].split(":")
    try:
        return spec[0], float(spec[1]), float(spec[2])
    except (IndexError, ValueError):
        return None


def _inputs_panel(ax, ds, k):
    """The uncertain parts: for each, its distribution's density (line, from the dataset's
    ``distribution_<name>`` attribute) over the histogram of the Sobol points' values, one
    inset a part (each on its own scale)."""
    names = [str(n) for n in ds["parameter"].values]
    ax.set_axis_off()
    panel_label(ax, k, "uncertain parts: density and sampled points")
    ax.set_title(ax.get_title(loc="left"), loc="left", fontsize=9)
    n = len(names)
    for i, name in enumerate(names):
        sub = ax.inset_axes([0.08, 1.0 - (i + 1) / n + 0.16 / n, 0.88, 0.62 / n])
        vals = ds["value"].sel(parameter=name).values
        spec = _distribution_spec(ds, name)
        lo, hi = float(vals.min()), float(vals.max())
        if spec is not None and spec[0] == "uniform":
            lo, hi = spec[1], spec[2]
        elif spec is not None and spec[0] == "normal":
            lo, hi = spec[1] - 3 * spec[2], spec[1] + 3 * spec[2]
        if not hi > lo:                   # a part held at one value: a line there
            sub.axvline(lo, color="black", lw=1.2, label="density (one value)")
            sub.set_xlim(lo - 0.5 * abs(lo) - 1e-3, lo + 0.5 * abs(lo) + 1e-3)
            spec, lo, hi = None, lo - 1e-9 * (1 + abs(lo)), hi + 1e-9 * (1 + abs(hi))
        sub.hist(vals, bins=np.linspace(lo, hi, 11), density=True, color="0.8",
                 edgecolor="0.4", lw=0.5, label="Sobol points")
        if spec is not None and spec[0] == "uniform":
            sub.plot([lo, lo, hi, hi], [0, 1 / (hi - lo), 1 / (hi - lo), 0], color="black",
                     lw=1.2, label="density")
        elif spec is not None and spec[0] == "normal":
            x = np.linspace(lo, hi, 200)
            sub.plot(x, np.exp(-0.5 * ((x - spec[1]) / spec[2]) ** 2)
                     / (spec[2] * np.sqrt(2 * np.pi)), color="black", lw=1.2, label="density")
        what = str(ds.attrs.get(f"distribution_{name}", "")).partition(" ")[2].strip("()")
        sub.set_xlabel(f"{name}" + (f" ({what})" if what else ""), fontsize=8, labelpad=1)
        sub.tick_params(labelsize=7)
        sub.set_yticks([])
        if i == 0:
            sub.legend(fontsize=7, frameon=False, loc="upper right")


def uncertainty_figure(studies):
    """Per study a row: the uncertain parts' distributions, the distribution of the worst
    ratio over the Sobol points, the Sobol indices with their intervals, the VI NES's
    regime at its worst point."""
    fig, axes = figure(len(studies), 4, width=19.0, height=4.6 * len(studies))
    for i, ds in enumerate(studies):
        _inputs_panel(axes[i, 0], ds, 4 * i)
        _distribution_panel(axes[i, 1], ds, 4 * i + 1)
        _indices_panel(axes[i, 2], ds, 4 * i + 2)
        _regime_panel(axes[i, 3], ds, 4 * i + 3)
    summary_and_legend(fig, [uncertainty_summary(ds) for ds in studies])
    return fig
