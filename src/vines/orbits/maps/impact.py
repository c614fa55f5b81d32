"""Impact-to-impact maps P1 (L->R), P2 (R->L), P3 (L->L), P4 (R->R) and their Jacobians.

State: the pre-impact state at a wall, x = (z_m', z_b', z_b, t); z_m = z_b + wall follows
from the wall (L: w = z_m - z_b = +1, R: w = -1). One map applies the impact law at the
starting wall, follows the closed-form flight (``vines.flow``, local time s = t_next - t)
and stops when w(s) reaches the target wall. The impact time solves
G(s) = w(s) - to_wall = 0 by a safeguarded Newton iteration on the closed form, i.e. on
the analytic continuation of the flight: the root found need not be the first contact,
so non-admissible roots (the ball would have hit a wall earlier, or the root is reached
moving away from the wall) are found as well and are flagged by ``is_admissible``.

Jacobian (4x4, columns d/d z_m', d/d z_b', d/d z_b, d/d t) by implicit differentiation
of the closed form. With post-impact velocities (v_m+, v_b+) = I (z_m', z_b')
(I the impact matrix), theta0 = omega t + phi, and the flow
    z_m(s) = z_p(s; theta0) + (z_m0 - z_p(0)) C(s) + (v_m+ - z_p'(0)) S(s),
the derivatives at fixed s are dz/dz_m0 = C, dz/dv_m+ = S and
dz/dtheta0 = flow(0, 0, cos theta0, -sin theta0)(s) (the flow is linear in (sin, cos)),
dz/dt = omega dz/dtheta0; the impact time moves by ds/dx = -(dG/dx)/(dG/ds) with
dG/ds = w'(s), and every output is differentiated along (explicit + w.r.t. s * ds/dx).
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..._jit import njit
from ...core.exact import oscillators
from ...core.flow import I_RATE, I_W, N_OSC, flow
from ...core.kernel import first_contact
from ...core.params import ModelParams
from ...core.walls import WALL_L, WALL_R, impact_velocities

ROOT_TOL = 1e-13
ADMISSIBLE_TOL = 1e-8       # first contact and map root must agree to this (relative to 1+s)

# status codes of the kernels
OK, NO_ROOT = 0, 1

# The model of the compiled kernels: the free oscillator's packed constants (``core.flow``:
# omega = mdl[I_W], F = mdl[I_F]) followed by eta, r and phi.
M_ETA, M_R, M_PHI = N_OSC, N_OSC + 1, N_OSC + 2
N_MODEL = N_OSC + 3


@njit(cache=True, nogil=True)
def pack_model(osc, eta, r, phi):
    """The kernels' model array: a copy of the free oscillator osc with eta, r, phi after it."""
    mdl = np.empty(N_MODEL)
    mdl[:N_OSC] = osc[:N_OSC]
    mdl[M_ETA], mdl[M_R], mdl[M_PHI] = eta, r, phi
    return mdl


def model_array(params: ModelParams, osc: np.ndarray | None = None) -> np.ndarray:
    """``pack_model`` of a validated model (osc: its free oscillator, if already built)."""
    if osc is None:
        osc = oscillators(params)[0]
    return pack_model(osc, params.eta, params.r, params.phi)


@njit(cache=True, nogil=True)
def _gap(osc, st0, ph0, s, to_wall):
    """(G, G', G'') with G = w(s) - to_wall, for the flight from st0 = (z_m, z_m'+, z_b,
    z_b'+) with forcing phase ph0 = (sin, cos) at s = 0."""
    zm0, vp, zb0, vbp = st0
    z, v, a, _, _ = flow(osc, zm0, vp, ph0[0], ph0[1], s)
    return z - zb0 - vbp * s - to_wall, v - vbp, a


@njit(cache=True, nogil=True)
def _newton_s(osc, st0, ph0, to_wall, s):
    """Safeguarded Newton on G(s) = 0 from s > 0; returns s (nan when it fails)."""
    lim = 0.5 / osc[I_RATE]
    for _ in range(80):
        G, Gd, Gdd = _gap(osc, st0, ph0, s, to_wall)
        if Gd == 0.0 or not math.isfinite(G):
            return math.nan
        ds = -G / Gd
        # Halley correction when it is small (faster on curved stretches)
        den = 1.0 - 0.5 * ds * Gdd / Gd
        if abs(den - 1.0) < 0.5:
            ds = ds / den
        if ds > lim:
            ds = lim
        elif ds < -lim:
            ds = -lim
        s_new = s + ds
        if s_new <= 0.0:
            s_new = 0.5 * s
        if abs(s_new - s) <= 1e-15 * (1.0 + abs(s)) + 1e-300:
            return s_new
        if abs(ds) <= 1e-12 * (1.0 + abs(s)):
            s = s_new
            G, Gd, Gdd = _gap(osc, st0, ph0, s, to_wall)
            if Gd != 0.0:
                s = s - G / Gd
            return s
        s = s_new
    return math.nan


