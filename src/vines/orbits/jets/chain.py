"""Compiled exact derivatives of the map residual of any wall sequence (``map_systems``).

The orbit residual of a family (``family.map_systems``: R(x_0) = M^sym P_{m-1}(...P_0(x_0))
- x_0 - (0, 0, 0, span), M the mirror for symmetric families, span = N T or N T / 2) is a
chain of m flights, each the closed-form ``shooting.flight`` (recorded as ``Model.tape``)
run on Taylor jets by ``kernels.flight_local``. Flight k starts at walls[k] from the
previous flight's end, for the time s_k that the impact map solved (``maps.impact``); s_k
is eliminated by the implicit function theorem (gap(x_k, s_k; eta, omega, F) = its wall,
so ds_k = -(d gap at fixed s) / gap_s): the derivatives are those of the maps, the x_0
columns of dR equal A - I.

Global variables (the columns, ``NG``): x_0 = (z_m', z_b', z_b, t) (4), eta, omega, F.
Condition codes (as ``kernels``): -1 none (order-1 jets), 0 fold det(A - I), 1 det(A + I)
(flip, symmetry-breaking), 2 neimark-sacker det(A^[2] - I); a condition's gradient needs
the maps' second derivatives (order-2 jets). The pure-Python ``taylor`` jets and central
differences of the maps are the references of the tests.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..._jit import njit
from .kernels import (
    INLINE,
    KW,
    N1,
    N2,
    NL,
    compound2_gradient,
    det_gradient,
    flight_local,
    global_jets,
    map_jacobian,
    product_gradient,
)
from .shooting import Model

NG = 7                      # global variables: x_0 (4), eta, omega, F
I_OMEGA = 5                 # column of omega
#: condition codes of ``chain_jacobian`` by bifurcation kind
CONDITIONS = {"fold": 0, "flip": 1, "symmetry-breaking": 1, "neimark-sacker": 2}


@njit(**INLINE)
def _eliminate_time(Y, inner):
    """inner[4] = the global gradient of the flight time solved from gap = const."""
    gap = Y[4]
    row = np.zeros(inner.shape[1])
    for j in range(NL):
        if j != 4:
            row += gap[1 + j] * inner[j]
    inner[4] = -row / gap[1 + 4]


@njit(**INLINE)
def _condition(cond, A, dA):
    """The determinant of condition ``cond`` (module docstring) and its gradient."""
    if cond == 2:
        A, dA = compound2_gradient(A, dA)
    else:
        A = A.copy()
    shift = 1.0 if cond == 1 else -1.0
    for i in range(A.shape[0]):
        A[i, i] += shift
    return det_gradient(A, dA)


@njit(**KW)
def chain_jacobian(tp, walls, symmetric, x0, fl, par, span, cond):
    """(R, dR (4, NG), g, dg (NG)) of the residual of the flights from walls[k] lasting
    fl[k] (the maps' flight times) from x0, at par = (eta, omega, F); tp: ``Model.tape``;
    g, dg: condition ``cond`` (0.0, zeros when cond = -1)."""
    size = N2 if cond >= 0 else N1
    inner = np.zeros((NL, NG))
    for k in range(4):
        inner[k, k] = 1.0
    for k in range(3):
        inner[5 + k, 4 + k] = 1.0
    x = x0.copy()
    A, dA = np.eye(4), np.zeros((4, 4, NG))
    for k in range(walls.size):
        Y = flight_local(tp, x, fl[k], par, walls[k], size)
        _eliminate_time(Y, inner)
        y, gy = global_jets(Y, inner)
        if cond >= 0:
            J, dJ = map_jacobian(Y, inner)
            A, dA = (J, dJ) if k == 0 else product_gradient(J, dJ, A, dA)
        x = y[:4].copy()
        inner[:4] = gy[:4]
    sign = np.array([-1.0, -1.0, -1.0, 1.0]) if symmetric else np.ones(4)
    R = sign * x - x0
    R[3] -= span
    dR = sign.reshape(4, 1) * inner[:4]
    for k in range(4):
        dR[k, k] -= 1.0
    dR[3, I_OMEGA] += span / par[1]         # span is proportional to T = 2 pi / omega
    if cond < 0:
        return R, dR, 0.0, np.zeros(NG)
    for i in range(4):
        A[i] *= sign[i]
        dA[i] *= sign[i]
    g, dg = _condition(cond, A, dA)
    return R, dR, g, dg


@njit(**KW)
def shooting_jacobian(tp, walls, symmetric, x0, fl, sg, par, span, graze):
    """(E, dE/d(x_0, fl (m), s_g, eta, omega, F)) of the shooting form of the grazing
    system (``map_systems.GrazingSystem``: flight k from walls[k] to walls[k + 1] (cyclic,
    the last to walls[m] given) lasts the unknown fl[k]); graze = (k, wall): flight k (from
    0) grazes at its arrival (wall 0: w' = 0) or at wall code ``wall`` at s_g (w = wall,
    w' = 0). Order-1 jets."""
    m = fl.size
    ip = 5 + m                              # column of eta
    inner = np.zeros((NL, ip + 3))
    for k in range(4):
        inner[k, k] = 1.0
    for k in range(3):
        inner[5 + k, ip + k] = 1.0
    ne = m + 4 + (1 if graze[1] == 0 else 2)
    E, dE = np.empty(ne), np.zeros((ne, ip + 3))
    r, x = 0, x0.copy()
    for k in range(m):
        inner[4] = 0.0
        inner[4, 4 + k] = 1.0
        y, gy = global_jets(flight_local(tp, x, fl[k], par, walls[k], N1), inner)
        E[r], dE[r] = y[4] - walls[k] - walls[k + 1], gy[4]
        r += 1
        if k == graze[0]:
            r = _graze(tp, (x, inner, walls[k]), (sg, ip - 1), par, graze[1], (y, gy),
                       (E, dE, r))
        x = y[:4].copy()
        inner[:4] = gy[:4]
    sign = np.array([-1.0, -1.0, -1.0, 1.0]) if symmetric else np.ones(4)
    for i in range(3):
        E[r + i], dE[r + i] = sign[i] * x[i] - x0[i], sign[i] * inner[i]
        dE[r + i, i] -= 1.0
    E[r + 3] = fl.sum() - span
    dE[r + 3, 4:4 + m] = 1.0
    dE[r + 3, ip + 1] = span / par[1]
    return E, dE


@njit(**INLINE)
def _graze(tp, start, at, par, wall, arrival, rows):
    """Rows r.. of the grazing conditions of a flight from x (start = (x, inner, its
    wall)), at its arrival (wall 0: w' there, arrival = the flight's (y, gy)) or at
    at = (s_g, its column) (w - wall, w'); returns the next row."""
    E, dE, r = rows
    if wall == 0:
        E[r], dE[r] = arrival[0][5], arrival[1][5]
        return r + 1
    x, inner, w0 = start
    ig = inner.copy()
    ig[4] = 0.0
    ig[4, at[1]] = 1.0
    y, gy = global_jets(flight_local(tp, x, at[0], par, w0, N1), ig)
    E[r], dE[r] = y[4] - w0 - wall, gy[4]
    E[r + 1], dE[r + 1] = y[5], gy[5]
    return r + 2


@lru_cache(maxsize=32)
def _model(r: float, d: float, phi: float) -> Model:
    return Model(r, d, phi)


def model_of(r: float, d: float, phi: float) -> Model | None:
    """The (cached) ``shooting.Model`` of r, d, phi, or None where the jets do not apply
    (d outside (0, 2): not an underdamped oscillator)."""
    if not 0.0 < d < 2.0:
        return None
    return _model(float(r), float(d), float(phi))


def residual_derivatives(model: Model, walls, symmetric: bool, span: float, par, x0, fl,
                         kind: str | None = None) -> tuple:
    """``chain_jacobian`` for a bifurcation ``kind`` (``CONDITIONS``, None: no condition);
    walls: the wall codes (int) of the starting walls of the residual's flights."""
    cond = -1 if kind is None else CONDITIONS[kind]
    return chain_jacobian(model.tape, np.asarray(walls, dtype=np.int64), bool(symmetric),
                          np.asarray(x0, float), np.asarray(fl, float),
                          tuple(float(q) for q in par), float(span), cond)


def grazing_derivatives(model: Model, walls, symmetric: bool, span: float, par, u,
                        graze: tuple) -> tuple:
    """``shooting_jacobian`` at u = (x_0, flights (m), s_g); walls: the m + 1 wall codes
    of the impacts the flights join; graze = (flight k from 0, wall code or 0: arrival)."""
    u = np.asarray(u, float)
    m = len(walls) - 1
    return shooting_jacobian(model.tape, np.asarray(walls, dtype=np.int64), bool(symmetric),
                             u[:4], u[4:4 + m], float(u[4 + m]),
                             tuple(float(q) for q in par), float(span),
                             (int(graze[0]), int(graze[1])))
