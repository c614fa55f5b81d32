"""Convergence of the measures with run length and window, sticking threshold and grid.

Three studies, each returning a self-describing :class:`xarray.Dataset` (CF-1.10: every
variable has ``long_name`` and ``units``; ``"1"`` for dimensionless numbers):

* :func:`window_convergence`: KE ratio, x_max and regime at named parameter points over a
  grid of run lengths ``t_end`` and window rules (a fixed window length, or a fraction of
  the run), compared with the longest run's widest window.
* :func:`vstick_convergence`: the same measures against the sticking threshold ``v_stick``
  (log-spaced), compared with the smallest ``v_stick``, with the cost of every run.
* :func:`grid_convergence`: the KE ratio = ``level`` contour over (eta, omega) grids of
  increasing, nested resolution, compared with the finest grid's contour.

Conventions: dimensionless time (t = w0 t_dim) and displacements in units of L, as in
``vines.simulate``; ``xmax_m`` in metres. Every run starts from rest at t = 0 (forcing phase
phi = 0), so runs of different length share one trajectory and differ only in where the
window [t_transient, t_end] lies. Each point is computed on its own, so no result depends on
``n_threads`` (``run_time`` is a wall-clock measurement and does).
"""
from __future__ import annotations

import math
import os
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import xarray as xr

from ..data.netcdf import COORD_ATTRS, CONVENTIONS
from ..core.params import (D_DEFAULT, L_HALF_M, MAX_IMPACTS_DEFAULT, R_DEFAULT, ROOT_TOL_DEFAULT,
                     T_END_DEFAULT, T_TRANSIENT_DEFAULT, V_STICK_DEFAULT)
from ..core.simulation import BATCH_FIELDS, simulate_batch

#: per-run measures kept in the window and v_stick datasets (names of BATCH_FIELDS)
RUN_FIELDS = ("ke_ratio", "xmax", "regime", "status", "impacts_per_period", "n_impacts",
              "t_stuck", "period")
_FLAG = {"flag_values": np.array([0, 1], dtype="i1")}


# ------------------------------------------------------------------ shared helpers

def _var(dims, data, long_name, units, **extra) -> xr.Variable:
    return xr.Variable(dims, data, {"long_name": long_name, "units": units, **extra})


def _flag(dims, mask, long_name, meanings) -> xr.Variable:
    return _var(dims, np.asarray(mask).astype("i1"), long_name, "1", **_FLAG,
                flag_meanings=meanings)


def _check_points(points) -> list[dict]:
    out = []
    for i, p in enumerate(points):
        try:
            q = {k: float(p[k]) for k in ("eta", "omega", "F")}
        except (KeyError, TypeError, ValueError) as err:
            raise ValueError(f"point {i} ({p!r}) needs numbers eta, omega, F") from err
        q["label"] = str(p.get("label", "")) or (
            f"eta={q['eta']:g} W={q['omega']:g} F={q['F']:g}")
        out.append(q)
    if not out:
        raise ValueError("no parameter points given")
    return out


def _point_coords(pts: list[dict]) -> dict:
    n = len(pts)
    c = {"point": _var(("point",), np.arange(n), "parameter point index", "1")}
    for k in ("eta", "omega", "F"):
        c[k] = xr.Variable(("point",), np.array([p[k] for p in pts]), COORD_ATTRS[k])
    c["label"] = _var(("point",), np.array([p["label"] for p in pts]), "parameter point", "")
    return c


