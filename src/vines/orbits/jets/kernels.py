"""Compiled exact derivatives of the 1:1 shooting systems (``shooting``, ``augmented``).

The closed-form flight ``shooting.flight``, recorded once per model as a tape of
elementary operations (``tape``, ``shooting.Model.tape``), is evaluated here on Taylor
jets stored as flat arrays: a = (value, gradient (NL), Hessian (NL x NL, row-major)) over
the NL = 8 local variables (z_m', z_b', z_b, t, s, eta, omega, F) of one flight; an
order-1 jet is the first 1 + NL entries. A flight's outputs (y = (z_m', z_b', z_b, t) at
s, gap, w') are then re-expressed over the global unknowns (u, eta, omega, F, s_g) by the
chain rule, with inner[k] = the global gradient of local variable k (as in
``shooting.map_jacobian_jets``). ``jets`` and ``shooting`` hold the reference (pure
Python) implementation that the tests compare these kernels against. The flight and matrix
helpers (``flight_local``, ``global_jets``, ``map_jacobian``, ``product_gradient``,
``compound2_gradient``, ``det_gradient``) also serve ``chain`` (any wall sequence).

Codes: family 0 symmetric, 1 asymmetric; condition 0 fold det(A - I), 1 det(A + I)
(symmetry-breaking / flip), 2 neimark-sacker det(A (x) A - I), 3 grazing; grazing wall 0
start, 1 target, 2 arrival. Global columns: u (nu), eta, omega, F, s_g (always present;
zero where unused).
"""
from __future__ import annotations

import math

import numpy as np

from ..._jit import njit
from ...core.walls import WALL_L, WALL_R

NL = 8                       # local variables of one flight
N1 = 1 + NL                  # length of an order-1 jet
N2 = 1 + NL + NL * NL        # length of an order-2 jet
KW = dict(cache=True, nogil=True, error_model="numpy")
INLINE = dict(KW, inline="always")     # helpers: inlined into the entry points


# ------------------------------------------------------------------ jet arithmetic
# in place: out = f(a, b); out may not be a or b

@njit(**INLINE)
def _lin(out, a, ca, b, cb):
    """out = ca a + cb b."""
    for i in range(out.size):
        out[i] = ca * a[i] + cb * b[i]


@njit(**INLINE)
def _mul(out, a, b):
    out[0] = a[0] * b[0]
    for i in range(1, out.size):
        out[i] = a[0] * b[i] + b[0] * a[i]
    if out.size == N2:
        for i in range(NL):
            ai, bi = a[1 + i], b[1 + i]
            if ai != 0.0 or bi != 0.0:
                for j in range(NL):
                    out[N1 + i * NL + j] += ai * b[1 + j] + bi * a[1 + j]


@njit(**INLINE)
def _unary(out, x, f, f1, f2):
    """Chain rule for a scalar function with value f, derivatives f1, f2 at x[0]."""
    out[0] = f
    for i in range(1, out.size):
        out[i] = f1 * x[i]
    if out.size == N2:
        for i in range(NL):
            if x[1 + i] != 0.0:
                for j in range(NL):
                    out[N1 + i * NL + j] += f2 * x[1 + i] * x[1 + j]


@njit(**KW)
def _apply(code, out, a, b, scratch):
    """Operation ``tape.OPS[code]`` (not const) on jets a (and b) into out."""
    v = a[0]
    if code == 0:
        _lin(out, a, 1.0, b, 1.0)
    elif code == 1:
        _lin(out, a, 1.0, b, -1.0)
    elif code == 2:
        _mul(out, a, b)
    elif code == 3:
        q = 1.0 / b[0]
        _unary(scratch, b, q, -q * q, 2.0 * q * q * q)
        _mul(out, a, scratch)
    elif code == 4:
        _lin(out, a, -1.0, a, 0.0)
    elif code == 5:
        _unary(out, a, math.sin(v), math.cos(v), -math.sin(v))
    elif code == 6:
        _unary(out, a, math.cos(v), -math.sin(v), -math.cos(v))
    elif code == 7:
        e = math.exp(v)
        _unary(out, a, e, e, e)
    else:
        q = math.sqrt(v)
        _unary(out, a, q, 0.5 / q, -0.25 / (q * v))


