"""Basin slices: the attractor reached from each initial (z_m(0), z_m'(0)) with the ball at
rest in the middle of the cavity, one panel per slice (basins basin_*), each attractor in
its own colour (legend: regime, KE ratio, share of the slice), the start from rest marked."""
import numpy as np
from matplotlib.colors import BoundaryNorm, ListedColormap

import vines.plotting as P
from vines.pipeline.jobs import run_job

#: attractor colours in table order (largest basin first; the palette's categorical
#: colours, black kept for "other"); grey: run stopped early
COLOURS = [c for c in P.palette.CATEGORICAL if c != P.palette.OKABE_ITO["black"]]
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


def draw(ax, ds):
    idx = ds["attractor"].values
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
    rest = int(ds["from_rest"].values)
    notes = mirror_notes(ds, shown)
    for k in range(shown):
        frac = float(ds["basin_fraction"].values[k])
        mark = " (from rest)" if k == rest else ""
        handles.append(ax.fill_between([], [], color=COLOURS[k], label=(
            f"{k + 1}: {ds['regime'].values[k]}, KE {float(ds['ke_ratio'].values[k]):.3f}, "
            f"{100 * frac:.1f} %{notes[k]}{mark}")))
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.14), fontsize=7,
              frameon=False, ncol=1)
    ax.set_xlabel(r"initial LO displacement $z_m(0)$")
    ax.set_ylabel(r"initial LO velocity $\dot z_m(0)$")
    ax.set_aspect("equal")


def main(sm):
    P.configure(sm)
    slices = [P.basin_slice(p) for p in sm.input.slices]
    fig, axes = P.figure(1, len(slices), width=4.8 * len(slices), height=6.4)
    for j, ds in enumerate(slices):
        draw(axes[0, j], ds)
        a = ds.attrs
        P.panel_label(axes[0, j], j, rf"$\eta$ = {P.fmt(a['eta'])}, $\Omega$ = "
                                     rf"{P.fmt(a['omega'])}, $F$ = {P.fmt(a['F'])}")
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
