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

from ..._jit import njit
from ...core.flow import I_NRES, I_W, flow, flow_zv, s_factors
from ...core.walls import impact_velocities
from .impact import M_ETA, M_R
from .newton import solve_into

N_SCAN = 96             # s0 samples of a scan
N_SEEDS_MAX = 16        # most seeds of one scan


@njit(cache=True, nogil=True)
def _flight(mdl, start, s, f):
    """(z, z', sin, cos of omega s) after a flight of time s from start = (z, z', sin, cos
    of theta); f: ``flow.s_factors`` of s, or None (the near-resonant undamped oscillator:
    ``flow`` itself)."""
    if f is None:
        z, v, _, _, _ = flow(mdl, start[0], start[1], start[2], start[3], s)
        w = mdl[I_W]
        return z, v, math.sin(w * s), math.cos(w * s)
    z, v = flow_zv(mdl, start, s, f)
    return z, v, f[4], f[5]


@njit(cache=True, nogil=True)
def _chain(mdl, u, legs, f1, f2, E):
    """Residuals of one or two flights from u at wall w0, legs = (m, w0, w1, s0, s1, sign,
    carry): flights of fixed times s0 (and s1), arrival at w1 (two flights), then at
    sign * w0; closure of (z_m', z_b', z_b) on sign times the start (sign -1: mirror image).
    The second flight starts at its wall (carry False) or where the first one ended (carry
    True: the form of the 1:1 scan). f1, f2: the ``flow.s_factors`` of s0, s1 (f2 unused
    for one flight), or None (``_flight``). Affine in u; m + 3 residuals."""
    m, w0, w1, s0, s1, sign, carry = legs
    eta, r = mdl[M_ETA], mdl[M_R]
    vm, vb, zb, sth, cth = u[0], u[1], u[2], u[3], u[4]
    vp, vbp = impact_velocities(eta, r, vm, vb)
    z, v, sn, c = _flight(mdl, (zb + w0, vp, sth, cth), s0, f1)
    zb = zb + vbp * s0
    if m == 2:
        E[0] = z - zb - w1
        sth, cth = sth * c + cth * sn, cth * c - sth * sn
        vp, vbp = impact_velocities(eta, r, v, vbp)
        z0 = z if carry else zb + w1
        z, v, _, _ = _flight(mdl, (z0, vp, sth, cth), s1, f2)
        zb = zb + vbp * s1
    E[m - 1] = z - zb - sign * w0
    E[m] = v - sign * u[0]
    E[m + 1] = vbp - sign * u[1]
    E[m + 2] = zb - sign * u[2]


@njit(cache=True, nogil=True)
def chain_workspace(m):
    """Scratch of ``affine_chain`` for m flights: (u, E)."""
    return np.empty(5), np.empty(m + 3)


@njit(cache=True, nogil=True)
def affine_chain(mdl, chain, A, b, ws):
    """E(u) = A u + b for ``_chain`` of chain = (w, s, mode) (A: (m+3) x 5); ws:
    ``chain_workspace(m)``. The s-dependent factors of the flows are computed once."""
    s = chain[1]
    if mdl[I_NRES] > 0.5:
        _fill_affine(mdl, chain, (None, None), A, b, ws)
    else:
        f1 = s_factors(mdl, s[0])
        f2 = s_factors(mdl, s[1]) if s.size == 2 else f1
        _fill_affine(mdl, chain, (f1, f2), A, b, ws)


@njit(cache=True, nogil=True)
def _fill_affine(mdl, chain, fs, A, b, ws):
    """``affine_chain`` given fs = (f1, f2) of ``_chain``."""
    w, s, mode = chain
    f1, f2 = fs
    m = s.size
    legs = (m, w[0], w[1] if m == 2 else w[0], s[0], s[1] if m == 2 else s[0]) + mode
    u, E = ws
    u[:] = 0.0
    _chain(mdl, u, legs, f1, f2, E)
    for i in range(m + 3):
        b[i] = E[i]
    for k in range(5):
        u[:] = 0.0
        u[k] = 1.0
        _chain(mdl, u, legs, f1, f2, E)
        for i in range(m + 3):
            A[i, k] = E[i] - b[i]


