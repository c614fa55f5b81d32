"""Augmented systems of codimension-one points of orbits of any wall sequence.

A family (``Family``) is a wall sequence, its number of forcing periods and whether
its orbits are symmetric (sequence with the half symmetry, odd periods, orbit invariant
under the mirror z -> -z, t -> t + periods T / 2; ``sequence``). The orbit unknown is the
pre-impact state x_0 at walls[0]; the orbit residual R(x_0) is

    asymmetric   P_{n-1}(...P_0(x_0)) - x_0 - (0, 0, 0, N T)          A = J_{n-1} ... J_0
    symmetric    M P_{h-1}(...P_0(x_0)) - x_0 - (0, 0, 0, N T / 2)     A = M J_{h-1} ... J_0

(h = n / 2, M = diag(-1, -1, -1, 1) the mirror; A is the Jacobian of the (half-)map, so
R_x = A - I exactly, from the map Jacobians of ``maps``). On a symmetric orbit the
monodromy matrix is A^2: an eigenvalue +1 of A is a fold, -1 a symmetry-breaking point
(both are +1 of A^2). The condition added to R:

    fold                 det(A - I) = 0
    flip                 det(A + I) = 0          (asymmetric)
    symmetry-breaking    det(A + I) = 0          (symmetric: half-map mu = -1)
    neimark-sacker       det(A^[2] - I) = 0      (A^[2] the second compound matrix)

The derivatives of R in x_0 are exact (the maps' Jacobians); those of R in the parameters
and of the condition (which needs the maps' second derivatives) are exact too with
``derivatives="jets"`` (the default: ``jets.chain``, Taylor jets of the composed flights),
central differences with ``"differences"`` and wherever the jets do not apply (d outside
(0, 2)). They steer Newton only: every point is a root of the system to the corrector's
tolerance.

Grazing (admissibility lost) cannot use the maps: at an arrival with zero relative velocity
the map's flight time has a square-root branch. Its system keeps the flight times s_k as
unknowns (shooting): z = (x_0, s_0 .. s_{m-1}, [s_g], parameters), equations w_k(s_k) =
target wall (each flight, closed-form flow), the closure of (z_m', z_b', z_b) (mirrored for
symmetric families) and sum s_k = N T (or N T / 2), plus the grazing of flight k at wall
"L" or "R" (w_k(s_g) = wall, w_k'(s_g) = 0, 0 < s_g < s_k) or at its "arrival"
(w_k'(s_k) = 0); flights are numbered from 1 (flight k from impact k to impact k + 1, so
that for "LR" flight 1 is L->R and 2 is R->L, as for the 1:1 curves). Its derivatives come
from the jets of the same flights (``jets.chain.shooting_jacobian``), or central
differences as for the maps.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ...core.exact import oscillators
from ...core.flow import flow
from ...core.params import PARAM_NAMES, ModelParams, ParameterError, check_choice
from ...core.walls import impact_velocities
from ..jets import chain as jet_chain
from ..maps.impact import impact_map, model_array
from ..maps.newton import monodromy
from .family import MIRROR_SIGNS, WALL_CODES, Family
from .sequence import SequenceOrbit, orbit_through
from .systems import KINDS, compound2

FD_PARAM = 1e-7         # relative central-difference step of a parameter column
FD_STATE = 1e-6         # relative central-difference step of the condition's gradient
#: the derivative methods of the systems: exact Taylor jets (``jets.chain``), central
#: differences (the fallback where the jets do not apply)
DERIVATIVES = ("jets", "differences")


def family_of(orbit: SequenceOrbit) -> Family:
    return Family(orbit.walls, int(orbit.periods), bool(orbit.symmetric))


def with_values(base: ModelParams, values: dict) -> ModelParams:
    """``base`` with some parameters replaced (validated)."""
    return dataclasses.replace(base, **{k: float(v) for k, v in values.items()})


# --------------------------------------------------------------------------- maps

def chain(p: ModelParams, fam: Family, x0, s_guess):
    """(xs, Js, flights) of the family's flights from x0 (maps with Jacobians; flight
    guesses s_guess, <= 0: first contact), or None when a map fails."""
    mdl = model_array(p)
    codes = fam.codes()
    n, m = codes.size, fam.flights
    xs = np.empty((m + 1, 4))
    Js = np.empty((m, 4, 4))
    fl = np.empty(m)
    xs[0] = x0
    for k in range(m):
        s = impact_map(mdl, xs[k], (codes[k], codes[(k + 1) % n]), s_guess[k], xs[k + 1],
                       Js[k])
        if not math.isfinite(s):
            return None
        fl[k] = s
    return xs, Js, fl


def orbit_residual(p: ModelParams, fam: Family, x0, s_guess):
    """(R, A, flights) of the module docstring at x0, or None when a map fails."""
    got = chain(p, fam, x0, s_guess)
    if got is None:
        return None
    xs, Js, fl = got
    A = monodromy(Js)
    end = xs[-1]
    if fam.symmetric:
        end, A = MIRROR_SIGNS * end, MIRROR_SIGNS[:, None] * A
    R = end - x0
    R[3] -= fam.span(p)
    return R, A, fl


def exact_derivatives(p: ModelParams, fam: Family, x0, fl, kind: str | None = None):
    """(dR (4, 7), dg (7)): R's Jacobian and the gradient of ``kind``'s condition (zeros
    for None) over (x_0, eta, omega, F), exact (``jets.chain``) at the maps' flight times
    fl; None where the jets do not apply (d outside (0, 2)) or give no finite number."""
    model = jet_chain.model_of(p.r, p.d, p.phi)
    if model is None:
        return None
    _, dR, _, dg = jet_chain.residual_derivatives(
        model, fam.codes()[:fam.flights], fam.symmetric, fam.span(p), (p.eta, p.omega, p.F),
        x0, fl, kind)
    if not (np.isfinite(dR).all() and np.isfinite(dg).all()):
        return None
    return dR, dg


def param_columns(free: tuple) -> list[int]:
    """The columns of the parameters ``free`` in ``exact_derivatives``."""
    return [4 + PARAM_NAMES.index(q) for q in free]


def condition(kind: str, A) -> float:
    """The determinant of the module docstring for ``kind``."""
    if kind == "neimark-sacker":
        return float(np.linalg.det(np.array(compound2(A)) - np.eye(6)))
    return float(np.linalg.det(A + (-1.0 if kind == "fold" else 1.0) * np.eye(4)))


# --------------------------------------------------------------------------- systems

class _Layout:
    """The unknowns z = (x_0, [flights, s_g], free parameters) and the parameter point."""

    def __init__(self, base: ModelParams, free: tuple, n_front: int):
        self.base, self.free, self.n_front = base, tuple(free), n_front

    def params(self, z) -> ModelParams:
        return with_values(self.base, dict(zip(self.free, z[self.n_front:], strict=True)))

    def step(self, z, i) -> float:
        scale = FD_PARAM if i >= self.n_front else FD_STATE
        return scale * (1.0 + abs(z[i]))

    def pair(self, z, i) -> tuple[np.ndarray, np.ndarray, float]:
        """(z + h e_i, z - h e_i, h): the central-difference pair of unknown i."""
        h = self.step(z, i)
        zp, zm = z.copy(), z.copy()
        zp[i] += h
        zm[i] -= h
        return zp, zm, h


class MapSystem:
    """G(z) = (R, condition) of a fold, flip, symmetry-breaking or Neimark-Sacker point:
    z = (x_0, free parameters); G, G_z = self(z) (module docstring); ``derivatives``: one
    of ``DERIVATIVES``."""

    def __init__(self, base: ModelParams, fam: Family, kind: str, free: tuple,
                 derivatives: str = "jets"):
        if kind not in KINDS[fam.symmetric] or kind == "grazing":
            raise ValueError(f"{kind!r} is not a map condition of {fam.name} orbits")
        self.fam, self.kind, self.graze = fam, kind, None
        self.derivatives = check_choice("derivatives", derivatives, DERIVATIVES)
        self.family = fam.name
        self.lay = _Layout(base, free, 4)
        self.s = np.full(fam.flights, -1.0)

    def _value(self, z, update=False):
        try:
            got = orbit_residual(self.lay.params(z), self.fam, z[:4], self.s)
        except ParameterError:      # a parameter left its range
            return None
        if got is None:
            return None
        R, A, fl = got
        if update:
            self.s = fl.copy()
        return R, A, condition(self.kind, A)

    def __call__(self, z):
        z = np.asarray(z, float)
        got = self._value(z, update=True)
        if got is None:
            return np.full(5, np.nan), np.full((5, z.size), np.nan)
        R, A, g = got
        Gz = np.empty((5, z.size))
        Gz[:4, :4] = A - np.eye(4)
        if self.derivatives == "jets" and self._exact(z, Gz):
            return np.append(R, g), Gz
        return self._differences(z, (R, g), Gz)

    def _exact(self, z, Gz) -> bool:
        """Fill Gz's parameter columns and condition row from the jets; False where they
        do not apply."""
        got = exact_derivatives(self.lay.params(z), self.fam, z[:4], self.s, self.kind)
        if got is None:
            return False
        dR, dg = got
        cols = param_columns(self.lay.free)
        Gz[:4, 4:] = dR[:, cols]
        Gz[4] = dg[[0, 1, 2, 3, *cols]]
        return True

    def _differences(self, z, G, Gz):
        """(G, Gz) with Gz's parameter columns and condition row central differences."""
        R, g = G
        bad = (np.full(5, np.nan), np.full(Gz.shape, np.nan))
        for i in range(z.size):
            zp, zm, h = self.lay.pair(z, i)
            vp, vm = self._value(zp), self._value(zm)
            if vp is None or vm is None:
                return bad
            if i >= 4:
                Gz[:4, i] = (vp[0] - vm[0]) / (2.0 * h)
            Gz[4, i] = (vp[2] - vm[2]) / (2.0 * h)
        return np.append(R, g), Gz

    def flights(self, z) -> np.ndarray | None:
        """The full sequence's flight times of the orbit at z (None if a map fails)."""
        got = self._value(np.asarray(z, float))
        return None if got is None else self.fam.full_flights(self.s)


