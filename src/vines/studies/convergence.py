"""Convergence of the measures with run length and window, sticking threshold and grid.

Three studies, each returning a result object of plain numpy arrays and the settings that
describe them (``vines.data.builders.convergence_dataset`` makes it a CF dataset):

* :func:`window_convergence` -> :class:`WindowConvergence`: KE ratio, x_max and regime at
  named parameter points over a grid of run lengths ``t_end`` and window rules (a fixed
  window length, or a fraction of the run), compared with the longest run's widest window.
* :func:`vstick_convergence` -> :class:`VStickConvergence`: the same measures against the
  sticking threshold ``v_stick`` (log-spaced), compared with the smallest ``v_stick``, with
  the cost of every run.
* :func:`grid_convergence` -> :class:`GridConvergence`: the KE ratio = ``level`` contour
  over (eta, omega) grids of increasing, nested resolution, compared with the finest grid's
  contour (geometry in :mod:`vines.studies.contours`).

Conventions: dimensionless time (t = w0 t_dim) and displacements in units of L, as in
``vines.simulate``; ``xmax_m`` in metres. Every run starts from rest at t = 0 (forcing phase
phi = 0), so runs of different length share one trajectory and differ only in where the
window [t_transient, t_end] lies. Each point is computed on its own, so no result depends on
``n_threads`` (``run_time`` is a wall-clock measurement and does).
"""
from __future__ import annotations

import inspect
import math
import os
import time
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass

import numpy as np

from ..core.params import (
    D_DEFAULT,
    L_HALF_M,
    MAX_IMPACTS_DEFAULT,
    R_DEFAULT,
    ROOT_TOL_DEFAULT,
    T_END_DEFAULT,
    T_END_MAX,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    V_STICK_MAX,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_bool,
    check_int,
    check_param,
    check_real,
    check_reals,
)
from ..core.simulation import BATCH_FIELDS, simulate_batch
from .contours import area_above, contour_distance, contour_lines, line_length, nested_axis

#: per-run measures kept in the window and v_stick studies (names of BATCH_FIELDS)
RUN_FIELDS = ("ke_ratio", "xmax", "regime", "status", "impacts_per_period", "n_impacts",
              "t_stuck", "period")
#: differences to the reference run: d_ke, rel_d_xmax (float), converged, regime_same (bool)
DIFF_FIELDS = ("d_ke", "rel_d_xmax", "converged", "regime_same")


# ------------------------------------------------------------------ results

@dataclass(frozen=True)
class WindowConvergence:
    """Result of :func:`window_convergence`; arrays over (point, window, t_end) unless noted.

    ``points``: dicts eta, omega, F, label. ``t_end``: run lengths (increasing). ``rules``:
    window rules ("length", L) or ("fraction", f), one per window index. ``t_transient``:
    window starts. ``measures``: RUN_FIELDS and ``xmax_m`` (metres). ``differences``:
    DIFF_FIELDS to the reference. ``converged_from_t_end`` (point, window): shortest run from
    which every longer run of the rule is converged (NaN: none). ``reference_t_transient``
    (point,). ``tested_window``, ``tested_t_end_index``: indices of the tested setting
    ``tested_t_end``/``tested_t_transient``; ``tested``: DIFF_FIELDS there (point,).
    ``solver``: the fixed solver settings (v_stick, r, d, max_impacts, root_tol).
    """

    points: list
    t_end: np.ndarray
    rules: list
    t_transient: np.ndarray
    measures: dict
    differences: dict
    converged_from_t_end: np.ndarray
    reference_t_transient: np.ndarray
    tested: dict
    tested_window: int
    tested_t_end_index: int
    tested_t_end: float
    tested_t_transient: float
    ke_tol: float
    xmax_rtol: float
    whole_periods: bool
    solver: dict


