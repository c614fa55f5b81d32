"""Uncertain parts (beyond the paper; docs/design.md): per ``uncertainty`` entry, the
distribution of the worst ratio x_max/A over the Sobol points for the VI NES (orange) and
the TMD (blue) with their nominal values (dashed) and 95 % quantiles (dotted); the
first-order and total Sobol indices of each with 95 % bootstrap intervals (unreliable ones
hatched); the regime of the VI NES at its worst point, share of the points."""
import numpy as np
from matplotlib.patches import Patch
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

import vines.plotting as P
from vines.pipeline.jobs import run_job

C_TMD, C_VINES = P.palette.OKABE_ITO["blue"], P.palette.OKABE_ITO["orange"]
#: regime groups -> colour (the regime figures' colours)
REGIME_COLOURS = {"no-impact": P.palette.REGIMES[0][1], "1:1": P.palette.REGIMES[1][1],
                  "other periodic": P.palette.REGIMES[3][1],
                  "irregular": P.palette.REGIMES[4][1], "chatter": P.palette.REGIMES[5][1]}
SYSTEMS = (("vines", "VI NES", C_VINES), ("tmd", "TMD", C_TMD))


def study(path):
    ds = P.load(path)
    P.require(ds, variables=("parameter", "regime_group", "vines_first_order",
                             "vines_total_order", "tmd_first_order", "tmd_total_order"),
              finite=("vines_worst_ratio", "tmd_worst_ratio", "regime_share", "vines_mean",
                      "vines_q95", "vines_nominal", "tmd_mean", "tmd_q95", "tmd_nominal"))
    return ds


def distribution_panel(ax, ds, k):
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
    ax.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel(r"worst $x_{\max}/A$ over the band and amplitudes")
    ax.set_ylabel("points")
    ax.legend(fontsize=7, loc="upper center", frameon=False)
    P.panel_label(ax, k, f"{ds.sizes['point']} points, dashed: exact parts, dotted: 95 %")


def indices_panel(ax, ds, k):
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
    P.panel_label(ax, k, "Sobol indices, 95 % bootstrap intervals")


def regime_panel(ax, ds, k):
    groups = list(ds["regime_group"].values)
    shares = ds["regime_share"].values
    ax.bar(range(len(groups)), shares, color=[REGIME_COLOURS[g] for g in groups],
           edgecolor="black", lw=0.5)
    for i, v in enumerate(shares):
        ax.text(i, v + 0.02, f"{v:.0%}", ha="center", fontsize=8)
    ax.set_xticks(range(len(groups)), groups, rotation=20)
    ax.set_ylim(0, 1.12)
    ax.set_ylabel("share of the points")
    P.panel_label(ax, k, "VI NES regime at its worst point")


def summary(ds) -> str:
    return (f"VI NES eta {float(ds['vines_eta']):.3g}, L "
            f"{float(ds['vines_clearance']) * 1e3:.3g} mm: worst x_max/A mean "
            f"{float(ds['vines_mean']):.3g} (exact parts {float(ds['vines_nominal']):.3g}); "
            f"TMD {float(ds['tmd_mean']):.3g} ({float(ds['tmd_nominal']):.3g}); VI NES "
            f"better at {float(ds['vines_better_probability']):.0%} of the points; "
            f"1:1 at the worst point {float(ds['efficient_probability']):.0%}")


def main(sm):
    P.configure(sm)
    studies = [study(p) for p in sm.input.studies]
    fig, axes = P.figure(len(studies), 3, width=15.0, height=4.4 * len(studies))
    for i, ds in enumerate(studies):
        distribution_panel(axes[i, 0], ds, 3 * i)
        indices_panel(axes[i, 1], ds, 3 * i + 1)
        regime_panel(axes[i, 2], ds, 3 * i + 2)
        print(summary(ds))
    fig.suptitle("\n".join(summary(ds) for ds in studies), fontsize=9)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
