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

import numpy as np

from .. import progress
from ..core.params import ModelParams, SolverSettings, check_real
from ..core.sweep import SweepLine
from .lyapunov import N_BATCHES_DEFAULT, spectrum


def _exponents_at(line: SweepLine, p: ModelParams, state, t_run: float, t_window: float,
                  n_batches: int):
    st = SolverSettings(t_end=t_run, t_transient=t_run - t_window, v_stick=line.v_stick,
                        max_impacts=int(line.max_impacts_per_period * t_run / p.period) + 100,
                        state0=state)
    return spectrum(p, st, n_batches=n_batches)


def sweep_exponents(line: SweepLine, *, t_window: float = 1000.0,
                    n_batches: int = N_BATCHES_DEFAULT) -> dict:
    """Spectrum at every value of one sweep line (``line.values`` in sweep order; each
    point's run and impact budget as in ``core.sweep.bifurcation_sweep``).

    Returns 1-D arrays over the values: value, phi (as the sweep's), regime, status,
    n_impacts, n_sticks (in the window), and exponents (n, 4) descending per unit
    dimensionless time (-inf: a direction removed by sticking), ci (n, 4, 2) 95 %
    batch-means intervals. ``t_window`` must not exceed min(t_settle, t_step) (every point's
    run is longer by the n_record periods: the frame is aligned before the window).
    """
    values = line.values
    t_window = check_real("t_window", t_window, lo=0.0, lo_open=True,
                          hi=min(line.t_settle, line.t_step))
    n = values.size
    out = {"value": values, "phi": np.zeros(n), "regime": np.empty(n, "U16"),
           "status": np.empty(n, "U16"), "n_impacts": np.zeros(n, "i8"),
           "n_sticks": np.zeros(n, "i8"), "exponents": np.full((n, 4), np.nan),
           "ci": np.full((n, 4, 2), np.nan)}
    state, theta = (0.0, 0.0, 0.0, 0.0), 0.0
    for k in progress.track(range(n), n, "lyapunov sweep", "points"):
        p = line.point(k, theta)
        res = _exponents_at(line, p, state, line.t_run(k, p), t_window, n_batches)
        _, _, state, theta = line.run_point(k, p, state)
        out["phi"][k] = p.phi
        out["regime"][k], out["status"][k] = res.regime, res.status
        out["n_impacts"][k], out["n_sticks"][k] = res.n_impacts, res.n_sticks
        out["exponents"][k], out["ci"][k] = res.exponents, res.ci
    return out