@dataclass(frozen=True)
class VStickConvergence:
    """Result of :func:`vstick_convergence`; arrays over (point, v_stick) unless noted.

    ``v_stick``: thresholds (increasing; the first is the reference). ``measures``,
    ``differences`` as in :class:`WindowConvergence`; ``run_time``: wall-clock seconds of
    each run. ``converged_below`` (point,): largest v_stick at and below which every run is
    converged (NaN: none). ``tested``: DIFF_FIELDS at ``tested_v_stick`` (index
    ``tested_index``). ``solver``: t_end, t_transient, r, d, max_impacts, root_tol.
    """

    points: list
    v_stick: np.ndarray
    measures: dict
    differences: dict
    run_time: np.ndarray
    converged_below: np.ndarray
    tested: dict
    tested_index: int
    tested_v_stick: float
    ke_tol: float
    xmax_rtol: float
    solver: dict


@dataclass(frozen=True)
class GridConvergence:
    """Result of :func:`grid_convergence`.

    ``eta``, ``omega``: axes of the finest grid; ``fields``: its ke_ratio, xmax, regime over
    (eta, omega). ``resolution``: points per axis (increasing); ``per_resolution``: arrays
    over the resolutions: stride, spacing_eta, spacing_omega, contour_dist_mean,
    contour_dist_max, contour_hausdorff, contour_length, area_fraction, d_area_fraction.
    ``F``, ``level``; ``solver``: t_end, t_transient, v_stick, r, d, max_impacts, root_tol.
    """

    eta: np.ndarray
    omega: np.ndarray
    fields: dict
    resolution: np.ndarray
    per_resolution: dict
    F: float
    level: float
    solver: dict


# ------------------------------------------------------------------ shared helpers

def _check_points(points) -> list[dict]:
    """The parameter points (dicts eta, omega, F, optional label), each value checked."""
    if not isinstance(points, (list, tuple)) or not points:
        raise ParameterError("points", points, "must be a non-empty list of dicts with eta, "
                                               "omega, F (and optionally label)")
    out = []
    for i, p in enumerate(points):
        if not isinstance(p, dict) or not all(k in p for k in ("eta", "omega", "F")):
            raise ParameterError(f"points[{i}]", p, "needs numbers eta, omega, F")
        q = {k: check_param(k, p[k]) for k in ("eta", "omega", "F")}
        q["label"] = str(p.get("label", "")) or (
            f"eta={q['eta']:g} omega={q['omega']:g} F={q['F']:g}")
        out.append(q)
    return out


@dataclass(frozen=True)
class StudySolver:
    """The settings shared by every run of a study, validated on construction (each bad
    value raises ParameterError naming it): the run's end t_end and window start
    t_transient (dimensionless time), v_stick (units of L w0), max_impacts and root_tol as
    in ``SolverSettings``; restitution r and LO damping d as in ``ModelParams``;
    periodic_shortcut as in ``simulate_batch``. A study may vary some of them per case."""

    t_end: float
    t_transient: float
    v_stick: float
    r: float
    d: float
    max_impacts: int
    root_tol: float
    periodic_shortcut: bool

    def __post_init__(self):
        st = SolverSettings(t_end=self.t_end, t_transient=self.t_transient,
                            v_stick=self.v_stick, max_impacts=self.max_impacts,
                            root_tol=self.root_tol)
        model = ModelParams(eta=1.0, omega=1.0, F=0.0, r=self.r, d=self.d)
        set_ = object.__setattr__
        for name in ("t_end", "t_transient", "v_stick", "max_impacts", "root_tol"):
            set_(self, name, getattr(st, name))
        set_(self, "r", model.r)
        set_(self, "d", model.d)
        set_(self, "periodic_shortcut", check_bool("periodic_shortcut",
                                                   self.periodic_shortcut))

    def run_kwargs(self, *varied: str) -> dict:
        """Keyword arguments of ``simulate_batch`` for every case, less the ``varied``
        ones (set per case)."""
        return {k: v for k, v in asdict(self).items() if k not in varied}

    def record(self, *varied: str) -> dict:
        """The settings as a study's result stores them (``solver``; the flag as 0/1),
        less the ``varied`` ones (its axes)."""
        out = self.run_kwargs(*varied)
        out["periodic_shortcut"] = int(out["periodic_shortcut"])
        return out


