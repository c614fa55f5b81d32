"""Compiled exact derivatives of the 1:1 shooting systems (``shooting``, ``augmented``).

The same closed-form flight as ``shooting.flight`` / ``shooting.lo_state``, evaluated on
Taylor jets stored as flat arrays: a = (value, gradient (NL), Hessian (NL x NL, row-major))
over the NL = 8 local variables (z_m', z_b', z_b, t, s, eta, omega, F) of one flight; an
order-1 jet is the first 1 + NL entries. A flight's outputs (y = (z_m', z_b', z_b, t) at
s, gap, w') are then re-expressed over the global unknowns (u, eta, omega, F, s_g) by the
chain rule, with inner[k] = the global gradient of local variable k (as in
``shooting.map_jacobian_jets``). ``jets`` and ``shooting`` hold the reference (pure
Python) implementation that the tests compare these kernels against.

Codes: family 0 symmetric, 1 asymmetric; condition 0 fold det(A - I), 1 det(A + I)
(symmetry-breaking / flip), 2 neimark-sacker det(A (x) A - I), 3 grazing; grazing wall 0
start, 1 target, 2 arrival. Global columns: u (nu), eta, omega, F, s_g (always present;
zero where unused).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

NL = 8                       # local variables of one flight
N1 = 1 + NL                  # length of an order-1 jet
N2 = 1 + NL + NL * NL        # length of an order-2 jet
WALL_L, WALL_R = 1.0, -1.0   # as core.walls (w = z_m - z_b at the left / right wall)
KW = dict(cache=True, nogil=True, error_model="numpy")


# ------------------------------------------------------------------ jet arithmetic

@njit(**KW)
def _mul(a, b):
    out = a[0] * b + b[0] * a
    out[0] = a[0] * b[0]
    if a.size == N2:
        for i in range(NL):
            ai, bi = a[1 + i], b[1 + i]
            if ai != 0.0 or bi != 0.0:
                for j in range(NL):
                    out[N1 + i * NL + j] += ai * b[1 + j] + bi * a[1 + j]
    return out


@njit(**KW)
def _unary(x, f, f1, f2):
    """Chain rule for a scalar function with value f, derivatives f1, f2 at x[0]."""
    out = f1 * x
    out[0] = f
    if x.size == N2:
        for i in range(NL):
            if x[1 + i] != 0.0:
                for j in range(NL):
                    out[N1 + i * NL + j] += f2 * x[1 + i] * x[1 + j]
    return out


@njit(**KW)
def _div(a, b):
    q = 1.0 / b[0]
    return _mul(a, _unary(b, q, -q * q, 2.0 * q * q * q))


@njit(**KW)
def _addc(a, c):
    out = a.copy()
    out[0] += c
    return out


@njit(**KW)
def _sin(x):
    s, c = math.sin(x[0]), math.cos(x[0])
    return _unary(x, s, c, -s)


@njit(**KW)
def _cos(x):
    s, c = math.sin(x[0]), math.cos(x[0])
    return _unary(x, c, -s, -c)


@njit(**KW)
def _exp(x):
    e = math.exp(x[0])
    return _unary(x, e, e, e)


# ------------------------------------------------------------------ the flight on jets

@njit(**KW)
def _lo_state(d, sigma, wd, z0, v0, th0, s, omega, F):
    """(z_m, z_m') at local time s (``shooting.lo_state``) on jets."""
    det = _addc(-_mul(omega, omega), 1.0)
    dw = d * omega
    dw2 = _mul(dw, dw)
    den = _mul(det, det) + dw2
    ps = _div(_mul(F, det + dw2), den)
    pc = _div(-d * _mul(_mul(_mul(F, omega), omega), omega), den)
    s0, c0 = _sin(th0), _cos(th0)
    th = th0 + _mul(omega, s)
    s1, c1 = _sin(th), _cos(th)
    zp0 = _mul(ps, s0) + _mul(pc, c0)
    zp10 = _mul(omega, _mul(ps, c0) - _mul(pc, s0))
    zp = _mul(ps, s1) + _mul(pc, c1)
    zp1 = _mul(omega, _mul(ps, c1) - _mul(pc, s1))
    e = _exp(-sigma * s)
    ecw = _mul(e, _cos(wd * s))
    S = _mul(e, _sin(wd * s)) / wd
    C = ecw + sigma * S
    dS = ecw - sigma * S
    xh, vh = z0 - zp0, v0 - zp10
    return zp + _mul(xh, C) + _mul(vh, S), zp1 - _mul(xh, S) + _mul(vh, dS)


@njit(**KW)
def flight_local(model, x, s, eta, omega, F, from_wall, size):
    """Rows (z_m', z_b', z_b, t at s, gap, w') of ``shooting.flight`` as jets of length
    ``size`` (N1 or N2) over the local variables; model = (r, d, phi, sigma, wd)."""
    r, d, phi, sigma, wd = model[0], model[1], model[2], model[3], model[4]
    v = np.zeros((NL, size))
    for k, val in enumerate((x[0], x[1], x[2], x[3], s, eta, omega, F)):
        v[k, 0] = val
        v[k, 1 + k] = 1.0
    vm, vb, zb, t, sj, etaj, omj, Fj = v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]
    one = _addc(etaj, 1.0)
    vp = _div(_mul(_addc(-r * etaj, 1.0), vm) + (1.0 + r) * _mul(etaj, vb), one)
    vbp = _div((1.0 + r) * vm + _mul(_addc(etaj, -r), vb), one)
    z, vel = _lo_state(d, sigma, wd, _addc(zb, from_wall), vp, _addc(_mul(omj, t), phi),
                       sj, omj, Fj)
    zb1 = zb + _mul(vbp, sj)
    out = np.empty((6, size))
    out[0], out[1], out[2], out[3] = vel, vbp, zb1, t + sj
    out[4] = _addc(z - zb1, from_wall)
    out[5] = vel - vbp
    return out


