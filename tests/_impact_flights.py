"""An independent impact-to-impact flight for the orbit tests: the free flight of SPEC.md
section 1 integrated by scipy's DOP853 (rtol = atol = ``RTOL``) from the impact law of
SPEC.md (Eq. 10), written out here; no vines code. States are pre-impact
x = (z_m', z_b', z_b, t) at a wall (L: w = z_m - z_b = +1, R: w = -1)."""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

RTOL = 1e-12
WALLS = {"L": 1.0, "R": -1.0}


def after_impact(p, vm, vb):
    """Velocities just after an impact (SPEC.md, Eq. 10)."""
    eta, r = p.eta, p.r
    return (((1 - r * eta) * vm + eta * (1 + r) * vb) / (1 + eta),
            ((1 + r) * vm + (eta - r) * vb) / (1 + eta))


def _rhs(p):
    W, F, d, phi = p.omega, p.F, p.d, p.phi

    def f(t, y):
        th = W * t + phi
        return [y[1], -d * y[1] - y[0] + F * math.sin(th) + d * W * F * math.cos(th), y[3], 0.0]
    return f


def _wall_events():
    def at_L(t, y):
        return y[0] - y[2] - 1.0
    at_L.terminal, at_L.direction = True, 1.0

    def at_R(t, y):
        return y[0] - y[2] + 1.0
    at_R.terminal, at_R.direction = True, -1.0
    return at_L, at_R


def flight(p, x, wall: str, t_max: float, dense: bool = False):
    """From the pre-impact state x at ``wall``: (the wall reached first, the pre-impact
    state there, the solution object). The wall is None when none is reached before
    x[3] + t_max."""
    vm, vb, zb, t0 = x
    vmp, vbp = after_impact(p, vm, vb)
    sol = solve_ivp(_rhs(p), (t0, t0 + t_max), [zb + WALLS[wall], vmp, zb, vbp],
                    method="DOP853", rtol=RTOL, atol=RTOL, events=_wall_events(),
                    dense_output=dense)
    for name, te, ye in zip("LR", sol.t_events, sol.y_events, strict=True):
        if len(te):
            y = ye[0]
            return name, np.array([y[1], y[3], y[2], te[0]]), sol
    return None, None, sol


def orbit_flights(p, walls: str, x0, span: float, dense: bool = False):
    """The walls reached and the pre-impact states after each of len(walls) flights from
    x0 at walls[0] (each flight at most ``span``), and the flights' solution objects."""
    x, reached, states, sols = np.asarray(x0, float), [], [], []
    for w in walls:
        to, x, sol = flight(p, x, w, span, dense)
        reached.append(to)
        states.append(x)
        sols.append(sol)
        if to is None:
            break
    return reached, states, sols