def _check_threads(n_threads) -> None:
    if n_threads is not None:
        check_int("n_threads", n_threads, lo=1)


def _check_tols(ke_tol, xmax_rtol) -> tuple[float, float]:
    return (check_real("ke_tol", ke_tol, lo=0.0), check_real("xmax_rtol", xmax_rtol, lo=0.0))


def _run_cases(cases: list[dict], settings: dict, n_threads) -> tuple[dict, np.ndarray]:
    """Run every case (eta, omega, F and any per-case setting) on its own, on ``n_threads``
    threads (None: all cores; the kernel releases the GIL).

    Returns (fields, run_time): arrays over the cases, fields named as BATCH_FIELDS, run_time
    the wall-clock seconds of each run (time.perf_counter).
    """
    n = len(cases)
    out = {k: np.empty(n, dtype=BATCH_FIELDS[k]) for k in BATCH_FIELDS}
    run_time = np.empty(n)

    def work(i):
        kw = {**settings, **cases[i]}
        t0 = time.perf_counter()
        res = simulate_batch(n_threads=1, **kw)
        run_time[i] = time.perf_counter() - t0
        for k in BATCH_FIELDS:
            out[k][i] = res[k][()]
        return i

    n_threads = (os.cpu_count() or 1) if n_threads is None else check_int("n_threads",
                                                                          n_threads, lo=1)
    if n_threads == 1:
        for i in range(n):
            work(i)
    else:
        with ThreadPoolExecutor(max_workers=n_threads) as ex:
            list(ex.map(work, range(n)))
    return out, run_time


def _measures(f: dict, shape) -> dict:
    """RUN_FIELDS of the runs, shaped, and x_max in metres."""
    m = {k: f[k].reshape(shape) for k in RUN_FIELDS}
    m["xmax_m"] = m["xmax"] * L_HALF_M
    return m


def _differences(m: dict, ref_ke, ref_xmax, ref_regime, ke_tol, xmax_rtol) -> dict:
    """DIFF_FIELDS of the measures ``m`` to the reference values (broadcast)."""
    d_ke = m["ke_ratio"] - ref_ke
    xmax = m["xmax"]
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(ref_xmax != 0, (xmax - ref_xmax) / np.abs(ref_xmax),
                       np.where(xmax == ref_xmax, 0.0, np.inf))
    conv = (np.abs(d_ke) <= ke_tol) & (np.abs(rel) <= xmax_rtol)
    return {"d_ke": d_ke, "rel_d_xmax": rel, "converged": conv,
            "regime_same": m["regime"] == ref_regime}


# ------------------------------------------------------------------ (a) run length, window

def _window_rules(t_ends, window_lengths, window_fractions, t_end, t_transient):
    """(t_ends with the tested t_end, rules, tested window length), arguments checked."""
    tested_len = float(t_end) - float(t_transient)
    if not tested_len > 0:
        raise ParameterError("t_transient", t_transient, f"must be < t_end = {t_end}")
    t_ends = np.unique(np.append(
        check_reals("t_ends", t_ends, lo=0.0, lo_open=True, hi=T_END_MAX, min_size=0),
        float(t_end)))
    lengths = [float(x) for x in check_reals("window_lengths", window_lengths, min_size=0)]
    if tested_len not in lengths:
        lengths.append(tested_len)
    fractions = [float(x) for x in check_reals("window_fractions", window_fractions,
                                               min_size=0)]
    if any(not 0 < f < 1 for f in fractions):
        raise ParameterError("window_fractions", window_fractions,
                             "window fractions must lie in (0, 1)")
    if any(x <= 0 for x in lengths) or any(x >= t_ends[0] for x in lengths):
        raise ParameterError("window_lengths", window_lengths,
                             f"window lengths {lengths} (with the tested t_end - t_transient) "
                             f"must be > 0 and < the shortest t_end {t_ends[0]:g}")
    rules = [("length", x) for x in sorted(lengths)] + [("fraction", f) for f in fractions]
    return t_ends, rules, tested_len


