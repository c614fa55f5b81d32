"""The tracer of codimension-one curves in (eta, omega), shared by every family.

A curve is continued both ways by pseudo-arclength (``continuation.arclength.Tracer``) on an
augmented system (``family.augmented.Codim1System`` for the 1:1 orbits,
``family.map_systems`` for any wall sequence; free parameters eta and omega last) until it
leaves the box (the crossing is located), closes, or has ``max_points`` points per
direction. ``Traced`` keeps the curves traced so far and, through a family's kit (its
``system(seed)`` and ``keep(curve)``), their stretches that are class edges.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ... import progress
from ..continuation.arclength import Tracer

CURVE_TYPES = ("fold", "flip", "neimark-sacker", "symmetry-breaking", "grazing")

U_WEIGHT = 0.2          # weight of the orbit unknowns in the arclength (eta, omega: 1)

BOX_TOL = 1e-9          # a located exit lies this close to the box side (then set on it)
#: a kept neimark-sacker point has a complex pair this close to |mu| = 1 (the tolerance of a
#: located neimark-sacker event is ``continuation.follower.NS_LOCATE_TOL``)
NS_KEEP_TOL = 1e-6


@dataclass
class Curve:
    """One traced curve: points (n, 2) of (eta, omega) and the full unknowns z (n, m)."""

    type: str
    family: str
    graze: tuple | None
    points: np.ndarray
    z: np.ndarray
    stopped: list = field(default_factory=list)

    def to_dict(self) -> dict:
        out = {"type": self.type, "family": self.family,
               "points": [[float(a), float(b)] for a, b in self.points]}
        if self.graze is not None:
            out["flight"], out["wall"] = int(self.graze[0]), self.graze[1]
        return out


class CurveTracer:
    """Continuation of one curve inside the box."""

    def __init__(self, system, box, step, max_points):
        self.sys, self.box, self.step, self.max_points = system, box, step, max_points

    def inside(self, z) -> bool:
        return in_box(z[-2:], self.box)

    def half(self, z0, sign):
        """Points from z0 (excluded) in one direction; (list of z, why it stopped)."""
        scale = np.full(len(z0), U_WEIGHT)
        scale[-2:] = 1.0
        d = np.zeros(len(z0))
        try:
            tr = Tracer(self.sys, z0, d, self.step, 1e-6, self.step, scale=scale)
        except (np.linalg.LinAlgError, ValueError):
            return [], "singular start"
        tr.t = sign * tr.tangent(self.sys(z0)[1], np.ones(len(z0)))
        out = []
        while len(out) < self.max_points:
            progress.check()
            st = tr.step()
            if st is None:
                return out, "step below min_step"
            if not self.inside(st.z1):
                out.append(self._exit(tr, st))
                return [z for z in out if z is not None], "left the box"
            out.append(st.z1)
            if len(out) > 5 and np.hypot(*(st.z1[-2:] - z0[-2:])) < 0.5 * tr.h:
                return out, "closed"
        return out, "max_points"

    def _exit(self, tr, st):
        """The point where the step leaves the box: the first crossing of a box side
        along the step (None if no crossing can be located inside the box)."""
        (e0, e1), (w0, w1) = self.box
        z = st.z1
        best = None
        for k, lo, hi in ((-2, e0, e1), (-1, w0, w1)):
            if lo <= z[k] <= hi:
                continue
            b = hi if z[k] > hi else lo
            loc = tr.locate(st, lambda zz, t, k=k, b=b: zz[k] - b, st.z0[k] - b, z[k] - b)
            if loc is None or abs(loc[1][k] - b) > BOX_TOL:
                continue
            loc[1][k] = b
            if self.inside(loc[1]) and (best is None or loc[0] < best[0]):
                best = loc
        return None if best is None else best[1]


@dataclass(frozen=True)
class CurveSettings:
    """How curves are traced: largest arclength step, most points per direction."""

    step: float = 0.01
    max_points: int = 400


def trace(system, z0, box, settings: CurveSettings = CurveSettings()) -> Curve:
    """The curve through z0 of an augmented system (``augmented.Codim1System`` or
    ``map_systems``; free parameters eta, omega last), both ways inside the box."""
    ct = CurveTracer(system, box, settings.step, settings.max_points)
    fwd, why_f = ct.half(np.asarray(z0, float), 1.0)
    bwd, why_b = ct.half(np.asarray(z0, float), -1.0)
    zs = np.array(bwd[::-1] + [np.asarray(z0, float)] + fwd)
    return Curve(system.kind, system.family, system.graze, zs[:, -2:].copy(), zs,
                 [why_b, why_f])


def pieces_of(curve: Curve, ok) -> list:
    """The stretches of at least two consecutive points of ``curve`` where ``ok``."""
    ok = np.array(ok, bool)
    pieces = []
    start = None
    for i, g in enumerate(list(ok) + [False]):
        if g and start is None:
            start = i
        elif not g and start is not None:
            if i - start >= 2:
                sl = slice(start, i)
                pieces.append(Curve(curve.type, curve.family, curve.graze,
                                    curve.points[sl], curve.z[sl], curve.stopped))
            start = None
    return pieces


class Traced:
    """The curves traced so far and their kept stretches (module docstring, step 3);
    ``kit`` makes a seed's augmented system and keeps a curve's class edges."""

    def __init__(self, kit, box, settings: CurveSettings):
        self.kit, self.box, self.settings = kit, box, settings
        self.curves, self.kept = [], []

    def add(self, seed):
        """Trace the curve through a seed unless a curve of its kind passes there."""
        z0 = seed[3]
        if not in_box(z0[-2:], self.box) or _on_curve(self.curves, seed,
                                                          self.settings.step):
            return
        c = trace(self.kit.system(seed), z0, self.box, self.settings)
        c.all_points = c.points
        self.curves.append(c)
        self.kept.extend(self.kit.keep(c))

    def explains(self, edge) -> bool:
        """A kept curve passes within 1.5 cells of the middle of a class-changing edge."""
        if not self.kept:
            return False
        (a, b), cell = edge[:2], edge[2]
        mid = 0.5 * (np.asarray(a) + np.asarray(b))
        pts = np.concatenate([c.points for c in self.kept])
        return float(np.min(np.hypot(*((pts - mid) / cell).T))) <= 1.5


def in_box(point, box) -> bool:
    """(eta, omega) = point lies in the box ((eta_lo, eta_hi), (omega_lo, omega_hi))."""
    (e0, e1), (w0, w1) = box
    return e0 <= point[0] <= e1 and w0 <= point[1] <= w1


def _on_curve(curves, seed, step) -> bool:
    family, kind, graze, z0 = seed
    # the mirror image of an asymmetric orbit swaps its flights: one curve for both
    key = (family, kind, None if graze is None else graze[1])
    for c in curves:
        if ((c.family, c.type, None if c.graze is None else c.graze[1]) == key
                and np.min(np.hypot(*(c.all_points - z0[-2:]).T)) < 3.0 * step):
            return True
    return False


def crossings(curve: Curve, line: tuple, solve) -> list[np.ndarray]:
    """Exact points (eta, omega) where a curve crosses the line param = value (line =
    (param, value), param eta or omega): ``solve(z)`` solves the family's square system with
    the other parameter free from the unknowns z (that parameter last) interpolated
    between the curve points around each sign change; the solution or None."""
    param, value = line
    k = 0 if param == "eta" else 1
    out = []
    w = curve.points[:, k] - value
    for i in np.nonzero(np.sign(w[:-1]) * np.sign(w[1:]) < 0)[0]:
        f = w[i] / (w[i] - w[i + 1])
        z = curve.z[i] + f * (curve.z[i + 1] - curve.z[i])
        zs = solve(np.append(z[:-2], z[-1 - k]))
        if zs is not None:
            pt = [value, float(zs[-1])] if k == 0 else [float(zs[-1]), value]
            out.append(np.array(pt))
    return out
