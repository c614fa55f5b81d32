"""The clearance that minimises the peak LO amplitude over a band, from the slow flow.

A base amplitude A and a clearance L give F = A/L; the LO's largest amplitude is L X (X in
units of L), i.e. the transmissibility X/F. At each frequency the motion from rest
(docs/slowflow.md, section 7) is the linear response while it stays inside the clearance
(X_lin < 1, no impact); otherwise the largest attracting two-impact fixed point (beyond the
SIM's symmetry-breaking point too, where a 1:1 orbit with unequal flights takes over at
about that amplitude), or, with none,
the strongly modulated response, whose LO amplitude reaches X = 1. The worst case over the
band (and over the amplitudes A_i) is minimised over L on a logarithmic grid, then refined
by golden-section search in log L around the grid's best point.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..core.params import D_DEFAULT, R_DEFAULT, ParameterError, check_int, check_reals
from .api import model, regimes, warnings_for
from .response import Model, fixed_points, linear_amplitude

#: frequencies of the band, F (or L) values of the grid, golden-section steps
N_OMEGA_DEFAULT = 401
N_GRID_DEFAULT = 61
N_GOLDEN = 40
#: default search range of F = A/L
F_RANGE_DEFAULT = (1e-3, 2.0)


def from_rest_amplitude(m: Model, W: np.ndarray) -> np.ndarray:
    """LO amplitude (units of L) of the motion from rest at each frequency W."""
    R = fixed_points(m, W)
    xl = linear_amplitude(m, W)
    regime = regimes(R, xl)
    out = np.where(regime == "SMR", 1.0, xl)
    best = np.full(W.size, -np.inf)
    np.maximum.at(best, R.index[R.attracting], R.X[R.attracting])
    impact = (regime == "two-impact") & (xl >= 1.0)
    out[impact] = best[impact]
    return out


def ratios(m: Model, F: np.ndarray, W: np.ndarray) -> np.ndarray:
    """Transmissibility X/F from rest of the model m at every F (rows) and W (columns): one
    vectorised evaluation (the model's F replaced by the rows' values)."""
    FF, WW = np.repeat(F, W.size), np.tile(W, F.size)
    x = from_rest_amplitude(Model(eta=m.eta, F=FF, r=m.r, d=m.d), WW)
    return (x / FF).reshape(F.size, W.size)


def worst_ratio(eta, F_values, W, r, d) -> float:
    """Largest transmissibility X/F over the frequencies W and the values F."""
    return float(ratios(model(eta, 1.0, r, d), np.asarray(F_values, dtype=float), W).max())


@dataclass(frozen=True)
class Optimum:
    """The slow flow's best design: clearance_m (None for optimal_F), F (the values A_i/L),
    worst_ratio (peak x_max/A over band and amplitudes), omega_peak, warnings."""

    clearance_m: float | None
    F: list
    worst_ratio: float
    omega_peak: float
    warnings: list

    def to_dict(self) -> dict:
        return {"model": "slowflow", "clearance_m": self.clearance_m, "F": list(self.F),
                "worst_ratio": self.worst_ratio, "omega_peak": self.omega_peak,
                "warnings": list(self.warnings)}


def _band(band, n_omega) -> np.ndarray:
    lo, hi = check_reals("omega_band", band, lo=0.0, lo_open=True, hi=1000.0,
                         min_size=2, max_size=2)
    if not lo < hi:
        raise ParameterError("omega_band", band, "must be two numbers LO < HI")
    return np.linspace(lo, hi, check_int("n_omega", n_omega, lo=3, hi=100_001))


def _minimise(worst, lo: float, hi: float, n_grid: int) -> float:
    """Argmin over u in [lo, hi] of worst(u) (u an array: one value per entry): the best of
    a grid, then golden section in the grid cells beside it (the function may jump: the
    grid's best value is never lost)."""
    grid = np.linspace(lo, hi, n_grid)
    vals = worst(grid)
    j = int(np.argmin(vals))
    a, b = grid[max(j - 1, 0)], grid[min(j + 1, n_grid - 1)]
    best_u, best_v = grid[j], vals[j]
    g = (math.sqrt(5.0) - 1.0) / 2.0
    c, e = b - g * (b - a), a + g * (b - a)
    fc, fe = worst(np.array([c, e]))
    for _ in range(N_GOLDEN):
        if fc < fe:
            b, e, fe = e, c, fc
            c = b - g * (b - a)
            fc = worst(np.array([c]))[0]
        else:
            a, c, fc = c, e, fe
            e = a + g * (b - a)
            fe = worst(np.array([e]))[0]
    for u, v in ((c, fc), (e, fe)):
        if v < best_v:
            best_u, best_v = u, v
    return float(best_u)


def _worst_of(m: Model, A: np.ndarray, W: np.ndarray):
    """worst(u): for clearances 10**u, the largest X/F over the amplitudes A (F = A/L)
    and W."""
    def worst(u):
        F = (A[None, :] / 10.0 ** np.asarray(u)[:, None]).ravel()
        return ratios(m, F, W).reshape(len(u), A.size * W.size).max(axis=1)
    return worst


def _peak(m: Model, F, W) -> tuple[float, float]:
    """(worst ratio, its frequency) over the values F and the frequencies W."""
    x = ratios(m, np.asarray(F, dtype=float), W)
    i, j = np.unravel_index(int(np.argmax(x)), x.shape)
    return float(x[i, j]), float(W[j])


def optimal_F(eta, omega_band=(0.8, 1.2), *, r=R_DEFAULT, d=D_DEFAULT,
              F_range=F_RANGE_DEFAULT, n_omega=N_OMEGA_DEFAULT,
              n_grid=N_GRID_DEFAULT) -> Optimum:
    """F = A/L minimising the peak transmissibility over the band (one base amplitude A:
    the clearance is A/F)."""
    W = _band(omega_band, n_omega)
    lo, hi = check_reals("F_range", F_range, lo=0.0, lo_open=True, hi=1000.0, min_size=2,
                         max_size=2)
    if not lo < hi:
        raise ParameterError("F_range", F_range, "must be two numbers LO < HI")
    m = model(eta, 1.0, r, d)
    # with A = 1 the clearance 10**u is 1/F: search u = -log10 F
    u = _minimise(_worst_of(m, np.ones(1), W), -math.log10(hi), -math.log10(lo),
                  check_int("n_grid", n_grid, lo=3, hi=10_000))
    F = 10.0 ** -u
    ratio, w_peak = _peak(m, [F], W)
    return Optimum(clearance_m=None, F=[F], worst_ratio=ratio, omega_peak=w_peak,
                   warnings=warnings_for(model(eta, F, r, d), W))


def design_ratio(eta, amplitudes_m, clearance_m, omega_band, *, r=R_DEFAULT, d=D_DEFAULT,
                 n_omega=N_OMEGA_DEFAULT) -> tuple[float, float]:
    """(worst transmissibility, its frequency) of the design (eta, clearance_m [m]) over
    the band and the base amplitudes [m]."""
    A = check_reals("amplitudes_m", amplitudes_m, lo=0.0, lo_open=True, hi=1e3)
    L = check_reals("clearance_m", clearance_m, lo=0.0, lo_open=True, hi=1e6, max_size=1)[0]
    return _peak(model(eta, 1.0, r, d), A / L, _band(omega_band, n_omega))


def optimal_clearance(eta, amplitudes_m: float | Sequence[float], omega_band=(0.8, 1.2), *,
                      r=R_DEFAULT, d=D_DEFAULT, clearance_range_m=None,
                      n_omega=N_OMEGA_DEFAULT, n_grid=N_GRID_DEFAULT) -> Optimum:
    """Clearance L [m] minimising the worst transmissibility x_max/A over the band and the
    base amplitudes A_i [m] (F_i = A_i/L); default range [A_max/2, 100 A_min]."""
    A = check_reals("amplitudes_m", amplitudes_m, lo=0.0, lo_open=True, hi=1e3)
    W = _band(omega_band, n_omega)
    if clearance_range_m is None:
        clearance_range_m = (0.5 * A.max(), 100.0 * A.min())
    lo, hi = check_reals("clearance_range_m", clearance_range_m, lo=0.0, lo_open=True,
                         hi=1e6, min_size=2, max_size=2)
    if not lo < hi:
        raise ParameterError("clearance_range_m", clearance_range_m,
                             "must be two numbers LO < HI")
    m = model(eta, 1.0, r, d)
    L = 10.0 ** _minimise(_worst_of(m, A, W), math.log10(lo), math.log10(hi),
                          check_int("n_grid", n_grid, lo=3, hi=10_000))
    ratio, w_peak = _peak(m, A / L, W)
    return Optimum(clearance_m=L, F=[float(x) for x in A / L], worst_ratio=ratio,
                   omega_peak=w_peak,
                   warnings=warnings_for(model(eta, float(A.max() / L), r, d), W))


