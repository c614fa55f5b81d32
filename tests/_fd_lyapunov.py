"""Finite-difference Lyapunov exponents: Benettin's method on perturbed trajectories of the
exact solver, independent of the saltation matrices of ``core.variational``.

k neighbours at distance ``delta`` along an orthonormal frame are integrated next to the
trajectory (the exact solver's flow map, ``flow_map``); after each forcing period the
differences are re-orthonormalised by QR and log |R_ii| accumulated. An interval in which
a neighbour crosses a different number of walls than the trajectory, and is not within
1e3 delta of it (an impact one of them has not had yet), is extended by T/8 until they
agree: a difference across an impact the other has not had is not linear in delta.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.stats import t as student_t

from vines.core.exact import KernelRun, Span, oscillators
from vines.core.params import ModelParams, SolverSettings


def flow_map(p, oscs, x0, t0, t1):
    """State of the exact trajectory at t1 from x0 at t0 (free flight at t0), and the number
    of impacts on the way."""
    run = KernelRun(p, SolverSettings(t_end=t1, t_transient=t0), oscs, np.asarray(x0, float),
                    t0, Span(t1, t0, t0), 0)
    run.run()
    return run.cur[1:5].copy(), int(run.cnt[0])


def _step(p, oscs, x, frame, delta, t, t_stop):
    """The trajectory and its neighbours from t over one forcing period (or longer, see the
    module docstring): (end time, end state, difference matrix / delta)."""
    t1 = min(t + p.period, t_stop)
    while True:
        xa, na = flow_map(p, oscs, x, t, t1)
        ends = [flow_map(p, oscs, x + delta * frame[:, i], t, t1) for i in range(frame.shape[1])]
        diffs = np.column_stack([(ya - xa) / delta for ya, _ in ends])
        linear = all(nb == na or np.linalg.norm(d) <= 1e3 for (_, nb), d in zip(ends, diffs.T,
                                                                            strict=True))
        if linear or t1 >= t_stop:
            return t1, xa, diffs
        t1 = min(t1 + p.period / 8.0, t_stop)


def benettin(p: ModelParams, x0, t_start: float, t_stop: float, *, k: int = 2,
             delta: float = 1e-9, n_batches: int = 10, t0: float = 0.0):
    """The k leading exponents over [t_start, t_stop] of the trajectory from x0 at t0
    (the frame is aligned over [t0, t_start]). Returns (mean (k,), 95 % batch-means
    half-widths (k,)), per unit dimensionless time."""
    oscs = oscillators(p)
    frame, _ = np.linalg.qr(np.array([[1.0, -0.5, 0.3, 0.7], [0.2, 0.9, -0.4, 0.1],
                                      [-0.3, 0.2, 0.8, 0.5], [0.6, 0.1, 0.2, -0.9]]).T[:, :k])
    edges = np.linspace(t_start, t_stop, n_batches + 1)
    logs = np.zeros((n_batches, k))
    x, t = np.asarray(x0, float), t0
    while t < t_stop - 1e-9:
        t1, x, diffs = _step(p, oscs, x, frame, delta, t, t_stop)
        q, r = np.linalg.qr(diffs)
        if t1 > t_start:                     # an interval across t_start counts whole
            b = min(np.searchsorted(edges, t1, side="left") - 1, n_batches - 1)
            logs[b] += np.log(np.abs(np.diag(r)))
        frame, t = q * np.sign(np.diag(r)), t1
    batch = logs / np.diff(edges)[:, None]
    half = student_t.ppf(0.975, n_batches - 1) * batch.std(axis=0, ddof=1) / math.sqrt(n_batches)
    return batch.mean(axis=0), half
