"""1:1 orbits as closed-form shooting systems, with exact derivatives (``jets``).

Unlike ``newton.newton_sequence`` (the impact time solved inside each map) the flight times
are explicit here, as in multi-segment shooting for hybrid periodic orbits: every
condition is then a closed-form function of the unknowns and of (eta, omega, F), so the
derivatives with respect to the parameters, and the second derivatives needed by the
augmented systems of ``boundaries``, come exactly from Taylor jets: ``flight`` is recorded
once per ``Model`` as a tape (``tape``) that ``kernels`` runs on jets in compiled
code (``residual_jacobian``, ``augmented.Codim1System``); the pure-Python ``jets``
evaluate these formulas directly (``residual_jacobian_jets``, ``monodromy_jets``: the
reference of the compiled derivatives).

Families (unknowns u, residual E(u; eta, omega, F) = 0):

* ``symmetric``: u = (z_m', z_b', z_b, t_L); the L->R flight lasts T/2 and ends on the
  mirror image of the start: E = (w(T/2) + 1, z_m'(T/2) + z_m', z_b'+ + z_b',
  z_b(T/2) + z_b) (the conditions of ``affine._chain`` with sign -1).
* ``asymmetric``: u = (z_m', z_b', z_b, t_L, s1); flights s1 (L->R) and s2 = T - s1:
  E = (arrival at R, arrival at L, periodicity of z_m', z_b', z_b).

The flight is the closed-form free flight of ``core.flow`` for the underdamped LO
(0 < d < 2, mass 1, non-resonant particular solution), the impact law that of
``core.walls``.
"""
from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from ...core.params import PARAM_NAMES, ParameterError
from ...core.walls import WALL_L, WALL_R
from . import kernels
from . import taylor as jets
from .tape import record
from .taylor import cos, exp, sin

#: the two kinds of 1:1 orbits, each with its own shooting system
ORBIT_KINDS = ("symmetric", "asymmetric")
N_UNKNOWNS = {"symmetric": 4, "asymmetric": 5}
#: a number of the closed forms: a float or a Taylor jet (``jets.Jet``)
Num = float | jets.Jet


class Model:
    """Fixed constants r, d, phi of a shooting system (d in (0, 2): underdamped LO)."""

    def __init__(self, r: float, d: float, phi: float = 0.0):
        if not 0.0 < d < 2.0:
            raise ParameterError("d", d, "must lie in (0, 2) for continuation (underdamped "
                                         "LO with a non-resonant particular solution)")
        self.r, self.d, self.phi = float(r), float(d), float(phi)
        self.sigma = 0.5 * d
        self.wd = math.sqrt(1.0 - self.sigma ** 2)
        # ``flight`` as the compiled kernels evaluate it (``kernels``)
        self.tape = record(lambda *v: _flight_outputs(self, v), 9)


def flight(m: Model, x: Sequence[Num], s: Num, eta: Num, omega: Num, F: Num,
           from_wall: int) -> tuple[tuple, Num, Num]:
    """Impact at from_wall, then free flight of local duration s from x = (z_m', z_b', z_b,
    t). Returns (y, gap, w_dot): y = (z_m', z_b', z_b, t) at s, gap = w(s) - (-from_wall)
    (zero on arrival at the other wall), w_dot = w'(s). Floats or jets throughout."""
    vm, vb, zb, t = x
    one = 1.0 + eta
    vp = ((1.0 - m.r * eta) * vm + eta * (1.0 + m.r) * vb) / one
    vbp = ((1.0 + m.r) * vm + (eta - m.r) * vb) / one
    z, v = lo_state(m, zb + from_wall, vp, omega * t + m.phi, s, omega, F)
    zb1 = zb + vbp * s
    return (v, vbp, zb1, t + s), z - zb1 + from_wall, v - vbp


def _flight_outputs(m: Model, v) -> list:
    """flight with inputs v = (x (4), s, eta, omega, F, from_wall) as one list (6)."""
    y, gap, w_dot = flight(m, v[:4], v[4], v[5], v[6], v[7], v[8])
    return [*y, gap, w_dot]


def lo_state(m: Model, z0: Num, v0: Num, th0: Num, s: Num, omega: Num,
             F: Num) -> tuple[Num, Num]:
    """(z_m, z_m') at local time s of the forced damped LO from (z0, v0), forcing phase th0."""
    d = m.d
    det = 1.0 - omega * omega
    dw = d * omega
    den = det * det + dw * dw
    ps = F * (det + dw * dw) / den
    pc = -F * d * omega * omega * omega / den
    th = th0 + omega * s
    s0, c0, s1, c1 = sin(th0), cos(th0), sin(th), cos(th)
    zp0, zp10 = ps * s0 + pc * c0, omega * (ps * c0 - pc * s0)
    zp, zp1 = ps * s1 + pc * c1, omega * (ps * c1 - pc * s1)
    e = exp(-m.sigma * s)
    sw, cw = sin(m.wd * s), cos(m.wd * s)
    S = e * sw / m.wd
    C = e * cw + m.sigma * S
    dS = e * cw - m.sigma * S
    xh, vh = z0 - zp0, v0 - zp10
    return zp + xh * C + vh * S, zp1 - xh * S + vh * dS


def period(omega: Num) -> Num:
    """Forcing period T = 2 pi / omega."""
    return 2.0 * math.pi / omega


