"""Lyapunov spectra of the VINES by saltation matrices (Benettin re-orthonormalisation).

The trajectory is the exact solver's (``core.exact``: the same numbers as ``simulate``
without the periodic shortcut); the tangent dynamics along it are exact too
(``core.variational``: closed-form state-transition matrices between events, saltation
matrices at impacts and sticks). An orthonormal frame of four tangent vectors is carried
from t = 0 and re-orthonormalised by QR after every segment; log |R_ii| summed over the
window [t_transient, t_end] and divided by its length gives the exponents, per unit
dimensionless time, in descending order (the frame is aligned during the transient).

Confidence intervals: the window is cut into ``n_batches`` equal batches; each batch gives
an estimate of the spectrum, and the 95 % interval is the Student t interval of their mean
(batch means). It measures the finite-time fluctuation, not a bias that decays with the
window (e.g. the log(t)/t of the ball's free drift when nothing hits it).

Sticking removes two dimensions: a stick maps a neighbourhood onto the 2-D stuck manifold
{w = wall, w' = 0} in finite time, so the linearised flow over any stretch containing a
stick has rank 2. Only two tangent vectors are carried from a stick to the release; the
window's lambda_3 and lambda_4 are then -inf (null in JSON) and lambda_1, lambda_2 are the
exponents of the two directions that survive. ``n_sticks`` says how many sticks the window
had.

The spectrum is a finite-time answer: it describes the motion in the window, which may be
a transient (``vines.attractors.census`` with ``t_max`` says whether it is).
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from .. import progress
from ..core.params import (
    D_DEFAULT,
    MAX_IMPACTS_DEFAULT,
    R_DEFAULT,
    ROOT_TOL_DEFAULT,
    T_END_DEFAULT,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_int,
)

#: batches of the window for the batch-means confidence intervals
N_BATCHES_DEFAULT = 16
CI_LEVEL = 0.95


@dataclass
class LyapunovResult:
    """Lyapunov spectrum over the window [t_transient, t_end].

    ::

        exponents   the four exponents, descending, per unit dimensionless time (-inf: a
                    direction removed by sticking)
        ci          (4, 2) 95 % batch-means intervals
        regime      regime label of the window (``core.regime``, as ``simulate`` reports it)
        n_impacts   impacts in the window; n_sticks: stick starts in the window
        status      "ok" or why the run stopped early (then the window is incomplete)
    """

    exponents: np.ndarray
    ci: np.ndarray
    regime: str
    period: int
    n_impacts: int
    n_sticks: int
    status: str
    n_batches: int
    params: ModelParams
    settings: SolverSettings
    batch_exponents: np.ndarray = field(repr=False, default=None)

    @property
    def lambda_max(self) -> float:
        return float(self.exponents[0])

    def to_dict(self) -> dict:
        """JSON-ready: exponents, ci, regime, period, n_impacts, n_sticks, status,
        n_batches, ci_method, params, settings (-inf becomes null in the CLI's JSON)."""
        return {"exponents": [float(v) for v in self.exponents],
                "ci": [[float(a), float(b)] for a, b in self.ci],
                "regime": self.regime, "period": int(self.period),
                "n_impacts": int(self.n_impacts), "n_sticks": int(self.n_sticks),
                "status": self.status, "n_batches": int(self.n_batches),
                "ci_method": f"batch means, {self.n_batches} batches, Student t "
                             f"{CI_LEVEL:.0%}",
                "params": self.params.as_dict(), "settings": self.settings.as_dict()}


def batch_ci(batch: np.ndarray, level: float = CI_LEVEL) -> np.ndarray:
    """(k, 2) Student t intervals of the mean of the rows of ``batch`` (nb, k); a column
    holding -inf gives [-inf, -inf]."""
    from scipy.stats import t as student_t
    nb = batch.shape[0]
    out = np.empty((batch.shape[1], 2))
    q = student_t.ppf(0.5 + 0.5 * level, nb - 1) if nb > 1 else math.inf
    for j in range(batch.shape[1]):
        col = batch[:, j]
        if np.any(np.isneginf(col)):
            out[j] = -math.inf
            continue
        half = q * col.std(ddof=1) / math.sqrt(nb) if nb > 1 else math.inf
        out[j] = col.mean() - half, col.mean() + half
    return out


class _WindowRecord:
    """What ``core.regime.classify`` needs from the window, collected chunk by chunk."""

    def __init__(self, p: ModelParams, st: SolverSettings, oscs):
        from ..core.regime import strobe_times
        self.p, self.st, self.oscs = p, st, oscs
        self.ts = strobe_times(p.period, st.t_transient, st.t_end)
        self.strobe = np.full((4, self.ts.size), np.nan)
        self.walls, self.times = [], []

    def on_chunk(self, seg, n_done, t_done):
        """Strobe states at the section times inside the completed segments seg[:n_done]
        (valid up to t_done)."""
        from ..core import kernel as eng
        t_lo = seg[0, 0]
        sel = np.flatnonzero((self.ts >= t_lo) & (self.ts <= t_done))
        if sel.size:
            times = np.ascontiguousarray(self.ts[sel])
            idx = (np.searchsorted(seg[:n_done, 0], times, side="right") - 1).astype(np.int64)
            out = np.empty((4, times.size))
            eng.dense_states(seg, idx, times, *self.oscs, self.p.omega, self.p.phi, out)
            self.strobe[:, sel] = out

    def add_impacts(self, imp: np.ndarray) -> None:
        w = imp[:, 0] >= self.st.t_transient
        self.times.append(imp[w, 0].copy())
        self.walls.append(imp[w, 5].astype(np.int8))

    def regime(self, t_stuck_window: float) -> tuple[str, int]:
        from ..core.regime import classify
        walls = np.concatenate(self.walls) if self.walls else np.zeros(0, np.int8)
        times = np.concatenate(self.times) if self.times else np.zeros(0)
        return classify(walls, times, self.strobe, self.ts, t_stuck_window, self.p.period)


def spectrum(p: ModelParams, st: SolverSettings, state0: Sequence[float] | None = None, *,
             t0: float = 0.0,
             mode: int = 0, n_batches: int = N_BATCHES_DEFAULT,
             with_regime: bool = True) -> LyapunovResult:
    """Lyapunov spectrum of the exact trajectory from ``state0`` (default st.state0) at t0
    (segment ``mode``) over [st.t_transient, st.t_end] (module docstring)."""
    from ..core import kernel as eng
    from ..core.exact import oscillators
    from ..core.variational import TP_IMP, TangentRun
    oscs = oscillators(p)
    s0 = st.state0 if state0 is None else state0
    edges = np.linspace(st.t_transient, st.t_end, n_batches + 1)
    tr = TangentRun(p, st, oscs, s0, t0, edges, mode)
    rec = _WindowRecord(p, st, oscs) if with_regime else None
    if rec is not None:
        def on_chunk(seg, n_done, t_done):
            rec.on_chunk(seg, n_done, t_done)
            n_imp = int(tr.tp[TP_IMP])     # impacts matched so far in this chunk
            rec.add_impacts(tr.run_.imp[:n_imp])
    with progress.task(st.t_end - t0, "lyapunov spectrum", "t"):
        tr.run(on_chunk if rec is not None else None)
    width = np.diff(edges)[:, None]
    batch = tr.sums / width
    with np.errstate(invalid="ignore"):
        total = tr.sums.sum(axis=0) / (st.t_end - st.t_transient)
    regime, period = ("", 0)
    if rec is not None:
        if tr.status == "ok":
            regime, period = rec.regime(float(tr.run_.acc[eng.A_TSTUCK_WIN]))
        else:
            regime = {"max_impacts": "unfinished"}.get(tr.status, "failed")
    order = np.argsort(-total, kind="stable")   # Benettin's columns are descending once
    total, batch = total[order], batch[:, order]  # aligned; sorted for short windows
    return LyapunovResult(exponents=total, ci=batch_ci(batch),
                          regime=regime, period=int(period), n_impacts=tr.n_impacts,
                          n_sticks=tr.n_sticks, status=tr.status, n_batches=n_batches,
                          params=p, settings=st, batch_exponents=batch)


def lyapunov(*, eta: float, omega: float, F: float, r: float = R_DEFAULT,
             d: float = D_DEFAULT, phi: float = 0.0, state0: Sequence[float] | None = None,
             t_end: float = T_END_DEFAULT, t_transient: float = T_TRANSIENT_DEFAULT,
             v_stick: float = V_STICK_DEFAULT, max_impacts: int = MAX_IMPACTS_DEFAULT,
             root_tol: float = ROOT_TOL_DEFAULT,
             n_batches: int = N_BATCHES_DEFAULT) -> LyapunovResult:
    """Lyapunov spectrum at (eta, omega, F) from ``state0`` = (z_m, z_m', z_b, z_b') at t = 0
    (default: rest) over the window [t_transient, t_end] (module docstring).

    Returns a LyapunovResult (exponents descending per unit dimensionless time, ci,
    regime, n_impacts, n_sticks). Raises ParameterError naming a bad argument.
    """
    p = ModelParams(eta=eta, omega=omega, F=F, r=r, d=d, phi=phi)
    st = SolverSettings(t_end=t_end, t_transient=t_transient, v_stick=v_stick,
                        max_impacts=max_impacts, root_tol=root_tol,
                        state0=(0.0, 0.0, 0.0, 0.0) if state0 is None else state0)
    n_batches = check_int("n_batches", n_batches, lo=2, hi=10_000)
    from ..core.exact import oscillators
    oscillators(p)                   # ParameterError for near-resonant points, up front
    if (st.t_end - st.t_transient) / n_batches < p.period:
        raise ParameterError("n_batches", n_batches,
                             f"each batch must span at least one forcing period: at most "
                             f"{int((st.t_end - st.t_transient) / p.period)} for this window")
    return spectrum(p, st, n_batches=n_batches)
