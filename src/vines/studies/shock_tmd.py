"""The TMD after a shock: its decay rate, the tuning that decays fastest, its peak travel
and the fastest tuning whose travel stays within a limit (docs/design.md, "Shocks").

Linear, dimensionless as ``studies.shock``: state (x, x', y, y') of the LO and the TMD's
mass (``tmd_system``), the LO given the velocity 1 at t = 0 (travel scales with it).

* decay rate: the slowest mode's -Re(lambda) over the eigenvalues of A (``decay_rate``).
* fastest decay (``tmd_fastest``): the characteristic polynomial
  lambda^4 + (c (1 + mu) + d) lambda^3 + (1 + k (1 + mu) + d c) lambda^2 + (c + d k) lambda + k
  (k = f^2, c = 2 zeta f) made a perfect square (lambda^2 + a lambda + f)^2: both modes
  coalesce with the decay rate a/2. For d = 0: f = 1/(1 + mu), zeta = sqrt(mu/(1 + mu)),
  rate sqrt(mu/(1 + mu))/2; for d > 0 two equations in (a, f), solved from that point.
* peak travel (``peak_response``): the largest |c . x(t)| over t >= 0: the flow stepped by
  expm(A h) (32 steps per period of the fastest mode), each sign change of the derivative
  c . A x refined by a root solve, until a bound of |c . x| for all later times (the
  energy x^T P x / 2 never grows; or the modes' envelopes) falls below the largest found.
* ``tmd_equal_travel``: the fastest decay with peak travel <= a limit: ``tmd_fastest``
  when it meets it, else along the boundary peak(f, zeta) = limit (the peak travel falls
  as zeta grows: a root in log zeta), the rate maximised over f (a grid, then a bounded
  scalar search).
"""
from __future__ import annotations

import math

import numpy as np

from ..core.params import ParameterError, check_param, check_real
from .design_checks import check_eta

# ----------------------------------------------------------------- linear systems

def lo_system(d: float) -> tuple:
    """(A, P, Q_damping, Q_absorber) of the LO alone, state (x, x'): x' = A x,
    E = x^T P x / 2, dissipated powers x^T Q x."""
    A = np.array([[0.0, 1.0], [-1.0, -d]])
    Q = np.diag([0.0, d])
    return A, np.eye(2), Q, np.zeros((2, 2))


def tmd_system(d: float, mu: float, f: float, zeta: float) -> tuple:
    """(A, P, Q_damping, Q_absorber) of the LO with a TMD (mass ratio mu, frequency ratio
    f, damping ratio zeta), state (x, x', y, y') of absolute displacements, base at rest."""
    k, c = mu * f * f, 2.0 * mu * zeta * f
    A = np.array([[0.0, 1.0, 0.0, 0.0],
                  [-1.0 - k, -d - c, k, c],
                  [0.0, 0.0, 0.0, 1.0],
                  [k / mu, c / mu, -k / mu, -c / mu]])
    P = np.array([[1.0 + k, 0.0, -k, 0.0], [0.0, 1.0, 0.0, 0.0],
                  [-k, 0.0, k, 0.0], [0.0, 0.0, 0.0, mu]])
    Q_d = np.zeros((4, 4))
    Q_d[1, 1] = d
    u = np.array([0.0, -1.0, 0.0, 1.0])
    return A, P, Q_d, c * np.outer(u, u)


#: grid steps per period of the fastest mode when stepping a free response
STEPS_PER_PERIOD = 32
#: grid steps taken at once, and which sign changes of the slope are refined
BLOCK = 128
REFINE_WITHIN = 0.99
#: longest free response followed (dimensionless time) before giving up on the bound
T_MAX = 2.0e5
#: range of log zeta searched for the travel boundary, and the f grid of the constrained
#: search (then refined between the best point's neighbours)
LOG_ZETA_RANGE = (math.log(1e-3), math.log(1e3))
F_GRID = np.linspace(0.4, 1.6, 13)


def decay_rate(A: np.ndarray) -> float:
    """Slowest decay rate min(-Re lambda) over the eigenvalues of A."""
    return float(-np.linalg.eigvals(A).real.max())