@njit(cache=True, nogil=True)
def _scan_s(osc, st0, ph0, to_wall, s_max):
    """First s in (0, s_max] where w crosses the target wall moving towards it (sampling)."""
    h = 0.05 / osc[I_RATE]
    s_prev = 0.0
    g_prev = 1.0
    s = h
    while s <= s_max:
        G, Gd, _ = _gap(osc, st0, ph0, s, to_wall)
        g = -to_wall * G            # distance to the target wall, > 0 inside
        if g <= 0.0 and g_prev > 0.0 and s_prev > 0.0:
            # bisection to a tight bracket, then Newton
            a, b = s_prev, s
            for _ in range(40):
                m = 0.5 * (a + b)
                Gm, _, _ = _gap(osc, st0, ph0, m, to_wall)
                if -to_wall * Gm > 0.0:
                    a = m
                else:
                    b = m
                if b - a < 1e-6 * (1.0 + b):
                    break
            return _newton_s(osc, st0, ph0, to_wall, 0.5 * (a + b))
        s_prev = s
        g_prev = g
        s += h
    return math.nan


@njit(cache=True, nogil=True)
def _no_map(y, J):
    """Mark y and J undefined (nan) and return the flight time nan: no map here."""
    for i in range(4):
        y[i] = math.nan
        for k in range(4):
            J[i, k] = math.nan
    return math.nan


@njit(cache=True, nogil=True)
def impact_map(mdl, x, walls, s_guess, y, J):
    """Apply one map to x (pre-impact at walls[0]); fill y (next pre-impact state, at
    walls[1]) and J. mdl: ``pack_model``.

    s_guess > 0 starts Newton there; otherwise the first contact (or, when the flight hits
    the other wall first, the first crossing of the continued flight) seeds it.
    Returns the flight time s (nan when no root was found).
    """
    osc = mdl
    eta, r, omega, phi = mdl[M_ETA], mdl[M_R], mdl[I_W], mdl[M_PHI]
    from_wall, to_wall = walls
    vm, vb, zb, t = x[0], x[1], x[2], x[3]
    zm0 = zb + from_wall
    vp, vbp = impact_velocities(eta, r, vm, vb)
    one = 1.0 + eta
    a11, a12 = (1.0 - r * eta) / one, eta * (1.0 + r) / one
    a21, a22 = (1.0 + r) / one, (eta - r) / one
    th0 = omega * t + phi
    sth = math.sin(th0)
    cth = math.cos(th0)
    st0 = (zm0, vp, zb, vbp)
    ph0 = (sth, cth)
    if s_guess > 0.0:
        s = _newton_s(osc, st0, ph0, to_wall, s_guess)
    else:
        s_max = 4.0 * 2.0 * math.pi / omega + 20.0 / osc[I_RATE]
        wall, sc, _, _ = first_contact(osc, st0, ph0, s_max, ROOT_TOL)
        if wall == to_wall and sc > 0.0:
            s = _newton_s(osc, st0, ph0, to_wall, sc)
        else:
            s = _scan_s(osc, st0, ph0, to_wall, s_max)
    if not (s > 0.0) or not math.isfinite(s):
        return _no_map(y, J)
    z, v, acc, _, _ = flow(osc, zm0, vp, sth, cth, s)
    wd = v - vbp                 # relative velocity at arrival
    if wd == 0.0:
        # grazing arrival: no transversal impact, the map's Jacobian has a pole here
        return _no_map(y, J)
    # derivatives at fixed s
    C = 0.0
    dC = 0.0
    S = 0.0
    dS = 0.0
    # C, S from the flow itself (linear in the initial state): C = z(1,0,0,0), S = z(0,1,0,0)
    zc, vc, _, _, _ = flow(osc, 1.0, 0.0, 0.0, 0.0, s)
    zs, vs, _, _, _ = flow(osc, 0.0, 1.0, 0.0, 0.0, s)
    C, dC, S, dS = zc, vc, zs, vs
    zt, vt, _, _, _ = flow(osc, 0.0, 0.0, cth, -sth, s)     # d/dtheta0
    zt *= omega
    vt *= omega
    y[0] = v
    y[1] = vbp
    y[2] = zb + vbp * s
    y[3] = t + s
    # explicit partials of G = z - zb - vbp s - to_wall, of z', and of the outputs
    # (scalars, not small arrays: no allocation per call)
    ds0 = -(S * a11 - a21 * s) / wd
    ds1 = -(S * a12 - a22 * s) / wd
    ds2 = -(C - 1.0) / wd
    ds3 = -zt / wd
    J[0, 0] = dS * a11 + acc * ds0
    J[0, 1] = dS * a12 + acc * ds1
    J[0, 2] = dC + acc * ds2
    J[0, 3] = vt + acc * ds3
    J[1, 0], J[1, 1], J[1, 2], J[1, 3] = a21, a22, 0.0, 0.0
    J[2, 0] = a21 * s + vbp * ds0
    J[2, 1] = a22 * s + vbp * ds1
    J[2, 2] = 1.0 + vbp * ds2
    J[2, 3] = vbp * ds3
    J[3, 0], J[3, 1], J[3, 2], J[3, 3] = ds0, ds1, ds2, ds3 + 1.0
    return s


