"""Curves of codimension-one points of 1:1 orbits in the (eta, omega) plane at fixed F.

``boundaries(F, eta_range, omega_range)``:

1. seeds: one-parameter continuations (``continuation.continue_branch``, arclength, with
   switching onto the asymmetric branches) along ``n_scan`` lines omega = const (in eta)
   and ``n_scan`` lines eta = const (in omega), from every 1:1 orbit the map solver finds
   at the line's start; their events on admissible orbits are the seeds (an
   admissibility-loss becomes the grazing closest to contact, ``augmented.grazing_guess``);
2. each seed not already on a traced curve of its kind is continued both ways with
   pseudo-arclength (``arclength.Tracer``) on its augmented system
   (``augmented.Codim1System``, free parameters eta and omega) until the curve leaves the
   box (the crossing is located), closes, or has ``max_points`` points per direction;
3. fold, flip, neimark-sacker and symmetry-breaking curves keep only their stretches on
   admissible orbits (elsewhere they are no edge of a stability class); neimark-sacker
   curves only where the crossing pair is complex (the second compound matrix also
   vanishes at real pairs lambda_1 lambda_2 = 1);
4. seeds a scan line never meets (e.g. an unstable family whose arrival velocity vanishes
   along a whole curve): on a coarse stability map (``stability_map``), every pair of
   neighbouring cells of different class with a cell in the box and no kept curve within
   1.5 cells is joined by a short one-parameter continuation from each admissible end; its
   events seed step 2.

These curves are the edges of the classes of ``stability_map`` (Fig 16).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from .. import progress
from ..core.params import (
    D_DEFAULT,
    R_DEFAULT,
    ModelParams,
    ParameterError,
    as_float_array,
    check_int,
    check_param,
    check_real,
    check_reals,
)
from . import augmented as ag
from . import shooting as sh
from .arclength import Tracer
from .branches import is_ns, orbit_at
from .sequence import check_periods, check_walls

CURVE_TYPES = ("fold", "flip", "neimark-sacker", "symmetry-breaking", "grazing")
U_WEIGHT = 0.2          # weight of the orbit unknowns in the arclength (eta, omega: 1)
BOX_TOL = 1e-9          # a located exit lies this close to the box side (then set on it)


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


@dataclass
class Boundaries:
    """The curves of one F and family (``boundaries``)."""

    F: float
    eta_range: tuple
    omega_range: tuple
    curves: list
    walls: str = "LR"
    periods: int = 1

    def to_dict(self) -> dict:
        out = {"F": self.F, "eta_range": list(self.eta_range),
               "omega_range": list(self.omega_range),
               "curves": [c.to_dict() for c in self.curves]}
        if (self.walls, self.periods) != ("LR", 1):     # the 1:1 output as it always was
            out.update(walls=self.walls, periods=self.periods)
        return out


def _system(model, family, kind, graze, F):
    return ag.Codim1System(model, family, kind, ("eta", "omega"), {"F": F}, graze)


class _CurveTracer:
    """Continuation of one curve inside the box."""

    def __init__(self, system, box, step, max_points):
        self.sys, self.box, self.step, self.max_points = system, box, step, max_points

    def inside(self, z) -> bool:
        return _in_box(z[-2:], self.box)

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
    ``sequence_curves``; free parameters eta, omega last), both ways inside the box."""
    ct = _CurveTracer(system, box, settings.step, settings.max_points)
    fwd, why_f = ct.half(np.asarray(z0, float), 1.0)
    bwd, why_b = ct.half(np.asarray(z0, float), -1.0)
    zs = np.array(bwd[::-1] + [np.asarray(z0, float)] + fwd)
    return Curve(system.kind, system.family, system.graze, zs[:, -2:].copy(), zs,
                 [why_b, why_f])


