"""Seeds of periodic orbits from the affine forms of the flight conditions.

With the flight times fixed, a chain of flights from the pre-impact state u = (z_m', z_b',
z_b, sin theta_0, cos theta_0) at a wall is affine in u: the flow is linear in the initial
state and in the sine and cosine of the forcing phase, the impact law is linear. The
conditions (arrival at each next wall, closure of the velocities and position on the start,
or on its mirror image for the half-period symmetry) are E(u) = A u + b, and an orbit needs
sin^2 + cos^2 = 1:

* one flight of fixed time S: 4 conditions in 5 unknowns, a line meeting the unit circle,
  0 or 2 seeds in closed form (``closed_form_kernel``);
* two flights s0, S - s0: 5 conditions, one solution per s0; s0 is scanned over (0, S) and
  the sign changes of sin^2 + cos^2 - 1 are refined by bisection (``scan_seeds``).

A seed is a row (z_m', z_b', z_b, theta_0[, s0]); ``newton.newton_sequence`` polishes it on
the true maps.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..core.flow import I_W, flow
from ..core.walls import impact_velocities
from .maps import M_ETA, M_R
from .newton import solve_into

N_SCAN = 96             # s0 samples of a scan
N_SEEDS_MAX = 16        # most seeds of one scan


@njit(cache=True, nogil=True)
def _chain(mdl, u, w, s, sign, carry, E):
    """Residuals of m = s.size flights with fixed times s from u at wall w[0]: arrivals at
    w[1], ..., w[m-1], then sign * w[0]; closure of (z_m', z_b', z_b) on sign times the
    start (sign -1: mirror image). A flight starts at its wall (carry False) or where the
    previous flight ended (carry True: the form of the 1:1 scan). Affine in u; m + 3
    residuals."""
    eta, r, omega = mdl[M_ETA], mdl[M_R], mdl[I_W]
    m = s.size
    vm, vb, zb, sth, cth = u[0], u[1], u[2], u[3], u[4]
    z = zb + w[0]
    for k in range(m):
        target = w[k + 1] if k + 1 < m else sign * w[0]
        vp, vbp = impact_velocities(eta, r, vm, vb)
        z0 = z if carry and k > 0 else zb + w[k]
        z, v, _, _, _ = flow(mdl, z0, vp, sth, cth, s[k])
        zb = zb + vbp * s[k]
        E[k] = z - zb - target
        c = math.cos(omega * s[k])
        sn = math.sin(omega * s[k])
        sth, cth = sth * c + cth * sn, cth * c - sth * sn
        vm, vb = v, vbp
    E[m] = vm - sign * u[0]
    E[m + 1] = vb - sign * u[1]
    E[m + 2] = zb - sign * u[2]


@njit(cache=True, nogil=True)
def affine_chain(mdl, w, s, sign, carry, A, b):
    """E(u) = A u + b for ``_chain`` (A: (m+3) x 5)."""
    m = s.size
    u = np.zeros(5)
    E = np.empty(m + 3)
    _chain(mdl, u, w, s, sign, carry, E)
    for i in range(m + 3):
        b[i] = E[i]
    for k in range(5):
        u[:] = 0.0
        u[k] = 1.0
        _chain(mdl, u, w, s, sign, carry, E)
        for i in range(m + 3):
            A[i, k] = E[i] - b[i]


@njit(cache=True, nogil=True)
def _circle2(mdl, w, s0, S, sign, carry, u):
    """sin^2 + cos^2 - 1 of the affine solution u of two flights s0, S - s0 (nan if
    singular)."""
    s = np.empty(2)
    s[0], s[1] = s0, S - s0
    A = np.empty((5, 5))
    b = np.empty(5)
    affine_chain(mdl, w, s, sign, carry, A, b)
    for i in range(5):
        b[i] = -b[i]
    if not solve_into(A, b, u):
        return math.nan
    return u[3] * u[3] + u[4] * u[4] - 1.0


@njit(cache=True, nogil=True)
def scan_seeds(mdl, w, S, sign, carry, out):
    """Two-flight seeds (z_m', z_b', z_b, theta_0, s0) from a scan of s0 over (0, S) (N_SCAN
    samples) with sign changes of the circle residual refined by bisection (a sign change
    through a pole is no root); returns how many (<= len(out))."""
    u = np.empty(5)
    n = 0
    h_prev = math.nan
    s_prev = 0.0
    for k in range(N_SCAN):
        sk = S * (k + 0.5) / N_SCAN
        h = _circle2(mdl, w, sk, S, sign, carry, u)
        if math.isfinite(h) and math.isfinite(h_prev) and (h > 0.0) != (h_prev > 0.0) \
                and n < out.shape[0]:
            a, fa, bb = s_prev, h_prev, sk
            for _ in range(50):
                mid = 0.5 * (a + bb)
                fm = _circle2(mdl, w, mid, S, sign, carry, u)
                if not math.isfinite(fm):
                    break
                if (fm > 0.0) == (fa > 0.0):
                    a, fa = mid, fm
                else:
                    bb = mid
                if bb - a < 1e-13 * S:
                    break
            mid = 0.5 * (a + bb)
            fm = _circle2(mdl, w, mid, S, sign, carry, u)
            if math.isfinite(fm) and abs(fm) < 1e-3:
                out[n, 0], out[n, 1], out[n, 2] = u[0], u[1], u[2]
                out[n, 3] = math.atan2(u[3], u[4])
                out[n, 4] = mid
                n += 1
        h_prev = h
        s_prev = sk
    return n


@njit(cache=True, nogil=True)
def closed_form_kernel(mdl, w, S, sign, out):
    """One flight of time S from wall w[0]: the line of solutions of the 4 affine conditions
    meets the unit circle in rows out[k] = (z_m', z_b', z_b, theta_0); returns 0 or 2.

    The line from LAPACK's dgesdd (null vector) and dgelsd (rcond = 5 eps, numpy's default
    for a 4 x 5 matrix), as numpy's svd and lstsq compute it.
    """
    A = np.empty((4, 5))
    b = np.empty(4)
    s = np.empty(1)
    s[0] = S
    affine_chain(mdl, w, s, sign, False, A, b)
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
    # |(p3 + lam q3, p4 + lam q4)|^2 = 1 (x * x, not x ** 2)
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


def closed_form_seeds(mdl: np.ndarray, w: np.ndarray, S: float, sign: int) -> list:
    """``closed_form_kernel`` as a list of (z_m', z_b', z_b, theta_0)."""
    out = np.empty((2, 4))
    n = closed_form_kernel(mdl, w, float(S), int(sign), out)
    return [tuple(float(v) for v in row) for row in out[:n]]


def scan(mdl: np.ndarray, w: np.ndarray, S: float, sign: int, carry: bool = False) -> np.ndarray:
    """``scan_seeds`` as an array of rows (z_m', z_b', z_b, theta_0, s0)."""
    out = np.empty((N_SEEDS_MAX, 5))
    n = scan_seeds(mdl, w, float(S), int(sign), bool(carry), out)
    return out[:n]