def residual(m: Model, family: str, u: Sequence[Num], eta: Num, omega: Num, F: Num) -> list:
    """E(u; eta, omega, F) of the family (module docstring); floats or jets."""
    if family == "symmetric":
        y, gap, _ = flight(m, u[:4], math.pi / omega, eta, omega, F, WALL_L)
        return [gap, y[0] + u[0], y[1] + u[1], y[2] + u[2]]
    y1, gap1, _ = flight(m, u[:4], u[4], eta, omega, F, WALL_L)
    y2, gap2, _ = flight(m, y1, period(omega) - u[4], eta, omega, F, WALL_R)
    return [gap1, gap2, y2[0] - u[0], y2[1] - u[1], y2[2] - u[2]]


def flight_times(family: str, u: Sequence[Num], omega: Num) -> tuple:
    T = period(jets.value(omega))
    s1 = 0.5 * T if family == "symmetric" else jets.value(u[4])
    return s1, T - s1


def residual_jacobian(m: Model, family: str, u: ArrayLike, par: dict,
                      free: tuple) -> tuple[np.ndarray, np.ndarray]:
    """(E, dE/d(u, free params)) at u with par = {eta, omega, F}; ``free`` names the
    parameters differentiated (in that order, after u). Compiled
    (``kernels.residual_jacobian``); ``residual_jacobian_jets`` is the reference."""
    u = np.asarray(u, dtype=float)
    E, dE = kernels.residual_jacobian(m.tape, ORBIT_KINDS.index(family), u,
                                      float(par["eta"]), float(par["omega"]), float(par["F"]))
    n = len(u)
    return E, dE[:, list(range(n)) + [n + PARAM_NAMES.index(q) for q in free]]


def residual_jacobian_jets(m: Model, family: str, u: ArrayLike, par: dict,
                           free: tuple) -> tuple[np.ndarray, np.ndarray]:
    """``residual_jacobian`` from the Python jets (the reference of the compiled one)."""
    n = len(u)
    z = jets.variables(list(u) + [par[q] for q in free])
    p = dict(par)
    for k, q in enumerate(free):
        p[q] = z[n + k]
    E = residual(m, family, z[:n], p["eta"], p["omega"], p["F"])
    return jets.values(E), jets.jacobian(E, len(z))


# --------------------------------------------------------------- map Jacobians as jets

def map_jacobian_jets(m: Model, x: Sequence[Num], s: Num, eta: Num, omega: Num, F: Num,
                      from_wall: int, inner: np.ndarray) -> list:
    """Jacobian (4x4, as in ``maps.impact_map``) of the map whose flight from x lasts s,
    as order-1 jets over global variables; x, s, eta, omega, F are given as values and
    inner[k] is the global gradient of local variable k of (x0..x3, s, eta, omega, F)."""
    loc = jets.variables([jets.value(q) for q in (*x, s, eta, omega, F)], order=2)
    y, gap, _ = flight(m, loc[:4], loc[4], loc[5], loc[6], loc[7], from_wall)
    n = len(loc)
    dgap = jets.lift(gap, n)
    J = []
    for yi in y:
        dyi = jets.lift(yi, n)
        J.append([jets.compose(dyi[k] - dyi[4] * dgap[k] / dgap[4], inner)
                  for k in range(4)])
    return J


def monodromy_jets(m: Model, family: str, u: Sequence[Num], eta: Num, omega: Num,
                   F: Num) -> list:
    """Half-map (symmetric: Mirror J_P1) or full (asymmetric: J_P2 J_P1) monodromy matrix
    as order-1 jets over the global variables (u, eta, omega, F)."""
    nu = len(u)
    n = nu + 3
    eye = np.eye(n)
    ie, io, iF = nu, nu + 1, nu + 2
    T = period(omega)
    if family == "symmetric":
        s_grad = eye[io] * (-0.5 * T / omega)
        inner = np.array([eye[0], eye[1], eye[2], eye[3], s_grad, eye[ie], eye[io], eye[iF]])
        J1 = map_jacobian_jets(m, u[:4], 0.5 * T, eta, omega, F, WALL_L, inner)
        return [[-q for q in row] for row in J1[:3]] + [J1[3]]
    inner1 = np.array([eye[0], eye[1], eye[2], eye[3], eye[4], eye[ie], eye[io], eye[iF]])
    J1 = map_jacobian_jets(m, u[:4], u[4], eta, omega, F, WALL_L, inner1)
    zv = jets.variables(list(u) + [eta, omega, F])
    y1, _, _ = flight(m, zv[:4], zv[4], zv[5], zv[6], zv[7], WALL_L)
    s2_grad = -eye[4] + eye[io] * (-T / omega)
    inner2 = np.array([y1[0].g, y1[1].g, y1[2].g, y1[3].g, s2_grad, eye[ie], eye[io],
                       eye[iF]])
    J2 = map_jacobian_jets(m, [q.v for q in y1], T - u[4], eta, omega, F, WALL_R, inner2)
    return matmul(J2, J1)


def matmul(A: list, B: list) -> list:
    n = len(A)
    return [[sum((A[i][k] * B[k][j] for k in range(1, n)), A[i][0] * B[0][j])
             for j in range(n)] for i in range(n)]


def shifted(A: list, c: Num) -> list:
    """A + c I (lists of floats/jets)."""
    return [[A[i][j] + (c if i == j else 0.0) for j in range(len(A))] for i in range(len(A))]


def jacobian_float(J: list) -> np.ndarray:
    return np.array([[jets.value(q) for q in row] for row in J])