def _run_cases(cases: list[dict], settings: dict, n_threads) -> tuple[dict, np.ndarray]:
    """Run every case (eta, omega, F and any per-case setting) on its own, on ``n_threads``
    threads (None: all cores; the kernel releases the GIL).

    Returns (fields, run_time): arrays over the cases, fields named as BATCH_FIELDS, run_time
    the wall-clock seconds of each run (time.perf_counter).
    """
    n = len(cases)
    out = {k: np.empty(n, dtype=BATCH_FIELDS[k][0]) for k in BATCH_FIELDS}
    run_time = np.empty(n)

    def work(i):
        kw = {**settings, **cases[i]}
        t0 = time.perf_counter()
        res = simulate_batch(n_threads=1, **kw)
        run_time[i] = time.perf_counter() - t0
        for k in BATCH_FIELDS:
            out[k][i] = res[k][()]
        return i

    n_threads = (os.cpu_count() or 1) if n_threads is None else int(n_threads)
    if n_threads < 1:
        raise ValueError(f"n_threads must be >= 1, got {n_threads}")
    if n_threads == 1:
        for i in range(n):
            work(i)
    else:
        with ThreadPoolExecutor(max_workers=n_threads) as ex:
            list(ex.map(work, range(n)))
    return out, run_time


def _differences(ke, xmax, ref_ke, ref_xmax):
    """KE-ratio difference and relative x_max difference to the reference values."""
    d_ke = ke - ref_ke
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(ref_xmax != 0, (xmax - ref_xmax) / np.abs(ref_xmax),
                       np.where(xmax == ref_xmax, 0.0, np.inf))
    return d_ke, rel


def _measure_vars(dims, f: dict) -> dict:
    """The per-run measures as CF variables over ``dims`` (arrays already shaped)."""
    data = {}
    for k in RUN_FIELDS:
        _, long_name, units = BATCH_FIELDS[k]
        data[k] = _var(dims, f[k], long_name, units)
    data["xmax_m"] = _var(dims, f["xmax"] * L_HALF_M, "max |x_m| over the window", "m")
    return data


def _diff_vars(dims, d_ke, rel, same, ke_tol, xmax_rtol, ref: str) -> dict:
    conv = (np.abs(d_ke) <= ke_tol) & (np.abs(rel) <= xmax_rtol)
    return {
        "d_ke": _var(dims, d_ke, f"KE ratio minus its value at the {ref}", "1"),
        "rel_d_xmax": _var(dims, rel, f"relative difference of x_max to the {ref}", "1"),
        "converged": _flag(dims, conv, f"1 where |d_ke| <= {ke_tol:g} and |rel_d_xmax| <= "
                           f"{xmax_rtol:g} (difference to the {ref})",
                           "not_converged converged"),
        "regime_same": _flag(dims, same, f"1 where the regime equals the {ref}'s",
                             "regime_differs regime_same"),
    }


def _settings_attrs(**kw) -> dict:
    return {f"solver_{k}": v for k, v in kw.items()}


# ------------------------------------------------------------------ (a) run length, window