def _window_starts(pts, rules, t_ends, whole_periods) -> np.ndarray:
    """t_transient over (point, window, t_end) of every window rule."""
    t_tr = np.empty((len(pts), len(rules), t_ends.size))
    for j, (kind, x) in enumerate(rules):
        win = np.full(t_ends.size, x) if kind == "length" else x * t_ends
        for i, p in enumerate(pts):
            w = win
            if whole_periods:
                period = 2.0 * math.pi / p["omega"]
                w = np.floor(win / period) * period
                if np.any(w <= 0):
                    raise ParameterError("whole_periods", whole_periods,
                                         f"a window of rule {kind} {x:g} is shorter than one "
                                         f"forcing period at point {p['label']}")
            t_tr[i, j] = t_ends - w
    return t_tr


def window_convergence(points: Sequence[dict],
                       t_ends: Sequence[float] = (7000.0, 10000.0, 14000.0, 20000.0, 28000.0),
                       window_lengths: Sequence[float] = (3000.0,),
                       window_fractions: Sequence[float] = (0.5,), *,
                       whole_periods: bool = False, ke_tol: float = 1e-2,
                       xmax_rtol: float = 1e-2, t_end: float = T_END_DEFAULT,
                       t_transient: float = T_TRANSIENT_DEFAULT,
                       v_stick: float = V_STICK_DEFAULT, r: float = R_DEFAULT,
                       d: float = D_DEFAULT, max_impacts: int = MAX_IMPACTS_DEFAULT,
                       root_tol: float = ROOT_TOL_DEFAULT, periodic_shortcut: bool = True,
                       n_threads: int | None = None) -> WindowConvergence:
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
    equals the reference's. Arrays over (point, window, t_end).
    """
    pts = _check_points(points)
    run = StudySolver(t_end, t_transient, v_stick, r, d, max_impacts, root_tol,
                      periodic_shortcut)
    _check_threads(n_threads)
    ke_tol, xmax_rtol = _check_tols(ke_tol, xmax_rtol)
    whole_periods = check_bool("whole_periods", whole_periods)
    t_ends, rules, tested_len = _window_rules(t_ends, window_lengths, window_fractions,
                                              t_end, t_transient)
    t_tr = _window_starts(pts, rules, t_ends, whole_periods)
    n_p, n_w, n_t = t_tr.shape
    cases = [dict(eta=p["eta"], omega=p["omega"], F=p["F"], t_end=float(t_ends[k]),
                  t_transient=float(t_tr[i, j, k]))
             for i, p in enumerate(pts) for j in range(n_w) for k in range(n_t)]
    f, _ = _run_cases(cases, run.run_kwargs("t_end", "t_transient"), n_threads)
    m = _measures(f, (n_p, n_w, n_t))
    # reference: longest run, widest window (smallest t_transient of the last t_end column)
    j_ref = np.argmin(t_tr[:, :, -1], axis=1)
    ip = np.arange(n_p)
    ref = {k: m[k][ip, j_ref, -1][:, None, None] for k in ("ke_ratio", "xmax", "regime")}
    diff = _differences(m, ref["ke_ratio"], ref["xmax"], ref["regime"], ke_tol, xmax_rtol)
    # smallest t_end from which every longer run (same window rule) is converged
    conv = diff["converged"]
    tail = np.flip(np.logical_and.accumulate(np.flip(conv, -1), -1), -1)
    first = np.where(tail.any(-1), t_ends[np.argmax(tail, -1)], np.nan)
    j_t = rules.index(("length", tested_len))
    k_t = int(np.flatnonzero(t_ends == float(t_end))[0])
    return WindowConvergence(
        points=pts, t_end=t_ends, rules=rules, t_transient=t_tr, measures=m,
        differences=diff, converged_from_t_end=first,
        reference_t_transient=t_tr[ip, j_ref, -1],
        tested={k: v[:, j_t, k_t] for k, v in diff.items()}, tested_window=j_t,
        tested_t_end_index=k_t, tested_t_end=float(t_end),
        tested_t_transient=float(t_transient), ke_tol=float(ke_tol),
        xmax_rtol=float(xmax_rtol), whole_periods=bool(whole_periods),
        solver=run.record("t_end", "t_transient"))


# ------------------------------------------------------------------ (b) sticking threshold

V_STICKS_DEFAULT = tuple(10.0 ** -np.arange(3, 11))

def vstick_convergence(points: Sequence[dict], v_sticks: Sequence[float] = V_STICKS_DEFAULT,
                       *, ke_tol: float = 1e-3, xmax_rtol: float = 1e-2,
                       t_end: float = T_END_DEFAULT, t_transient: float = T_TRANSIENT_DEFAULT,
                       v_stick: float = V_STICK_DEFAULT, r: float = R_DEFAULT,
                       d: float = D_DEFAULT, max_impacts: int = MAX_IMPACTS_DEFAULT,
                       root_tol: float = ROOT_TOL_DEFAULT, periodic_shortcut: bool = True,
                       n_threads: int | None = None) -> VStickConvergence:
    """Measures at ``points`` (dicts eta, omega, F, optional label) against ``v_sticks``.

    ``v_sticks``: sticking thresholds on the relative velocity after an impact
    (dimensionless, units of L w0); the tested ``v_stick`` (library default 1e-6) is added.
    Reference: the smallest v_stick. ``d_ke``, ``rel_d_xmax``, ``converged`` (|d_ke| <=
    ke_tol and |rel_d_xmax| <= xmax_rtol), ``regime_same`` as in window_convergence;
    ``run_time`` is the wall-clock cost of each run in seconds. ``converged_below``: the
    largest v_stick at and below which every run is converged. Arrays over (point,
    v_stick), v_stick increasing.
    """
    pts = _check_points(points)
    run = StudySolver(t_end, t_transient, v_stick, r, d, max_impacts, root_tol,
                      periodic_shortcut)
    _check_threads(n_threads)
    ke_tol, xmax_rtol = _check_tols(ke_tol, xmax_rtol)
    vs = np.unique(np.append(check_reals("v_sticks", v_sticks, lo=0.0, lo_open=True,
                                         hi=V_STICK_MAX, min_size=0), float(v_stick)))
    if not np.all(vs > 0):
        raise ParameterError("v_stick", v_stick, "must be > 0 in a v_stick study")
    cases = [dict(eta=p["eta"], omega=p["omega"], F=p["F"], v_stick=float(v))
             for p in pts for v in vs]
    f, run_time = _run_cases(cases, run.run_kwargs("v_stick"), n_threads)
    shape = (len(pts), vs.size)
    m = _measures(f, shape)
    diff = _differences(m, m["ke_ratio"][:, :1], m["xmax"][:, :1], m["regime"][:, :1],
                        ke_tol, xmax_rtol)
    n_ok = np.logical_and.accumulate(diff["converged"], -1).sum(-1)
    below = np.where(n_ok > 0, vs[np.maximum(n_ok - 1, 0)], np.nan)
    k_t = int(np.flatnonzero(vs == float(v_stick))[0])
    return VStickConvergence(
        points=pts, v_stick=vs, measures=m, differences=diff,
        run_time=run_time.reshape(shape), converged_below=below,
        tested={k: v[:, k_t] for k, v in diff.items()}, tested_index=k_t,
        tested_v_stick=float(v_stick), ke_tol=float(ke_tol), xmax_rtol=float(xmax_rtol),
        solver=run.record("v_stick"))


# ------------------------------------------------------------------ (c) grid resolution

def _contour_measures(eta, omega, ke, strides, level, area_total) -> dict:
    """Per stride: contour distances to the finest grid's contour, length, area fraction
    (of ``area_total``, the area of the (eta, omega) rectangle)."""
    # contours in (x, y) = (omega, eta); sample the lines 4x finer than the finest spacing
    ds = 0.25 * min(eta[1] - eta[0], omega[1] - omega[0])
    lines = [contour_lines(omega[::s], eta[::s], ke[::s, ::s], level) for s in strides]
    ref = lines[-1]
    mean, mx, haus, length, area = [], [], [], [], []
    for ln, s in zip(lines, strides, strict=False):
        if s == 1:      # the finest grid itself: zero by definition (not round-off)
            m1 = x1 = x2 = 0.0 if ln else math.nan
        else:
            m1, x1 = contour_distance(ln, ref, ds)
            _, x2 = contour_distance(ref, ln, ds)
        mean.append(m1)
        mx.append(x1)
        haus.append(max(x1, x2))
        length.append(line_length(ln))
        area.append(area_above(omega[::s], eta[::s], ke[::s, ::s], level) / area_total)
    area = np.array(area)
    return {"contour_dist_mean": np.array(mean), "contour_dist_max": np.array(mx),
            "contour_hausdorff": np.array(haus), "contour_length": np.array(length),
            "area_fraction": area, "d_area_fraction": area - area[-1]}


RESOLUTION_MAX = 10_001      # points per axis of the finest grid (1e8 runs)


def _check_range(name, value) -> tuple[float, float]:
    """(lo, hi) of eta or omega, lo < hi, both within the parameter's bounds."""
    q = name.split("_")[0]
    lo, hi = check_reals(name, value, min_size=2, max_size=2)
    try:
        lo, hi = check_param(q, lo), check_param(q, hi)
    except ParameterError as err:
        raise ParameterError(name, value, f"{err.allowed} (both ends)") from None
    if not lo < hi:
        raise ParameterError(name, value, "must be two numbers lo < hi")
    return lo, hi


