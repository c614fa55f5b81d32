"""Orbit atlases (``orbit_atlas`` datasets) on figures: the stable family group at each
point, the simulation's regime in the same groups, and their agreement where the two grids
share points (``agreement``); the atlas figure (``atlas_figure``: each atlas beside the
simulation's regimes). Reads datasets only."""
from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib import patheffects
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from . import palette
from .bifurcation import curve_handles, draw_curves
from .checks import FigureInputError, fixed_value, load, require
from .draw import LABELS, class_map, figure, fmt, panel_label

#: category codes of the atlas map: 0 nothing found, 1 found but none stable, else 2 + the
#: index of the group in palette.FAMILY_GROUPS
NONE_FOUND, NONE_STABLE, FIRST_GROUP = 0, 1, 2
GROUPS = list(palette.FAMILY_GROUPS)
#: simulated regimes (``core.regime`` labels) -> atlas group (1:1 unsplit: both 1:1 groups)
SIM_GROUPS = {"1:1": ("1:1 symmetric", "1:1 asymmetric"), "2:2": ("2:2",), "2:1": ("2:1",),
              "3:2": ("3:2",), "3:3": ("3:3",), "period-2": ("period-2",)}


def atlas(path) -> xr.Dataset:
    """An orbit atlas over (eta, omega) with flags per family and the attribute F."""
    ds = load(path)
    require(ds, coords=("eta", "omega"), min_size=2,
            variables=("found", "admissible", "stable", "lambda_max", "paper_label"))
    if "F" not in ds.attrs:
        raise FigureInputError(f"{ds.attrs['_path']}: global attribute 'F' is missing")
    return ds


def family_group(ds: xr.Dataset) -> list[str]:
    """Group (key of palette.FAMILY_GROUPS) of each family of the atlas."""
    out = []
    for fam, label in zip(ds["family"].values, ds["paper_label"].values, strict=True):
        if label == "1:1":
            label = "1:1 asymmetric" if str(fam).endswith("-asym") else "1:1 symmetric"
        out.append(str(label))
    return out


def stable_groups(ds: xr.Dataset) -> np.ndarray:
    """Bool (group, eta, omega): a family of the group is stable and admissible."""
    groups = np.array(family_group(ds))
    st = ds["stable"].values.astype(bool)
    return np.stack([st[groups == g].any(axis=0) for g in GROUPS])