def window_convergence(points, t_ends=(7000.0, 10000.0, 14000.0, 20000.0, 28000.0),
                       window_lengths=(3000.0,), window_fractions=(0.5,), *,
                       whole_periods=False, ke_tol=1e-2, xmax_rtol=1e-2,
                       t_end=T_END_DEFAULT, t_transient=T_TRANSIENT_DEFAULT,
                       v_stick=V_STICK_DEFAULT, r=R_DEFAULT, d=D_DEFAULT,
                       max_impacts=MAX_IMPACTS_DEFAULT, root_tol=ROOT_TOL_DEFAULT,
                       n_threads=None) -> xr.Dataset:
    """Measures at ``points`` (dicts eta, omega, F, optional label) over run lengths and windows.

    Axes: ``t_ends`` (dimensionless run lengths) x window rules: each of ``window_lengths``
    (window [t_end - length, t_end]) and of ``window_fractions`` (window [(1 - f) t_end,
    t_end], 0 < f < 1). The tested setting (``t_end``, ``t_transient``) -- by default the
    paper's 7000/4000 -- is added to the axes (its window length as a length rule).
    ``whole_periods``: shorten every window to a whole number of forcing periods 2 pi/omega
    ending at t_end (time averages of a periodic attractor then do not depend on where the
    window starts).
    Reference: the longest ``t_end`` with its widest window. ``d_ke`` = KE ratio minus the
    reference, ``rel_d_xmax`` = (x_max - reference)/reference, ``converged`` where
    |d_ke| <= ke_tol and |rel_d_xmax| <= xmax_rtol, ``regime_same`` where the regime label
    equals the reference's. Dims (point, window, t_end).
    """
    pts = _check_points(points)
    tested_len = float(t_end) - float(t_transient)
    if not tested_len > 0:
        raise ValueError(f"t_transient = {t_transient} must be < t_end = {t_end}")
    t_ends = np.unique(np.append(np.asarray(t_ends, float), float(t_end)))
    lengths = [float(x) for x in window_lengths]
    if tested_len not in lengths:
        lengths.append(tested_len)
    fractions = [float(x) for x in window_fractions]
    if any(not 0 < f < 1 for f in fractions):
        raise ValueError(f"window fractions must lie in (0, 1), got {fractions}")
    if any(x <= 0 for x in lengths) or any(x >= t_ends[0] for x in lengths):
        raise ValueError(f"window lengths {lengths} must be > 0 and < the shortest t_end "
                         f"{t_ends[0]:g}")
    rules = [("length", x) for x in sorted(lengths)] + [("fraction", f) for f in fractions]
    n_p, n_w, n_t = len(pts), len(rules), t_ends.size
    t_tr = np.empty((n_p, n_w, n_t))
    for j, (kind, x) in enumerate(rules):
        win = np.full(n_t, x) if kind == "length" else x * t_ends
        for i, p in enumerate(pts):
            w = win
            if whole_periods:
                period = 2.0 * math.pi / p["omega"]
                w = np.floor(win / period) * period
                if np.any(w <= 0):
                    raise ValueError(f"a window of rule {kind} {x:g} is shorter than one "
                                     f"forcing period at point {p['label']}")
            t_tr[i, j] = t_ends - w
    cases = [dict(eta=p["eta"], omega=p["omega"], F=p["F"], t_end=float(t_ends[k]),
                  t_transient=float(t_tr[i, j, k]))
             for i, p in enumerate(pts) for j in range(n_w) for k in range(n_t)]
    f, _ = _run_cases(cases, dict(v_stick=v_stick, r=r, d=d, max_impacts=max_impacts,
                                  root_tol=root_tol), n_threads)
    shape = (n_p, n_w, n_t)
    f = {k: v.reshape(shape) for k, v in f.items()}
    # reference: longest run, widest window (smallest t_transient of the last t_end column)
    j_ref = np.argmin(t_tr[:, :, -1], axis=1)
    ip = np.arange(n_p)
    ref_ke = f["ke_ratio"][ip, j_ref, -1][:, None, None]
    ref_x = f["xmax"][ip, j_ref, -1][:, None, None]
    ref_regime = f["regime"][ip, j_ref, -1][:, None, None]
    d_ke, rel = _differences(f["ke_ratio"], f["xmax"], ref_ke, ref_x)
    dims = ("point", "window", "t_end")
    data = _measure_vars(dims, f)
    ref = "longest run's widest window"
    data.update(_diff_vars(dims, d_ke, rel, f["regime"] == ref_regime, ke_tol, xmax_rtol,
                           ref))
    data["t_transient"] = _var(dims, t_tr, "start of the measurement window", "1")
    # smallest t_end from which every longer run (same window rule) is converged
    conv = data["converged"].values.astype(bool)
    tail = np.flip(np.logical_and.accumulate(np.flip(conv, -1), -1), -1)
    first = np.where(tail.any(-1), t_ends[np.argmax(tail, -1)], np.nan)
    data["converged_from_t_end"] = _var(("point", "window"), first,
                                        "shortest run from which every longer run of the "
                                        "same window rule is converged", "1")
    data["reference_t_transient"] = _var(("point",), t_tr[ip, j_ref, -1],
                                         "window start of the reference run", "1")
    j_t = rules.index(("length", tested_len))
    k_t = int(np.flatnonzero(t_ends == float(t_end))[0])
    for name in ("d_ke", "rel_d_xmax", "converged", "regime_same"):
        v = data[name]
        data[f"tested_{name}"] = _var(("point",), v.values[:, j_t, k_t],
                                      f"{v.attrs['long_name']}, at the tested setting "
                                      f"t_end = {float(t_end):g}, t_transient = "
                                      f"{float(t_transient):g}", v.attrs["units"],
                                      **{a: v.attrs[a] for a in ("flag_values",
                                                                 "flag_meanings")
                                         if a in v.attrs})
    coords = _point_coords(pts)
    coords["t_end"] = _var(("t_end",), t_ends, "end of the run (from rest at t = 0)", "1")
    coords["window"] = _var(("window",), np.arange(n_w), "window rule index", "1")
    coords["window_rule"] = _var(("window",), np.array([k for k, _ in rules]),
                                 "window rule: fixed length or fraction of the run", "")
    coords["window_length"] = _var(("window",), np.array(
        [x if k == "length" else np.nan for k, x in rules]),
        "window length t_end - t_transient (length rules)", "1")
    coords["window_fraction"] = _var(("window",), np.array(
        [x if k == "fraction" else np.nan for k, x in rules]),
        "window length as a fraction of t_end (fraction rules)", "1")
    attrs = {"Conventions": CONVENTIONS,
             "title": "convergence of the measures with run length and window",
             "reference": "largest t_end, widest window", "ke_tol": float(ke_tol),
             "xmax_rtol": float(xmax_rtol), "whole_periods": int(bool(whole_periods)),
             "tested_t_end": float(t_end), "tested_t_transient": float(t_transient),
             "tested_window": j_t,
             **_settings_attrs(v_stick=float(v_stick), r=float(r), d=float(d),
                               max_impacts=int(max_impacts), root_tol=float(root_tol))}
    return xr.Dataset(data, coords=coords, attrs=attrs)


