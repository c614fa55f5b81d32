"""1:1 periodic orbits: fixed points of P2∘P1 with the time shifted by T = 2 pi / omega.

Unknowns x_L = (z_m', z_b', z_b, t_L), the pre-impact state at wall L. The orbit solves
P2(P1(x_L)) = x_L + (0, 0, 0, T); Newton uses the exact Jacobian J_P2(x_R) J_P1(x_L) - I.

Seeds (every seed is polished by that Newton iteration on the true maps, then deduplicated):

* symmetric ansatz: P1(x_L) = mirror(x_L) + (0, 0, 0, T/2), mirror flipping the signs of
  positions and velocities (the model is invariant under z -> -z, t -> t + T/2). With the
  flight time fixed at T/2 every condition is affine in (z_m', z_b', z_b, sin theta_L,
  cos theta_L) (the flow is linear in the initial state and in the forcing phase's sine and
  cosine), so the symmetric orbits are the intersections of a line with the unit circle:
  zero or two per parameter point, in closed form. This replaces a scan of t_L over [0, T).
* asymmetric scan: with the L->R flight time s1 fixed (R->L flight T - s1) the five
  conditions (arrival at R, arrival at L, periodicity of z_m', z_b', z_b) are again affine in
  those five unknowns; the orbit exists where the solution has sin^2 + cos^2 = 1. s1 is
  scanned over (0, T) and sign changes of sin^2 + cos^2 - 1 are refined by bisection.
* a short simulation (t_end ~ 600) from rest: its last L impact followed by R and L.
* caller-supplied seeds (continuation): x_L arrays, optionally with flight times.

``orbit_solve``/``orbit_classify``/``seed_kernel`` (end of the module) are nogil versions
of ``solve_orbit``/``seed_orbits(simulation=False)`` on float rows, bitwise equal to them,
for threaded per-point drivers (``stability_map``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..core.exact import oscillators
from ..core.flow import I_ARES, I_NRES, I_PC, I_PS, I_RES, I_W, flow, fundamentals
from ..core.params import (
    D_DEFAULT,
    R_DEFAULT,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_bool,
    check_reals,
)
from ..core.walls import WALL_L, WALL_R, impact_velocities
from ._lapack import lambda_max_4
from .maps import admissible_kernel, map_kernel

SYM_TOL = 1e-6          # flight times equal to this: symmetric
DEDUP_TOL = 1e-8
N_SCAN = 96             # s1 samples of the asymmetric scan


# --------------------------------------------------------------------------- linear algebra

@njit(cache=True, nogil=True)
def _solve(A, b, out):
    """Gaussian elimination with partial pivoting; False when (numerically) singular."""
    return _solve_into(A.copy(), b.copy(), out)


@njit(cache=True, nogil=True)
def _solve_into(M, v, out):
    """``_solve`` overwriting M and v (no allocation)."""
    n = M.shape[0]
    scale = 0.0
    for i in range(n):
        for j in range(n):
            scale = max(scale, abs(M[i, j]))
    if scale == 0.0 or not math.isfinite(scale):
        return False
    for k in range(n):
        p = k
        for i in range(k + 1, n):
            if abs(M[i, k]) > abs(M[p, k]):
                p = i
        if abs(M[p, k]) <= 1e-14 * scale:
            return False
        if p != k:
            for j in range(n):
                M[k, j], M[p, j] = M[p, j], M[k, j]
            v[k], v[p] = v[p], v[k]
        for i in range(k + 1, n):
            f = M[i, k] / M[k, k]
            for j in range(k, n):
                M[i, j] -= f * M[k, j]
            v[i] -= f * v[k]
    for k in range(n - 1, -1, -1):
        acc = v[k]
        for j in range(k + 1, n):
            acc -= M[k, j] * out[j]
        out[k] = acc / M[k, k]
    return True


# --------------------------------------------------------------------------- Newton

@njit(cache=True, nogil=True)
def newton_1to1(osc, eta, r, omega, phi, x0, s1, s2, x, xR, J1, J2, fl):
    """Newton on P2(P1(x)) - x - (0,0,0,T) from x0 (flight-time guesses s1, s2).

    Fills x (fixed point), xR = P1(x), the Jacobians J1 = J_P1(x), J2 = J_P2(xR) and
    fl = (s1, s2). Returns the final residual norm (inf on failure).
    """
    T = 2.0 * math.pi / omega
    for i in range(4):
        x[i] = x0[i]
    y2 = np.empty(4)
    R = np.empty(4)
    M = np.empty((4, 4))
    dx = np.empty(4)
    res = math.inf
    for it in range(40):
        s1n = map_kernel(osc, eta, r, omega, phi, x, WALL_L, WALL_R, s1, xR, J1)
        if not math.isfinite(s1n):
            return math.inf
        s2n = map_kernel(osc, eta, r, omega, phi, xR, WALL_R, WALL_L, s2, y2, J2)
        if not math.isfinite(s2n):
            return math.inf
        s1, s2 = s1n, s2n
        fl[0], fl[1] = s1, s2
        res = 0.0
        xs = 1.0
        for i in range(4):
            R[i] = y2[i] - x[i]
            xs = max(xs, abs(x[i]))
        R[3] -= T
        for i in range(4):
            res = max(res, abs(R[i]))
        if res <= 1e-13 * xs:
            return res
        for i in range(4):
            for k in range(4):
                acc = 0.0
                for m in range(4):
                    acc += J2[i, m] * J1[m, k]
                M[i, k] = acc - (1.0 if i == k else 0.0)
        for i in range(4):
            R[i] = -R[i]
        if not _solve_into(M, R, dx):        # M and R are rebuilt every iteration
            return math.inf
        # damping: keep steps moderate (time by at most T/8, velocities by 1)
        fac = 1.0
        big = max(abs(dx[0]), abs(dx[1]), abs(dx[2]))
        if big > 1.0:
            fac = 1.0 / big
        if abs(dx[3]) * fac > 0.125 * T:
            fac = 0.125 * T / abs(dx[3])
        for i in range(4):
            x[i] += fac * dx[i]
        # slow final convergence (near a fold): accept when the step is negligible
        if (it > 6 and res < 1e-9 * xs and fac == 1.0
                and max(abs(dx[0]), abs(dx[1]), abs(dx[2]), abs(dx[3])) <= 1e-13 * xs):
            return res
    return res if res <= 1e-10 else math.inf


# --------------------------------------------------------------------------- affine seeds

@njit(cache=True, nogil=True)
def _two_flights(osc, eta, r, omega, u, s1, s2, E, sym):
    """Residuals of the 1:1 conditions for u = (vm, vb, zb, sth, cth) (affine in u).

    sym: 4 conditions of the symmetric ansatz with s1 = T/2; else 5 conditions for flights
    s1 (L->R) and s2 (R->L).
    """
    vm, vb, zb, sth, cth = u[0], u[1], u[2], u[3], u[4]
    vp, vbp = impact_velocities(eta, r, vm, vb)
    z1, v1, _, _, _ = flow(osc, zb + 1.0, vp, sth, cth, s1)
    zb1 = zb + vbp * s1
    E[0] = z1 - zb1 + 1.0                       # arrival at R
    if sym:
        E[1] = v1 + vm
        E[2] = vbp + vb
        E[3] = zb1 + zb
        return
    c = math.cos(omega * s1)
    sn = math.sin(omega * s1)
    sth1 = sth * c + cth * sn
    cth1 = cth * c - sth * sn
    vp2, vbp2 = impact_velocities(eta, r, v1, vbp)
    z2, v2, _, _, _ = flow(osc, z1, vp2, sth1, cth1, s2)
    zb2 = zb1 + vbp2 * s2
    E[1] = z2 - zb2 - 1.0                       # arrival at L
    E[2] = v2 - vm
    E[3] = vbp2 - vb
    E[4] = zb2 - zb


@njit(cache=True, nogil=True)
def _affine(osc, eta, r, omega, s1, s2, sym, A, b):
    """E(u) = A u + b for the conditions of ``_two_flights``."""
    n = A.shape[0]
    u = np.zeros(5)
    E = np.empty(5)
    _two_flights(osc, eta, r, omega, u, s1, s2, E, sym)
    for i in range(n):
        b[i] = E[i]
    for k in range(5):
        u[:] = 0.0
        u[k] = 1.0
        _two_flights(osc, eta, r, omega, u, s1, s2, E, sym)
        for i in range(n):
            A[i, k] = E[i] - b[i]


@njit(cache=True, nogil=True)
def _s_factors(osc, s):
    """The factors of ``flow`` that depend on s only: (C, C', S, S', sin, cos of omega s)."""
    C, dC, S, dS = fundamentals(osc, s)
    w = osc[I_W]
    return C, dC, S, dS, math.sin(w * s), math.cos(w * s)


@njit(cache=True, nogil=True)
def _flow_zv(osc, x0, v0, sth0, cth0, s, fs):
    """(z, z') of ``flow`` given fs = ``_s_factors(osc, s)``, by flow's own arithmetic (same
    bits); not for the near-resonant undamped form (osc[I_NRES])."""
    C, dC, S, dS, sw, cw = fs
    omega = osc[I_W]
    res = osc[I_RES] > 0.5
    ps = osc[I_PS]
    pc = osc[I_PC]
    if res:
        zp0, zp10 = 0.0, osc[I_ARES] * cth0
    else:
        zp0, zp10 = ps * sth0 + pc * cth0, omega * (ps * cth0 - pc * sth0)
    xh = x0 - zp0
    vh = v0 - zp10
    zh = xh * C + vh * S
    zh1 = xh * dC + vh * dS
    sth = sth0 * cw + cth0 * sw
    cth = cth0 * cw - sth0 * sw
    if res:
        A = osc[I_ARES]
        zp = A * s * cth
        zp1 = A * cth - A * omega * s * sth
    else:
        zp = ps * sth + pc * cth
        zp1 = omega * (ps * cth - pc * sth)
    return zp + zh, zp1 + zh1


@njit(cache=True, nogil=True)
def _two_flights_c(osc, eta, r, u, s1, s2, f1, f2, E):
    """The 5 asymmetric conditions of ``_two_flights`` with the s-factors f1, f2 of s1, s2
    precomputed (same arithmetic, same bits)."""
    vm, vb, zb, sth, cth = u[0], u[1], u[2], u[3], u[4]
    vp, vbp = impact_velocities(eta, r, vm, vb)
    z1, v1 = _flow_zv(osc, zb + 1.0, vp, sth, cth, s1, f1)
    zb1 = zb + vbp * s1
    E[0] = z1 - zb1 + 1.0                       # arrival at R
    c = f1[5]
    sn = f1[4]
    sth1 = sth * c + cth * sn
    cth1 = cth * c - sth * sn
    vp2, vbp2 = impact_velocities(eta, r, v1, vbp)
    z2, v2 = _flow_zv(osc, z1, vp2, sth1, cth1, s2, f2)
    zb2 = zb1 + vbp2 * s2
    E[1] = z2 - zb2 - 1.0                       # arrival at L
    E[2] = v2 - vm
    E[3] = vbp2 - vb
    E[4] = zb2 - zb


@njit(cache=True, nogil=True)
def _circle_residual(osc, eta, r, omega, s1, T, u, ws):
    """sin^2 + cos^2 - 1 of the affine solution at L->R flight time s1 (nan if singular).

    ws = (A 5x5, b, E, M 5x5, v) scratch. E(u) = A u + b is built as ``_affine`` does, with
    the s-dependent factors computed once (not for the near-resonant undamped form).
    """
    A, b, E, M, v = ws
    s2 = T - s1
    if osc[I_NRES] > 0.5:
        _affine(osc, eta, r, omega, s1, s2, False, A, b)
    else:
        f1 = _s_factors(osc, s1)
        f2 = _s_factors(osc, s2)
        u[:] = 0.0
        _two_flights_c(osc, eta, r, u, s1, s2, f1, f2, E)
        for i in range(5):
            b[i] = E[i]
        for k in range(5):
            u[:] = 0.0
            u[k] = 1.0
            _two_flights_c(osc, eta, r, u, s1, s2, f1, f2, E)
            for i in range(5):
                A[i, k] = E[i] - b[i]
    for i in range(5):
        v[i] = -b[i]
        for k in range(5):
            M[i, k] = A[i, k]
    if not _solve_into(M, v, u):
        return math.nan
    return u[3] * u[3] + u[4] * u[4] - 1.0


@njit(cache=True, nogil=True)
def asymmetric_seeds(osc, eta, r, omega, n_scan, out):
    """Seeds (vm, vb, zb, theta_L, s1) from the scan of s1; returns how many (<= len(out))."""
    T = 2.0 * math.pi / omega
    u = np.empty(5)
    ws = (np.empty((5, 5)), np.empty(5), np.empty(5), np.empty((5, 5)), np.empty(5))
    n = 0
    h_prev = math.nan
    s_prev = 0.0
    for k in range(n_scan):
        s = T * (k + 0.5) / n_scan
        h = _circle_residual(osc, eta, r, omega, s, T, u, ws)
        if math.isfinite(h) and math.isfinite(h_prev) and (h > 0.0) != (h_prev > 0.0) \
                and n < out.shape[0]:
            a, fa, bb = s_prev, h_prev, s
            for _ in range(50):
                m = 0.5 * (a + bb)
                fm = _circle_residual(osc, eta, r, omega, m, T, u, ws)
                if not math.isfinite(fm):
                    break
                if (fm > 0.0) == (fa > 0.0):
                    a, fa = m, fm
                else:
                    bb = m
                if bb - a < 1e-13 * T:
                    break
            m = 0.5 * (a + bb)
            fm = _circle_residual(osc, eta, r, omega, m, T, u, ws)
            # a sign change through a pole is no root
            if math.isfinite(fm) and abs(fm) < 1e-3:
                out[n, 0], out[n, 1], out[n, 2] = u[0], u[1], u[2]
                out[n, 3] = math.atan2(u[3], u[4])
                out[n, 4] = m
                n += 1
        h_prev = h
        s_prev = s
    return n


def symmetric_seeds(osc, eta, r, omega) -> list:
    """The (0 or 2) symmetric 1:1 candidates: list of (vm, vb, zb, theta_L)."""
    T = 2.0 * math.pi / omega
    A = np.empty((4, 5))
    b = np.empty(4)
    _affine(osc, eta, r, omega, 0.5 * T, 0.5 * T, True, A, b)
    if not np.all(np.isfinite(A)) or not np.all(np.isfinite(b)):
        return []
    # general solution u = p + lam q of A u = -b
    _, sv, Vt = np.linalg.svd(A)
    if sv[-1] <= 1e-14 * sv[0]:
        return []
    q = Vt[-1]
    p = np.linalg.lstsq(A, -b, rcond=None)[0]
    # |(p3 + lam q3, p4 + lam q4)|^2 = 1 (x * x, not x ** 2: numpy's power of a float64
    # scalar can be 1 ulp off on some CPUs; this keeps ``symmetric_seeds_kernel`` equal)
    a2 = q[3] * q[3] + q[4] * q[4]
    a1 = 2.0 * (p[3] * q[3] + p[4] * q[4])
    a0 = p[3] * p[3] + p[4] * p[4] - 1.0
    disc = a1 * a1 - 4.0 * a2 * a0
    if a2 == 0.0 or disc < 0.0:
        return []
    sq = math.sqrt(disc)
    out = []
    for lam in ((-a1 - sq) / (2.0 * a2), (-a1 + sq) / (2.0 * a2)):
        u = p + lam * q
        out.append((u[0], u[1], u[2], math.atan2(u[3], u[4])))
    return out


@njit(cache=True, nogil=True)
def symmetric_seeds_kernel(osc, eta, r, omega, out):
    """Compiled ``symmetric_seeds``: rows out[k] = (vm, vb, zb, theta_L); returns 0 or 2.

    Same LAPACK routines as numpy's svd and lstsq (dgesdd, dgelsd with numpy's default
    rcond = 5 eps), so the seeds equal those of ``symmetric_seeds`` bit for bit.
    """
    T = 2.0 * math.pi / omega
    A = np.empty((4, 5))
    b = np.empty(4)
    _affine(osc, eta, r, omega, 0.5 * T, 0.5 * T, True, A, b)
    for i in range(4):
        if not math.isfinite(b[i]):
            return 0
        for k in range(5):
            if not math.isfinite(A[i, k]):
                return 0
    _, sv, Vt = np.linalg.svd(A)
    if sv[-1] <= 1e-14 * sv[0]:
        return 0
    q = Vt[-1]
    p = np.linalg.lstsq(A, -b, rcond=5.0 * 2.220446049250313e-16)[0]
    a2 = q[3] * q[3] + q[4] * q[4]
    a1 = 2.0 * (p[3] * q[3] + p[4] * q[4])
    a0 = p[3] * p[3] + p[4] * p[4] - 1.0
    disc = a1 * a1 - 4.0 * a2 * a0
    if a2 == 0.0 or disc < 0.0:
        return 0
    sq = math.sqrt(disc)
    for k in range(2):
        lam = (-a1 - sq) / (2.0 * a2) if k == 0 else (-a1 + sq) / (2.0 * a2)
        for m in range(3):
            out[k, m] = p[m] + lam * q[m]
        out[k, 3] = math.atan2(p[3] + lam * q[3], p[4] + lam * q[4])
    return 2


# --------------------------------------------------------------------------- orbits

@dataclass
class PeriodicOrbit:
    """One 1:1 orbit (fixed point of P2∘P1) and its stability.

    x_L, x_R        pre-impact states (z_m', z_b', z_b, t) at L and at R (t_L in [0, T))
    flight_times    [L->R, R->L]
    eigenvalues     of J_P2(x_R) J_P1(x_L); lambda_max = max |eigenvalue|
    stable          all |lambda| < 1 and admissible
    dw_L, dw_R      relative velocity w' = z_m' - z_b' just before the L and R impacts
    phase_L/_R      impact phases mod(omega t + phi, 2 pi)
    """

    x_L: np.ndarray
    x_R: np.ndarray
    flight_times: list
    symmetric: bool
    admissible: bool
    eigenvalues: np.ndarray
    lambda_max: float
    stable: bool
    dw_L: float
    dw_R: float
    phase_L: float
    phase_R: float
    residual: float = 0.0
    params: ModelParams | None = field(default=None, repr=False)

    def to_dict(self) -> dict:
        return {
            "symmetric": bool(self.symmetric),
            "admissible": bool(self.admissible),
            "stable": bool(self.stable),
            "lambda_max": float(self.lambda_max),
            "eigenvalues": [[float(z.real), float(z.imag)] for z in self.eigenvalues],
            "dw_L": float(self.dw_L),
            "dw_R": float(self.dw_R),
            "phase_L": float(self.phase_L),
            "phase_R": float(self.phase_R),
            "flight_times": [float(s) for s in self.flight_times],
            "x_L": [float(v) for v in self.x_L],
            "x_R": [float(v) for v in self.x_R],
        }


def solve_orbit(p: ModelParams, x0, s1=-1.0, s2=-1.0, osc=None):
    """Newton from x0 (flight-time guesses s1, s2, <= 0: first contact). PeriodicOrbit or None."""
    if osc is None:
        osc = oscillators(p)[0]
    T = p.period
    x = np.empty(4)
    xR = np.empty(4)
    J1 = np.empty((4, 4))
    J2 = np.empty((4, 4))
    fl = np.empty(2)
    x0 = np.asarray(x0, dtype=float).copy()
    res = newton_1to1(osc, p.eta, p.r, p.omega, p.phi, x0, float(s1), float(s2), x, xR, J1,
                      J2, fl)
    if not math.isfinite(res) or not np.all(np.isfinite(x)):
        return None
    if not (fl[0] > 0.0 and fl[1] > 0.0) or abs(fl[0] + fl[1] - T) > 1e-8 * (1.0 + T):
        return None
    # t_L into [0, T) (the maps commute with t -> t + T)
    k = math.floor(x[3] / T)
    if k != 0:
        x[3] -= k * T
        xR[3] -= k * T
    return _orbit(p, osc, x, xR, J1, J2, fl, res)


def _orbit(p, osc, x, xR, J1, J2, fl, res) -> PeriodicOrbit:
    adm = bool(admissible_kernel(osc, p.eta, p.r, p.omega, p.phi, x, WALL_L, WALL_R, fl[0])
               and admissible_kernel(osc, p.eta, p.r, p.omega, p.phi, xR, WALL_R, WALL_L,
                                     fl[1]))
    ev = np.linalg.eigvals(J2 @ J1)
    ev = ev[np.argsort(-np.abs(ev))]
    lam = float(np.hypot(ev.real, ev.imag).max())      # as ``_lapack.lambda_max_4``
    two_pi = 2.0 * math.pi
    return PeriodicOrbit(
        x_L=x.copy(), x_R=xR.copy(), flight_times=[float(fl[0]), float(fl[1])],
        symmetric=bool(abs(fl[0] - fl[1]) <= SYM_TOL), admissible=adm, eigenvalues=ev,
        lambda_max=lam, stable=bool(adm and lam < 1.0), dw_L=float(x[0] - x[1]),
        dw_R=float(xR[0] - xR[1]), phase_L=float(np.mod(p.omega * x[3] + p.phi, two_pi)),
        phase_R=float(np.mod(p.omega * xR[3] + p.phi, two_pi)), residual=float(res), params=p)


def _same(a: PeriodicOrbit, b: PeriodicOrbit, T: float) -> bool:
    dt = abs(a.x_L[3] - b.x_L[3]) % T
    dt = min(dt, T - dt)
    return dt <= DEDUP_TOL * (1.0 + T) and np.all(np.abs(a.x_L[:3] - b.x_L[:3])
                                                    <= DEDUP_TOL * (1.0 + np.abs(a.x_L[:3])))


def _dedup(orbits, T):
    out = []
    for o in orbits:
        if o is not None and not any(_same(o, q, T) for q in out):
            out.append(o)
    return out


def _theta_to_t(theta, p: ModelParams) -> float:
    return float(np.mod((theta - p.phi) / p.omega, p.period))


def seed_orbits(p: ModelParams, osc=None, simulation=True, scan=True) -> list:
    """Every distinct 1:1 orbit reachable from the built-in seeds (not yet sorted)."""
    if osc is None:
        osc = oscillators(p)[0]
    T = p.period
    if p.F == 0.0:
        return []
    found = []
    for vm, vb, zb, th in symmetric_seeds(osc, p.eta, p.r, p.omega):
        found.append(solve_orbit(p, [vm, vb, zb, _theta_to_t(th, p)], 0.5 * T, 0.5 * T, osc))
    if scan:
        buf = np.empty((16, 5))
        n = asymmetric_seeds(osc, p.eta, p.r, p.omega, N_SCAN, buf)
        for vm, vb, zb, th, s1 in buf[:n]:
            found.append(solve_orbit(p, [vm, vb, zb, _theta_to_t(th, p)], s1, T - s1, osc))
    if simulation:
        found.extend(_simulation_seed(p, osc))
    return _dedup(found, T)


def _simulation_seed(p: ModelParams, osc, t_end=600.0) -> list:
    from ..core.simulation import simulate_exact
    try:
        st = SolverSettings(t_end=t_end, t_transient=0.5 * t_end, max_impacts=200_000)
        res = simulate_exact(p, st)
    except Exception:                        # pragma: no cover - a seed is optional
        return []
    imp = res.impacts
    w = imp["wall"]
    idx = np.nonzero((w[:-2] == WALL_L) & (w[1:-1] == WALL_R) & (w[2:] == WALL_L))[0]
    if idx.size == 0:
        return []
    k = idx[-1]
    x0 = [imp["v_m"][k], imp["v_b"][k], imp["z_b"][k], imp["t"][k]]
    return [solve_orbit(p, x0, imp["t"][k + 1] - imp["t"][k], imp["t"][k + 2] - imp["t"][k + 1],
                        osc)]


def _sort_key(o: PeriodicOrbit):
    return (not o.admissible, not o.stable, not o.symmetric, o.lambda_max)


def find_1to1(eta: float, omega: float, F: float, r: float = R_DEFAULT, d: float = D_DEFAULT,
              phi: float = 0.0, seeds=None, simulation: bool = True) -> list[PeriodicOrbit]:
    """Every distinct 1:1 orbit found (admissible or not), stable admissible ones first.

    ``seeds``: extra starting points, each an x_L = (z_m', z_b', z_b, t_L) or a pair
    (x_L, (s1, s2)) with flight-time guesses; ``simulation=False`` skips the short
    simulation seed.
    """
    p = ModelParams(eta=eta, omega=omega, F=F, r=r, d=d, phi=phi)
    return orbits_1to1(p, seeds=check_seeds(seeds),
                       simulation=check_bool("simulation", simulation))


SEEDS_ALLOWED = ("must be None or a list of seeds, each a PeriodicOrbit, an x_L = "
                 "(z_m', z_b', z_b, t_L) of 4 finite numbers or a pair (x_L, (s1, s2))")


def check_seeds(seeds) -> list:
    """The seeds of ``find_1to1`` as a list of PeriodicOrbit or (x_L, (s1, s2)) (s <= 0: first
    contact, as ``solve_orbit``); ParameterError naming ``seeds`` otherwise."""
    if seeds is None:
        return []
    if isinstance(seeds, (str, bytes, dict)) or not hasattr(seeds, "__iter__"):
        raise ParameterError("seeds", seeds, SEEDS_ALLOWED)
    out = []
    for sd in seeds:
        if isinstance(sd, PeriodicOrbit):
            out.append(sd)
            continue
        try:
            pair = len(sd) == 2 and not isinstance(sd, str)
            x_L, flights = (sd[0], sd[1]) if pair else (sd, (-1.0, -1.0))
            out.append((check_reals("seeds", x_L, min_size=4, max_size=4),
                        tuple(check_reals("seeds", flights, min_size=2, max_size=2))))
        except (TypeError, ParameterError):
            raise ParameterError("seeds", seeds, SEEDS_ALLOWED) from None
    return out


def orbits_1to1(p: ModelParams, *, seeds=None, simulation: bool = True) -> list[PeriodicOrbit]:
    """``find_1to1`` at the validated model ``p``."""
    osc = oscillators(p)[0]
    found = seed_orbits(p, osc, simulation=simulation)
    for sd in seeds or ():
        if isinstance(sd, PeriodicOrbit):
            found.append(solve_orbit(p, sd.x_L, *sd.flight_times, osc=osc))
        elif len(sd) == 2:      # (x_L, (s1, s2)), as ``check_seeds`` returns them
            found.append(solve_orbit(p, sd[0], sd[1][0], sd[1][1], osc))
        else:
            found.append(solve_orbit(p, sd, osc=osc))
    out = _dedup(found, p.period)
    out.sort(key=_sort_key)
    return out


# --------------------------------------------------------------------------- compiled candidates
# nogil versions of solve_orbit / seed_orbits(simulation=False) for per-point drivers that
# run on threads (``stability_map``). An orbit is a row of floats (ROW_* columns); the
# arithmetic is that of the Python functions above, so the rows equal their PeriodicOrbits
# (lambda_max of admissible orbits: the same dgeev; see ``_lapack``).

ROW_X, ROW_FL, ROW_ADM, ROW_LAM, ROW_SYM, ROW_DWL = 0, 4, 6, 7, 8, 9
N_ROW = 10                  # callers may append their own columns after these
N_SEED_MAX = 2 + 16         # symmetric + asymmetric seeds of one parameter point


@njit(cache=True, nogil=True)
def orbit_workspace():
    """Scratch of ``orbit_solve``/``orbit_classify``: (x0, x, xR, J1, J2, fl, M, a, wr, wi,
    work); x0 is the starting point, the rest is filled by the solve."""
    return (np.empty(4), np.empty(4), np.empty(4), np.empty((4, 4)), np.empty((4, 4)),
            np.empty(2), np.empty((4, 4)), np.empty(16), np.empty(4), np.empty(4),
            np.empty(64))


@njit(cache=True, nogil=True)
def orbit_solve(osc, eta, r, omega, phi, s1, s2, row, ws):
    """Newton part of ``solve_orbit`` from ws[0] = x0: fills row's x_L (t_L in [0, T)) and
    flight times; False where solve_orbit gives None. ``orbit_classify`` completes the row."""
    x0, x, xR, J1, J2, fl = ws[0], ws[1], ws[2], ws[3], ws[4], ws[5]
    T = 2.0 * math.pi / omega
    res = newton_1to1(osc, eta, r, omega, phi, x0, s1, s2, x, xR, J1, J2, fl)
    if not math.isfinite(res):
        return False
    for i in range(4):
        if not math.isfinite(x[i]):
            return False
    if not (fl[0] > 0.0 and fl[1] > 0.0) or abs(fl[0] + fl[1] - T) > 1e-8 * (1.0 + T):
        return False
    k = math.floor(x[3] / T)
    if k != 0:
        x[3] -= k * T
        xR[3] -= k * T
    for i in range(4):
        row[ROW_X + i] = x[i]
    row[ROW_FL] = fl[0]
    row[ROW_FL + 1] = fl[1]
    return True


@njit(cache=True, nogil=True)
def orbit_classify(osc, eta, r, omega, phi, row, ws):
    """Admissibility, symmetry, dw_L and, for admissible orbits only, lambda_max (nan
    otherwise) of the orbit the last ``orbit_solve`` with ws found (as ``_orbit``).

    An admissible orbit whose monodromy matrix is not finite (numpy's eigvals would raise)
    is marked non-admissible.
    """
    x, xR, J1, J2, fl, M, a, wr, wi, work = ws[1:]
    adm = (admissible_kernel(osc, eta, r, omega, phi, x, WALL_L, WALL_R, fl[0])
           and admissible_kernel(osc, eta, r, omega, phi, xR, WALL_R, WALL_L, fl[1]))
    lam = math.nan
    if adm:
        np.dot(J2, J1, M)
        lam = lambda_max_4(M, a, wr, wi, work)
        adm = math.isfinite(lam)
    row[ROW_ADM] = 1.0 if adm else 0.0
    row[ROW_LAM] = lam
    row[ROW_SYM] = 1.0 if abs(fl[0] - fl[1]) <= SYM_TOL else 0.0
    row[ROW_DWL] = x[0] - x[1]


@njit(cache=True, nogil=True)
def same_rows(a, b, T):
    """``_same`` on rows (a the new orbit, b a kept one)."""
    dt = abs(a[ROW_X + 3] - b[ROW_X + 3]) % T
    dt = min(dt, T - dt)
    if not dt <= DEDUP_TOL * (1.0 + T):
        return False
    for i in range(3):
        if not abs(a[ROW_X + i] - b[ROW_X + i]) <= DEDUP_TOL * (1.0 + abs(a[ROW_X + i])):
            return False
    return True


@njit(cache=True, nogil=True)
def seed_kernel(osc, eta, r, omega, phi, F, rows, ws):
    """Compiled ``seed_orbits(simulation=False)``: distinct orbits into rows[:n]; returns n.

    rows needs N_SEED_MAX rows (of >= N_ROW columns). Duplicates are dropped before
    ``orbit_classify`` (their admissibility and eigenvalues are never needed).
    """
    if F == 0.0:
        return 0
    T = 2.0 * math.pi / omega
    x0 = ws[0]
    buf = np.empty((16, 5))
    n = 0
    ns = symmetric_seeds_kernel(osc, eta, r, omega, buf)
    for k in range(ns):
        x0[0], x0[1], x0[2] = buf[k, 0], buf[k, 1], buf[k, 2]
        x0[3] = np.mod((buf[k, 3] - phi) / omega, T)
        if orbit_solve(osc, eta, r, omega, phi, 0.5 * T, 0.5 * T, rows[n], ws) \
                and _is_new(rows, n, T):
            orbit_classify(osc, eta, r, omega, phi, rows[n], ws)
            n += 1
    na = asymmetric_seeds(osc, eta, r, omega, N_SCAN, buf)
    for k in range(na):
        x0[0], x0[1], x0[2] = buf[k, 0], buf[k, 1], buf[k, 2]
        x0[3] = np.mod((buf[k, 3] - phi) / omega, T)
        s1 = buf[k, 4]
        if orbit_solve(osc, eta, r, omega, phi, s1, T - s1, rows[n], ws) \
                and _is_new(rows, n, T):
            orbit_classify(osc, eta, r, omega, phi, rows[n], ws)
            n += 1
    return n


@njit(cache=True, nogil=True)
def _is_new(rows, n, T):
    """rows[n] is not ``same_rows`` as any of rows[:n]."""
    for q in range(n):  # noqa: SIM110 (numba: no generator in all())
        if same_rows(rows[n], rows[q], T):
            return False
    return True
