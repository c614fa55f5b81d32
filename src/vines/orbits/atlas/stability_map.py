"""|lambda_max| of the 1:1 orbit over an (eta, omega) grid (paper Fig. 16).

At every grid point the candidates are: the closed-form symmetric orbits, the asymmetric
orbits of the flight-time scan (``vines.periodic``), and the admissible orbits of the
previous eta point of the same omega column, continued by Newton (secant predictor when two
previous points are available). Candidates are deduplicated in that order (the first of
equal orbits is kept). Among the admissible candidates a stable one is preferred, then a
symmetric one, then the smallest |lambda_max| (the first of equals).

Columns (one omega each) are independent and processed in order of increasing eta index,
so the result does not depend on how the columns are spread over threads.

Design: a whole column is one call of the compiled ``_column_kernel`` (numba, nogil), so
the columns run truly in parallel on the threads of a ThreadPoolExecutor (inside a
Snakemake job: ``n_threads`` = the job's threads). Orbits are rows of a float array
(``periodic.ROW_*`` columns, then this module's ``ROW_SRC*``: the orbit a continued one
came from). The kernel repeats the arithmetic of the Python solvers (``seed_orbits``,
``solve_orbit``), so it returns the same bits as ``stability_map_python``, the Python
version kept as the reference (tests), given the same monodromy product and eigenvalues:
the kernel takes numba's np.dot and scipy's dgeev, the Python solvers numpy's (the two agree
to round-off, bit for bit where numpy and scipy ship the same BLAS/LAPACK). Admissibility
and eigenvalues are only computed for orbits that survive deduplication, and eigenvalues
only for admissible ones (the only ones the map uses).
"""
from __future__ import annotations

import math
import os
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from numpy.typing import ArrayLike

from ..._jit import njit
from ...core.exact import oscillators
from ...core.flow import I_W, make_osc
from ...core.params import (
    D_DEFAULT,
    MAX_GAIN,
    R_DEFAULT,
    ModelParams,
    ParameterError,
    as_float_array,
    check_callable,
    check_conditioning,
    check_int,
)
from ..family.periodic import (
    N_ROW,
    N_SEED_MAX,
    ROW_ADM,
    ROW_DWL,
    ROW_FL,
    ROW_LAM,
    ROW_SYM,
    ROW_X,
    orbit_classify,
    orbit_solve,
    orbit_workspace,
    seed_kernel,
    seed_orbits,
    solve_orbit,
)
from ..maps.impact import M_ETA, pack_model

CLS_NONE, CLS_SYM_STABLE, CLS_ASYM_STABLE, CLS_UNSTABLE = 0, 1, 2, 3

# Row columns after periodic's: the orbit this one was continued from (the secant's
# second point): flag, its eta, x_L and flight times.
ROW_SRC, ROW_SRC_ETA, ROW_SRC_X, ROW_SRC_FL = N_ROW, N_ROW + 1, N_ROW + 2, N_ROW + 6
N_COL = N_ROW + 8


# --------------------------------------------------------------------------- compiled driver