# ------------------------------------------------------------------ (b) sticking threshold

def vstick_convergence(points, v_sticks=tuple(10.0 ** -np.arange(3, 11)), *, ke_tol=1e-3,
                       xmax_rtol=1e-2, t_end=T_END_DEFAULT, t_transient=T_TRANSIENT_DEFAULT,
                       v_stick=V_STICK_DEFAULT, r=R_DEFAULT, d=D_DEFAULT,
                       max_impacts=MAX_IMPACTS_DEFAULT, root_tol=ROOT_TOL_DEFAULT,
                       n_threads=None) -> xr.Dataset:
    """Measures at ``points`` (dicts eta, omega, F, optional label) against ``v_sticks``.

    ``v_sticks``: sticking thresholds on the relative velocity after an impact
    (dimensionless, units of L w0); the tested ``v_stick`` (library default 1e-6) is added.
    Reference: the smallest v_stick. ``d_ke``, ``rel_d_xmax``, ``converged`` (|d_ke| <=
    ke_tol and |rel_d_xmax| <= xmax_rtol), ``regime_same`` as in window_convergence;
    ``run_time`` is the wall-clock cost of each run in seconds. ``converged_below``: the
    largest v_stick at and below which every run is converged. Dims (point, v_stick), v_stick
    increasing.
    """
    pts = _check_points(points)
    vs = np.unique(np.append(np.asarray(v_sticks, float), float(v_stick)))
    if not np.all(vs > 0):
        raise ValueError(f"v_sticks must be > 0, got {vs.tolist()}")
    cases = [dict(eta=p["eta"], omega=p["omega"], F=p["F"], v_stick=float(v))
             for p in pts for v in vs]
    f, run_time = _run_cases(cases, dict(t_end=t_end, t_transient=t_transient, r=r, d=d,
                                         max_impacts=max_impacts, root_tol=root_tol),
                             n_threads)
    shape = (len(pts), vs.size)
    f = {k: v.reshape(shape) for k, v in f.items()}
    dims = ("point", "v_stick")
    d_ke, rel = _differences(f["ke_ratio"], f["xmax"], f["ke_ratio"][:, :1], f["xmax"][:, :1])
    data = _measure_vars(dims, f)
    data.update(_diff_vars(dims, d_ke, rel, f["regime"] == f["regime"][:, :1], ke_tol,
                           xmax_rtol, "smallest v_stick"))
    data["run_time"] = _var(dims, run_time.reshape(shape),
                            "wall-clock time of the run (time.perf_counter)", "s")
    conv = data["converged"].values.astype(bool)
    head = np.logical_and.accumulate(conv, -1)
    n_ok = head.sum(-1)
    data["converged_below"] = _var(("point",), np.where(n_ok > 0, vs[np.maximum(n_ok - 1, 0)],
                                                        np.nan),
                                   "largest v_stick at and below which every run is "
                                   "converged", "1")
    k_t = int(np.flatnonzero(vs == float(v_stick))[0])
    for name in ("d_ke", "rel_d_xmax", "converged", "regime_same"):
        v = data[name]
        data[f"tested_{name}"] = _var(("point",), v.values[:, k_t],
                                      f"{v.attrs['long_name']}, at the tested v_stick = "
                                      f"{float(v_stick):g}", v.attrs["units"],
                                      **{a: v.attrs[a] for a in ("flag_values",
                                                                 "flag_meanings")
                                         if a in v.attrs})
    coords = _point_coords(pts)
    coords["v_stick"] = _var(("v_stick",), vs, "sticking threshold on the relative velocity "
                             "after an impact", "1")
    attrs = {"Conventions": CONVENTIONS,
             "title": "convergence of the measures with the sticking threshold v_stick",
             "reference": "smallest v_stick", "ke_tol": float(ke_tol),
             "xmax_rtol": float(xmax_rtol), "tested_v_stick": float(v_stick),
             **_settings_attrs(t_end=float(t_end), t_transient=float(t_transient),
                               r=float(r), d=float(d), max_impacts=int(max_impacts),
                               root_tol=float(root_tol))}
    return xr.Dataset(data, coords=coords, attrs=attrs)