def grid_convergence(eta_range: Sequence[float] = (0.01, 1.0),
                     omega_range: Sequence[float] = (0.5, 1.5), F: float = 0.4,
                     resolutions: Sequence[int] = (11, 21, 41, 81), level: float = 0.5, *,
                     t_end: float = T_END_DEFAULT, t_transient: float = T_TRANSIENT_DEFAULT,
                     v_stick: float = V_STICK_DEFAULT, r: float = R_DEFAULT,
                     d: float = D_DEFAULT, max_impacts: int = MAX_IMPACTS_DEFAULT,
                     root_tol: float = ROOT_TOL_DEFAULT, periodic_shortcut: bool = True,
                     n_threads: int | None = None) -> GridConvergence:
    """KE ratio = ``level`` contour over (eta, omega) at ``resolutions`` points per axis.

    Grids are linspace over ``eta_range`` x ``omega_range`` at fixed F; every coarse grid is
    nested in the finest (its points are a subset of the finest grid's points, taken every
    ``stride``-th value), so only the finest grid is simulated. Per resolution: distances of
    its contour to the finest grid's contour, Euclidean in the (omega, eta) parameter plane
    (both dimensionless): ``contour_dist_mean`` (arc-length mean) and ``contour_dist_max``
    (one-sided Hausdorff, coarse -> finest), ``contour_hausdorff`` (symmetric); and the area
    fraction of the rectangle where KE ratio > level. ``fields`` holds the finest grid's
    ``ke_ratio``/``xmax``/``regime`` over (eta, omega): the coarse grids are
    ``[::stride, ::stride]``.
    """
    g = _grid_inputs(dict(locals()))
    f = simulate_batch(*np.meshgrid(g["eta"], g["omega"], indexing="ij"), g["F"],
                       n_threads=n_threads, **g["run"].run_kwargs())
    return _grid_result(g, f)