def flight(osc, p: ModelParams, x, s, wall):
    """(w, w', next pre-impact state) of the flight of length s from x at ``wall``."""
    vp, vbp = impact_velocities(p.eta, p.r, x[0], x[1])
    th0 = p.omega * x[3] + p.phi
    z, v, _, _, _ = flow(osc, x[2] + wall, vp, math.sin(th0), math.cos(th0), s)
    zb = x[2] + vbp * s
    return z - zb, v - vbp, np.array([v, vbp, zb, x[3] + s])


class GrazingSystem:
    """G(z) of a grazing point: z = (x_0, flights, [s_g], free parameters), graze =
    (k, wall): flight k (from 1) and wall "L", "R" (interior contact) or "arrival" (module
    docstring)."""

    kind = "grazing"

    def __init__(self, base: ModelParams, fam: Family, graze: tuple, free: tuple,
                 derivatives: str = "jets"):
        self.fam, self.graze = fam, (int(graze[0]), str(graze[1]))
        self.derivatives = check_choice("derivatives", derivatives, DERIVATIVES)
        self.family = fam.name
        self.m = fam.flights
        self.has_sg = self.graze[1] != "arrival"
        self.lay = _Layout(base, free, 4 + self.m + int(self.has_sg))

    def residual(self, z):
        try:
            p = self.lay.params(z)
            osc = oscillators(p)[0]
        except ParameterError:
            return None
        codes = self.fam.codes()
        n, m = codes.size, self.m
        x, s = np.asarray(z[:4], float), z[4:4 + m]
        E = []
        for k in range(m):
            w, wd, y = flight(osc, p, x, s[k], codes[k])
            E.append(w - codes[(k + 1) % n])
            if k + 1 == self.graze[0]:
                E += self._graze(osc, p, x, codes[k], (wd, z))
            x = y
        end = MIRROR_SIGNS * x if self.fam.symmetric else x
        E += list(end[:3] - z[:3]) + [float(np.sum(s)) - self.fam.span(p)]
        return np.array(E)

    def _graze(self, osc, p, x, wall, at):
        wd, z = at
        if not self.has_sg:
            return [wd]
        w, wdg, _ = flight(osc, p, x, z[4 + self.m], wall)
        return [w - WALL_CODES[self.graze[1]], wdg]

    def __call__(self, z):
        z = np.asarray(z, float)
        G = self.residual(z)
        ne = self.m + 4 + (2 if self.has_sg else 1)
        if G is None:
            return np.full(ne, np.nan), np.full((ne, z.size), np.nan)
        if self.derivatives == "jets":
            Gz = self._exact(z)
            if Gz is not None:
                return G, Gz
        Gz = np.empty((ne, z.size))
        for i in range(z.size):
            zp, zm, h = self.lay.pair(z, i)
            Gp, Gm = self.residual(zp), self.residual(zm)
            if Gp is None or Gm is None:
                return np.full(ne, np.nan), np.full((ne, z.size), np.nan)
            Gz[:, i] = (Gp - Gm) / (2.0 * h)
        return G, Gz

    def _exact(self, z):
        """G_z from the jets (``jets.chain.shooting_jacobian``), or None where they do not
        apply."""
        p = self.lay.params(z)
        model = jet_chain.model_of(p.r, p.d, p.phi)
        if model is None:
            return None
        codes, m = self.fam.codes(), self.m
        walls = [codes[k % codes.size] for k in range(m + 1)]
        wall = 0 if not self.has_sg else WALL_CODES[self.graze[1]]
        u = np.append(z[:4 + m + int(self.has_sg)], 0.0)
        _, dE = jet_chain.grazing_derivatives(model, walls, self.fam.symmetric,
                                              self.fam.span(p), (p.eta, p.omega, p.F), u,
                                              (self.graze[0] - 1, wall))
        cols = [*range(4 + m + int(self.has_sg)), *(1 + m + c for c in
                                                     param_columns(self.lay.free))]
        Gz = dE[:, cols]
        return Gz if np.isfinite(Gz).all() else None

    def flights(self, z) -> np.ndarray:
        return self.fam.full_flights(np.asarray(z[4:4 + self.m], float))


