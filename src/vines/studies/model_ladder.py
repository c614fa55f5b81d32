"""The model ladder: one frequency band at one eta answered by the averaged slow flow
(``vines.slowflow``), by the exact symmetric 1:1 orbits (map solve at every frequency of
the grid, and their continuation in omega) and by the exact simulation from rest; each
model's amplitude and its cost (wall time, ``time.perf_counter``).

Amplitudes are max |z_m| over a period in units of L (the slow flow's ``amplitude``; the
exact orbit's x_max over one period; the simulation's x_max over its window). The slow
flow's error at a frequency is measured against the exact orbits there: when both give the
same number of orbits, the largest relative difference of their amplitudes sorted
(``error_max``); NaN when the counts differ. Each slow-flow fixed point also gets the
relative difference to the nearest exact orbit at its frequency (``nearest_error``).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

#: the models, in ladder order (cheapest first)
MODELS = ("slowflow", "map_solve", "continuation", "simulation")
#: a timed round of the slow flow lasts at least this long (s): its FRC takes ~0.1 ms
MIN_TIME = 0.05
#: tolerances of the bands reported (relative amplitude error)
TOLERANCES = (0.01, 0.05)


@dataclass(frozen=True)
class Ladder:
    """One panel of the ladder at (eta, F) over ``omega`` (the grid). Rows of the slow
    flow's and the map solve's orbits carry the index of their grid frequency; the
    continuation's points the index of their curve. ``seconds``: wall time per model of
    ``MODELS``; ``dense``: the slow flow on a finer grid (for drawing)."""

    eta: float
    F: float
    omega: np.ndarray
    slowflow: dict
    dense: dict
    exact: dict
    continuation: dict
    simulation: dict
    error_max: np.ndarray
    seconds: dict
    xi_min: float


def timed(fn, min_time: float = MIN_TIME):
    """(fn(), mean seconds per call over repeated calls lasting >= min_time)."""
    t0 = time.perf_counter()
    out = fn()
    n, total = 1, time.perf_counter() - t0
    while total < min_time:
        k = max(1, int(math.ceil(n * (min_time / max(total, 1e-9) - 1.0))))
        t0 = time.perf_counter()
        for _ in range(k):
            fn()
        total += time.perf_counter() - t0
        n += k
    return out, total / n


def _frc_rows(frc, W: np.ndarray) -> dict:
    """The FRC's fixed points as rows with the index of their grid frequency."""
    index = np.searchsorted(W, frc.omega)
    return {"index": index, "omega": np.asarray(frc.omega, float),
            "amplitude": np.asarray(frc.amplitude, float),
            "stable": np.asarray(frc.stable, bool), "branch": np.asarray(frc.branch, int)}


def slowflow_rows(eta, W, F, r, d) -> tuple[dict, float, float]:
    """(rows, seconds per FRC over W, xi_min) of the slow flow (``vines.slowflow.frc``)."""
    from ..slowflow import frc
    out, seconds = timed(lambda: frc(eta, W, F, r=r, d=d))
    return _frc_rows(out, W), seconds, float(out.xi_min)


def orbit_amplitude(p, st, oscs, orbit) -> float:
    """max |z_m| over one period of an exact 1:1 orbit (units of L)."""
    from ..attractors.orbit import section_of_1to1
    return float(section_of_1to1(p, st, oscs, orbit)["xmax"])


def _amplitudes(eta, F, r, d, pairs) -> tuple[np.ndarray, np.ndarray]:
    """(amplitude, stable) of the admissible symmetric orbits of ``pairs`` (omega, orbit);
    NaN, False for the others."""
    from ..core.exact import oscillators
    from ..core.params import ModelParams, SolverSettings
    st = SolverSettings()
    amp, stable, cache = [], [], {}
    for w, o in pairs:
        if not (o.symmetric and o.admissible):
            amp.append(math.nan)
            stable.append(False)
            continue
        if w not in cache:
            p = ModelParams(eta=eta, omega=float(w), F=F, r=r, d=d)
            cache = {w: (p, oscillators(p))}
        p, oscs = cache[w]
        amp.append(orbit_amplitude(p, st, oscs, o))
        stable.append(bool(o.stable))
    return np.asarray(amp, float), np.asarray(stable, bool)