def atlas_codes(ds: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """(codes, coexist) over (eta, omega): the group of the stable family with the smallest
    lambda_max (NONE_FOUND / NONE_STABLE otherwise), and where >= 2 groups are stable."""
    groups = np.array(family_group(ds))
    lam = np.where(ds["stable"].values.astype(bool), ds["lambda_max"].values, np.inf)
    best = np.argmin(lam, axis=0)
    codes = FIRST_GROUP + np.array([GROUPS.index(g) for g in groups])[best]
    codes = np.where(np.isfinite(np.min(lam, axis=0)), codes, NONE_STABLE)
    codes = np.where(ds["found"].values.astype(bool).any(axis=0), codes, NONE_FOUND)
    return codes, stable_groups(ds).sum(axis=0) >= 2


def atlas_classes() -> dict:
    """code -> (label, colour) of ``atlas_codes`` for ``draw.class_map``."""
    out = {NONE_FOUND: ("no orbit found (finite search)", palette.ATLAS_NONE_FOUND),
           NONE_STABLE: ("orbits found, none stable and admissible", palette.ATLAS_NONE_STABLE)}
    out.update({FIRST_GROUP + i: (g, palette.FAMILY_GROUPS[g]) for i, g in enumerate(GROUPS)})
    return out


SIM_LABELS = ["1:1", "2:2", "2:1", "3:2", "3:3", "period-2", "other periodic", "irregular",
              "chatter", "no-impact"]


def sim_classes() -> dict:
    """code -> (label, colour) of ``sim_codes``."""
    colours = {"1:1": palette.FAMILY_GROUPS["1:1 symmetric"], **{
        k: palette.FAMILY_GROUPS[k] for k in ("2:2", "2:1", "3:2", "3:3", "period-2")},
        **palette.SIM_OTHER}
    return {i: (lab, colours[lab]) for i, lab in enumerate(SIM_LABELS)}


def legend_entries(atlas_drawn, sim_drawn) -> list[tuple[str, str]]:
    """(label, colour) of every class drawn, as drawn: the family groups found in either
    panel (a simulated family in its group's colour, a simulated 1:1 of either symmetry in
    the symmetric one's), then the atlas-only classes (codes ``atlas_drawn`` of
    ``atlas_classes``) and the simulation-only regimes (codes ``sim_drawn`` of
    ``sim_classes``)."""
    atlas_cls, sim_cls = atlas_classes(), sim_classes()
    atlas_drawn = {int(c) for c in np.unique(atlas_drawn)}
    sim_labels = {sim_cls[int(c)][0] for c in np.unique(sim_drawn)}
    groups, atlas_only = [], []
    for code, (label, colour) in atlas_cls.items():
        simulated = ("1:1" if label == "1:1 symmetric" else label) in sim_labels
        if code < FIRST_GROUP:
            if code in atlas_drawn:
                atlas_only.append((f"atlas: {label}", colour))
        elif code in atlas_drawn or simulated:
            if label == "1:1 symmetric" and simulated:
                label += " (simulation: 1:1 of either symmetry)"
            groups.append((label, colour))
    sim_only = [(f"simulation: {lab}", col) for lab, col in sim_cls.values()
                if lab in palette.SIM_OTHER and lab in sim_labels]
    return groups + atlas_only + sim_only


def _sim_label(regime: str) -> str:
    if regime in SIM_LABELS:
        return regime
    return "other periodic" if ":" in regime or regime.startswith("period-") else "irregular"


def sim_codes(regime: np.ndarray) -> np.ndarray:
    """Codes of ``sim_classes`` of an array of regime labels."""
    return np.vectorize(lambda r: SIM_LABELS.index(_sim_label(str(r))), otypes=[int])(regime)


def agreement(ds: xr.Dataset, eta, omega, regime) -> dict:
    """Where the simulation from rest (``regime`` over (eta, omega)) settles on a family
    group of the atlas, at the points the two grids share: the points counted, those where
    a family of that group is stable and admissible in the atlas, and the rest as
    (eta, omega, regime)."""
    ie = {round(float(v), 12): i for i, v in enumerate(ds["eta"].values)}
    iw = {round(float(v), 12): j for j, v in enumerate(ds["omega"].values)}
    groups = stable_groups(ds)
    n, ok, misses = 0, 0, []
    for a, e in enumerate(np.asarray(eta, float)):
        for b, w in enumerate(np.asarray(omega, float)):
            reg = str(regime[a, b])
            i, j = ie.get(round(e, 12)), iw.get(round(w, 12))
            if reg not in SIM_GROUPS or i is None or j is None:
                continue
            n += 1
            if any(groups[GROUPS.index(g), i, j] for g in SIM_GROUPS[reg]):
                ok += 1
            else:
                misses.append((e, w, reg))
    return {"n": n, "agree": ok, "misses": misses}


# ------------------------------------------------------------------ the figure

def _atlas_panel(ax, ds, k, curves):
    """The atlas at one F and the boundary curves ``curves`` (datasets at that F); returns
    the class codes and the (curve type, family) pairs drawn."""
    eta, W = ds["eta"].values, ds["omega"].values
    codes, coexist = atlas_codes(ds)
    class_map(ax, eta, W, codes.T, atlas_classes())
    _mark_coexistence(ax, eta, W, coexist)
    _axes(ax, eta, W)
    drawn = set()
    for c in curves:
        drawn |= draw_curves(ax, c, lw=CURVE_LW)
    families = sorted({fam for _, fam in drawn})
    panel_label(ax, k, rf"orbit atlas, $F$ = {fmt(float(ds.attrs['F']))}"
                + (f"; boundaries of {', '.join(families)}" if families else ""))
    return codes, drawn


#: width of the boundary curves on the atlas (over the class colours: wider than elsewhere)
CURVE_LW = 2.2
#: the mark of a point where >= 2 family groups are stable: white on a black outline, seen
#: on every class colour (a hatch in one colour vanished on the dark ones)
COEXIST_MARK = dict(marker="x", ls="none", color="white", ms=4.5, mew=1.3,
                    path_effects=[patheffects.Stroke(linewidth=3.0, foreground="black"),
                                  patheffects.Normal()])


def _mark_coexistence(ax, eta, W, coexist):
    """A mark at every grid point of the atlas where >= 2 family groups are stable."""
    i, j = np.nonzero(coexist)
    if i.size:
        ax.plot(eta[i], W[j], **COEXIST_MARK)


def _sim_panel(ax, grid, k):
    eta, W = grid["eta"].values, grid["omega"].values
    regime = grid["regime"].isel(F=0).transpose("eta", "omega").values
    class_map(ax, eta, W, sim_codes(regime).T, sim_classes())
    _axes(ax, eta, W)
    panel_label(ax, k, rf"simulation from rest (Fig. 12 grid), $F$ = "
                       rf"{fmt(fixed_value(grid, 'F'))}")
    return regime


def _axes(ax, eta, W):
    ax.set_xlim(eta.min(), eta.max())
    ax.set_ylim(W.min(), W.max())
    ax.set_xlabel(LABELS["eta"])
    ax.set_ylabel(LABELS["omega"])


def _report(ds, grid, regime):
    codes, coexist = atlas_codes(ds)
    F = float(ds.attrs["F"])
    counts = {lab: int((codes == c).sum()) for c, (lab, _) in atlas_classes().items()}
    print(f"F = {F}: atlas points by group {counts}; >= 2 groups stable at "
          f"{int(coexist.sum())} of {coexist.size}")
    if grid is not None:
        agr = agreement(ds, grid["eta"].values, grid["omega"].values, regime)
        print(f"F = {F}: simulation on an atlas family at {agr['n']} shared points, stable "
              f"and admissible in the atlas at {agr['agree']}; others (eta, W, regime): "
              + ", ".join(f"({e:.4g}, {w:.4g}, {r})" for e, w, r in agr["misses"]))


def _legend(fig, drawn_atlas, drawn_sim, any_coexist, drawn_curves):
    """One legend of what the panels draw, in their colours, in three titled columns:
    the periodic families (both panels), what only one panel draws, the atlas's marks and
    curves."""
    entries = legend_entries(drawn_atlas, drawn_sim)
    families = [Patch(facecolor=col, edgecolor="black", lw=0.5, label=lab)
                for lab, col in entries if not lab.startswith(("atlas:", "simulation:"))]
    one_panel = [Patch(facecolor=col, edgecolor="black", lw=0.5, label=lab)
                 for lab, col in entries if lab.startswith(("atlas:", "simulation:"))]
    marks = [Line2D([], [], label="atlas: >= 2 family groups stable", **COEXIST_MARK)
             ] if any_coexist else []
    marks += curve_handles(drawn_curves, note=False)
    columns = [("periodic family (both panels)", families),
               ("one panel only", one_panel), ("atlas: marks and curves", marks)]
    columns = [(title, hs) for title, hs in columns if hs]
    rows = max(len(hs) for _, hs in columns) + 1
    handles = []
    for title, hs in columns:      # column-major: each column a title, its entries, blanks
        blank = [Patch(visible=False, label="")] * (rows - 1 - len(hs))
        handles += [Patch(visible=False, label=title), *hs, *blank]
    leg = fig.legend(handles=handles, loc="outside lower center", ncol=len(columns),
                     fontsize=7, frameon=False)
    for text, h in zip(leg.get_texts(), handles, strict=True):
        if not h.get_visible() and text.get_text():
            text.set_fontweight("bold")


def atlas_figure(atlases, grids: dict, curves):
    """Per atlas (one row each, sorted by F) the atlas with the boundary curves of
    ``curves`` at its F, beside the regime from rest of ``grids[F]`` (Fig 12's grid)."""
    n = len(atlases)
    fig, axes = figure(n, 2, width=9.8, height=3.5 * n + 0.6)
    drawn_atlas, drawn_sim, any_coexist, drawn_curves = [], [], False, set()
    for i, ds in enumerate(atlases):
        F = round(float(ds.attrs["F"]), 9)
        codes, drawn = _atlas_panel(axes[i, 0], ds, 2 * i,
                                    [c for c in curves if round(float(c.attrs["F"]), 9) == F])
        drawn_atlas.append(codes.ravel())
        drawn_curves |= drawn
        if drawn:
            print(f"F = {F}: boundary curves drawn on the atlas (type, family): "
                  + ", ".join(f"{t} {fam}" for t, fam in sorted(drawn)))
        any_coexist |= bool(atlas_codes(ds)[1].any())
        grid = grids.get(round(float(ds.attrs["F"]), 9))
        regime = None
        if grid is None:
            axes[i, 1].set_axis_off()
            axes[i, 1].text(0.5, 0.5, "no Fig. 12 grid at this F", ha="center",
                            transform=axes[i, 1].transAxes)
        else:
            regime = _sim_panel(axes[i, 1], grid, 2 * i + 1)
            drawn_sim.append(sim_codes(regime).ravel())
        _report(ds, grid, regime)
    _legend(fig, np.concatenate(drawn_atlas), np.concatenate(drawn_sim or [[]]).astype(int),
            any_coexist, drawn_curves)
    fig.suptitle("atlas: finite search (absent = no seed reached the family); "
                 "simulation: finite-time regime from rest", fontsize=8)
    return fig
