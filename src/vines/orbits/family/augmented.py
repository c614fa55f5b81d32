"""Augmented systems of codimension-one points of 1:1 orbits, with exact Jacobians.

The unknowns are z = (u, [s_g], free parameters): the family's shooting unknowns u
(``shooting``), the grazing time s_g (grazing only) and one or two of eta, omega, F.
The equations are the family's residual E(u) = 0 plus the defining condition of the point
(A = Mirror J_P1 for symmetric orbits, A = J_P2 J_P1 for asymmetric ones):

    fold                 det(A - I) = 0
    flip                 det(A + I) = 0                    (asymmetric)
    symmetry-breaking    det(A + I) = 0                    (symmetric: half-map mu = -1)
    neimark-sacker       det(A (x) A - I) = 0               (second compound matrix)
    grazing              flight k touches a wall: w(s_g) = wall, w'(s_g) = 0 ("start" or
                         "target" wall, 0 < s_g < s_k), or arrives with w' = 0 ("arrival")

With one free parameter the system is square (a point, ``solve``); with two it defines a
curve in the parameter plane (``boundaries``). Every derivative is exact: first derivatives
of E and of the grazing conditions, and the derivatives of the determinants (which need the
flight's second derivatives), from Taylor jets, compiled (``kernels.codim1``);
``Codim1System.evaluate_jets`` computes the same from the pure-Python jets behind
``shooting.monodromy_jets`` (the reference).
"""
from __future__ import annotations

import numpy as np

from ...core.params import PARAM_NAMES
from ...core.walls import WALL_L, WALL_R
from ..jets import kernels as sk
from ..jets import shooting as sh
from ..jets import taylor as jets
from .systems import KINDS, compound2, solve

GRAZE_WALLS = ("start", "target", "arrival")
# the condition codes of ``kernels.codim1`` (index) and the kinds they serve
CONDITIONS = (("fold",), ("symmetry-breaking", "flip"), ("neimark-sacker",), ("grazing",))


class Codim1System:
    """G(z) = 0 of one codimension-one condition (module docstring); G, G_z = self(z).

    graze = (k, wall): flight k (1: L->R, 2: R->L) and wall in GRAZE_WALLS.
    """

    def __init__(self, model: sh.Model, family: str, kind: str, free: tuple, fixed: dict,
                 graze=None):
        if kind not in KINDS[family == "symmetric"]:
            raise ValueError(f"kind {kind!r} is not a condition of {family} orbits")
        self.m, self.family, self.kind = model, family, kind
        self.free, self.fixed = tuple(free), dict(fixed)
        self.graze = graze
        self.nu = sh.N_UNKNOWNS[family]
        self.has_sg = kind == "grazing" and graze[1] != "arrival"

    def par(self, z) -> dict:
        p = dict(self.fixed)
        for k, q in enumerate(self.free):
            p[q] = float(z[len(z) - len(self.free) + k])
        return p

    def _columns(self):
        """Global-variable indices (u, eta, omega, F, s_g) of the unknowns z."""
        cols = list(range(self.nu))
        if self.has_sg:
            cols.append(self.nu + 3)
        return cols + [self.nu + PARAM_NAMES.index(q) for q in self.free]

    def __call__(self, z):
        """(G, G_z) from the compiled kernel (``kernels.codim1``)."""
        z = np.asarray(z, dtype=float)
        p = self.par(z)
        k, wall = self.graze if self.graze is not None else (1, "arrival")
        G, Gg = sk.codim1(self.m.tape, sh.ORBIT_KINDS.index(self.family), self._cond,
                          int(k), GRAZE_WALLS.index(wall), z[:self.nu],
                          (p["eta"], p["omega"], p["F"]),
                          float(z[self.nu]) if self.has_sg else 0.0)
        return G, Gg[:, self._columns()]

    @property
    def _cond(self) -> int:
        return next(i for i, c in enumerate(CONDITIONS) if self.kind in c)

    def evaluate_jets(self, z):
        """(G, G_z) from the Python jets: the reference of the compiled ``__call__``."""
        z = np.asarray(z, dtype=float)
        p = self.par(z)
        u = z[:self.nu]
        sg = [z[self.nu]] if self.has_sg else []
        gv = jets.variables(list(u) + [p["eta"], p["omega"], p["F"]] + sg)
        E = sh.residual(self.m, self.family, gv[:self.nu], *gv[self.nu:self.nu + 3])
        if self.kind == "grazing":
            E += self._grazing(gv)
        else:
            E.append(self._test(u, p, len(gv)))
        return jets.values(E), jets.jacobian(E, len(gv))[:, self._columns()]

    def _test(self, u, p, n_global):
        A = sh.monodromy_jets(self.m, self.family, list(u), p["eta"], p["omega"], p["F"])
        if self.kind == "neimark-sacker":
            M = sh.shifted(compound2(A), -1.0)
        else:
            M = sh.shifted(A, -1.0 if self.kind == "fold" else 1.0)
        d = jets.det(M)
        g = np.zeros(n_global)
        g[:len(d.g)] = d.g
        return jets.Jet(d.v, g)

    def _grazing(self, gv):
        k, wall = self.graze
        u, (eta, omega, F) = gv[:self.nu], gv[self.nu:self.nu + 3]
        T = 2.0 * np.pi / omega
        s1 = 0.5 * T if self.family == "symmetric" else u[4]
        x, s_k, w0 = u[:4], s1, WALL_L
        if k == 2:
            x, _, _ = sh.flight(self.m, u[:4], s1, eta, omega, F, WALL_L)
            s_k, w0 = T - s1, WALL_R
        if wall == "arrival":
            return [sh.flight(self.m, x, s_k, eta, omega, F, w0)[2]]
        _, gap, wdot = sh.flight(self.m, x, gv[-1], eta, omega, F, w0)
        return [gap - (2.0 * w0 if wall == "start" else 0.0), wdot]


