"""The shock figure's panels: the fraction of a shock's energy dissipated within the window
against the initial energy (with its spread over random ball starts), the energy left in
time at a few initial energies, and each absorber's travel against the initial energy, for
the VI NES, the equal-mass TMDs (band-tuned, fastest, fastest within the clearance) and the
LO alone (datasets of the stage ``shock``)."""
from __future__ import annotations

import numpy as np
import xarray as xr

from . import palette
from .checks import load, require
from .draw import figure, panel_label, plain_log_ticks, summary_and_legend

C_LO_ALONE, C_TMD = "0.45", palette.OKABE_ITO["blue"]
C_VINES = palette.OKABE_ITO["orange"]
#: the VI NES's decays in time: one colour per initial energy, light to dark
C_HISTORY = ("#F5C26B", palette.OKABE_ITO["orange"], palette.OKABE_ITO["vermillion"],
             "#8B3A00", "#4A1F00")
#: the lowest energy fraction drawn on the decay panel
E_FLOOR = 1e-6


def shock(path) -> xr.Dataset:
    """A shock dataset, checked: the curve, the decays in time, the linear systems."""
    ds = load(path)
    return require(ds, coords=("energy", "history_energy", "time_periods"), min_size=1,
                   variables=("vines_remaining",),
                   finite=("vines_dissipated_fraction", "vines_by_impacts", "tmd_remaining",
                           "lo_alone_remaining", "tmd_dissipated_fraction",
                           "lo_alone_dissipated_fraction", "activation_energy"))


def curve_panel(ax, ds: xr.Dataset) -> None:
    """Dissipated fraction within the window against E0 (log): the VI NES (dots, its share
    by impacts dashed), the TMD and the LO alone (flat: linear), the activation energy
    (dotted) and the VI NES's best energy (triangle)."""
    E = ds["energy"].values
    ax.axhline(float(ds["lo_alone_dissipated_fraction"]), color=C_LO_ALONE, lw=1.6,
               label="LO alone")
    ax.axhline(float(ds["tmd_dissipated_fraction"]), color=C_TMD, lw=1.6,
               label=rf"TMD, equal mass, band-tuned ($f$ = {float(ds['tmd_frequency_ratio']):.3g}, "
                     rf"$\zeta$ = {float(ds['tmd_damping_ratio']):.3g})")
    for name, ls, what in (("tmd_fastest", "-.", "fastest decay"),
                           ("tmd_equal_travel", ":", "fastest decay, stroke <= L")):
        if f"{name}_dissipated_fraction" in ds:
            ax.axhline(float(ds[f"{name}_dissipated_fraction"]), color=C_TMD, ls=ls, lw=1.6,
                       label=f"TMD, {what}")
    if "vines_start_quantile" in ds:
        q = ds["vines_start_quantile"].values
        ax.fill_between(E, q[:, 0], q[:, -1], color=C_VINES, alpha=0.18, lw=0,
                        label=f"VI NES, {ds.sizes['start']} random ball starts: 5-95 %")
        ax.fill_between(E, q[:, 1], q[:, -2], color=C_VINES, alpha=0.35, lw=0,
                        label="VI NES, random ball starts: 25-75 %")
    ax.plot(E, ds["vines_dissipated_fraction"].values, "o-", color=C_VINES, ms=3, lw=1.4,
            label="VI NES, total (ball at rest in the centre)")
    ax.plot(E, ds["vines_by_impacts"].values, "--", color=C_VINES, lw=1.2,
            label="VI NES, by impacts")
    ax.axvline(float(ds["activation_energy"]), color="black", ls=":", lw=1.0,
               label="activation (first peak reaches the wall)")
    ax.plot(float(ds["optimal_energy"]), float(ds["optimal_dissipated_fraction"]), "v",
            color="black", ms=6, label="VI NES best")
    ax.set_xscale("log")
    plain_log_ticks(ax.xaxis, subs=(1.0,))
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel(r"initial energy $E_0 = M V_0^2/2$ (J)")
    ax.set_ylabel(f"fraction of $E_0$ dissipated in {ds.attrs['periods']:g} periods")


