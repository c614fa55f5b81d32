"""Quasi-periodic motion: do the strobe points of a lasting motion fill a closed curve?

A motion on a 2-torus (two incommensurate frequencies: the forcing and a modulation, e.g.
the strongly modulated response of a light absorber) has its states at t = k T (the
forcing period; the stroboscopic section) on a closed invariant curve, on which the
section map acts like an irrational rotation: for every lag q, x_(k+q) - x_k is small for
*all* k once q times the rotation number is close to an integer (Dirichlet: some q <= N/2
brings it within 2/N). Chaotic motion has no such lag (neighbouring states separate), and a
periodic orbit returns exactly.

``closed_curve`` applies that test to N strobe points: each coordinate scaled by its range
over the points (a coordinate without spread dropped), the return error of lag q is
e(q) = max_k max_j |y_(k+q), j - y_k, j| (k < N - q), the return lag q* minimises it over
1 <= q <= N/2, and the points fill a closed curve when RETURN_FLOOR < e(q*) <= RETURN_TOL
(at or below RETURN_FLOOR they repeat: a periodic orbit, not a curve, and q* is the
smallest such lag, its period). q* T is the lag of the best return: for a modulated
motion a period of the modulation or a multiple of it.

``envelope``: the LO amplitude max |z_m| over each forcing period (units of L), from
ENV_SAMPLES samples per period (a smooth maximum is missed by at most
(pi / ENV_SAMPLES)^2 / 2 of it, 0.12 %); its min and max are the modulation range, and the
mean time between its upward crossings of its mid level the modulation period.

``modulation`` runs a motion's state at t_end on to t_max (the census's continuation) and
applies both over its strobe window, the last min(N_STROBE, half of [t_end, t_max])
forcing periods, with the leading Lyapunov exponent over that window (the tangent frame
carried from t_end, aligned by the first half); ``asymptotic.is_quasi_periodic`` reads it.
"""
from __future__ import annotations

import math

import numpy as np

from ..core.params import ModelParams, SolverSettings

#: strobe points tested (the last ones up to t_max); fewer when [t_end, t_max] is shorter
N_STROBE = 4096
#: fewest strobe points the test accepts (fewer: no verdict)
N_STROBE_MIN = 256
#: a closed curve returns to within this share of its range in every coordinate
RETURN_TOL = 0.1
#: a return closer than this (share of the range) is an exact repeat: a periodic orbit
RETURN_FLOOR = 1e-6
#: samples per forcing period of the LO amplitude envelope
ENV_SAMPLES = 64


def return_errors(points: np.ndarray) -> np.ndarray:
    """e(q) for q = 1 ... N // 2 (index q - 1) of the strobe points (N, 4) (module
    docstring); all zeros when no coordinate has any spread."""
    x = np.asarray(points, float)
    span = x.max(axis=0) - x.min(axis=0)
    keep = span > 0.0
    out = np.zeros(x.shape[0] // 2)
    if not keep.any():
        return out
    y = (x[:, keep] - x[:, keep].min(axis=0)) / span[keep]
    for q in range(1, out.size + 1):
        out[q - 1] = np.abs(y[q:] - y[:-q]).max()
    return out


def closed_curve(points: np.ndarray) -> dict:
    """Whether the strobe points (N, 4) fill a closed curve: ``closed`` (bool, None when
    N < N_STROBE_MIN), the return lag ``lag`` (forcing periods) and its error
    ``return_error`` (share of the range), ``periodic`` (an exact repeat)."""
    n = int(np.shape(points)[0])
    if n < N_STROBE_MIN:
        return {"closed": None, "lag": None, "return_error": None, "periodic": False,
                "n_strobe": n}
    e = return_errors(points)
    periodic = bool(e.min() <= RETURN_FLOOR)
    q = int(np.argmax(e <= RETURN_FLOOR) if periodic else np.argmin(e)) + 1
    err = float(e[q - 1])
    return {"closed": bool(not periodic and err <= RETURN_TOL), "lag": q,
            "return_error": err, "periodic": bool(periodic), "n_strobe": n}


def envelope(raw, T: float, k0: int, k1: int) -> np.ndarray:
    """max |z_m| over each forcing period [k T, (k + 1) T], k0 <= k < k1, of a run ``raw``
    whose records cover [k0 T, k1 T] (ENV_SAMPLES samples per period)."""
    s = np.arange(ENV_SAMPLES + 1) / ENV_SAMPLES
    t = ((np.arange(k0, k1)[:, None] + s[None, :]) * T).ravel()
    t = np.minimum(t, raw.t_last)
    z = raw.state_at(t)[0].reshape(k1 - k0, ENV_SAMPLES + 1)
    return np.abs(z).max(axis=1)


def modulation_period(env: np.ndarray) -> float:
    """Mean number of forcing periods between upward crossings of the envelope's mid
    level (NaN with fewer than two crossings)."""
    mid = 0.5 * (env.min() + env.max())
    up = np.flatnonzero((env[:-1] < mid) & (env[1:] >= mid))
    return float(np.diff(up).mean()) if up.size >= 2 else math.nan


def strobe_window(T: float, t_end: float, t_max: float, n: int = N_STROBE) -> tuple:
    """(k0, k1): the periods k0 <= k < k1 tested, the last min(n, half of [t_end, t_max])
    before t_max (the first half at least aligns the Lyapunov frame)."""
    k1 = math.floor(t_max / T)
    return k1 - max(0, min(n, (k1 - math.ceil(t_end / T)) // 2)), k1


def modulation(p: ModelParams, st: SolverSettings, t_max: float, state: np.ndarray,
               n: int = N_STROBE) -> dict:
    """The closed-curve test of the continuation of ``state`` (a motion's state at
    st.t_end) over its strobe window [k0 T, k1 T] (``strobe_window``): ``closed_curve``'s
    keys, the LO amplitude envelope's range ``amplitude`` [min, max] (units of L) and
    ``period`` (forcing periods), the leading Lyapunov exponent over the window
    ``lambda_1`` and its 95 % interval ``lambda_1_ci`` (the frame carried from st.t_end),
    and ``window`` [k0 T, k1 T]."""
    from ..core.exact import run_exact
    from .asymptotic import asymptotic_settings
    from .lyapunov import spectrum
    T = p.period
    k0, k1 = strobe_window(T, st.t_end, t_max, n)
    out = {"amplitude": None, "period": None, "lambda_1": None, "lambda_1_ci": None,
           "window": [k0 * T, k1 * T]}
    st_w = asymptotic_settings(st, t_max, k0 * T)
    raw = run_exact(p, st_w, record_from=st.t_end, state0=tuple(state), t0=st.t_end)
    if raw.status != "ok" or k1 - k0 < N_STROBE_MIN:
        return closed_curve(np.zeros((0, 4))) | out
    env = envelope(raw, T, k0, k1)
    lyap = spectrum(p, st_w, tuple(state), t0=st.t_end, with_regime=False)
    return closed_curve(raw.state_at(np.arange(k0, k1) * T).T) | out | {
        "amplitude": [float(env.min()), float(env.max())], "period": modulation_period(env),
        "lambda_1": float(lyap.exponents[0]),
        "lambda_1_ci": [float(lyap.ci[0][0]), float(lyap.ci[0][1])]}