@njit(cache=True, nogil=True)
def _continue(mdl, e_prev, prv, row, ws):
    """Newton from the orbit prv of the previous eta (secant predictor when prv was itself
    continued, unless t_L wrapped); fills row's x_L, flight times and source (not yet
    classified). False when Newton fails. mdl: ``maps.pack_model`` at this eta."""
    eta = mdl[M_ETA]
    T = 2.0 * math.pi / mdl[I_W]
    x0 = ws[0]
    for k in range(4):
        x0[k] = prv[ROW_X + k]
    f0, f1 = prv[ROW_FL], prv[ROW_FL + 1]
    if prv[ROW_SRC] > 0.0 and e_prev != prv[ROW_SRC_ETA]:
        f = (eta - e_prev) / (e_prev - prv[ROW_SRC_ETA])
        if abs(prv[ROW_X + 3] - prv[ROW_SRC_X + 3]) < 0.25 * T:
            for k in range(4):
                x0[k] = prv[ROW_X + k] + f * (prv[ROW_X + k] - prv[ROW_SRC_X + k])
            f0 = prv[ROW_FL] + f * (prv[ROW_FL] - prv[ROW_SRC_FL])
            f1 = prv[ROW_FL + 1] + f * (prv[ROW_FL + 1] - prv[ROW_SRC_FL + 1])
    if not math.isfinite(orbit_solve(mdl, (f0, f1), row, ws)):
        return False
    row[ROW_SRC] = 1.0
    row[ROW_SRC_ETA] = e_prev
    for k in range(4):
        row[ROW_SRC_X + k] = prv[ROW_X + k]
    row[ROW_SRC_FL] = prv[ROW_FL]
    row[ROW_SRC_FL + 1] = prv[ROW_FL + 1]
    return True


@njit(cache=True, nogil=True)
def _is_new(rows, n, T):
    """rows[n] is no orbit of rows[:n] for the map's deduplication (same t_L mod T to
    1e-8 (1 + T) and velocities/position to 1e-8 absolute)."""
    a = rows[n]
    for q in range(n):
        b = rows[q]
        dt = abs(a[ROW_X + 3] - b[ROW_X + 3]) % T
        dt = min(dt, T - dt)
        if dt <= 1e-8 * (1.0 + T) and abs(a[ROW_X] - b[ROW_X]) <= 1e-8 \
                and abs(a[ROW_X + 1] - b[ROW_X + 1]) <= 1e-8 \
                and abs(a[ROW_X + 2] - b[ROW_X + 2]) <= 1e-8:
            return False
    return True


@njit(cache=True, nogil=True)
def _pick(rows, n):
    """Index of the admissible orbit with the smallest (not stable, not symmetric,
    lambda_max), the first of equals; -1 when none is admissible."""
    best = -1
    kb0, kb1, kb2 = 2, 2, math.inf
    for k in range(n):
        if rows[k, ROW_ADM] == 0.0:
            continue
        lam = rows[k, ROW_LAM]
        k0 = 0 if lam < 1.0 else 1
        k1 = 0 if rows[k, ROW_SYM] > 0.0 else 1
        if best < 0 or (k0, k1, lam) < (kb0, kb1, kb2):
            best, kb0, kb1, kb2 = k, k0, k1, lam
    return best


@njit(cache=True, nogil=True)
def _point(mdl, e_prev, prev, rows, ws):
    """Candidates of one grid point (mdl) into rows[:n]: seeds, then the continued orbits of
    prev that are new (``_is_new``, seeds first: the old list order); returns n."""
    T = 2.0 * math.pi / mdl[I_W]
    n = seed_kernel(mdl, rows, ws)
    for k in range(prev.shape[0]):
        if _continue(mdl, e_prev, prev[k], rows[n], ws) and _is_new(rows, n, T):
            orbit_classify(mdl, rows[n], ws)
            n += 1
    return n