def _keep(curve: Curve, model, F) -> list:
    """The stretches of a curve that are class edges (module docstring, step 3)."""
    if curve.type == "grazing":
        return [curve]
    ok = []
    for z in curve.z:
        p = ModelParams(eta=z[-2], omega=z[-1], F=F, r=model.r, d=model.d, phi=model.phi)
        o = orbit_at(p, curve.family, z[:sh.N_UNKNOWNS[curve.family]])
        good = o is not None and o.admissible
        if good and curve.type == "neimark-sacker":
            good = is_ns(curve.family, o, tol=1e-6)
        ok.append(good)
    return pieces_of(curve, ok)


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


def crossings(curve: Curve, model, F, omega: float) -> list:
    """Exact eta values where the curve crosses omega = const (square system in eta)."""
    out = []
    w = curve.z[:, -1] - omega
    for i in np.nonzero(np.sign(w[:-1]) * np.sign(w[1:]) < 0)[0]:
        f = w[i] / (w[i] - w[i + 1])
        z = curve.z[i] + f * (curve.z[i + 1] - curve.z[i])
        system = ag.Codim1System(model, curve.family, curve.type, ("eta",),
                                 {"F": F, "omega": omega}, curve.graze)
        zs = ag.solve(system, z[:-1])
        if zs is not None:
            out.append(float(zs[-1]))
    return out


def boundaries(F: float, eta_range: Sequence[float], omega_range: Sequence[float],
               r: float = R_DEFAULT, d: float = D_DEFAULT, n_scan: int = 5,
               step: float = 0.01, max_points: int = 400, n_map: int = 25,
               class_map: tuple | None = None, walls: str = "LR",
               periods: int = 1) -> Boundaries:
    """Codimension-one curves of the orbits of ``walls``/``periods`` (default the 1:1
    family) in the box eta_range x omega_range at F.

    ``n_scan`` scan lines per parameter seed the curves. For the 1:1 family, class changes
    of an ``n_map`` x ``n_map`` stability map farther than 1.5 cells from every kept curve
    then seed more (module docstring, step 4; ``n_map = 0`` skips it); ``class_map`` =
    (eta, omega, cls): a stability map already computed at this F (``stability_map``),
    whose class changes are used instead of the n_map x n_map one. Other families
    (``sequence_boundaries``) are seeded by continuations through the n_scan x n_scan
    crossings of the scan lines and ignore n_map; ``class_map`` is for 1:1 only."""
    F = check_param("F", F)
    box = (_range("eta_range", eta_range), _range("omega_range", omega_range))
    n_scan = check_int("n_scan", n_scan, lo=1, hi=100)
    settings = CurveSettings(check_real("step", step, lo=1e-5, hi=1.0),
                             check_int("max_points", max_points, lo=1, hi=100_000))
    n_map = check_int("n_map", n_map, lo=0, hi=1000)
    class_map = _check_class_map(class_map)
    walls, periods = check_walls(walls), check_periods(periods)
    p = ModelParams(eta=1.0, omega=1.0, F=F, r=r, d=d)     # validates r and d
    if (walls, periods) != ("LR", 1):
        if class_map is not None:
            raise ParameterError("class_map", "(eta, omega, cls)", "must be None for a "
                                 "family other than 1:1 (walls LR, periods 1)")
        from .sequence_boundaries import sequence_boundaries
        curves = sequence_boundaries(p, (walls, periods), box, (n_scan, settings))
        return Boundaries(F, box[0], box[1], curves, walls, periods)
    model = sh.Model(p.r, p.d)
    traced = _Traced(_OneToOne(model, F), box, settings)
    for seed in _seeds(model, F, box, n_scan):
        traced.add(seed)
    if class_map is not None:
        edges = class_edges(*class_map)
    else:
        edges = _map_edges(model, F, box, n_map) if n_map >= 2 else []
    for edge in progress.track(edges, len(edges), "boundary edges", "edges"):
        # an edge with both cells outside the box cannot seed a curve inside it
        if (_in_box(edge[0], box) or _in_box(edge[1], box)) and not traced.explains(edge):
            for seed in _edge_seeds(model, F, edge):
                traced.add(seed)
    return Boundaries(F, box[0], box[1], traced.kept)