def _grid_arguments(kwargs: dict) -> dict:
    """``grid_convergence``'s arguments: its defaults updated by ``kwargs``."""
    return {k: p.default for k, p in
            inspect.signature(grid_convergence).parameters.items()} | kwargs


def grid_convergence_part(start: int, stop: int, **kwargs) -> dict:
    """The runs of ``grid_convergence(**kwargs)`` at the finest grid's eta rows
    [start, stop): its ``simulate_batch`` fields there, a part for
    ``grid_convergence_of_parts``."""
    a = _grid_arguments(kwargs)
    g = _grid_inputs(a)
    E, OM = np.meshgrid(g["eta"][start:stop], g["omega"], indexing="ij")
    return simulate_batch(E, OM, g["F"], n_threads=a["n_threads"], **g["run"].run_kwargs())


def grid_convergence_of_parts(parts: list, **kwargs) -> GridConvergence:
    """``grid_convergence(**kwargs)`` from the ``grid_convergence_part`` results that cover
    the finest grid's eta rows in order (their runs are not repeated; the same result)."""
    g = _grid_inputs(_grid_arguments(kwargs))
    f = {k: np.concatenate([part[k] for part in parts], axis=0) for k in parts[0]}
    if f["ke_ratio"].shape != (g["eta"].size, g["omega"].size):
        raise ValueError(f"parts hold {f['ke_ratio'].shape} runs, the finest grid "
                         f"{(g['eta'].size, g['omega'].size)}")
    return _grid_result(g, f)