@njit(cache=True, nogil=True)
def admissible_kernel(mdl, x, walls, s):
    """True when the flight of length s from x (walls = (from, to)) is a genuine
    impact-to-impact flight. mdl: ``pack_model``.

    The state must approach its starting wall, the exact first-contact search of the
    simulator (``_engine.first_contact``) on the post-impact state must return the target
    wall at the same time, and the arrival must approach the target wall.
    """
    osc = mdl
    eta, r, omega, phi = mdl[M_ETA], mdl[M_R], mdl[I_W], mdl[M_PHI]
    from_wall, to_wall = walls
    vm, vb, zb, t = x[0], x[1], x[2], x[3]
    if not ((vm - vb) * from_wall > 0.0) or not (s > 0.0):
        return False
    zm0 = zb + from_wall
    vp, vbp = impact_velocities(eta, r, vm, vb)
    th0 = omega * t + phi
    sth = math.sin(th0)
    cth = math.cos(th0)
    tol = ADMISSIBLE_TOL * (1.0 + s)
    st0 = (zm0, vp, zb, vbp)
    ph0 = (sth, cth)
    wall, sc, _, _ = first_contact(osc, st0, ph0, s + 10.0 * tol, ROOT_TOL)
    if wall != to_wall or abs(sc - s) > tol:
        return False
    _, wd, _ = _gap(osc, st0, ph0, s, to_wall)
    return wd * to_wall > 0.0


# --------------------------------------------------------------------------- Python API

def _walls(from_wall: int, to_wall: int) -> tuple[int, int]:
    for name, w in (("from_wall", from_wall), ("to_wall", to_wall)):
        if w not in (WALL_L, WALL_R):
            raise ValueError(f"{name} must be +1 (L) or -1 (R), got {w!r}")
    return int(from_wall), int(to_wall)


def _s_guess(x: np.ndarray, t_guess: float | None) -> float:
    return -1.0 if t_guess is None else float(t_guess) - float(x[3])


def map_with_jacobian(params: ModelParams, x: ArrayLike, from_wall: int, to_wall: int,
                      t_guess: float | None = None) -> tuple[np.ndarray, float, np.ndarray]:
    """(y, s, J): next pre-impact state, flight time and the 4x4 Jacobian dy/dx.

    y and J are nan (and s nan) when no impact time was found.
    """
    from_wall, to_wall = _walls(from_wall, to_wall)
    x = np.ascontiguousarray(x, dtype=float)
    y = np.empty(4)
    J = np.empty((4, 4))
    s = impact_map(model_array(params), x, (from_wall, to_wall), _s_guess(x, t_guess), y, J)
    return y, float(s), J


def apply_map(params: ModelParams, x: ArrayLike, from_wall: int, to_wall: int,
              t_guess: float | None = None) -> tuple[np.ndarray, float]:
    """Next pre-impact state y = (z_m', z_b', z_b, t) and the flight time s.

    ``t_guess``: optional guess of the absolute time of the next impact (Newton starts
    there, which can select a non-admissible root); by default the first contact of the
    flight seeds it.
    """
    y, s, _ = map_with_jacobian(params, x, from_wall, to_wall, t_guess)
    return y, s


def map_jacobian(params: ModelParams, x: ArrayLike, from_wall: int, to_wall: int,
                 t_guess: float | None = None) -> np.ndarray:
    """4x4 Jacobian of the map at x (columns d/d z_m', d/d z_b', d/d z_b, d/d t)."""
    return map_with_jacobian(params, x, from_wall, to_wall, t_guess)[2]


def is_admissible(params: ModelParams, x: ArrayLike, from_wall: int, to_wall: int,
                  t_guess: float | None = None, s: float | None = None) -> bool:
    """True when the map's flight from x has no earlier wall contact and approaches its wall."""
    from_wall, to_wall = _walls(from_wall, to_wall)
    x = np.ascontiguousarray(x, dtype=float)
    if s is None:
        _, s = apply_map(params, x, from_wall, to_wall, t_guess)
    if not math.isfinite(s):
        return False
    return bool(admissible_kernel(model_array(params), x, (from_wall, to_wall), float(s)))


def mirror(x: ArrayLike, T: float) -> np.ndarray:
    """Symmetry of the model: (z, velocities) -> -(z, velocities), t -> t + T/2."""
    x = np.asarray(x, dtype=float)
    return np.array([-x[0], -x[1], -x[2], x[3] + 0.5 * T])