@njit(**KW)
def run_tape(tp, inputs, size):
    """Outputs (rows) of the tape tp = (ops, consts, output registers) (``tape.record``) as
    jets of length size; inputs k < NL are the local variables, the others constants."""
    ops, consts, outs = tp
    n_in = inputs.size
    regs = np.zeros((n_in + ops.shape[0], size))
    scratch = np.empty(size)
    for k in range(n_in):
        regs[k, 0] = inputs[k]
        if k < NL:
            regs[k, 1 + k] = 1.0
    for i in range(ops.shape[0]):
        code = ops[i, 0]
        if code == 9:
            regs[n_in + i, 0] = consts[ops[i, 1]]
        else:
            _apply(code, regs[n_in + i], regs[ops[i, 1]], regs[ops[i, 2]], scratch)
    out = np.empty((outs.size, size))
    for j in range(outs.size):
        out[j] = regs[outs[j]]
    return out


@njit(**INLINE)
def flight_local(tp, x, s, par, from_wall, size):
    """Rows (z_m', z_b', z_b, t at s, gap, w') of ``shooting.flight`` (recorded as the
    tape tp, ``shooting.Model.tape``) as jets of length size (N1 or N2) over the local
    variables; par = (eta, omega, F)."""
    eta, omega, F = par
    inputs = np.array([x[0], x[1], x[2], x[3], s, eta, omega, F, float(from_wall)])
    return run_tape(tp, inputs, size)


@njit(**INLINE)
def global_jets(Y, inner):
    """(values, gradients over the global variables) of local jets Y."""
    return Y[:, 0].copy(), np.ascontiguousarray(Y[:, 1:N1]) @ inner


@njit(**INLINE)
def map_jacobian(Y, inner):
    """Jacobian (4x4) of the map whose flight is Y (order 2, the impact time solved from
    gap = 0 as in ``maps.impact_map``) and its gradients (4, 4, N) over the globals."""
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

@njit(**INLINE)
def _inner(n_glob, cols, grads):
    """inner (NL, n_glob): row k = grads[k] if cols[k] < 0 else the unit row cols[k]."""
    inner = np.zeros((NL, n_glob))
    for k in range(NL):
        if cols[k] >= 0:
            inner[k, cols[k]] = 1.0
        else:
            inner[k] = grads[k]
    return inner


@njit(**INLINE)
def _flights(tp, fam, u, par, size):
    """The flights of the orbit u at par = (eta, omega, F): (Y1, inner1, Y2, inner2,
    n_glob); Y2 is Y1 for the symmetric family (whose residual uses one flight)."""
    omega = par[1]
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
    Y1 = flight_local(tp, u, s1, par, WALL_L, size)
    if fam == 0:
        return Y1, inner1, Y1, inner1, n_glob
    y1, gy1 = global_jets(Y1, inner1)
    cols2 = np.array([-1, -1, -1, -1, -1, ie, io, iF])
    grads2 = np.zeros((NL, n_glob))
    grads2[:4] = gy1[:4]
    grads2[4, 4] = -1.0
    grads2[4, io] = -T / omega
    inner2 = _inner(n_glob, cols2, grads2)
    Y2 = flight_local(tp, y1, T - u[4], par, WALL_R, size)
    return Y1, inner1, Y2, inner2, n_glob


@njit(**INLINE)
def _residual(fam, u, Y1, inner1, Y2, inner2, n_glob):
    """E and dE/d(globals) (``shooting.residual``)."""
    nu = 4 + fam
    E = np.empty(nu)
    dE = np.zeros((nu, n_glob))
    if fam == 0:
        y, gy = global_jets(Y1, inner1)
        E[0], dE[0] = y[4], gy[4]
        for k in range(3):
            E[1 + k] = y[k] + u[k]
            dE[1 + k] = gy[k]
            dE[1 + k, k] += 1.0
        return E, dE
    y1, gy1 = global_jets(Y1, inner1)
    y2, gy2 = global_jets(Y2, inner2)
    E[0], dE[0] = y1[4], gy1[4]
    E[1], dE[1] = y2[4], gy2[4]
    for k in range(3):
        E[2 + k] = y2[k] - u[k]
        dE[2 + k] = gy2[k]
        dE[2 + k, k] -= 1.0
    return E, dE