# ------------------------------------------------------------------ (c) grid resolution

def nested_axis(lo: float, hi: float, n_fine: int, n: int) -> np.ndarray:
    """The n-point axis nested in linspace(lo, hi, n_fine): every (n_fine-1)/(n-1)-th value."""
    if n < 2 or (n_fine - 1) % (n - 1):
        raise ValueError(f"a grid of {n} points per axis is not nested in one of {n_fine}: "
                         f"(n_fine - 1) must be a multiple of (n - 1)")
    return np.linspace(lo, hi, n_fine)[::(n_fine - 1) // (n - 1)]


def contour_lines(x, y, z, level) -> list[np.ndarray]:
    """Lines of z = level (z shape (len(y), len(x))) as (k, 2) arrays of (x, y) vertices."""
    import contourpy
    gen = contourpy.contour_generator(np.asarray(x, float), np.asarray(y, float),
                                      np.ma.masked_invalid(np.asarray(z, float)),
                                      name="serial", line_type="Separate")
    return [ln for ln in gen.lines(float(level)) if len(ln) >= 2]


def area_above(x, y, z, level) -> float:
    """Area of {z > level} in (x, y) units, from the filled contour (holes subtracted)."""
    import contourpy
    z = np.ma.masked_invalid(np.asarray(z, float))
    top = float(z.max()) if z.count() else level
    if not top > level:
        return 0.0
    gen = contourpy.contour_generator(np.asarray(x, float), np.asarray(y, float), z,
                                      name="serial", fill_type="OuterOffset")
    polys, offsets = gen.filled(float(level), np.nextafter(top, np.inf))
    area = 0.0
    for pts, off in zip(polys, offsets):
        for a, b in zip(off[:-1], off[1:]):
            px, py = pts[a:b, 0], pts[a:b, 1]
            ring = 0.5 * abs(np.dot(px, np.roll(py, -1)) - np.dot(py, np.roll(px, -1)))
            area += ring if a == off[0] else -ring
    return area


def _sample_lines(lines, ds):
    """Points along polylines at most ``ds`` apart (piece midpoints) and their arc weights."""
    pts, wts = [], []
    for ln in lines:
        a, b = ln[:-1], ln[1:]
        seg = np.hypot(*(b - a).T)
        m = np.maximum(1, np.ceil(seg / ds).astype(int))
        rep = np.repeat(np.arange(seg.size), m)
        frac = (np.concatenate([np.arange(k) for k in m]) + 0.5) / m[rep]
        pts.append(a[rep] + frac[:, None] * (b - a)[rep])
        wts.append(seg[rep] / m[rep])
    if not pts:
        return np.zeros((0, 2)), np.zeros(0)
    return np.concatenate(pts), np.concatenate(wts)


def _dist_to_lines(p, lines, block=512):
    """Euclidean distance from each point of p (k, 2) to the nearest segment of ``lines``."""
    a = np.concatenate([ln[:-1] for ln in lines])
    b = np.concatenate([ln[1:] for ln in lines])
    ab = b - a
    ab2 = np.einsum("ij,ij->i", ab, ab)
    ab2 = np.where(ab2 > 0, ab2, 1.0)
    out = np.empty(len(p))
    for s in range(0, len(p), block):
        q = p[s:s + block, None, :]
        t = np.clip(np.einsum("kij,ij->ki", q - a, ab) / ab2, 0.0, 1.0)
        diff = q - (a + t[..., None] * ab)
        out[s:s + block] = np.sqrt(np.min(np.einsum("kij,kij->ki", diff, diff), axis=1))
    return out


def contour_distance(lines, ref_lines, ds) -> tuple[float, float]:
    """(arc-length mean, max) distance from ``lines`` to ``ref_lines``, sampled every ``ds``.

    The max is the one-sided Hausdorff distance. NaN when either set of lines is empty.
    """
    if not lines or not ref_lines:
        return math.nan, math.nan
    p, w = _sample_lines(lines, ds)
    dist = _dist_to_lines(p, ref_lines)
    return float(np.sum(w * dist) / np.sum(w)), float(dist.max())


def grid_convergence(eta_range=(0.01, 1.0), omega_range=(0.5, 1.5), F=0.4,
                     resolutions=(11, 21, 41, 81), level=0.5, *, t_end=T_END_DEFAULT,
                     t_transient=T_TRANSIENT_DEFAULT, v_stick=V_STICK_DEFAULT, r=R_DEFAULT,
                     d=D_DEFAULT, max_impacts=MAX_IMPACTS_DEFAULT, root_tol=ROOT_TOL_DEFAULT,
                     n_threads=None) -> xr.Dataset:
    """KE ratio = ``level`` contour over (eta, omega) at ``resolutions`` points per axis.

    Grids are linspace over ``eta_range`` x ``omega_range`` at fixed F; every coarse grid is
    nested in the finest (its points are a subset of the finest grid's points, taken every
    ``stride``-th value), so only the finest grid is simulated. Per resolution: distances of
    its contour to the finest grid's contour, Euclidean in the (omega, eta) parameter plane
    (both dimensionless): ``contour_dist_mean`` (arc-length mean) and ``contour_dist_max``
    (one-sided Hausdorff, coarse -> finest), ``contour_hausdorff`` (symmetric); and the area
    fraction of the rectangle where KE ratio > level. The dataset holds the finest grid's
    ``ke_ratio``/``xmax``/``regime`` over (eta, omega): the coarse grids are
    ``isel(eta=slice(None, None, stride), omega=...)``.
    """
    res = sorted({int(n) for n in resolutions})
    if not res or res[0] < 2:
        raise ValueError(f"resolutions must be >= 2 points per axis, got {resolutions}")
    n_f = res[-1]
    e0, e1 = (float(v) for v in eta_range)
    w0, w1 = (float(v) for v in omega_range)
    if not (e1 > e0 and w1 > w0):
        raise ValueError(f"empty range eta {eta_range} or omega {omega_range}")
    strides = [(n_f - 1) // (n - 1) for n in res]
    for n in res:
        nested_axis(e0, e1, n_f, n)           # raises when not nested
    eta = np.linspace(e0, e1, n_f)
    omega = np.linspace(w0, w1, n_f)
    E, W = np.meshgrid(eta, omega, indexing="ij")
    f = simulate_batch(E, W, float(F), r=r, d=d, t_end=t_end, t_transient=t_transient,
                       v_stick=v_stick, max_impacts=max_impacts, root_tol=root_tol,
                       n_threads=n_threads)
    ke = f["ke_ratio"]
    # contours in (x, y) = (omega, eta); sample the lines 4x finer than the finest spacing
    ds = 0.25 * min(eta[1] - eta[0], omega[1] - omega[0])
    lines = [contour_lines(omega[::s], eta[::s], ke[::s, ::s], level) for s in strides]
    ref = lines[-1]
    area_total = (e1 - e0) * (w1 - w0)
    mean, mx, haus, length, area = [], [], [], [], []
    for ln, s in zip(lines, strides):
        if s == 1:      # the finest grid itself: zero by definition (not round-off)
            m1 = x1 = x2 = 0.0 if ln else math.nan
        else:
            m1, x1 = contour_distance(ln, ref, ds)
            _, x2 = contour_distance(ref, ln, ds)
        mean.append(m1)
        mx.append(x1)
        haus.append(max(x1, x2))
        length.append(float(sum(np.hypot(*np.diff(p, axis=0).T).sum() for p in ln)))
        area.append(area_above(omega[::s], eta[::s], ke[::s, ::s], level) / area_total)
    rdim = ("resolution",)
    area = np.array(area)
    data = {
        "ke_ratio": _var(("eta", "omega"), ke, *BATCH_FIELDS["ke_ratio"][1:]),
        "xmax": _var(("eta", "omega"), f["xmax"], *BATCH_FIELDS["xmax"][1:]),
        "regime": _var(("eta", "omega"), f["regime"], *BATCH_FIELDS["regime"][1:]),
        "stride": _var(rdim, np.array(strides), "index step of the grid in the finest grid",
                       "1"),
        "spacing_eta": _var(rdim, (e1 - e0) / (np.array(res) - 1.0), "grid spacing in eta",
                            "1"),
        "spacing_omega": _var(rdim, (w1 - w0) / (np.array(res) - 1.0),
                              "grid spacing in omega", "1"),
        "contour_dist_mean": _var(rdim, np.array(mean), "arc-length mean distance of the "
                                  "contour to the finest grid's contour", "1"),
        "contour_dist_max": _var(rdim, np.array(mx), "max distance of the contour to the "
                                 "finest grid's contour (one-sided Hausdorff)", "1"),
        "contour_hausdorff": _var(rdim, np.array(haus), "symmetric Hausdorff distance of "
                                  "the contour and the finest grid's contour", "1"),
        "contour_length": _var(rdim, np.array(length), "length of the contour in the "
                               "(omega, eta) plane", "1"),
        "area_fraction": _var(rdim, area, "fraction of the (eta, omega) rectangle where the "
                              "KE ratio exceeds the level", "1"),
        "d_area_fraction": _var(rdim, area - area[-1], "area fraction minus the finest "
                                "grid's", "1"),
    }
    coords = {"eta": xr.Variable(("eta",), eta, COORD_ATTRS["eta"]),
              "omega": xr.Variable(("omega",), omega, COORD_ATTRS["omega"]),
              "resolution": _var(rdim, np.array(res), "grid points per axis", "1")}
    attrs = {"Conventions": CONVENTIONS,
             "title": "convergence of the KE-ratio contour with grid resolution",
             "F": float(F), "level": float(level),
             "distance": "Euclidean in the (omega, eta) plane, parameter units",
             **_settings_attrs(t_end=float(t_end), t_transient=float(t_transient),
                               v_stick=float(v_stick), r=float(r), d=float(d),
                               max_impacts=int(max_impacts), root_tol=float(root_tol))}
    return xr.Dataset(data, coords=coords, attrs=attrs)