def grazing_guess(orbit: SequenceOrbit, fam: Family, n_sample=400):
    """The contact of the orbit's flights closest to a grazing: ((k, wall), s_g, margin);
    margin = |w'| at the arrival, or the distance to a wall at an interior minimum."""
    p = orbit.params
    osc = oscillators(p)[0]
    codes = fam.codes()
    best = None
    for k in range(fam.flights):
        x, s_k, w0 = orbit.states[k], orbit.flight_times[k], codes[k]
        cands = [((k + 1, "arrival"), s_k, abs(flight(osc, p, x, s_k, w0)[1]))]
        ss = np.linspace(0.0, s_k, n_sample + 1)[1:-1]
        w = np.array([flight(osc, p, x, s, w0)[0] for s in ss])
        for wall in ("L", "R"):
            dist = 1.0 - WALL_CODES[wall] * w       # > 0 inside the cavity
            i = int(np.argmin(dist[1:-1])) + 1
            if dist[i] <= dist[i - 1] and dist[i] <= dist[i + 1]:
                cands.append(((k + 1, wall), ss[i], abs(dist[i])))
        for c in cands:
            if best is None or c[2] < best[2]:
                best = c
    return best


def make_system(base: ModelParams, fam: Family, kind: str, graze, free: tuple,
                derivatives: str = "jets"):
    if kind == "grazing":
        return GrazingSystem(base, fam, graze, free, derivatives)
    return MapSystem(base, fam, kind, free, derivatives)


def unknowns(orbit: SequenceOrbit, fam: Family, graze=None, s_g=None) -> list:
    """The leading unknowns (x_0, [flights, s_g]) of an orbit for a system of ``fam``."""
    u = list(orbit.states[0])
    if graze is None:
        return u
    u += list(orbit.flight_times[:fam.flights])
    return u + ([] if graze[1] == "arrival" else [float(s_g)])


def orbit_of(system, z) -> SequenceOrbit | None:
    """The classified orbit through the point z of a system, as it stands
    (``sequence.orbit_through``: no second Newton, ill-conditioned at a fold)."""
    fl = system.flights(z)
    if fl is None:
        return None
    try:
        p = system.lay.params(z)
    except ParameterError:
        return None
    fam = system.fam
    return orbit_through(p, fam.walls, fam.periods, z[:4], fl)