@njit(cache=True, nogil=True)
def _column_kernel(etas, mdl, out, j):
    """Column j (one omega: mdl, ``maps.pack_model`` of phi = 0, its eta overwritten) of the
    map, eta in the given order (module docstring); writes [:, j] of the arrays out =
    (lambda_max, cls, dw_L, symmetric). Runs without the GIL."""
    lam_out, cls_out, dw_out, sym_out = out
    ws = orbit_workspace()
    prev = np.empty((0, N_COL))
    rows = np.zeros((N_SEED_MAX + 8, N_COL))
    for i in range(etas.size):
        if rows.shape[0] < N_SEED_MAX + prev.shape[0]:
            rows = np.zeros((N_SEED_MAX + 2 * prev.shape[0], N_COL))
        rows[:, ROW_SRC] = 0.0
        mdl[M_ETA] = etas[i]
        n = _point(mdl, etas[i - 1] if i > 0 else math.nan, prev, rows, ws)
        b = _pick(rows, n)
        if b < 0:
            lam_out[i, j] = math.nan
            cls_out[i, j] = CLS_NONE
            dw_out[i, j] = math.nan
            sym_out[i, j] = False
        else:
            lam = rows[b, ROW_LAM]
            sym = rows[b, ROW_SYM] > 0.0
            lam_out[i, j] = lam
            cls_out[i, j] = (CLS_UNSTABLE if not lam < 1.0 else
                             CLS_SYM_STABLE if sym else CLS_ASYM_STABLE)
            dw_out[i, j] = rows[b, ROW_DWL]
            sym_out[i, j] = sym
        n_adm = 0
        for k in range(n):
            n_adm += rows[k, ROW_ADM] > 0.0
        prev = np.empty((n_adm, N_COL))
        m = 0
        for k in range(n):
            if rows[k, ROW_ADM] > 0.0:
                prev[m, :] = rows[k, :]
                m += 1


# --------------------------------------------------------------------------- Python reference

def _pick_py(orbits):
    adm = [o for o in orbits if o.admissible]
    if not adm:
        return None
    adm.sort(key=lambda o: (not o.stable, not o.symmetric, o.lambda_max))
    return adm[0]


def _column_py(etas, omega, F, r, d, out, j):
    """The algorithm of ``_column_kernel`` on PeriodicOrbits (slow reference for tests)."""
    prev = []          # admissible orbits at the previous eta: list of (eta, orbit)
    prev2 = {}         # id(orbit) -> orbit at the eta before (for the secant predictor)
    for i, eta in enumerate(etas):
        p = ModelParams(eta=eta, omega=omega, F=F, r=r, d=d)
        osc = oscillators(p)[0]
        cands = seed_orbits(p, osc, simulation=False)
        new_prev2 = {}
        for e_prev, o_prev in prev:
            x = o_prev.x_L.copy()
            fl = list(o_prev.flight_times)
            older = prev2.get(id(o_prev))
            if older is not None:
                e_old, o_old = older
                if e_prev != e_old:
                    f = (eta - e_prev) / (e_prev - e_old)
                    dx = o_prev.x_L - o_old.x_L
                    if abs(dx[3]) < 0.25 * p.period:
                        x = x + f * dx
                        fl = [a + f * (a - b) for a, b in zip(o_prev.flight_times,
                                                              o_old.flight_times, strict=False)]
            o = solve_orbit(p, x, fl[0], fl[1], osc)
            if o is not None:
                cands.append(o)
                new_prev2[id(o)] = (e_prev, o_prev)
        uniq = []
        for o in cands:
            if not any(_close_py(o, q, p.period) for q in uniq):
                uniq.append(o)
        best = _pick_py(uniq)
        if best is not None:
            out["lambda_max"][i, j] = best.lambda_max
            out["cls"][i, j] = (CLS_UNSTABLE if not best.stable else
                                CLS_SYM_STABLE if best.symmetric else CLS_ASYM_STABLE)
            out["dw_L"][i, j] = best.dw_L
            out["symmetric"][i, j] = best.symmetric
        adm = [o for o in uniq if o.admissible]
        prev = [(eta, o) for o in adm]
        prev2 = {id(o): new_prev2[id(o)] for o in adm if id(o) in new_prev2}


def _close_py(a, b, T):
    dt = abs(a.x_L[3] - b.x_L[3]) % T
    dt = min(dt, T - dt)
    return dt <= 1e-8 * (1.0 + T) and np.all(np.abs(a.x_L[:3] - b.x_L[:3]) <= 1e-8)


