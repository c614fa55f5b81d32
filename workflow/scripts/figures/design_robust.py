"""Design over a drifting host (beyond the paper; docs/design.md, "Mistuning"): the worst
x_max/A over band and amplitudes against the host's frequency drift delta (natural
frequency (1 + delta) w0) for the LO alone (grey), the TMD (blue) and the VI NES from rest
(orange; dotted: over attractors), the designs chosen at delta = 0 (solid) and those
optimised for the worst case over the drift (dashed), one panel per entry."""
import numpy as np
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

import vines.plotting as P
from vines.pipeline.jobs import run_job

C_LO_ALONE, C_TMD, C_VINES = "0.45", P.palette.OKABE_ITO["blue"], P.palette.OKABE_ITO["orange"]


def robust(path):
    ds = P.load(path)
    P.require(ds, coords=("delta", "robust_delta"), min_size=1,
              finite=("lo_alone", "tmd", "vines", "robust_tmd", "robust_vines"))
    return ds


def panel(ax, ds, k):
    x, xr = ds["delta"].values, ds["robust_delta"].values
    ax.plot(x, ds["lo_alone"].values, color=C_LO_ALONE, lw=1.6, label="LO alone")
    ax.plot(x, ds["tmd"].values, color=C_TMD, lw=1.6, label=r"TMD tuned at $\delta$ = 0")
    ax.plot(xr, ds["robust_tmd"].values, "--", color=C_TMD, lw=1.6,
            label="TMD re-tuned for the drift")
    ax.plot(x, ds["vines"].values, "o-", color=C_VINES, ms=3, lw=1.4,
            label=r"VI NES designed at $\delta$ = 0, from rest")
    if "vines_any_attractor" in ds:
        ax.plot(x, ds["vines_any_attractor"].values, ":", color=C_VINES, lw=1.4,
                label="same, over attractors")
    ax.plot(xr, ds["robust_vines"].values, "s--", color=C_VINES, ms=3, lw=1.4,
            label="VI NES optimised for the drift, from rest")
    ax.set_yscale("log")
    ax.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel(r"host frequency drift $\delta$ (natural frequency $(1+\delta)\,\omega_0$)")
    ax.set_ylabel(r"worst $x_{\max}/A$ over band and amplitudes")
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    P.panel_label(ax, k, describe(ds))


def describe(ds) -> str:
    def v(name):
        return float(ds[name])
    return (f"TMD f {v('tmd_frequency_ratio'):.3f} -> {v('robust_tmd_frequency_ratio'):.3f}; "
            f"VI NES eta {v('vines_eta'):.3g}, L {1e3 * v('vines_clearance'):.3g} mm -> "
            f"eta {v('robust_vines_eta'):.3g}, L {1e3 * v('robust_vines_clearance'):.3g} mm")


def summary(ds) -> str:
    def w(name):
        x = float(ds[name])
        return "n/a" if np.isnan(x) else f"{x:.3g}"
    return (rf"$|\delta| \leq$ {float(ds.attrs['mistuning']):g}, worst over the drift: LO alone "
            f"{w('worst_lo_alone')}; TMD {w('worst_tmd')} (re-tuned {w('robust_worst_tmd')}); "
            f"VI NES {w('worst_vines')} (optimised for the drift {w('robust_worst_vines')})")


def main(sm):
    P.configure(sm)
    entries = [robust(p) for p in sm.input.robust]
    fig, axes = P.figure(len(entries), 1, width=8.0, height=4.6 * len(entries))
    for i, ds in enumerate(entries):
        panel(axes[i, 0], ds, i)
        print(summary(ds))
    fig.suptitle("\n".join(summary(ds) for ds in entries), fontsize=9)
    fig.legend(handles=axes[0, 0].get_legend_handles_labels()[0], loc="outside lower center",
               ncol=3, fontsize=8, frameon=False)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