def map_solve_rows(eta, W, F, r, d) -> tuple[dict, list, float]:
    """(rows, orbits per frequency, seconds) of the exact symmetric admissible 1:1 orbits
    found at each frequency of W (``orbits.family.periodic.find_1to1``) with their amplitudes."""
    from ..orbits.family.periodic import find_1to1
    t0 = time.perf_counter()
    per_w, pairs, index = [], [], []
    for i, w in enumerate(W):
        found = [o for o in find_1to1(eta, float(w), F, r=r, d=d)
                 if o.symmetric and o.admissible]
        per_w.append(found)
        pairs += [(float(w), o) for o in found]
        index += [i] * len(found)
    amp, stable = _amplitudes(eta, F, r, d, pairs)
    seconds = time.perf_counter() - t0
    rows = {"index": np.asarray(index, int), "omega": W[np.asarray(index, int)],
            "amplitude": amp, "stable": stable}
    return rows, per_w, seconds


def continuation_rows(eta, W, F, r, d, per_w: list, step: float) -> tuple[dict, float]:
    """(rows, seconds) of the exact branches continued in omega (arclength, through folds)
    from every orbit found at the band's first and last frequency with orbits, towards the
    other end; rows carry their curve's index and the points' amplitudes (NaN where not
    admissible)."""
    from ..orbits.continuation.one_to_one import continue_branch
    t0 = time.perf_counter()
    with_orbits = [i for i, found in enumerate(per_w) if found]
    starts = []
    if with_orbits:
        lo, hi = with_orbits[0], with_orbits[-1]
        starts = [(W[lo], W[-1], o) for o in per_w[lo]]
        if hi != lo:
            starts += [(W[hi], W[0], o) for o in per_w[hi]]
    curve, omega, amp, stable = [], [], [], []
    for k, (a, b, orbit) in enumerate(starts):
        br = continue_branch("omega", float(a), float(b), step=step,
                             fixed={"eta": eta, "F": F}, orbit=orbit, r=r, d=d)
        A, S = _amplitudes(eta, F, r, d, zip(br.omega, br.orbits, strict=True))
        curve += [k] * A.size
        omega.append(np.asarray(br.omega, float))
        amp.append(A)
        stable.append(S)
    seconds = time.perf_counter() - t0
    return {"curve": np.asarray(curve, int), "omega": _cat(omega, float),
            "amplitude": _cat(amp, float), "stable": _cat(stable, bool)}, seconds


def _cat(parts: list, dtype) -> np.ndarray:
    return np.concatenate(parts) if parts else np.zeros(0, dtype)


def simulation_rows(eta, W, F, r, d, t_end, t_transient) -> tuple[dict, float]:
    """({xmax, regime} per frequency, seconds) of the exact simulation from rest."""
    from ..core.simulation import simulate_batch
    t0 = time.perf_counter()
    out = simulate_batch(eta, W, F, r=r, d=d, t_end=t_end, t_transient=t_transient,
                         n_threads=1)
    return {"xmax": np.asarray(out["xmax"], float),
            "regime": np.asarray(out["regime"], str)}, time.perf_counter() - t0


def errors(n: int, sf: dict, ex: dict) -> tuple[np.ndarray, np.ndarray]:
    """(error_max per grid frequency, nearest_error per slow-flow row): module docstring.
    Both without orbits: error 0 (both say no symmetric 1:1 orbit)."""
    err = np.full(n, np.nan)
    nearest = np.full(sf["amplitude"].size, np.nan)
    for i in range(n):
        a = np.sort(sf["amplitude"][sf["index"] == i])
        b = np.sort(ex["amplitude"][ex["index"] == i])
        if a.size == b.size:
            err[i] = float(np.max(np.abs(a - b) / b)) if a.size else 0.0
        rows = np.flatnonzero(sf["index"] == i)
        if b.size:
            for j in rows:
                nearest[j] = float(np.min(np.abs(sf["amplitude"][j] - b) / b))
    return err, nearest


def band(omega: np.ndarray, error_max: np.ndarray, tol: float) -> tuple[float, float, float]:
    """(lo, hi, share): the widest run of consecutive grid frequencies where error_max <=
    tol (NaN, NaN if none) and the share of the grid within tol."""
    ok = np.nan_to_num(error_max, nan=np.inf) <= tol
    best, start, lo, hi = 0, None, math.nan, math.nan
    for i, good in enumerate(np.append(ok, False)):
        if good and start is None:
            start = i
        elif not good and start is not None:
            if i - start > best:
                best, lo, hi = i - start, float(omega[start]), float(omega[i - 1])
            start = None
    return lo, hi, float(ok.mean()) if ok.size else math.nan