class _OneToOne:
    """Augmented systems and kept stretches of the 1:1 curves (``augmented``)."""

    def __init__(self, model, F):
        self.model, self.F = model, F

    def system(self, seed):
        family, kind, graze, _ = seed
        return _system(self.model, family, kind, graze, self.F)

    def keep(self, curve) -> list:
        return _keep(curve, self.model, self.F)


class _Traced:
    """The curves traced so far and their kept stretches (module docstring, step 3);
    ``kit`` makes a seed's augmented system and keeps a curve's class edges."""

    def __init__(self, kit, box, settings: CurveSettings):
        self.kit, self.box, self.settings = kit, box, settings
        self.curves, self.kept = [], []

    def add(self, seed):
        """Trace the curve through a seed unless a curve of its kind passes there."""
        z0 = seed[3]
        if not _in_box(z0[-2:], self.box) or _on_curve(self.curves, seed,
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


def _map_edges(model, F, box, n_map):
    """The class-changing edges (``class_edges``) of an n_map x n_map stability map."""
    from .stability_map import stability_map
    eta, omega = np.linspace(*box[0], n_map), np.linspace(*box[1], n_map)
    cls = stability_map(eta, omega, F, r=model.r, d=model.d, n_threads=1)["cls"]
    return class_edges(eta, omega, cls)


def class_edges(eta: ArrayLike, omega: ArrayLike, cls: ArrayLike) -> list:
    """((eta, omega) of both cells, cell size, their classes) of every pair of neighbouring
    cells of a stability map (classes ``cls`` over the axes eta, omega) that differ."""
    eta, omega, cls = np.asarray(eta, float), np.asarray(omega, float), np.asarray(cls)
    cell = np.array([np.min(np.diff(eta)), np.min(np.diff(omega))])
    out = []
    for i in range(eta.size):
        for j in range(omega.size):
            for i2, j2 in ((i + 1, j), (i, j + 1)):
                if i2 < eta.size and j2 < omega.size and cls[i, j] != cls[i2, j2]:
                    out.append(((eta[i], omega[j]), (eta[i2], omega[j2]), cell,
                                (int(cls[i, j]), int(cls[i2, j2]))))
    return out


def _edge_seeds(model, F, edge):
    """Seeds of one-parameter continuations along a class-changing edge, from each end
    with an admissible 1:1 orbit towards the other (the event between them is the seed)."""
    from .continuation import continue_branch
    from .periodic import orbits_1to1
    a, b, _, classes = edge
    k = 0 if a[0] != b[0] else 1
    param = ("eta", "omega")[k]
    for start, stop, c in ((a, b, classes[0]), (b, a, classes[1])):
        if c == 0:
            continue
        fixed = {"F": F, ("omega", "eta")[k]: float(start[1 - k])}
        for o in orbits_1to1(ModelParams(eta=start[0], omega=start[1], F=F, r=model.r,
                                          d=model.d), simulation=False):
            if not o.admissible:
                continue
            kind = "symmetric" if o.symmetric else "asymmetric"
            br = continue_branch(param, float(start[k]), float(stop[k]),
                                 abs(stop[k] - start[k]) / 10.0, fixed, orbit=o, r=model.r,
                                 d=model.d, branch=kind, switch=kind == "symmetric",
                                 max_inadmissible=5, max_points=200)
            for bb in [br] + br.switched:
                yield from _branch_seeds(model, bb, param, fixed, F)


def _in_box(point, box) -> bool:
    """(eta, omega) = point lies in the box ((eta_lo, eta_hi), (omega_lo, omega_hi))."""
    (e0, e1), (w0, w1) = box
    return e0 <= point[0] <= e1 and w0 <= point[1] <= w1


def _check_class_map(class_map):
    """None or (eta, omega, cls): increasing axes of >= 2 values and integer classes of
    shape (len(eta), len(omega)), as ``stability_map`` returns them."""
    allowed = ("must be None or (eta, omega, cls) of a stability map: increasing axes of >= 2 "
               "values, classes of shape (len(eta), len(omega))")
    if class_map is None:
        return None
    if not isinstance(class_map, (list, tuple)) or len(class_map) != 3:
        raise ParameterError("class_map", class_map, allowed)
    try:
        eta = check_reals("class_map", class_map[0], min_size=2)
        omega = check_reals("class_map", class_map[1], min_size=2)
        cls = as_float_array("class_map", class_map[2])
    except ParameterError:
        raise ParameterError("class_map", class_map, allowed) from None
    if (np.any(np.diff(eta) <= 0) or np.any(np.diff(omega) <= 0)
            or cls.shape != (eta.size, omega.size) or not np.all(np.isfinite(cls))
            or np.any(cls != np.round(cls))):
        raise ParameterError("class_map", class_map, allowed)
    return class_map


def _range(name, value) -> tuple:
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be two numbers lo < hi") from None
    q = name.split("_")[0]
    try:
        lo, hi = check_param(q, lo), check_param(q, hi)
    except ParameterError as err:
        raise ParameterError(name, list(value), f"{err.allowed} (both ends)") from None
    if not lo < hi:
        raise ParameterError(name, value, "must be two numbers lo < hi")
    return lo, hi


def _on_curve(curves, seed, step) -> bool:
    family, kind, graze, z0 = seed
    # the mirror image of an asymmetric orbit swaps its flights: one curve for both
    key = (family, kind, None if graze is None else graze[1])
    for c in curves:
        if ((c.family, c.type, None if c.graze is None else c.graze[1]) == key
                and np.min(np.hypot(*(c.all_points - z0[-2:]).T)) < 3.0 * step):
            return True
    return False


def _seeds(model, F, box, n_scan):
    """(family, kind, graze, z0) from one-parameter scans (module docstring, step 1)."""
    from .continuation import continue_branch
    from .periodic import orbits_1to1
    (e0, e1), (w0, w1) = box
    lines = [("eta", e0, e1, {"omega": w, "F": F}) for w in np.linspace(w0, w1, n_scan)]
    lines += [("omega", w0, w1, {"eta": e, "F": F}) for e in np.linspace(e0, e1, n_scan)]
    for param, start, stop, fixed in progress.track(lines, len(lines), "boundary scan", "lines"):
        p = dict(fixed, **{param: start})
        orbits = orbits_1to1(ModelParams(eta=p["eta"], omega=p["omega"], F=F, r=model.r,
                                         d=model.d), simulation=False)
        for kind in ("symmetric", "asymmetric"):
            cands = [o for o in orbits if o.symmetric == (kind == "symmetric")]
            for o in cands[:1 if kind == "asymmetric" else 2]:
                br = continue_branch(param, start, stop, (stop - start) / 50.0, fixed,
                                     orbit=o, r=model.r, d=model.d, branch=kind,
                                     switch=kind == "symmetric", max_inadmissible=20,
                                     max_points=2000)
                for b in [br] + br.switched:
                    yield from _branch_seeds(model, b, param, fixed, F)


def _branch_seeds(model, br, param, fixed, F):
    for ev in br.events:
        o = br.orbits[ev["index"]]
        typ = ev["type"]
        if typ == "symmetry-breaking" and br.family == "asymmetric":
            continue
        z = np.asarray(ev["z"], float)
        par = dict(fixed, **{param: float(z[-1])})
        u = list(z[:-1])
        graze, extra = None, []
        if typ == "admissibility-loss":
            graze, s_g, margin = ag.grazing_guess(model, br.family, u, par)
            if margin > 1e-3:
                continue
            extra = [] if graze[1] == "arrival" else [s_g]
            typ = "grazing"
        elif not o.admissible:
            continue
        z0 = np.array(u + extra + [par["eta"], par["omega"]])
        system = ag.Codim1System(model, br.family, typ, (param,),
                                 {q: v for q, v in par.items() if q != param}, graze)
        zs = ag.solve(system, z0[:-1] if param == "eta" else np.append(z0[:-2], z0[-1]))
        if zs is None:
            continue
        z0[:-2] = zs[:-1]
        z0[-2 if param == "eta" else -1] = zs[-1]
        yield br.family, typ, graze, z0