@njit(cache=True, nogil=True)
def _lr_chain(mdl, u, s1, s2, f1, f2, E):
    """``_chain`` of the 1:1 scan (walls L, R, sign 1, carry, factors f1, f2) written out on
    scalars, bit for bit (tests): the generic form runs the 1:1 scan, the main cost of a
    stability map, about 1.5 times slower."""
    eta, r = mdl[M_ETA], mdl[M_R]
    vm, vb, zb, sth, cth = u[0], u[1], u[2], u[3], u[4]
    vp, vbp = impact_velocities(eta, r, vm, vb)
    z1, v1 = flow_zv(mdl, (zb + 1.0, vp, sth, cth), s1, f1)
    zb1 = zb + vbp * s1
    E[0] = z1 - zb1 + 1.0
    c = f1[5]
    sn = f1[4]
    sth1 = sth * c + cth * sn
    cth1 = cth * c - sth * sn
    vp2, vbp2 = impact_velocities(eta, r, v1, vbp)
    z2, v2 = flow_zv(mdl, (z1, vp2, sth1, cth1), s2, f2)
    zb2 = zb1 + vbp2 * s2
    E[1] = z2 - zb2 - 1.0
    E[2] = v2 - vm
    E[3] = vbp2 - vb
    E[4] = zb2 - zb


@njit(cache=True, nogil=True)
def _circle2(mdl, chain, s0, S, scratch):
    """sin^2 + cos^2 - 1 of the affine solution (scratch[2]) of the two flights s0, S - s0 of
    chain (nan if singular); scratch = (A, b, u, ``chain_workspace(2)``)."""
    A, b, u, ws = scratch
    s = chain[1]
    s[0], s[1] = s0, S - s0
    if chain[2][1] and mdl[I_NRES] < 0.5:
        f1 = s_factors(mdl, s[0])
        f2 = s_factors(mdl, s[1])
        E = ws[1]
        u[:] = 0.0
        _lr_chain(mdl, u, s[0], s[1], f1, f2, E)
        for i in range(5):
            b[i] = E[i]
        for k in range(5):
            u[:] = 0.0
            u[k] = 1.0
            _lr_chain(mdl, u, s[0], s[1], f1, f2, E)
            for i in range(5):
                A[i, k] = E[i] - b[i]
    else:
        affine_chain(mdl, chain, A, b, ws)
    for i in range(5):
        b[i] = -b[i]
    if not solve_into(A, b, u):
        return math.nan
    return u[3] * u[3] + u[4] * u[4] - 1.0


@njit(cache=True, nogil=True)
def scan_seeds(mdl, w, S, sign, carry, out):
    """Two-flight seeds (z_m', z_b', z_b, theta_0, s0) of the chain (w, (s0, S - s0), (sign,
    carry)) (``_chain``) from a scan of s0 over (0, S) (N_SCAN samples) with sign changes of
    the circle residual refined by bisection (a sign change through a pole is no root);
    returns how many (<= len(out))."""
    chain = (w, np.empty(2), (sign, carry))
    scratch = (np.empty((5, 5)), np.empty(5), np.empty(5), chain_workspace(2))
    u = scratch[2]
    n = 0
    h_prev = math.nan
    s_prev = 0.0
    for k in range(N_SCAN):
        sk = S * (k + 0.5) / N_SCAN
        h = _circle2(mdl, chain, sk, S, scratch)
        if math.isfinite(h) and math.isfinite(h_prev) and (h > 0.0) != (h_prev > 0.0) \
                and n < out.shape[0]:
            a, fa, bb = s_prev, h_prev, sk
            for _ in range(50):
                mid = 0.5 * (a + bb)
                fm = _circle2(mdl, chain, mid, S, scratch)
                if not math.isfinite(fm):
                    break
                if (fm > 0.0) == (fa > 0.0):
                    a, fa = mid, fm
                else:
                    bb = mid
                if bb - a < 1e-13 * S:
                    break
            mid = 0.5 * (a + bb)
            fm = _circle2(mdl, chain, mid, S, scratch)
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
    # np.bool_: typed as in _circle2's chains (a literal compiles a second specialization)
    affine_chain(mdl, (w, s, (sign, np.bool_(False))), A, b, chain_workspace(1))
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