def warm_up(r, d) -> None:
    """Every model once on a tiny case, so that no timing counts numba's loading of the
    compiled kernels (from its cache) into the first model that uses them."""
    W = np.array([0.99, 1.01])
    _, per_w, _ = map_solve_rows(0.05, W, 0.05, r, d)
    continuation_rows(0.05, W, 0.05, r, d, per_w, 0.01)
    simulation_rows(0.05, W, 0.05, r, d, 20.0, 10.0)
    slowflow_rows(0.05, W, 0.05, r, d)


def ladder(eta, F, omegas, *, r, d, t_end, t_transient, n_dense=1000,
           continuation_step=0.01) -> Ladder:
    """The four models over the grid ``omegas`` at (eta, F) (validated inputs; omegas
    increasing); the slow flow also on ``n_dense`` frequencies over the same band."""
    W = np.asarray(omegas, float)
    sf, t_sf, xi_min = slowflow_rows(eta, W, F, r, d)
    from ..slowflow import frc
    Wd = np.linspace(W[0], W[-1], int(n_dense))
    dense = {**_frc_rows(frc(eta, Wd, F, r=r, d=d), Wd), "grid": Wd}
    ex, per_w, t_ex = map_solve_rows(eta, W, F, r, d)
    cont, t_cont = continuation_rows(eta, W, F, r, d, per_w, continuation_step)
    sim, t_sim = simulation_rows(eta, W, F, r, d, t_end, t_transient)
    err, nearest = errors(W.size, sf, ex)
    sf["nearest_error"] = nearest
    seconds = dict(zip(MODELS, (t_sf, t_ex, t_cont, t_sim), strict=True))
    return Ladder(eta=float(eta), F=float(F), omega=W, slowflow=sf, dense=dense, exact=ex,
                  continuation=cont, simulation=sim, error_max=err, seconds=seconds,
                  xi_min=xi_min)


#: most frequencies of one panel's grid and of its dense slow-flow curve
N_OMEGA_MAX = 100_000


def check_inputs(*, etas, f, sigma_range, n_omega, n_dense, continuation_step, t_end,
                 t_transient, r, d) -> list[tuple[float, float, np.ndarray]]:
    """The panels (eta, F = f eta, omega = 1 + sigma eta on n_omega points) of a ladder,
    every value through the validators of the models it feeds (the slow flow's own bounds:
    eta <= 0.5, d <= 0.5, r < 1); ParameterError naming the argument."""
    from ..core.params import (
        ParameterError,
        SolverSettings,
        check_int,
        check_param,
        check_real,
    )
    from ..slowflow.api import model
    if isinstance(etas, (str, bytes)) or not hasattr(etas, "__iter__") or not len(etas):
        raise ParameterError("etas", etas, "must be a non-empty list of mass ratios")
    try:
        s_lo, s_hi = sigma_range
    except (TypeError, ValueError):
        raise ParameterError("sigma_range", sigma_range, "must be [lo, hi]") from None
    s_lo = check_real("sigma_range", s_lo)
    s_hi = check_real("sigma_range", s_hi, lo=s_lo, lo_open=True)
    n = check_int("n_omega", n_omega, lo=2, hi=N_OMEGA_MAX)
    check_int("n_dense", n_dense, lo=2, hi=N_OMEGA_MAX)
    check_real("continuation_step", continuation_step, lo=1e-6, hi=1.0)
    f = check_real("f", f, lo=0.0, lo_open=True)
    SolverSettings(t_end=t_end, t_transient=t_transient)
    panels = []
    for eta in etas:
        m = model(eta, f * check_real("etas", eta, lo=0.0, lo_open=True), r, d)
        W = 1.0 + np.linspace(s_lo, s_hi, n) * m.eta
        for w in (W[0], W[-1]):
            try:
                check_param("omega", float(w))
            except ParameterError:
                raise ParameterError("sigma_range", [s_lo, s_hi], f"gives omega = {w:g} at "
                                     f"eta = {m.eta:g}: omega must be > 0") from None
        panels.append((m.eta, m.F, W))
    return panels
