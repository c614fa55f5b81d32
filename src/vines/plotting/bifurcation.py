"""Bifurcation structure on the figures: asymmetric 1:1 branches (Figs 6, 15) and boundary
curves of the stability classes (Figs 12, 16).

Reads the datasets of the ``map_solve`` stage (a ragged array of branches: row 0 the
continued branch, then the asymmetric branches born at its symmetry-breaking points) and
of the ``boundaries`` stage (a ragged array of curves in (eta, omega) at one F).
"""
from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib import patheffects
from matplotlib.lines import Line2D

from ..data.builders import ragged_rows
from . import palette
from .checks import FigureInputError, load, require
from .draw import LABELS

#: colour of the asymmetric 1:1 branches (the symmetric one is C_BRANCH)
C_ASYMMETRIC = palette.C_ASYMMETRIC
#: colour of each boundary curve type, line style of each family (drawn over a thin white
#: halo, so they show on every class colour and colour map)
CURVE_COLOURS = {"fold": palette.OKABE_ITO["blue"], "flip": palette.OKABE_ITO["reddish purple"],
                 "neimark-sacker": palette.OKABE_ITO["bluish green"],
                 "symmetry-breaking": palette.OKABE_ITO["vermillion"],
                 "grazing": "#A6761D"}
FAMILY_STYLES = {"symmetric": "-", "asymmetric": (0, (4, 1.6))}
#: what a grazing curve is, for captions and legends
GRAZING_NOTE = ("the orbit touches a wall with zero relative velocity;\nbeyond it the ball "
                "would cross the wall:\nno admissible 1:1 orbit there")
HALO = [patheffects.Stroke(linewidth=2.4, foreground="white"), patheffects.Normal()]


# ------------------------------------------------------------------ branches (Figs 6, 15)

def _rows(br: xr.Dataset) -> list[slice]:
    """The point slice of every branch of a branch dataset (one slice if not ragged)."""
    if "row_size" not in br:
        return [slice(0, br.sizes["point"])]
    edges = np.concatenate([[0], np.cumsum(br["row_size"].values)])
    return [slice(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:], strict=False)]


def continued_branches(branches) -> list[xr.Dataset]:
    """The continued branch (row 0) of each branch dataset, as the zoom figures draw it."""
    return [br.isel(point=_rows(br)[0]) for br in branches]


def switched_branches(br: xr.Dataset) -> list[xr.Dataset]:
    """The branches switched onto at symmetry-breaking points (rows 1, 2, ...)."""
    return [br.isel(point=s) for s in _rows(br)[1:] if s.stop > s.start]


def _branch_curves(ax, sub: xr.Dataset, label: bool):
    adm = sub["admissible"].values.astype(bool)
    st = sub["stable"].values.astype(bool) & adm
    eta = sub["eta"].values
    for k, key in enumerate(("dw_L", "dw_R")):
        for mask, ls, lab in ((st, "-", "analytic asymmetric 1:1, stable"),
                              (adm & ~st, ":", "analytic asymmetric 1:1, unstable")):
            ax.plot(eta, np.where(mask, sub[key].values, np.nan), ls, color=C_ASYMMETRIC,
                    lw=1.4, label=lab if (label and k == 0) else None)


def draw_switched(fig, branches):
    """Add the asymmetric branches of each branch dataset to a zoom figure (row i of
    ``fig``: bifurcation panel, |lambda| panel): impact velocities (solid stable, dotted
    unstable) and lambda_max. Axis limits are kept."""
    axes = fig.axes
    for i, br in enumerate(branches):
        ax, axl = axes[2 * i], axes[2 * i + 1]
        subs = switched_branches(br)
        lims = ax.get_xlim(), ax.get_ylim(), axl.get_xlim(), axl.get_ylim()
        for j, sub in enumerate(subs):
            _branch_curves(ax, sub, label=j == 0)
            adm = sub["admissible"].values.astype(bool)
            axl.plot(sub["eta"].values, np.where(adm, sub["lambda_max"].values, np.nan), "-",
                     color=C_ASYMMETRIC, lw=1.0,
                     label=r"$|\lambda_{\max}|$ asymmetric" if j == 0 else None)
        ax.set_xlim(lims[0])
        ax.set_ylim(lims[1])
        axl.set_xlim(lims[2])
        axl.set_ylim(lims[3])
        if subs:
            ax.legend(fontsize=7, loc="best", markerscale=4)
            axl.legend(fontsize=7, loc="best", ncol=2)