@njit(**KW)
def _global(Y, inner):
    """(values, gradients over the global variables) of local jets Y."""
    return Y[:, 0].copy(), Y[:, 1:N1] @ inner


@njit(**KW)
def _map_jac(Y, inner):
    """Jacobian (4x4) of the map whose flight is Y (order 2, the impact time solved from
    gap = 0 as in ``maps.map_kernel``) and its gradients (4, 4, N) over the globals."""
    gap = Y[4]
    gs = gap[1 + 4]
    Hgap = gap[N1:].reshape(NL, NL)
    J = np.empty((4, 4))
    dJ = np.empty((4, 4, inner.shape[1]))
    for i in range(4):
        yi = Y[i]
        ys = yi[1 + 4]
        Hy = yi[N1:].reshape(NL, NL)
        for k in range(4):
            gk = gap[1 + k]
            J[i, k] = yi[1 + k] - ys * gk / gs
            loc = Hy[k] - (Hy[4] * gk + ys * Hgap[k]) / gs + (ys * gk / (gs * gs)) * Hgap[4]
            dJ[i, k] = loc @ inner
    return J, dJ


# ------------------------------------------------------------------ the shooting systems

@njit(**KW)
def _inner(n_glob, cols, grads):
    """inner (NL, n_glob): row k = grads[k] if cols[k] < 0 else the unit row cols[k]."""
    inner = np.zeros((NL, n_glob))
    for k in range(NL):
        if cols[k] >= 0:
            inner[k, cols[k]] = 1.0
        else:
            inner[k] = grads[k]
    return inner


