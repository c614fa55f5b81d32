"""Basin slices on figures: the attractor reached from each initial (z_m(0), z_m'(0)) with
the ball at rest in the middle of the cavity, each attractor in its own colour (datasets of
the stage ``basin_slice``), in the window view and, where the datasets have it, the
asymptotic one."""
from __future__ import annotations

import numpy as np
from matplotlib.colors import BoundaryNorm, ListedColormap

from . import palette
from .draw import figure, fmt, panel_label

#: attractor colours in table order (largest basin first; the palette's categorical
#: colours, black kept for "other"); grey: run stopped early
COLOURS = [c for c in palette.CATEGORICAL if c != palette.OKABE_ITO["black"]]
UNSETTLED = "0.5"


def mirror_notes(ds, shown: int) -> list:
    """Legend suffix ', mirror image of k' for attractors with the same regime, KE ratio
    and x_max (z -> -z, t -> t + T/2 maps an asymmetric orbit onto its twin)."""
    notes = [""] * shown
    ke, xm, reg = ds["ke_ratio"].values, ds["xmax_m"].values, ds["regime"].values
    for k in range(shown):
        for j in range(k):
            if reg[j] == reg[k] and np.isclose(ke[j], ke[k], rtol=1e-6, atol=0) \
                    and np.isclose(xm[j], xm[k], rtol=1e-6, atol=0):
                notes[j] = notes[j] or f", mirror image of {k + 1}"
                notes[k] = f", mirror image of {j + 1}"
                break
    return notes


def regime_label(ds, k: int, view: str) -> str:
    """Attractor k's regime: the window's label; in the asymptotic view the label at t_max
    (``regime_asymptotic``: quasi-periodic for a lasting motion on a torus) where the
    dataset has it, its legend text from the palette."""
    label = str(ds["regime"].values[k])
    if view == "asymptotic" and "regime_asymptotic" in ds:
        label = str(ds["regime_asymptotic"].values[k])
    return palette.CENSUS_REGIMES.get(label, (label,))[0]


#: view -> (attractor map, basin fraction, from-rest index) variables
VIEWS = {"window": ("attractor", "basin_fraction", "from_rest"),
         "asymptotic": ("attractor_asymptotic", "basin_fraction_asymptotic",
                        "from_rest_asymptotic")}


def draw(ax, ds, view="window"):
    var_map, var_frac, var_rest = VIEWS[view]
    idx = ds[var_map].values
    n_att = ds.sizes["attractor_index"]
    shown = min(n_att, len(COLOURS))
    codes = np.where(idx >= shown, shown, idx)      # beyond the palette: one "other" colour
    cmap = ListedColormap([UNSETTLED] + COLOURS[:shown] + ["black"])
    norm = BoundaryNorm(np.arange(-1.5, shown + 1.5), cmap.N)
    z, v = ds["z_m0"].values, ds["v_m0"].values
    ax.pcolormesh(z, v, codes.T, cmap=cmap, norm=norm, shading="nearest")
    ax.plot(0.0, 0.0, marker="*", ms=13, mfc="white", mec="black", ls="none",
            label="start from rest")
    handles = [ax.lines[-1]]
    rest = int(ds[var_rest].values)
    notes = mirror_notes(ds, shown)
    for k in range(shown):
        frac = float(ds[var_frac].values[k])
        mark = " (from rest)" if k == rest else ""
        status = f", {ds['status'].values[k]}" if view == "asymptotic" else ""
        handles.append(ax.fill_between([], [], color=COLOURS[k], label=(
            f"{k + 1}: {regime_label(ds, k, view)}, "
            f"KE {float(ds['ke_ratio'].values[k]):.3f}, "
            f"{100 * frac:.1f} %{status}{notes[k]}{mark}")))
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.14), fontsize=7,
              frameon=False, ncol=1)
    ax.set_xlabel(r"initial LO displacement $z_m(0)$")
    ax.set_ylabel(r"initial LO velocity $\dot z_m(0)$")
    ax.set_aspect("equal")


def basin_figure(slices):
    """One column per basin slice: the window view, and under it the asymptotic view when
    every slice has it (config t_max), each panel titled by its point and view."""
    views = ["window"] + (["asymptotic"] if all("attractor_asymptotic" in ds for ds in slices)
                          else [])
    n = len(slices)
    fig, axes = figure(len(views), n, width=4.8 * n, height=6.4 * len(views))
    for i, view in enumerate(views):
        for j, ds in enumerate(slices):
            draw(axes[i, j], ds, view)
            a = ds.attrs
            when = (rf"window view, state at $t$ = {fmt(a['solver_t_end'])}"
                    if view == "window" else
                    rf"asymptotic view, state at $t$ = {fmt(a['t_max'])}")
            panel_label(axes[i, j], i * n + j,
                        rf"$\eta$ = {fmt(a['eta'])}, $\Omega$ = {fmt(a['omega'])}, "
                        rf"$F$ = {fmt(a['F'])}" + "\n" + when)
    return fig
