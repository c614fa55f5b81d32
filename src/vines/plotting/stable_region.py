"""The stable 1:1 region of a stability map (Fig 16) drawn over other maps (Fig 12 (d-f)),
and the map's own classes on a raster that follows it (Fig 16, ``class_raster``).

The region's edges are placed where |lambda_max| crosses 1 by linear interpolation between
grid points (``stability_margin``), not half-way between a stable and an unstable cell: a
tongue whose edge lies just above a grid row (the symmetric tongue below Omega = 0.5 ends
at Omega ~ 0.5001) then shows as the sliver it is, not as a band one row high.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ..core.grids import cell_edges

#: margin given to grid points without an admissible 1:1 orbit (cls 0, lambda_max NaN)
NO_ORBIT_MARGIN = -1.0
#: regime label of the from-rest runs on the 1:1 orbit (vines.core.regime)
REGIME_1TO1 = "1:1"


def stability_margin(smap: xr.Dataset) -> np.ndarray:
    """1 - |lambda_max| over (omega, eta): > 0 stable, < 0 unstable; ``NO_ORBIT_MARGIN``
    where the map has no admissible 1:1 orbit."""
    lam = np.asarray(smap["lambda_max"].transpose("omega", "eta").values, dtype=float)
    none = np.asarray(smap["cls"].transpose("omega", "eta").values) == 0
    return np.where(none | ~np.isfinite(lam), NO_ORBIT_MARGIN, 1.0 - lam)


def stable_at(smap: xr.Dataset, eta, omega) -> np.ndarray:
    """True at the points (omega x eta, shape (len(omega), len(eta))) inside the stable 1:1
    region of ``smap`` (bilinear interpolation of ``stability_margin``); False outside the
    map's range."""
    from scipy.interpolate import RegularGridInterpolator  # only figures that outline need it
    f = RegularGridInterpolator((smap["omega"].values, smap["eta"].values),
                                stability_margin(smap), bounds_error=False,
                                fill_value=NO_ORBIT_MARGIN)
    W, E = np.meshgrid(np.asarray(omega, float), np.asarray(eta, float), indexing="ij")
    return f(np.stack([W, E], axis=-1)) > 0


def _subdivide(v, per_cell: int) -> np.ndarray:
    """``per_cell`` points to a cell of the grid ``v`` (centres of an even subdivision of
    each cell, ``core.grids.cell_edges``)."""
    e = cell_edges(v)
    k = (np.arange(per_cell) + 0.5) / per_cell
    return (e[:-1, None] + k[None, :] * np.diff(e)[:, None]).ravel()


def stable_orbit_share(eta, omega, fraction, smap: xr.Dataset, per_cell: int = 16):
    """The basin fraction of the stable 1:1 orbit, ``fraction`` (len(omega), len(eta); one
    census per grid point), on a raster of ``per_cell`` x ``per_cell`` points per census
    cell: the cell's value where the stability map ``smap`` has a stable 1:1 orbit
    (``stable_at``), 0 where it has none (the orbit whose basin the census measured does
    not exist there). A narrow stable tongue sampled by a grid row then shows as the tongue,
    not as a band one cell high. Kept as measured: cells whose census point is outside
    ``smap``'s range (the outer half of a cell beyond the map's edge takes the edge's
    class), and whole cells whose fraction is > 0 although none of their raster points is
    stable (data are never hidden). Returns (eta_r, omega_r, fraction_r, kept): the raster axes,
    the values (len(omega_r), len(eta_r)) and the number of cells kept whole."""
    frac = np.asarray(fraction, dtype=float)
    eta, omega = np.asarray(eta, float), np.asarray(omega, float)
    m = int(per_cell)
    er, wr = _subdivide(eta, m), _subdivide(omega, m)
    se, sw = smap["eta"].values, smap["omega"].values
    # cells whose census point lies in the map's range; their outer halves beyond the map's
    # edge take the class at the edge
    covered_eta = np.repeat((eta >= se.min()) & (eta <= se.max()), m)
    covered_W = np.repeat((omega >= sw.min()) & (omega <= sw.max()), m)
    inside = covered_W[:, None] & covered_eta[None, :]
    stable = stable_at(smap, np.clip(er, se.min(), se.max()), np.clip(wr, sw.min(), sw.max()))
    cell_shape = (len(omega), m, len(eta), m)
    no_stable = ~(inside & stable).reshape(cell_shape).any(axis=(1, 3))
    keep_whole = (frac > 0) & no_stable
    by_cell = np.repeat(np.repeat(frac, m, axis=0), m, axis=1)
    keep = np.repeat(np.repeat(keep_whole, m, axis=0), m, axis=1)
    values = np.where(inside & ~stable & ~keep, 0.0, by_cell)
    return er, wr, values, int(keep_whole.sum())