@njit(**KW)
def _flights(model, fam, u, eta, omega, F, size):
    """The flights of the orbit u: (Y1, inner1, Y2, inner2, n_glob); Y2 is Y1 for the
    symmetric family (whose residual uses one flight)."""
    nu = 4 + fam
    n_glob = nu + 4
    ie, io, iF = nu, nu + 1, nu + 2
    T = 2.0 * math.pi / omega
    grads = np.zeros((NL, n_glob))
    cols = np.array([0, 1, 2, 3, 4, ie, io, iF])
    if fam == 0:
        cols[4] = -1
        grads[4, io] = -0.5 * T / omega
        s1 = 0.5 * T
    else:
        s1 = u[4]
    inner1 = _inner(n_glob, cols, grads)
    Y1 = flight_local(model, u, s1, eta, omega, F, WALL_L, size)
    if fam == 0:
        return Y1, inner1, Y1, inner1, n_glob
    y1, gy1 = _global(Y1, inner1)
    cols2 = np.array([-1, -1, -1, -1, -1, ie, io, iF])
    grads2 = np.zeros((NL, n_glob))
    grads2[:4] = gy1[:4]
    grads2[4, 4] = -1.0
    grads2[4, io] = -T / omega
    inner2 = _inner(n_glob, cols2, grads2)
    Y2 = flight_local(model, y1, T - u[4], eta, omega, F, WALL_R, size)
    return Y1, inner1, Y2, inner2, n_glob


@njit(**KW)
def _residual(fam, u, Y1, inner1, Y2, inner2, n_glob):
    """E and dE/d(globals) (``shooting.residual``)."""
    nu = 4 + fam
    E = np.empty(nu)
    dE = np.zeros((nu, n_glob))
    if fam == 0:
        y, gy = _global(Y1, inner1)
        E[0], dE[0] = y[4], gy[4]
        for k in range(3):
            E[1 + k] = y[k] + u[k]
            dE[1 + k] = gy[k]
            dE[1 + k, k] += 1.0
        return E, dE
    y1, gy1 = _global(Y1, inner1)
    y2, gy2 = _global(Y2, inner2)
    E[0], dE[0] = y1[4], gy1[4]
    E[1], dE[1] = y2[4], gy2[4]
    for k in range(3):
        E[2 + k] = y2[k] - u[k]
        dE[2 + k] = gy2[k]
        dE[2 + k, k] -= 1.0
    return E, dE


@njit(**KW)
def residual_jacobian(model, fam, u, eta, omega, F):
    """(E, dE/d(u, eta, omega, F, s_g)) of the family's shooting system."""
    Y1, inner1, Y2, inner2, n_glob = _flights(model, fam, u, eta, omega, F, N1)
    return _residual(fam, u, Y1, inner1, Y2, inner2, n_glob)


@njit(**KW)
def _monodromy(fam, Y1, inner1, Y2, inner2):
    """A = Mirror J_P1 (symmetric) or J_P2 J_P1 (asymmetric) and dA (4, 4, N)."""
    J1, dJ1 = _map_jac(Y1, inner1)
    if fam == 0:
        for i in range(3):
            J1[i] = -J1[i]
            dJ1[i] = -dJ1[i]
        return J1, dJ1
    J2, dJ2 = _map_jac(Y2, inner2)
    A = J2 @ J1
    dA = np.zeros(dJ1.shape)
    for i in range(4):
        for j in range(4):
            for k in range(4):
                dA[i, j] += dJ2[i, k] * J1[k, j] + J2[i, k] * dJ1[k, j]
    return A, dA


@njit(**KW)
def _compound2(A, dA):
    """Second compound matrix (``shooting.compound2``) and its gradients."""
    pairs = [(p, q) for p in range(4) for q in range(p + 1, 4)]
    C = np.empty((6, 6))
    dC = np.empty((6, 6, dA.shape[2]))
    for a in range(6):
        p, q = pairs[a]
        for b in range(6):
            r, s = pairs[b]
            C[a, b] = A[p, r] * A[q, s] - A[p, s] * A[q, r]
            dC[a, b] = (dA[p, r] * A[q, s] + A[p, r] * dA[q, s]
                        - dA[p, s] * A[q, r] - A[p, s] * dA[q, r])
    return C, dC