def decay_panel(ax, ds: xr.Dataset) -> None:
    """Energy left E/E0 (log) against time in natural periods of the LO: the VI NES at each
    history energy, the TMD and the LO alone (any E0)."""
    t = ds["time_periods"].values
    floor = E_FLOOR
    ax.semilogy(t, np.maximum(ds["tmd_remaining"].values, floor), color=C_TMD, lw=1.6,
                label="TMD (any $E_0$)")
    for k, E0 in enumerate(ds["history_energy"].values):
        rem = ds["vines_remaining"].values[k]
        ax.semilogy(t, np.maximum(rem, floor), color=C_HISTORY[k % len(C_HISTORY)], lw=1.3,
                    label=rf"VI NES, $E_0$ = {E0:g} J")
    # on top, dashed: below activation the VI NES's decay is the LO alone's
    ax.semilogy(t, np.maximum(ds["lo_alone_remaining"].values, floor), "--",
                color=C_LO_ALONE, lw=1.4, zorder=3, label="LO alone (any $E_0$)")
    for level in (0.1, 0.01):
        ax.axhline(level, color="0.8", lw=0.8, zorder=0)
    ax.set_ylim(floor, 1.5)
    ax.set_xlim(t[0], t[-1])
    ax.set_xlabel(r"time after the shock $t\,\omega_0/2\pi$ (natural periods of the LO)")
    ax.set_ylabel(r"energy left $E/E_0$")


def travel_panel(ax, ds: xr.Dataset) -> None:
    """Peak travel relative to the LO against E0 (log-log): each TMD's peak |y - x| after
    the shock (linear: grows like V0), the VI NES's +-L and the LO alone's own x_max."""
    E = ds["energy"].values
    ax.axhline(1e3 * float(ds["vines_stroke"]), color=C_VINES, lw=1.8,
               label="VI NES: ball travel L")
    for name, ls in (("tmd", "-"), ("tmd_fastest", "-."), ("tmd_equal_travel", ":")):
        if f"{name}_stroke" in ds:
            ax.loglog(E, 1e3 * ds[f"{name}_stroke"].values, ls, color=C_TMD, lw=1.6)
    ax.loglog(E, 1e3 * ds["lo_alone_x_max"].values, "--", color=C_LO_ALONE, lw=1.2,
              label=r"LO alone: its own peak $|x|$")
    ax.set_xlabel(r"initial energy $E_0$ (J)")
    ax.set_ylabel(r"peak travel after the shock (mm)")


def summary(ds: xr.Dataset) -> str:
    """One line: the design, the activation and best energies, the three fractions."""
    a = ds.attrs
    return (f"eta = {a['eta']:g}, L = {a['clearance_m'] * 1e3:.3g} mm, {a['periods']:g} "
            f"periods: VI NES best {float(ds['optimal_dissipated_fraction']):.4f} at "
            f"{float(ds['optimal_energy']):.3g} J (activation "
            f"{float(ds['activation_energy']):.3g} J), TMD "
            f"{float(ds['tmd_dissipated_fraction']):.4f}, LO alone "
            f"{float(ds['lo_alone_dissipated_fraction']):.4f}")


def shock_figure(rows):
    """One row per shock dataset: ``curve_panel`` and ``decay_panel``; one legend below."""
    fig, axes = figure(len(rows), 3, width=15.0, height=3.9 * len(rows) + 0.9)
    for i, ds in enumerate(rows):
        curve_panel(axes[i, 0], ds)
        decay_panel(axes[i, 1], ds)
        travel_panel(axes[i, 2], ds)
        where = rf"$\eta$ = {ds.attrs['eta']:g}, $L$ = {ds.attrs['clearance_m'] * 1e3:.3g} mm"
        panel_label(axes[i, 0], 3 * i, f"dissipated against initial energy ({where})")
        panel_label(axes[i, 1], 3 * i + 1, f"energy left in time ({where})")
        panel_label(axes[i, 2], 3 * i + 2, "travel relative to the LO")
        axes[i, 1].legend(fontsize=7, loc="lower left", frameon=False)
        print(summary(ds))
    summary_and_legend(fig, [], axes[0, 0], ncol=3)
    return fig
