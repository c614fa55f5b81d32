"""Orbit atlas (beyond the paper; docs/bifurcation.md): per F a row, (left) the periodic
family group that is stable and admissible at each (eta, W) (orbit_atlas atlas_*; the
group of the smallest lambda_max where several are stable, hatched there), dark grey where only
unstable or non-admissible orbits were found, white where no seed reached any family;
with the boundary curves of the families beyond 1:1 computed at that F (boundaries
entries with walls, e.g. llrr_F0.4: fold, symmetry-breaking, grazing of LLRR/1-sym;
coloured by curve type as on Fig 16) where configured;
(right) the regime the simulation from rest settles on (Fig 12's grid at the same F,
grids.fig12_*): its periodic families in the atlas's colours, the other regimes in the
regime colours of every regime figure (palette.REGIMES). One legend of exactly the
classes drawn. The atlas is a finite search: absent means that no seed reached a family,
not that none exists."""

import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import atlas as A
from vines.plotting import bifurcation as B


def atlas_panel(ax, ds, k, curves):
    """The atlas at one F and the boundary curves ``curves`` (datasets at that F); returns
    the class codes and the (curve type, family) pairs drawn."""
    eta, W = ds["eta"].values, ds["omega"].values
    codes, coexist = A.atlas_codes(ds)
    P.class_map(ax, eta, W, codes.T, A.atlas_classes())
    P.hatch_cells(ax, eta, W, coexist.T, hatch="xx", color="0.5")
    _axes(ax, eta, W)
    drawn = set()
    for c in curves:
        drawn |= B.draw_curves(ax, c)
    families = sorted({fam for _, fam in drawn})
    P.panel_label(ax, k, rf"orbit atlas, $F$ = {P.fmt(float(ds.attrs['F']))}"
                  + (f"; boundaries of {', '.join(families)}" if families else ""))
    return codes, drawn


def sim_panel(ax, grid, k):
    eta, W = grid["eta"].values, grid["omega"].values
    regime = grid["regime"].isel(F=0).transpose("eta", "omega").values
    P.class_map(ax, eta, W, A.sim_codes(regime).T, A.sim_classes())
    _axes(ax, eta, W)
    P.panel_label(ax, k, rf"simulation from rest (Fig. 12 grid), $F$ = "
                         rf"{P.fmt(P.fixed_value(grid, 'F'))}")
    return regime


def _axes(ax, eta, W):
    ax.set_xlim(eta.min(), eta.max())
    ax.set_ylim(W.min(), W.max())
    ax.set_xlabel(P.LABELS["eta"])
    ax.set_ylabel(P.LABELS["omega"])


def report(ds, grid, regime):
    codes, coexist = A.atlas_codes(ds)
    F = float(ds.attrs["F"])
    counts = {lab: int((codes == c).sum()) for c, (lab, _) in A.atlas_classes().items()}
    print(f"F = {F}: atlas points by group {counts}; >= 2 groups stable at "
          f"{int(coexist.sum())} of {coexist.size}")
    if grid is not None:
        agr = A.agreement(ds, grid["eta"].values, grid["omega"].values, regime)
        print(f"F = {F}: simulation on an atlas family at {agr['n']} shared points, stable "
              f"and admissible in the atlas at {agr['agree']}; others (eta, W, regime): "
              + ", ".join(f"({e:.4g}, {w:.4g}, {r})" for e, w, r in agr["misses"]))


def legend(fig, drawn_atlas, drawn_sim, any_coexist, drawn_curves):
    """One legend of what the panels draw, in their colours."""
    handles = [P.Patch(facecolor=col, edgecolor="black", lw=0.5, label=lab)
               for lab, col in A.legend_entries(drawn_atlas, drawn_sim)]
    if any_coexist:
        handles.append(P.Patch(facecolor="white", edgecolor="0.5", hatch="xx",
                               label="atlas: >= 2 groups stable"))
    handles += B.curve_handles(drawn_curves, note=False)
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=7, frameon=False)


def main(sm):
    P.configure(sm)
    atlases = sorted(map(A.atlas, sm.input.atlases), key=lambda d: float(d.attrs["F"]))
    grids = {round(P.fixed_value(g, "F"), 9): g
             for g in (P.load(p) for p in sm.input.measures)}
    curves = [B.boundaries(p) for p in getattr(sm.input, "boundaries", [])]
    n = len(atlases)
    fig, axes = P.figure(n, 2, width=9.8, height=3.5 * n + 0.6)
    drawn_atlas, drawn_sim, any_coexist, drawn_curves = [], [], False, set()
    for i, ds in enumerate(atlases):
        F = round(float(ds.attrs["F"]), 9)
        codes, drawn = atlas_panel(axes[i, 0], ds, 2 * i,
                                   [c for c in curves if round(float(c.attrs["F"]), 9) == F])
        drawn_atlas.append(codes.ravel())
        drawn_curves |= drawn
        if drawn:
            print(f"F = {F}: boundary curves drawn on the atlas (type, family): "
                  + ", ".join(f"{t} {fam}" for t, fam in sorted(drawn)))
        any_coexist |= bool(A.atlas_codes(ds)[1].any())
        grid = grids.get(round(float(ds.attrs["F"]), 9))
        regime = None
        if grid is None:
            axes[i, 1].set_axis_off()
            axes[i, 1].text(0.5, 0.5, "no Fig. 12 grid at this F", ha="center",
                            transform=axes[i, 1].transAxes)
        else:
            regime = sim_panel(axes[i, 1], grid, 2 * i + 1)
            drawn_sim.append(A.sim_codes(regime).ravel())
        report(ds, grid, regime)
    legend(fig, np.concatenate(drawn_atlas), np.concatenate(drawn_sim or [[]]).astype(int),
           any_coexist, drawn_curves)
    fig.suptitle("atlas: finite search (absent = no seed reached the family); "
                 "simulation: finite-time regime from rest", fontsize=8)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