@njit(**KW)
def det_gradient(M, dM):
    """det M and its gradient (``jets.det``: elimination with partial pivoting on the
    values; the last pivot is never divided by)."""
    A, dA = M.copy(), dM.copy()
    n = A.shape[0]
    out, dout = 1.0, np.zeros(dM.shape[2])
    for k in range(n):
        p = k + int(np.argmax(np.abs(A[k:, k])))
        if p != k:
            for j in range(n):
                A[k, j], A[p, j] = A[p, j], A[k, j]
                tmp = dA[k, j].copy()
                dA[k, j] = dA[p, j]
                dA[p, j] = tmp
            out, dout = -out, -dout
        dout = out * dA[k, k] + A[k, k] * dout
        out = out * A[k, k]
        if k == n - 1:
            break
        if A[k, k] == 0.0:
            return 0.0, 0.0 * dout
        for i in range(k + 1, n):
            f = A[i, k] / A[k, k]
            df = (dA[i, k] - f * dA[k, k]) / A[k, k]
            for j in range(k + 1, n):
                dA[i, j] = dA[i, j] - (f * dA[k, j] + df * A[k, j])
                A[i, j] = A[i, j] - f * A[k, j]
    return out, dout


@njit(**KW)
def _test_function(fam, cond, Y1, inner1, Y2, inner2):
    """The determinant of a fold / det(A + I) / neimark-sacker condition and its gradient."""
    A, dA = _monodromy(fam, Y1, inner1, Y2, inner2)
    if cond == 2:
        A, dA = _compound2(A, dA)
    shift = -1.0 if cond == 0 or cond == 2 else 1.0
    for i in range(A.shape[0]):
        A[i, i] += shift
    return det_gradient(A, dA)


@njit(**KW)
def _grazing(model, fam, k, wall, u, eta, omega, F, sg, Y1, inner1, Y2, inner2):
    """The grazing conditions (``augmented.Codim1System._grazing``) and their gradients."""
    Yk, innerk = (Y1, inner1) if k == 1 else (Y2, inner2)
    w0 = WALL_L if k == 1 else WALL_R
    if wall == 2:
        y, gy = _global(Yk, innerk)
        return y[5:6], gy[5:6]
    n_glob = inner1.shape[1]
    if k == 1:
        x, gx = u[:4].copy(), inner1[:4]
    else:
        y1, gy1 = _global(Y1, inner1)
        x, gx = y1[:4], gy1[:4]
    grads = np.zeros((NL, n_glob))
    grads[:4] = gx
    cols = np.array([-1, -1, -1, -1, n_glob - 1, n_glob - 4, n_glob - 3, n_glob - 2])
    inner = _inner(n_glob, cols, grads)
    y, gy = _global(flight_local(model, x, sg, eta, omega, F, w0, N1), inner)
    if wall == 0:
        y[4] -= 2.0 * w0
    return y[4:6].copy(), gy[4:6].copy()


@njit(**KW)
def codim1(model, fam, cond, k, wall, u, eta, omega, F, sg):
    """(G, dG/d(u, eta, omega, F, s_g)) of ``augmented.Codim1System`` (codes: module
    docstring; k, wall and s_g used by grazing only)."""
    size = N1 if cond == 3 else N2
    Y1, inner1, Y2, inner2, n_glob = _flights(model, fam, u, eta, omega, F, size)
    E, dE = _residual(fam, u, Y1, inner1, Y2, inner2, n_glob)
    if cond == 3:
        g, dg = _grazing(model, fam, k, wall, u, eta, omega, F, sg, Y1, inner1, Y2, inner2)
    else:
        v, dv = _test_function(fam, cond, Y1, inner1, Y2, inner2)
        g, dg = np.array([v]), dv.reshape(1, n_glob)
    return np.concatenate((E, g)), np.vstack((dE, dg))
