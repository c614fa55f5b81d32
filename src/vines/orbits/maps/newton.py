"""Newton on composed impact maps: the one fixed-point iteration of every periodic orbit.

An orbit of the wall sequence walls[0], ..., walls[n-1] (periods forcing periods, NT =
periods T) is a fixed point of P_{n-1}∘...∘P_0 shifted in time: the pre-impact states
x_0 .. x_{n-1} (x = (z_m', z_b', z_b, t), ``maps``) with P_{n-1}(x_{n-1}) = x_0 + (0, 0, 0,
NT). ``newton_sequence`` runs a damped Newton iteration on x_0 with the exact Jacobian
J_{n-1} ... J_0 - I; the 1:1 orbits (``periodic``) are the sequence "LR", 1 of it and the
other families (``sequence``) the rest.
"""
from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..._jit import njit
from ...core.flow import I_W
from .impact import impact_map


@njit(cache=True, nogil=True)
def solve_into(M, v, out):
    """Gaussian elimination with partial pivoting of M out = v, overwriting M and v (no
    allocation); False when M is (numerically) singular."""
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


@njit(cache=True, nogil=True)
def newton_sequence(mdl, walls, NT, x0, s, xs, Js, P):
    """Newton on P_{n-1}(...P_0(x)) - x - (0, 0, 0, NT) from x0 (mdl: ``maps.pack_model``).

    walls: n wall codes (flight k from walls[k] to walls[(k+1) % n]); s: flight-time guesses
    (<= 0: first contact), overwritten with the flight times. Fills xs (n+1 states, xs[0] the
    fixed point, xs[k+1] = P_k(xs[k])), Js (the n map Jacobians) and P (their product
    J_{n-1} ... J_0). Returns the residual norm (inf on failure). Steps are damped: the
    velocities and position by at most 1, the time by at most T/8.
    """
    n = walls.size
    x = xs[0]
    for i in range(4):
        x[i] = x0[i]
    R = np.empty(4)
    M = np.empty((4, 4))
    Q = np.empty((4, 4))
    dx = np.empty(4)
    res = math.inf
    for it in range(40):
        for k in range(n):
            sk = impact_map(mdl, xs[k], (walls[k], walls[(k + 1) % n]), s[k], xs[k + 1],
                            Js[k])
            if not math.isfinite(sk):
                return math.inf
            s[k] = sk
        res = 0.0
        xsc = 1.0
        for i in range(4):
            R[i] = xs[n, i] - x[i]
            xsc = max(xsc, abs(x[i]))
        R[3] -= NT
        for i in range(4):
            res = max(res, abs(R[i]))
        _product(Js, P, Q)
        if res <= 1e-13 * xsc:
            return res
        for i in range(4):
            for k in range(4):
                M[i, k] = P[i, k] - (1.0 if i == k else 0.0)
        for i in range(4):
            R[i] = -R[i]
        if not solve_into(M, R, dx):        # M and R are rebuilt every iteration
            return math.inf
        fac = 1.0
        big = max(abs(dx[0]), abs(dx[1]), abs(dx[2]))
        if big > 1.0:
            fac = 1.0 / big
        T = 2.0 * math.pi / mdl[I_W]
        if abs(dx[3]) * fac > 0.125 * T:
            fac = 0.125 * T / abs(dx[3])
        for i in range(4):
            x[i] += fac * dx[i]
        # slow final convergence (near a fold): accept when the step is negligible
        if (it > 6 and res < 1e-9 * xsc and fac == 1.0
                and max(abs(dx[0]), abs(dx[1]), abs(dx[2]), abs(dx[3])) <= 1e-13 * xsc):
            return res
    return res if res <= 1e-10 else math.inf


@njit(cache=True, nogil=True)
def _product(Js, P, Q):
    """P = J_{n-1} ... J_0 (sums in the order of the matrix index m)."""
    n = Js.shape[0]
    for i in range(4):
        for k in range(4):
            P[i, k] = Js[0, i, k]
    for j in range(1, n):
        for i in range(4):
            for k in range(4):
                acc = 0.0
                for m in range(4):
                    acc += Js[j, i, m] * P[m, k]
                Q[i, k] = acc
        for i in range(4):
            for k in range(4):
                P[i, k] = Q[i, k]


def monodromy(jacobians: Sequence[np.ndarray]) -> np.ndarray:
    """J_{n-1} ... J_0 by numpy matmul (for n = 2: J2 @ J1 as ``family.periodic``)."""
    P = jacobians[0]
    for J in jacobians[1:]:
        P = J @ P
    return P