def grazing_point(model: sh.Model, family: str, u, param: str, par: dict, max_margin=1e-3):
    """The grazing that ends admissibility near the orbit u at par, solved as the square
    system with ``param`` free: (graze, u, value of param) or None (no grazing within
    ``max_margin`` of u, see ``grazing_guess``, or Newton fails).

    The shooting residual has the flight times as unknowns, so it stays regular where an
    arrival velocity vanishes (the maps' pole): the point is solved, not bisected for."""
    graze, s_g, margin = grazing_guess(model, family, u, par)
    if not margin <= max_margin:
        return None
    system = Codim1System(model, family, "grazing", (param,),
                          {q: v for q, v in par.items() if q != param}, graze)
    z0 = list(u[:system.nu]) + ([s_g] if system.has_sg else []) + [par[param]]
    z = solve(system, z0)
    if z is None:
        return None
    return graze, z[:system.nu], float(z[-1])


def grazing_guess(model: sh.Model, family: str, u, par: dict, n_sample=400):
    """The grazing of the orbit u closest to a wall contact: ((k, wall), s_g, margin).

    margin = |w' at arrival| for "arrival", else the distance to the wall at the interior
    minimum of the distance (s_g its time); the smallest margin wins."""
    eta, omega, F = par["eta"], par["omega"], par["F"]
    T = 2.0 * np.pi / omega
    s1 = 0.5 * T if family == "symmetric" else float(u[4])
    flights = [(1, list(u[:4]), s1, WALL_L)]
    if family == "asymmetric":
        y, _, _ = sh.flight(model, list(u[:4]), s1, eta, omega, F, WALL_L)
        flights.append((2, list(y), T - s1, WALL_R))
    best = None
    for k, x, s_k, w0 in flights:
        cands = [((k, "arrival"), s_k, abs(sh.flight(model, x, s_k, eta, omega, F, w0)[2]))]
        ss = np.linspace(0.0, s_k, n_sample + 1)[1:-1]
        w = np.array([sh.flight(model, x, s, eta, omega, F, w0)[1] - w0 for s in ss])
        for wall, dist in (("target", 1.0 + w0 * w), ("start", 1.0 - w0 * w)):
            # dist: distance to that wall (> 0 inside the cavity); interior minima only
            i = int(np.argmin(dist[1:-1])) + 1
            if dist[i] <= dist[i - 1] and dist[i] <= dist[i + 1]:
                cands.append(((k, wall), ss[i], abs(dist[i])))
        for c in cands:
            if best is None or c[2] < best[2]:
                best = c
    return best