def _bracket(v, x):
    """Index of the grid interval of ``v`` holding each ``x`` (clipped to ``v``'s range)
    and the position in it, 0 ... 1."""
    x = np.clip(x, v.min(), v.max())
    i = np.clip(np.searchsorted(v, x) - 1, 0, len(v) - 2)
    return i, (x - v[i]) / (v[i + 1] - v[i])


def class_raster(smap: xr.Dataset, per_eta: int = 4, per_omega: int = 8):
    """The classes of the stability map ``smap`` (``cls``) on a raster of ``per_eta`` x
    ``per_omega`` points per map cell, whose stable / not stable split follows the
    |lambda_max| = 1 edge interpolated between map points (``stability_margin``, the edge
    ``draw.stable_edge`` draws): each raster point takes the class of the nearest of its
    four surrounding map points that is on its side of the edge; a map point whose class
    would be on none of its cell's raster points keeps the points next to it (no map point
    is hidden). A stability edge that runs almost along a grid row is then drawn where the
    interpolated edge is, not as a staircase of whole cells (white single-cell notches in a
    stable band). Returns (eta_r, omega_r, cls_r), cls_r (len(omega_r), len(eta_r))."""
    eta, omega = smap["eta"].values, smap["omega"].values
    er, wr = _subdivide(eta, per_eta), _subdivide(omega, per_omega)
    margin = stability_margin(smap)
    cls = np.asarray(smap["cls"].transpose("omega", "eta").values)
    iw, tw = _bracket(omega, wr)
    ie, te = _bracket(eta, er)
    IW, IE = np.meshgrid(iw, ie, indexing="ij")
    TW, TE = np.meshgrid(tw, te, indexing="ij")
    corners = [(a, b) for a in (0, 1) for b in (0, 1)]
    weight = [(TW if a else 1 - TW) * (TE if b else 1 - TE) for a, b in corners]
    stable = sum(w * margin[IW + a, IE + b] for w, (a, b) in zip(weight, corners, strict=True)) > 0
    best, out = np.full(TW.shape, np.inf), np.zeros(TW.shape, cls.dtype)
    for a, b in corners:
        dist = np.hypot(TW - a, TE - b)
        take = ((margin[IW + a, IE + b] > 0) == stable) & (dist < best)
        out = np.where(take, cls[IW + a, IE + b], out)
        best = np.where(take, dist, best)
    return er, wr, _keep_every_class(out, cls, per_omega, per_eta)


def _keep_every_class(raster, cls, per_omega: int, per_eta: int) -> np.ndarray:
    """``raster`` with the raster points next to each map point set to its class where none
    of the raster points of its cell has it (a stable point between unstable ones whose
    interpolated stable patch is narrower than a raster point): no map point is hidden."""
    blocks = raster.reshape(cls.shape[0], per_omega, cls.shape[1], per_eta).copy()
    hidden = ~(blocks == cls[:, None, :, None]).any(axis=(1, 3))
    mid_w = slice((per_omega - 1) // 2, per_omega // 2 + 1)
    mid_e = slice((per_eta - 1) // 2, per_eta // 2 + 1)
    centre = blocks[:, mid_w, :, mid_e]
    blocks[:, mid_w, :, mid_e] = np.where(hidden[:, None, :, None], cls[:, None, :, None], centre)
    return blocks.reshape(raster.shape)


def reaches_1to1(grid: xr.Dataset) -> np.ndarray:
    """True where the grid's from-rest run settles on a 1:1 orbit (regime '1:1'), over
    (omega, eta) with the fixed F squeezed."""
    reg = grid["regime"]
    for d in [d for d in reg.dims if d not in ("eta", "omega")]:
        reg = reg.isel({d: 0})
    return np.asarray(reg.transpose("omega", "eta").values).astype(str) == REGIME_1TO1


def region_counts(grid: xr.Dataset, smap: xr.Dataset) -> dict:
    """Grid points inside the stable 1:1 region, how many of them the from-rest run reaches
    (regime 1:1) and how many have KE ratio 0 (no impact): the numbers of docs/figures.md."""
    eta, omega = grid["eta"].values, grid["omega"].values
    stable = stable_at(smap, eta, omega)
    ke = grid["ke_ratio"]
    for d in [d for d in ke.dims if d not in ("eta", "omega")]:
        ke = ke.isel({d: 0})
    ke = np.asarray(ke.transpose("omega", "eta").values, dtype=float)
    return {"stable": int(stable.sum()), "reached": int((stable & reaches_1to1(grid)).sum()),
            "ke_zero": int((stable & (ke == 0)).sum())}
