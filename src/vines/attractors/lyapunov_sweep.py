"""The Lyapunov spectrum along a bifurcation sweep (``core.sweep``), point by point.

Each point of a sweep line starts from the state (and forcing phase) the previous point
ended in and runs for t_settle (first point) or t_step, plus the ``n_record`` recorded
periods. ``sweep_exponents`` walks the same chain of states as ``core.sweep.bifurcation_sweep``
(the same ``sweep_point`` calls, so the same numbers: the same ``phi`` per point) and, at each
point, computes the spectrum (``lyapunov.spectrum``) of the point's own run from its starting
state over the last ``t_window`` time units of that run, i.e. the motion the bifurcation
diagram draws (its recorded periods and the time before them). The tangent frame is aligned
during the part of the run before the window.

A finite-time answer: the exponent describes the window of each point, which may be a
transient (``census(..., t_max=...)`` says whether it is).
"""
from __future__ import annotations

import math

import numpy as np

from .. import progress
from ..core.params import (
    D_DEFAULT,
    PARAM_NAMES,
    R_DEFAULT,
    V_STICK_DEFAULT,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_real,
)
from .lyapunov import N_BATCHES_DEFAULT, spectrum

#: as ``core.sweep.bifurcation_sweep``: impact budget per forcing period of a point's run
MAX_IMPACTS_PER_PERIOD = 400


def _exponents_at(p: ModelParams, state, t_run: float, t_window: float, v_stick: float,
                  n_batches: int):
    st = SolverSettings(t_end=t_run, t_transient=t_run - t_window, v_stick=v_stick,
                        max_impacts=int(MAX_IMPACTS_PER_PERIOD * t_run / p.period) + 100,
                        state0=state)
    return spectrum(p, st, n_batches=n_batches)


def sweep_exponents(param, values, *, eta=None, omega=None, F=None, r=R_DEFAULT, d=D_DEFAULT,
                    t_settle=4000.0, t_step=1000.0, n_record=50, v_stick=V_STICK_DEFAULT,
                    periodic_shortcut=True, t_window=1000.0,
                    n_batches=N_BATCHES_DEFAULT) -> dict:
    """Spectrum at every value of one sweep line (``values`` in sweep order).

    Returns 1-D arrays over the values: value, phi (as the sweep's), regime, status,
    n_impacts, n_sticks (in the window), and exponents (n, 4) descending per unit
    dimensionless time (-inf: a direction removed by sticking), ci (n, 4, 2) 95 %
    batch-means intervals. ``t_window`` must not exceed min(t_settle, t_step) (every point's
    run is longer by the n_record periods: the frame is aligned before the window).
    """
    from ..core.sweep import sweep_point
    if param not in PARAM_NAMES:
        raise ParameterError("param", param, f"must be one of {', '.join(PARAM_NAMES)}")
    fixed = {"eta": eta, "omega": omega, "F": F}
    values = np.asarray(values, dtype=float).ravel()
    t_window = check_real("t_window", t_window, lo=0.0, lo_open=True, hi=min(t_settle, t_step))
    n = values.size
    out = {"value": values, "phi": np.zeros(n), "regime": np.empty(n, "U16"),
           "status": np.empty(n, "U16"), "n_impacts": np.zeros(n, "i8"),
           "n_sticks": np.zeros(n, "i8"), "exponents": np.full((n, 4), np.nan),
           "ci": np.full((n, 4, 2), np.nan)}
    state, theta = (0.0, 0.0, 0.0, 0.0), 0.0
    for k, val in enumerate(progress.track(values, n, "lyapunov sweep", "points")):
        kw = {**fixed, param: val}
        p = ModelParams(eta=kw["eta"], omega=kw["omega"], F=kw["F"], r=r, d=d,
                        phi=math.fmod(theta, 2.0 * math.pi))
        t_run = (t_settle if k == 0 else t_step) + n_record * p.period
        res = _exponents_at(p, state, t_run, t_window, v_stick, n_batches)
        _, _, state, theta = sweep_point(p, state, t_run, n_record, v_stick,
                                         MAX_IMPACTS_PER_PERIOD, periodic_shortcut)
        out["phi"][k] = p.phi
        out["regime"][k], out["status"][k] = res.regime, res.status
        out["n_impacts"][k], out["n_sticks"][k] = res.n_impacts, res.n_sticks
        out["exponents"][k], out["ci"][k] = res.exponents, res.ci
    return out