def residual_jacobian(tp, fam, u, eta, omega, F):
    """(E, dE/d(u, eta, omega, F, s_g)) of the family's shooting system."""
    return codim1(tp, fam, -1, 1, 0, u, (eta, omega, F), 0.0)


@njit(**INLINE)
def _monodromy(fam, Y1, inner1, Y2, inner2):
    """A = Mirror J_P1 (symmetric) or J_P2 J_P1 (asymmetric) and dA (4, 4, N)."""
    J1, dJ1 = map_jacobian(Y1, inner1)
    if fam == 0:
        for i in range(3):
            J1[i] = -J1[i]
            dJ1[i] = -dJ1[i]
        return J1, dJ1
    J2, dJ2 = map_jacobian(Y2, inner2)
    return product_gradient(J2, dJ2, J1, dJ1)


@njit(**INLINE)
def product_gradient(J, dJ, A, dA):
    """(J A, its gradient) from 4x4 J, A and their gradients (4, 4, N)."""
    P = J @ A
    dP = np.zeros(dA.shape)
    for i in range(4):
        for j in range(4):
            for k in range(4):
                dP[i, j] += dJ[i, k] * A[k, j] + J[i, k] * dA[k, j]
    return P, dP


@njit(**INLINE)
def compound2_gradient(A, dA):
    """Second compound matrix (``family.systems.compound2``) and its gradients."""
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


@njit(**INLINE)
def _test_function(fam, cond, Y1, inner1, Y2, inner2):
    """The determinant of a fold / det(A + I) / neimark-sacker condition and its gradient."""
    A, dA = _monodromy(fam, Y1, inner1, Y2, inner2)
    if cond == 2:
        A, dA = compound2_gradient(A, dA)
    shift = -1.0 if cond == 0 or cond == 2 else 1.0
    for i in range(A.shape[0]):
        A[i, i] += shift
    return det_gradient(A, dA)


@njit(**INLINE)
def _grazing(tp, k, wall, u, par, sg, flight1, flight2):
    """The grazing conditions (``augmented.Codim1System._grazing``) and their gradients;
    par = (eta, omega, F), flight1, flight2 = (Y, inner) of the orbit's flights."""
    Y1, inner1 = flight1
    Yk, innerk = flight1 if k == 1 else flight2
    w0 = float(WALL_L if k == 1 else WALL_R)
    if wall == 2:
        y, gy = global_jets(Yk, innerk)
        return y[5:6], gy[5:6]
    n_glob = inner1.shape[1]
    if k == 1:
        x, gx = u[:4].copy(), inner1[:4]
    else:
        y1, gy1 = global_jets(Y1, inner1)
        x, gx = y1[:4], gy1[:4]
    grads = np.zeros((NL, n_glob))
    grads[:4] = gx
    cols = np.array([-1, -1, -1, -1, n_glob - 1, n_glob - 4, n_glob - 3, n_glob - 2])
    inner = _inner(n_glob, cols, grads)
    y, gy = global_jets(flight_local(tp, x, sg, par, w0, N1), inner)
    if wall == 0:
        y[4] -= 2.0 * w0
    return y[4:6].copy(), gy[4:6].copy()


@njit(**KW)
def codim1(tp, fam, cond, k, wall, u, par, sg):
    """(G, dG/d(u, eta, omega, F, s_g)) of ``augmented.Codim1System`` at par = (eta,
    omega, F) (codes: module docstring; k, wall and s_g used by grazing only); cond = -1:
    the shooting residual alone (``residual_jacobian``). The one compiled entry point
    (compiling is the cost)."""
    size = N2 if 0 <= cond <= 2 else N1
    Y1, inner1, Y2, inner2, n_glob = _flights(tp, fam, u, par, size)
    E, dE = _residual(fam, u, Y1, inner1, Y2, inner2, n_glob)
    if cond < 0:
        return E, dE
    if cond == 3:
        g, dg = _grazing(tp, k, wall, u, par, sg, (Y1, inner1), (Y2, inner2))
    else:
        v, dv = _test_function(fam, cond, Y1, inner1, Y2, inner2)
        g, dg = np.array([v]), dv.reshape(1, n_glob)
    return np.concatenate((E, g)), np.vstack((dE, dg))
