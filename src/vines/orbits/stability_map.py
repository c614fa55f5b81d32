"""|lambda_max| of the 1:1 orbit over an (eta, omega) grid (paper Fig. 16).

At every grid point the candidates are: the closed-form symmetric orbits, the asymmetric
orbits of the flight-time scan (``vines.periodic``), and the admissible orbits of the
previous eta point of the same omega column, continued by Newton (secant predictor when two
previous points are available). Among the admissible candidates a stable one is preferred,
then a symmetric one, then the smallest |lambda_max|.

Columns (one omega each) are independent and processed in order of increasing eta index,
so the result does not depend on how the columns are spread over threads.
"""
from __future__ import annotations

import math
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from ..core.exact import oscillators
from ..core.params import D_DEFAULT, R_DEFAULT, ModelParams, ParameterError, check_int
from .periodic import seed_orbits, solve_orbit

CLS_NONE, CLS_SYM_STABLE, CLS_ASYM_STABLE, CLS_UNSTABLE = 0, 1, 2, 3


def _pick(orbits):
    adm = [o for o in orbits if o.admissible]
    if not adm:
        return None
    adm.sort(key=lambda o: (not o.stable, not o.symmetric, o.lambda_max))
    return adm[0]


def _column(etas, omega, F, r, d, out, j):
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
                                                              o_old.flight_times)]
            o = solve_orbit(p, x, fl[0], fl[1], osc)
            if o is not None:
                cands.append(o)
                new_prev2[id(o)] = (e_prev, o_prev)
        # deduplicate against the seeds
        uniq = []
        for o in cands:
            if not any(_close(o, q, p.period) for q in uniq):
                uniq.append(o)
        best = _pick(uniq)
        if best is None:
            out["lambda_max"][i, j] = math.nan
            out["cls"][i, j] = CLS_NONE
            out["dw_L"][i, j] = math.nan
            out["symmetric"][i, j] = False
        else:
            out["lambda_max"][i, j] = best.lambda_max
            out["cls"][i, j] = (CLS_UNSTABLE if not best.stable else
                                CLS_SYM_STABLE if best.symmetric else CLS_ASYM_STABLE)
            out["dw_L"][i, j] = best.dw_L
            out["symmetric"][i, j] = best.symmetric
        adm = [o for o in uniq if o.admissible]
        prev = [(eta, o) for o in adm]
        prev2 = {id(o): new_prev2[id(o)] for o in adm if id(o) in new_prev2}


def _close(a, b, T):
    dt = abs(a.x_L[3] - b.x_L[3]) % T
    dt = min(dt, T - dt)
    return dt <= 1e-8 * (1.0 + T) and np.all(np.abs(a.x_L[:3] - b.x_L[:3]) <= 1e-8)


def stability_map(eta, omega, F, r=R_DEFAULT, d=D_DEFAULT, n_threads=None,
                  progress=None) -> dict:
    """2-D arrays of shape (len(eta), len(omega)).

    lambda_max  |lambda_max| of the chosen admissible 1:1 orbit (nan: none)
    cls         int8: 0 no admissible 1:1, 1 symmetric stable, 2 asymmetric stable, 3 unstable
    dw_L        relative velocity before the L impact of the chosen orbit
    symmetric   bool
    Also returns the axes ``eta``, ``omega`` and ``F``.
    """
    etas = np.atleast_1d(np.asarray(eta, dtype=float))
    omegas = np.atleast_1d(np.asarray(omega, dtype=float))
    if etas.ndim != 1 or omegas.ndim != 1:
        raise ParameterError("eta/omega", None, "must be 1-D arrays")
    for e in etas:
        ModelParams(eta=e, omega=1.0, F=0.0)
    for w in omegas:
        ModelParams(eta=1.0, omega=w, F=0.0)
    ModelParams(eta=1.0, omega=1.0, F=F, r=r, d=d)
    n_threads = check_int("n_threads", n_threads if n_threads is not None
                          else (os.cpu_count() or 1), lo=1)
    shape = (etas.size, omegas.size)
    out = {"lambda_max": np.full(shape, math.nan), "cls": np.zeros(shape, np.int8),
           "dw_L": np.full(shape, math.nan), "symmetric": np.zeros(shape, bool)}

    def work(j):
        _column(etas, float(omegas[j]), float(F), r, d, out, j)
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
    out.update(eta=etas, omega=omegas, F=float(F))
    return out