# ------------------------------------------------------------------ boundary curves (Figs 12, 16)

def boundaries(path) -> xr.Dataset:
    """Boundary curves of one F (``boundaries`` stage output)."""
    ds = load(path)
    require(ds, variables=("curve_type", "family", "row_size"), finite=("eta", "omega"))
    if "F" not in ds.attrs:
        raise FigureInputError(f"{path}: global attribute 'F' is missing")
    unknown = set(ds["curve_type"].values.tolist()) - set(CURVE_COLOURS)
    if unknown:
        raise FigureInputError(f"{path}: unknown curve types {sorted(unknown)}")
    return ds


def draw_curves(ax, ds: xr.Dataset) -> set:
    """Draw every curve of ``ds`` on ``ax`` (axis limits kept): colour by curve type, line
    style by family; returns the (type, family) pairs drawn."""
    xlim, ylim = ax.get_xlim(), ax.get_ylim()
    etas, omegas = ragged_rows(ds, "eta"), ragged_rows(ds, "omega")
    kinds = list(zip(ds["curve_type"].values.tolist(), ds["family"].values.tolist(),
                     strict=True))
    for (typ, fam), e, w in zip(kinds, etas, omegas, strict=False):
        ax.plot(e, w, color=CURVE_COLOURS[typ], ls=FAMILY_STYLES.get(fam, ":"), lw=1.2,
                path_effects=HALO)
    ax.set_xlim(xlim)
    ax.set_ylim(ylim)
    return set(kinds)


def curve_handles(drawn, note=True) -> list:
    """Legend entries of the curve types drawn (colours) and of the families (line styles);
    ``note``: the grazing entry says what grazing is."""
    types = {t for t, _ in drawn}
    fams = {f for _, f in drawn}
    out = [Line2D([], [], color=CURVE_COLOURS[t], lw=1.6, label=t.replace("-", " ") + " curve"
                  + (f" ({GRAZING_NOTE})" if t == "grazing" and note else ""))
           for t in CURVE_COLOURS if t in types]
    out += [Line2D([], [], color="0.2", ls=FAMILY_STYLES.get(f, ":"), lw=1.2,
                   label=f"{f} 1:1 family") for f in FAMILY_STYLES if f in fams]
    return out


def draw_on_panels(fig, axes, F_values, paths, legend=True) -> list:
    """Boundary curves on panels: ``axes[j]`` gets the curves computed at ``F_values[j]``
    (from the boundaries datasets ``paths``). Returns the legend handles of the curve types
    drawn; ``legend``: also draw them as one legend below the figure."""
    by_F = {round(float(ds.attrs["F"]), 9): ds for ds in map(boundaries, paths)}
    drawn = set()
    for ax, F in zip(axes, F_values, strict=False):
        ds = by_F.get(round(float(F), 9))
        if ds is None:
            raise FigureInputError(f"no boundary curves at F = {F} (curves at F = {sorted(by_F)})")
        drawn |= draw_curves(ax, ds)
    handles = curve_handles(drawn)
    if handles and legend:
        fig.legend(handles=handles, loc="outside lower center", ncol=len(handles), fontsize=8,
                   frameon=False, title=f"boundaries in ({LABELS['eta'].split()[-1]}, "
                                        f"{LABELS['omega'].split()[-1]})", title_fontsize=8)
    return handles