def tmd_fastest(mu: float, d: float) -> tuple[float, float, float]:
    """(f, zeta, rate): the TMD tuning whose free vibration on the LO (damping d) has the
    largest slowest decay rate: the two modes coalesce (module docstring)."""
    from scipy.optimize import fsolve
    mu, d = check_eta("mu", mu), check_param("d", d)
    g = 1.0 / (1.0 + mu)
    a0 = math.sqrt(mu * g)
    if d == 0.0:
        return g, a0, 0.5 * a0

    def equations(x):
        a, f = x
        c = (2.0 * a - d) * g
        return [2.0 * a * f - c - d * f * f,
                a * a + 2.0 * f - 1.0 - f * f / g - d * c]

    (a, f), info, _, _ = fsolve(equations, [a0, g], xtol=1e-13, full_output=True)
    residual = float(np.abs(info["fvec"]).max())
    if not (residual < 1e-12 and a > 0 and f > 0 and 2.0 * a > d and a * a < 4.0 * f):
        raise ParameterError("d", d, f"has no coalescing TMD tuning at mu = {mu:g}")
    return float(f), float((2.0 * a - d) * g / (2.0 * f)), float(0.5 * a)


def _bound(A, P, c):
    """A function of (t, x(t)) bounding |c . x(s)| for every s >= t: the energy bound
    sqrt(c^T P^-1 c x^T P x), or the modes' envelopes when smaller."""
    w_c = float(c @ np.linalg.solve(P, c))
    lam, V = np.linalg.eig(A)
    modal = np.linalg.cond(V) < 1e8
    cv = c @ V if modal else None
    Vinv = np.linalg.inv(V) if modal else None

    def bound(x):
        energy = math.sqrt(max(w_c * float(x @ P @ x), 0.0))
        if not modal:
            return energy
        env = float(np.abs(cv * (Vinv @ x)).sum())   # envelopes decay from here on
        return min(energy, env)
    return bound


def peak_response(A: np.ndarray, P: np.ndarray, c: np.ndarray, x0: np.ndarray
                  ) -> tuple[float, float]:
    """(max |c . x(t)|, where) over t >= 0 for x' = A x, x(0) = x0, A dissipative for the
    energy x^T P x / 2 (P positive definite): module docstring. Steps in blocks of BLOCK;
    a sign change of the slope is refined when a grid value beside it is within
    REFINE_WITHIN of the largest so far (between grid points a peak exceeds its grid
    neighbours by at most 1/cos(pi/STEPS_PER_PERIOD) - 1 = 0.5 %)."""
    lam = np.linalg.eigvals(A)
    h = 2.0 * math.pi / (STEPS_PER_PERIOD * max(float(np.abs(lam).max()), 1e-12))
    powers = np.empty((BLOCK, A.shape[0], A.shape[0]))
    powers[0] = _expm(A * h)
    for j in range(1, BLOCK):            # tiny products: numpy's loops, not threaded BLAS
        powers[j] = np.einsum("ij,jk->ik", powers[0], powers[j - 1])
    ca = c @ A
    bound = _bound(A, P, c)
    x, t = np.asarray(x0, dtype=float), 0.0
    best, arg = abs(float(c @ x)), 0.0
    while t < T_MAX and bound(x) > best:
        states = np.vstack([x, np.einsum("kij,j->ki", powers, x)])   # t, t + h, ...
        z, dz = states @ c, states @ ca
        k = int(np.abs(z).argmax())
        if abs(z[k]) > best:
            best, arg = float(abs(z[k])), t + k * h
        near = np.maximum(np.abs(z[:-1]), np.abs(z[1:])) >= REFINE_WITHIN * best
        for i in np.flatnonzero(near & (dz[:-1] * dz[1:] <= 0.0)):
            peak, s = _refine(A, ca, c, states[i], h)
            if peak > best:
                best, arg = peak, t + i * h + s
        x, t = states[-1], t + BLOCK * h
    return best, arg


