"""Censuses over parameter grids and slices of initial states (plain arrays out).

* ``robust_point``: the basin fractions a designer needs at one (eta, omega, F): of
  efficient motion (attractors whose KE ratio exceeds ``threshold``) and of the stable 1:1
  orbit, with the unsettled share and whether the start from rest is efficient.
* With ``t_max`` (``census(..., t_max=...)``) both views: the fields above are the window
  view (the state reached at t_end, unchanged), and the ``*_asymptotic`` ones say where the
  same states are at t_max (transient motions have escaped by then).
* ``slice_states`` / ``basin_slice``: the attractor reached from every point of a 2-D
  slice of initial states: z_m(0) against z_m'(0) with the ball at rest in the middle of
  the cavity (z_b = z_m, z_b' = 0); the from-rest start is the slice's origin.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..core.params import STATE_MAX, check_real, check_reals
from .census import census, census_of_parts, census_part

#: what ``robust_point`` returns, in this order
ROBUST_FIELDS = ("efficient_fraction", "stable_1to1_fraction", "unsettled_fraction",
                 "n_attractors", "from_rest_efficient", "from_rest_ke_ratio")
#: what ``robust_point`` adds with ``t_max``
ROBUST_ASYMPTOTIC_FIELDS = ("efficient_fraction_asymptotic", "stable_1to1_fraction_asymptotic",
                            "escaped_fraction", "from_rest_efficient_asymptotic")


def _stable_1to1(a) -> bool:
    return a.regime == "1:1" and a.orbit is not None and a.orbit["stable"]


def robust_point(eta: float, omega: float, F: float, *, threshold: float,
                 **census_kw) -> dict:
    """ROBUST_FIELDS at one point from ``census(eta, omega, F, **census_kw)``: basin
    fractions of the attractors with ke_ratio > threshold and of stable 1:1 orbits; with
    ``t_max`` in census_kw also ROBUST_ASYMPTOTIC_FIELDS (the same at t_max, the share of
    states that changed attractor between t_end and t_max)."""
    threshold = check_real("threshold", threshold)
    c = census(eta, omega, F, **census_kw)
    eff = sum(a.basin_fraction for a in c.attractors if a.ke_ratio > threshold)
    one = sum(a.basin_fraction for a in c.attractors if _stable_1to1(a))
    rest = c.attractors[c.from_rest] if c.from_rest is not None else None
    out = dict(efficient_fraction=float(eff), stable_1to1_fraction=float(one),
               unsettled_fraction=float(c.unsettled_fraction),
               n_attractors=len([a for a in c.attractors if a.count > 0]),
               from_rest_efficient=int(rest is not None and rest.ke_ratio > threshold),
               from_rest_ke_ratio=float(rest.ke_ratio) if rest is not None else np.nan)
    if c.t_max is not None:
        out |= _asymptotic_fields(c, threshold)
    return out


def _asymptotic_fields(c, threshold: float) -> dict:
    """ROBUST_ASYMPTOTIC_FIELDS of a census with its asymptotic view."""
    def frac(a):
        return a.asymptotic["basin_fraction_asymptotic"]
    rest = (c.attractors[c.from_rest_asymptotic] if c.from_rest_asymptotic is not None
            else None)
    return dict(
        efficient_fraction_asymptotic=float(sum(frac(a) for a in c.attractors
                                                if a.ke_ratio > threshold)),
        stable_1to1_fraction_asymptotic=float(sum(frac(a) for a in c.attractors
                                                  if _stable_1to1(a))),
        escaped_fraction=float(np.count_nonzero(c.members_asymptotic != c.members) / c.n),
        from_rest_efficient_asymptotic=int(rest is not None and rest.ke_ratio > threshold))


def slice_states(z_m0: ArrayLike, v_m0: ArrayLike) -> np.ndarray:
    """States (len(z_m0) * len(v_m0), 4) of the slice, z_m0 varying slowest: LO at
    (z_m0, v_m0), ball at rest in the middle of the cavity (z_b = z_m0, z_b' = 0)."""
    zm, vm = np.meshgrid(check_reals("z_m0", z_m0, lo=-STATE_MAX, hi=STATE_MAX),
                         check_reals("v_m0", v_m0, lo=-STATE_MAX, hi=STATE_MAX), indexing="ij")
    zm, vm = zm.ravel(), vm.ravel()
    return np.stack([zm, vm, zm, np.zeros_like(zm)], axis=1)


def basin_slice_part(eta: float, omega: float, F: float, z_m0: ArrayLike, v_m0: ArrayLike,
                     start: int, stop: int, **census_kw) -> dict:
    """The runs of the slice's states [start, stop) (``slice_states`` order): a part for
    ``basin_slice(..., parts=...)`` (``census.census_part``)."""
    return census_part(eta, omega, F, start, stop, states=slice_states(z_m0, v_m0),
                       **census_kw)


def basin_slice(eta: float, omega: float, F: float, z_m0: ArrayLike, v_m0: ArrayLike,
                **census_kw) -> dict:
    """Attractor index over the slice (shape (len(z_m0), len(v_m0)), -1: unsettled) and
    the attractor table (regime, period, ke_ratio, xmax_m, basin_fraction within the
    slice), from_rest (index into the table) and the census for further use. With ``t_max``
    in census_kw also the asymptotic view: attractor_asymptotic (the attractor each point
    is on at t_max), from_rest_asymptotic, and in the table basin_fraction_asymptotic and
    status (persistent / transient / unresolved); attractors reached only after t_end are
    in the table with basin_fraction 0."""
    c = census(eta, omega, F, states=slice_states(z_m0, v_m0), **census_kw)
    return _slice_result(c, z_m0, v_m0)


def basin_slice_of_parts(eta: float, omega: float, F: float, z_m0: ArrayLike,
                         v_m0: ArrayLike, parts: list, **census_kw) -> dict:
    """``basin_slice`` from the ``basin_slice_part`` results that cover the slice's states
    in order (their runs are not repeated; the same result)."""
    c = census_of_parts(eta, omega, F, parts, states=slice_states(z_m0, v_m0), **census_kw)
    return _slice_result(c, z_m0, v_m0)


def _slice_result(c, z_m0: ArrayLike, v_m0: ArrayLike) -> dict:
    """``basin_slice``'s dict of the census ``c`` of the slice's states."""
    shape = (np.size(z_m0), np.size(v_m0))
    table = {k: [getattr(a, k) for a in c.attractors]
             for k in ("regime", "period", "ke_ratio", "xmax_m", "basin_fraction")}
    out = dict(attractor=c.members.reshape(shape), table=table,
               from_rest=-1 if c.from_rest is None else int(c.from_rest), census=c)
    if c.t_max is not None:
        for k in ("basin_fraction_asymptotic", "status"):
            table[k] = [a.asymptotic[k] for a in c.attractors]
        out["attractor_asymptotic"] = c.members_asymptotic.reshape(shape)
        out["from_rest_asymptotic"] = (-1 if c.from_rest_asymptotic is None
                                       else int(c.from_rest_asymptotic))
    return out
