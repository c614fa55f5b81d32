"""Curves of codimension-one points of 1:1 orbits in the (eta, omega) plane at fixed F
(``one_to_one_curves``, called by ``boundaries.boundaries`` for the 1:1 family):

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

import numpy as np
from numpy.typing import ArrayLike

from ... import progress
from ...core.params import ModelParams
from ..atlas.stability_map import stability_map
from ..continuation.follower import is_ns, orbit_at
from ..continuation.one_to_one import continue_branch
from ..family import augmented as ag
from ..family.periodic import orbits_1to1
from ..family.systems import solve
from ..jets import shooting as sh
from . import tracer
from .tracer import NS_KEEP_TOL, Curve, CurveSettings, Traced, in_box, pieces_of


def one_to_one_curves(p: ModelParams, box, settings: CurveSettings, seeding: tuple) -> list:
    """Kept curves of the 1:1 orbits in the box at p's F (module docstring); seeding =
    (n_scan, n_map, class_map) as ``boundaries.boundaries`` takes them."""
    n_scan, n_map, class_map = seeding
    F = p.F
    model = sh.Model(p.r, p.d)
    traced = Traced(OneToOneKit(model, F), box, settings)
    for seed in _seeds(model, F, box, n_scan):
        traced.add(seed)
    if class_map is not None:
        edges = class_edges(*class_map)
    else:
        edges = _map_edges(model, F, box, n_map) if n_map >= 2 else []
    for edge in progress.track(edges, len(edges), "boundary edges", "edges"):
        # an edge with both cells outside the box cannot seed a curve inside it
        if (in_box(edge[0], box) or in_box(edge[1], box)) and not traced.explains(edge):
            for seed in _edge_seeds(model, F, edge):
                traced.add(seed)
    return traced.kept


def _system(model, family, kind, graze, F):
    return ag.Codim1System(model, family, kind, ("eta", "omega"), {"F": F}, graze)


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
            good = is_ns(curve.family, o, tol=NS_KEEP_TOL)
        ok.append(good)
    return pieces_of(curve, ok)


def crossings(curve: Curve, model, F, omega: float) -> list:
    """Exact eta values where the curve crosses omega = const (``tracer.crossings`` on the
    square system in eta)."""
    def solve_at(z):
        return solve(ag.Codim1System(model, curve.family, curve.type, ("eta",),
                                     {"F": F, "omega": omega}, curve.graze), z)

    return [float(pt[0]) for pt in tracer.crossings(curve, ("omega", omega), solve_at)]


class OneToOneKit:
    """Augmented systems and kept stretches of the 1:1 curves (``augmented``)."""

    def __init__(self, model, F):
        self.model, self.F = model, F

    def system(self, seed):
        family, kind, graze, _ = seed
        return _system(self.model, family, kind, graze, self.F)

    def keep(self, curve) -> list:
        return _keep(curve, self.model, self.F)


def _map_edges(model, F, box, n_map):
    """The class-changing edges (``class_edges``) of an n_map x n_map stability map."""
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


def _seeds(model, F, box, n_scan):
    """(family, kind, graze, z0) from one-parameter scans (module docstring, step 1)."""
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
        zs = solve(system, z0[:-1] if param == "eta" else np.append(z0[:-2], z0[-1]))
        if zs is None:
            continue
        z0[:-2] = zs[:-1]
        z0[-2 if param == "eta" else -1] = zs[-1]
        yield br.family, typ, graze, z0