def _expm(M: np.ndarray) -> np.ndarray:
    """expm of a small matrix: scaled to norm <= 1/2, Taylor to round-off, squared back
    (for 4 x 4 matrices faster than scipy's Pade, whose LAPACK calls dominate here)."""
    norm = float(np.abs(M).sum(axis=0).max())
    n_sq = max(0, math.ceil(math.log2(norm / 0.5))) if norm > 0.5 else 0
    M = M / 2.0 ** n_sq
    out = term = np.eye(M.shape[0])
    for n in range(1, 30):
        term = np.einsum("ij,jk->ik", term, M) / n
        out = out + term
        if np.abs(term).max() <= 1e-17 * np.abs(out).max():
            break
    for _ in range(n_sq):
        out = np.einsum("ij,jk->ik", out, out)
    return out


def _refine(A, ca, c, x, h) -> tuple[float, float]:
    """(|c . x(s)|, s) at the zero of the slope c . A x(s) in [0, h] (a sign change)."""
    from scipy.optimize import brentq

    def slope(s):
        return float(ca @ (_expm(A * s) @ x))
    a, b = slope(0.0), slope(h)
    if a == 0.0 or b == 0.0:
        s = 0.0 if a == 0.0 else h
    else:
        s = brentq(slope, 0.0, h, xtol=1e-15, rtol=4 * np.finfo(float).eps)
    return abs(float(c @ (_expm(A * s) @ x))), s


#: the relative displacement y - x and the LO's own x of ``tmd_system``'s state
TRAVEL = np.array([-1.0, 0.0, 1.0, 0.0])
LO_DISPLACEMENT = np.array([1.0, 0.0, 0.0, 0.0])


def shock_peaks(d: float, mu: float, f: float, zeta: float) -> dict:
    """Peak travel |y - x| and peak LO displacement |x| after the unit shock x'(0) = 1
    (multiply by V0/w0 for metres), and the slowest decay rate."""
    A, P, _, _ = tmd_system(d, mu, f, zeta)
    x0 = np.array([0.0, 1.0, 0.0, 0.0])
    return dict(travel=peak_response(A, P, TRAVEL, x0)[0],
                x_max=peak_response(A, P, LO_DISPLACEMENT, x0)[0], rate=decay_rate(A))


def _travel(d, mu, f, log_z) -> float:
    A, P, _, _ = tmd_system(d, mu, f, math.exp(log_z))
    return peak_response(A, P, TRAVEL, np.array([0.0, 1.0, 0.0, 0.0]))[0]


def _boundary(d, mu, f, limit) -> float | None:
    """log zeta in LOG_ZETA_RANGE where the peak travel of (f, zeta), falling as zeta
    grows (the damper locks the mass to the LO), crosses ``limit``; the range's lower end
    when all of it meets the limit; None when even its upper end does not."""
    from scipy.optimize import brentq
    excess = lambda s: _travel(d, mu, f, s) - limit  # noqa: E731
    lo, hi = LOG_ZETA_RANGE
    if excess(hi) > 0:
        return None
    if excess(lo) <= 0:
        return lo
    return brentq(excess, lo, hi, xtol=1e-12)


def tmd_equal_travel(mu: float, d: float, max_travel: float) -> tuple[float, float, float]:
    """(f, zeta, rate): the largest slowest decay rate with peak travel after the unit
    shock <= max_travel (module docstring); ParameterError when no tuning meets it."""
    from scipy.optimize import minimize_scalar
    max_travel = check_real("max_travel", max_travel, lo=0.0, lo_open=True)
    f, z, rate = tmd_fastest(mu, d)
    if shock_peaks(d, mu, f, z)["travel"] <= max_travel:
        return f, z, rate

    def neg_rate(f):
        s = _boundary(d, mu, f, max_travel)
        return math.inf if s is None else -decay_rate(tmd_system(d, mu, f, math.exp(s))[0])

    coarse = np.array([neg_rate(f) for f in F_GRID])
    i = int(np.argmin(coarse))
    if not np.isfinite(coarse[i]):
        raise ParameterError("max_travel", max_travel,
                             "is below the peak travel of every tuning: allow more travel")
    lo, hi = F_GRID[max(i - 1, 0)], F_GRID[min(i + 1, F_GRID.size - 1)]
    f = float(minimize_scalar(neg_rate, bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-8}).x)
    s = _boundary(d, mu, f, max_travel)
    return f, math.exp(s), decay_rate(tmd_system(d, mu, f, math.exp(s))[0])
