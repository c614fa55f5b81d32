"""The linear references of a design: the LO alone and the optimal tuned mass damper (TMD).

Dimensionless like the VI NES model (SPEC 1): time w0 t, omega = w/w0, d = c/(M w0). The
base moves as y = A sin(w t); the LO's absolute displacement x obeys
x'' + d (x' - y') + (x - y) = (force of the absorber). The transmissibility is |X/Y| (the
VI NES's x_max/A once the motion has settled on a harmonic response).

* LO alone: |X/Y| = |1 + i d omega| / |1 - omega^2 + i d omega| (``lo_ratio``).
* TMD of mass ratio mu = m_a/M, natural frequency ratio f = w_a/w0 and damping ratio zeta
  (c_a = 2 zeta m_a w_a), attached to the LO (not to the base): with
  G = (f^2 + 2 i zeta f omega) / (f^2 - omega^2 + 2 i zeta f omega) (absorber / LO motion),

      X/Y = (1 + i d omega) / (1 - omega^2 + i d omega - mu omega^2 G)     (``tmd_ratio``).

* Travel (stroke) of the TMD: its displacement u relative to the LO per unit base amplitude,
  from the absorber's equation z'' + 2 zeta f z' + f^2 z = -x'' for z = u - x:

      (U - X)/Y = (X/Y) omega^2 / (f^2 - omega^2 + 2 i zeta f omega)     (``tmd_travel``).

``optimal_tmd`` chooses (f, zeta) minimising the largest |X/Y| over a frequency band
(a minimax, the H-infinity criterion restricted to the band): a coarse (f, zeta) grid, then
Nelder-Mead on (log f, log zeta). With d = 0 and a band holding both of Den Hartog's fixed
points this is the classical H-infinity problem; ``den_hartog`` gives his fixed-point
approximation of its solution.

With ``max_travel`` T the band maximum of ``tmd_travel`` is bounded by T (T = L/A_max: a
clearance L over the largest base amplitude). When the free optimum's travel is within T it
is the answer, unchanged. Otherwise the constrained optimum lies on the boundary
travel(f, zeta) = T: the band travel falls as zeta grows (the damper locks the absorber to
the LO), so for each f the boundary is the largest zeta_T(f) where it crosses T (a root in
log zeta), and the worst ratio along it, a function of f alone, is minimised by a grid in f
(band maxima on the dense grid only) and a bounded scalar search (exact band maxima).
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..core.linear import stuck_amplitude, stuck_peak
from ..core.params import ParameterError, check_param, check_real
from .design_checks import check_band, check_eta

#: points of the dense grid on which band maxima are located before refinement
N_BAND_GRID = 2001
#: search box of the TMD's tuning: f = w_a/w0 and zeta (Nelder-Mead stays inside)
F_BOUNDS = (0.05, 20.0)
ZETA_BOUNDS = (1e-5, 10.0)
#: largest damping ratio of a travel-limited TMD (a small travel limit needs a stiff damper:
#: the band travel of an absorber locked by zeta falls like 1/zeta)
ZETA_MAX_LIMITED = 1e8


def lo_ratio(omega: ArrayLike, d: float) -> np.ndarray:
    """Transmissibility |X/Y| of the LO alone (closed form; broadcasts)."""
    return stuck_amplitude(0.0, omega, 1.0, d)


def lo_worst(band: Sequence[float], d: float) -> tuple[float, float]:
    """Exact (max, argmax) of ``lo_ratio`` over omega in band = (lo, hi): the closed-form
    peak (``core.linear.stuck_peak`` with eta = 0) when it lies in the band, else the larger
    band edge (the curve rises up to the peak and falls after it). inf at omega = 1 for
    d = 0."""
    lo, hi = band
    w_peak, peak = stuck_peak(0.0, 1.0, d)
    if lo <= w_peak <= hi:
        return float(peak), float(w_peak)
    edge = hi if lo_ratio(hi, d) > lo_ratio(lo, d) else lo
    return float(lo_ratio(edge, d)), float(edge)


def tmd_ratio(omega: ArrayLike, d: float, mu: float, f: float, zeta: float) -> np.ndarray:
    """Transmissibility |X/Y| of the LO with a TMD (module docstring); broadcasts."""
    w = np.asarray(omega, dtype=float)
    iw = 1j * w
    g = (f * f + 2.0 * zeta * f * iw) / (f * f - w * w + 2.0 * zeta * f * iw)
    return np.abs((1.0 + d * iw) / (1.0 - w * w + d * iw - mu * w * w * g))


def tmd_travel(omega: ArrayLike, d: float, mu: float, f: float, zeta: float) -> np.ndarray:
    """Travel |U - X|/|Y| of the TMD: its displacement relative to the LO per unit base
    amplitude (module docstring; closed form, broadcasts like ``tmd_ratio``)."""
    w = np.asarray(omega, dtype=float)
    iw = 1j * w
    den = f * f - w * w + 2.0 * zeta * f * iw
    g = (f * f + 2.0 * zeta * f * iw) / den
    x = (1.0 + d * iw) / (1.0 - w * w + d * iw - mu * w * w * g)
    return np.abs(x * (w * w) / den)


def band_max(fun: Callable[[float], float], band: Sequence[float],
             n: int = N_BAND_GRID) -> tuple[float, float]:
    """(max, argmax) of a smooth fun(omega) over the closed band: its values on n points,
    then each interior local maximum within 10 % of the largest is refined by a bounded
    scalar search between its grid neighbours."""
    from scipy.optimize import minimize_scalar
    w = np.linspace(band[0], band[1], n)
    y = fun(w)
    best = int(np.argmax(y))
    top, arg = float(y[best]), float(w[best])
    inner = np.flatnonzero((y[1:-1] >= y[:-2]) & (y[1:-1] >= y[2:])) + 1
    for i in inner[y[inner] >= 0.9 * top]:
        res = minimize_scalar(lambda x: -float(fun(x)), bounds=(w[i - 1], w[i + 1]),
                              method="bounded", options={"xatol": 1e-12 * max(1.0, w[i])})
        if -res.fun > top:
            top, arg = float(-res.fun), float(res.x)
    return top, arg


@dataclass(frozen=True)
class TunedMassDamper:
    """An optimal TMD: mass ratio ``eta`` = m_a/M, ``frequency_ratio`` f = w_a/w0,
    ``damping_ratio`` zeta = c_a/(2 m_a w_a), ``worst_ratio`` = largest |X/Y| over the band
    (exact up to the refinement of ``band_max``), ``worst_omega`` where it occurs,
    ``worst_travel`` = largest travel |U - X|/|Y| over the band (``tmd_travel``; multiply by
    the largest base amplitude for the stroke in metres)."""

    eta: float
    frequency_ratio: float
    damping_ratio: float
    worst_ratio: float
    worst_omega: float
    worst_travel: float

    def ratio(self, omega: ArrayLike, d: float) -> np.ndarray:
        """Transmissibility at omega for LO damping d."""
        return tmd_ratio(omega, d, self.eta, self.frequency_ratio, self.damping_ratio)

    def travel(self, omega: ArrayLike, d: float) -> np.ndarray:
        """Travel |U - X|/|Y| at omega for LO damping d."""
        return tmd_travel(omega, d, self.eta, self.frequency_ratio, self.damping_ratio)

    def to_dict(self) -> dict:
        return asdict(self)


def den_hartog(mu: float) -> tuple[float, float, float]:
    """Den Hartog's TMD on an undamped LO (force or, equivalently, base excitation through
    the spring): (frequency ratio 1/(1 + mu), damping ratio sqrt(3 mu / (8 (1 + mu)^3)),
    height sqrt(1 + 2/mu) of the fixed points)."""
    return (1.0 / (1.0 + mu), math.sqrt(3.0 * mu / (8.0 * (1.0 + mu) ** 3)),
            math.sqrt(1.0 + 2.0 / mu))


def _coarse_tuning(mu, d, band) -> tuple[float, float]:
    """Best (f, zeta) of a 41 x 41 grid (f linear around the band, zeta logarithmic), by
    the maximum over 401 band points."""
    f_grid = np.linspace(max(F_BOUNDS[0], 0.5 * band[0]), min(F_BOUNDS[1], 1.5 * band[1]), 41)
    z_grid = np.geomspace(1e-3, 1.0, 41)
    w = np.linspace(band[0], band[1], 401)
    worst = np.array([[tmd_ratio(w, d, mu, f, z).max() for z in z_grid] for f in f_grid])
    i, j = np.unravel_index(int(np.argmin(worst)), worst.shape)
    return float(f_grid[i]), float(z_grid[j])


def optimal_tmd(mu: float, d: float, band: Sequence[float], *,
                max_travel: float | None = None) -> TunedMassDamper:
    """TMD of mass ratio mu minimising the largest transmissibility over omega in band
    (module docstring). Deterministic: a fixed grid, then Nelder-Mead in (log f, log zeta)
    within F_BOUNDS x ZETA_BOUNDS to xatol 1e-9. ``max_travel`` (> 0, dimensionless: a
    clearance over the largest base amplitude) bounds the band maximum of ``tmd_travel``;
    None, or a bound the free optimum meets, gives the free optimum unchanged. A bound no
    tuning meets (damping ratio up to ZETA_MAX_LIMITED) raises ParameterError."""
    mu = check_eta("mu", mu)
    d = check_param("d", d)
    band = check_band(band, "band")
    if max_travel is not None:
        check_real("max_travel", max_travel, lo=0.0, lo_open=True)
    free = _free_optimum(mu, d, band)
    return free if max_travel is None else limit_travel(free, d, band, max_travel)


def limit_travel(free: TunedMassDamper, d: float, band: Sequence[float],
                 max_travel: float) -> TunedMassDamper:
    """``optimal_tmd(free.eta, d, band, max_travel=max_travel)`` given the free optimum
    ``free`` of the same (mu, d, band): ``free`` itself when its band travel is within
    max_travel, else the travel-limited optimum (module docstring)."""
    max_travel = check_real("max_travel", max_travel, lo=0.0, lo_open=True)
    if free.worst_travel <= max_travel:
        return free
    return _travel_limited_optimum(free.eta, d, band, max_travel)


def _design(mu, d, band, f, z) -> TunedMassDamper:
    top, arg = band_max(lambda w: tmd_ratio(w, d, mu, f, z), band)
    travel = band_max(lambda w: tmd_travel(w, d, mu, f, z), band)[0]
    return TunedMassDamper(eta=float(mu), frequency_ratio=f, damping_ratio=z,
                           worst_ratio=top, worst_omega=arg, worst_travel=travel)


def _free_optimum(mu, d, band) -> TunedMassDamper:
    from scipy.optimize import minimize

    def worst(x):
        f, z = math.exp(x[0]), math.exp(x[1])
        return band_max(lambda w: tmd_ratio(w, d, mu, f, z), band)[0]

    f0, z0 = _coarse_tuning(mu, d, band)
    bounds = [tuple(map(math.log, F_BOUNDS)), tuple(map(math.log, ZETA_BOUNDS))]
    res = minimize(worst, [math.log(f0), math.log(z0)], method="Nelder-Mead", bounds=bounds,
                   options={"xatol": 1e-9, "fatol": 1e-12, "maxiter": 4000,
                            "initial_simplex": [[math.log(f0), math.log(z0)],
                                                [math.log(f0) + 0.05, math.log(z0)],
                                                [math.log(f0), math.log(z0) + 0.2]]})
    return _design(mu, d, band, math.exp(res.x[0]), math.exp(res.x[1]))


class _TravelBoundary:
    """zeta_T(f): the largest damping ratio at which the band travel of a TMD (mu, f) on
    the LO (d) equals T, found in log zeta; ``exact`` chooses ``band_max`` (grid and
    refinement) or the dense grid alone (a fast estimate used to bracket)."""

    #: log-zeta grid scanned downwards from ZETA_MAX_LIMITED for the crossing
    LOG_ZETA = np.linspace(math.log(ZETA_MAX_LIMITED), math.log(ZETA_BOUNDS[0]), 53)

    def __init__(self, mu, d, band, limit):
        self.mu, self.d, self.band, self.limit = mu, d, band, limit
        self.w = np.linspace(band[0], band[1], N_BAND_GRID)

    def travel(self, f, log_z, exact):
        z = math.exp(log_z)
        if exact:
            return band_max(lambda w: tmd_travel(w, self.d, self.mu, f, z), self.band)[0]
        return float(tmd_travel(self.w, self.d, self.mu, f, z).max())

    def ratio(self, f, log_z, exact):
        z = math.exp(log_z)
        if exact:
            return band_max(lambda w: tmd_ratio(w, self.d, self.mu, f, z), self.band)[0]
        return float(tmd_ratio(self.w, self.d, self.mu, f, z).max())

    def log_zeta(self, f, exact, bracket=None) -> float | None:
        """log zeta_T(f): the crossing within ``bracket`` (hi, lo) when it holds one, else
        the first crossing of a scan down from ZETA_MAX_LIMITED; log ZETA_BOUNDS[0] when
        even the smallest damping meets T; None when even ZETA_MAX_LIMITED does not."""
        from scipy.optimize import brentq
        excess = lambda s: self.travel(f, s, exact) - self.limit  # noqa: E731
        root = lambda lo, hi: brentq(excess, lo, hi, xtol=1e-13,  # noqa: E731
                                     rtol=4 * np.finfo(float).eps)
        if bracket is not None:
            hi, lo = bracket
            if excess(hi) <= 0 < excess(lo):
                return root(lo, hi)
        grid = self.LOG_ZETA
        if excess(grid[0]) > 0:
            return None
        for hi, lo in zip(grid[:-1], grid[1:], strict=True):
            if excess(lo) > 0:
                return root(lo, hi)
        return float(grid[-1])

    def worst_ratio(self, f, exact) -> float:
        """Largest |X/Y| over the band at (f, zeta_T(f)); inf when no zeta meets T."""
        s = self.log_zeta(f, exact)
        return math.inf if s is None else self.ratio(f, s, exact)


def _travel_limited_optimum(mu, d, band, limit) -> TunedMassDamper:
    from scipy.optimize import minimize_scalar
    edge = _TravelBoundary(mu, d, band, limit)
    f_grid = np.linspace(max(F_BOUNDS[0], 0.5 * band[0]), min(F_BOUNDS[1], 1.5 * band[1]), 41)
    coarse = np.array([edge.worst_ratio(f, exact=False) for f in f_grid])
    i = int(np.argmin(coarse))
    lo, hi = f_grid[max(i - 1, 0)], f_grid[min(i + 1, len(f_grid) - 1)]

    def log_zeta(f):
        s = edge.log_zeta(f, exact=False)
        return None if s is None else edge.log_zeta(f, exact=True,
                                                    bracket=(s + 0.05, s - 0.05))

    def worst(f):
        s = log_zeta(f)
        return math.inf if s is None else edge.ratio(f, s, exact=True)

    if np.isfinite(coarse[i]):
        f = float(minimize_scalar(worst, bounds=(lo, hi), method="bounded",
                                  options={"xatol": 1e-9 * hi}).x)
        s = log_zeta(f)
    if not np.isfinite(coarse[i]) or s is None:
        raise ParameterError("max_travel", limit,
                             "is below the band travel of every tuning (damping ratio up to "
                             f"{ZETA_MAX_LIMITED:g}): allow more travel")
    return _design(mu, d, band, f, math.exp(s))