def grid_rows(**kwargs) -> int:
    """Rows (eta values) of the finest grid of ``grid_convergence(**kwargs)``."""
    return int(max(_grid_arguments(kwargs)["resolutions"]))


def _grid_inputs(a: dict) -> dict:
    """``grid_convergence``'s arguments validated: the solver, F, level, resolutions, their
    strides, the finest grid's axes and the rectangle."""
    run = StudySolver(a["t_end"], a["t_transient"], a["v_stick"], a["r"], a["d"],
                      a["max_impacts"], a["root_tol"], a["periodic_shortcut"])
    _check_threads(a["n_threads"])
    F = check_param("F", a["F"])
    level = check_real("level", a["level"])
    resolutions = a["resolutions"]
    counts = check_reals("resolutions", resolutions, lo=2, hi=RESOLUTION_MAX)
    if np.any(counts != np.round(counts)):
        raise ParameterError("resolutions", resolutions, "must be integers (points per axis)")
    res = sorted({int(n) for n in counts})
    n_f = res[-1]
    e0, e1 = _check_range("eta_range", a["eta_range"])
    w0, w1 = _check_range("omega_range", a["omega_range"])
    for n in res:
        try:
            nested_axis(e0, e1, n_f, n)           # raises when not nested
        except ValueError as err:
            raise ParameterError("resolutions", resolutions, str(err)) from None
    return dict(run=run, F=float(F), level=float(level), res=res,
                strides=[(n_f - 1) // (n - 1) for n in res], box=(e0, e1, w0, w1),
                eta=np.linspace(e0, e1, n_f), omega=np.linspace(w0, w1, n_f))


def _grid_result(g: dict, f: dict) -> GridConvergence:
    """The grid study of the inputs ``g`` from the finest grid's fields ``f``."""
    e0, e1, w0, w1 = g["box"]
    res, eta, omega = g["res"], g["eta"], g["omega"]
    per_res = {"stride": np.array(g["strides"]),
               "spacing_eta": (e1 - e0) / (np.array(res) - 1.0),
               "spacing_omega": (w1 - w0) / (np.array(res) - 1.0),
               **_contour_measures(eta, omega, f["ke_ratio"], g["strides"], g["level"],
                                  (e1 - e0) * (w1 - w0))}
    return GridConvergence(eta=eta, omega=omega,
                           fields={k: f[k] for k in ("ke_ratio", "xmax", "regime")},
                           resolution=np.array(res), per_resolution=per_res, F=g["F"],
                           level=g["level"], solver=g["run"].record())


#: the studies by name (the ``convergence`` config section's keys)
STUDIES = {"window": window_convergence, "vstick": vstick_convergence,
           "grid": grid_convergence}