def stability_map_python(eta: ArrayLike, omega: ArrayLike, F: float, r: float = R_DEFAULT,
                         d: float = D_DEFAULT) -> dict:
    """``stability_map`` by the Python orbit solvers, one thread (slow reference)."""
    etas, omegas, F, r, d, out = _setup(eta, omega, F, r, d)
    for j in range(omegas.size):
        _column_py(etas, float(omegas[j]), F, r, d, out, j)
    out.update(eta=etas, omega=omegas, F=F)
    return out


# --------------------------------------------------------------------------- API

def _setup(eta, omega, F, r, d):
    """Validated axes and parameters (as floats) and the NaN/zero-filled output arrays."""
    etas = np.atleast_1d(as_float_array("eta", eta))
    omegas = np.atleast_1d(as_float_array("omega", omega))
    if etas.ndim != 1 or omegas.ndim != 1:
        raise ParameterError("eta/omega", None, "must be 1-D arrays")
    for e in etas:
        ModelParams(eta=e, omega=1.0, F=0.0)
    for w in omegas:
        ModelParams(eta=1.0, omega=w, F=0.0)
    p = ModelParams(eta=1.0, omega=1.0, F=F, r=r, d=d)
    _check_conditioning(etas, omegas, p.F, p.d)
    shape = (etas.size, omegas.size)
    out = {"lambda_max": np.full(shape, math.nan), "cls": np.zeros(shape, np.int8),
           "dw_L": np.full(shape, math.nan), "symmetric": np.zeros(shape, bool)}
    return etas, omegas, p.F, p.r, p.d, out


def _check_conditioning(etas, omegas, F, d):
    """``check_conditioning`` at every grid point (vectorised screen, then the exact check
    at the few points near the limit, column by column)."""
    if F == 0.0 or d == 0.0 or etas.size == 0 or omegas.size == 0:
        return
    m = np.concatenate([[1.0], 1.0 + etas])[:, None]
    gain = 1.0 / np.hypot(1.0 - m * omegas * omegas, d * omegas)
    near = np.any(gain > MAX_GAIN * (1.0 - 1e-9), axis=0)
    for j in np.nonzero(near)[0]:
        for e in etas:
            check_conditioning(float(e), float(omegas[j]), F, d)


def stability_map(eta: ArrayLike, omega: ArrayLike, F: float, r: float = R_DEFAULT,
                  d: float = D_DEFAULT, n_threads: int | None = None,
                  progress: Callable[[int, int], None] | None = None) -> dict:
    """2-D arrays of shape (len(eta), len(omega)).

    lambda_max  |lambda_max| of the chosen admissible 1:1 orbit (nan: none)
    cls         int8: 0 no admissible 1:1, 1 symmetric stable, 2 asymmetric stable, 3 unstable
    dw_L        relative velocity before the L impact of the chosen orbit
    symmetric   bool
    Also returns the axes ``eta``, ``omega`` and ``F``. ``n_threads`` (default: all cores)
    columns are computed at once (compiled, without the GIL); the arrays do not depend on
    it. ``progress(done, total)`` is called after every column.
    """
    etas, omegas, F, r, d, out = _setup(eta, omega, F, r, d)
    progress = check_callable("progress", progress)
    n_threads = check_int("n_threads", n_threads if n_threads is not None
                          else (os.cpu_count() or 1), lo=1)
    arrays = (out["lambda_max"], out["cls"], out["dw_L"], out["symmetric"])

    def work(j):
        w = float(omegas[j])
        _column_kernel(etas, pack_model(make_osc(1.0, d, w, F), math.nan, r, 0.0), arrays, j)
        return j

    if n_threads == 1 or omegas.size <= 1:
        for done, j in enumerate(range(omegas.size), 1):
            work(j)
            if progress:
                progress(done, omegas.size)
    else:
        with ThreadPoolExecutor(max_workers=n_threads) as ex:
            for done, _ in enumerate(ex.map(work, range(omegas.size)), 1):
                if progress:
                    progress(done, omegas.size)
    out.update(eta=etas, omega=omegas, F=F)
    return out
