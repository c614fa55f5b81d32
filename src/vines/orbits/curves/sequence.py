"""Curves of codimension-one points of the orbits of any wall sequence in (eta, omega).

``sequence_boundaries`` (called by ``boundaries.boundaries`` for a family other than 1:1):

1. seeds: at the n_scan x n_scan crossings of the scan lines, every admissible orbit of the
   sequence ``sequence.find_sequence`` finds (the first symmetric and the first asymmetric
   one) is continued (``continuation.sequence.continue_sequence``) both ways along both lines
   through it; every event of those continuations becomes a seed, solved as a square
   system with the line's parameter free (``map_systems``): fold -> fold,
   flip -> flip (asymmetric orbits), symmetry-breaking -> symmetry-breaking,
   neimark-sacker -> neimark-sacker, admissibility-loss -> the grazing
   of the flight closest to a wall contact (``map_systems.grazing_guess``);
2. each seed not on a traced curve of its kind is continued both ways in (eta, omega)
   (``tracer.trace``: the same tracer and box handling as the 1:1 curves);
3. fold, flip, symmetry-breaking and neimark-sacker curves keep their stretches on
   admissible orbits of the family's kind (neimark-sacker: where the pair on the unit
   circle is complex); grazing curves are kept whole, except one lying on a grazing curve
   kept before (another flight grazing at the same parameters).

Families that no crossing of the scan lines meets are not found: n_scan sets how closely
the box is searched.
"""
from __future__ import annotations

import numpy as np

from ...core.params import ModelParams, ParameterError
from ..continuation.sequence import ContinueSettings, continue_sequence
from ..family.family import Family
from ..family.map_systems import (
    family_of,
    grazing_guess,
    make_system,
    orbit_of,
    unknowns,
    with_values,
)
from ..family.sequence import find_sequence, same_orbit, solve_sequence
from ..family.systems import solve
from . import tracer
from .tracer import NS_KEEP_TOL, Traced, pieces_of

GRAZE_MARGIN = 1e-3     # an admissibility loss seeds a grazing curve this close to contact
EVENT_KINDS = {"fold": "fold", "flip": "flip", "symmetry-breaking": "symmetry-breaking",
               "neimark-sacker": "neimark-sacker", "admissibility-loss": "grazing"}


class _SequenceKit:
    """Augmented systems and kept stretches of one sequence's curves (``boundaries``)."""

    def __init__(self, base: ModelParams, step: float):
        self.base, self.step = base, step
        self.families = {}
        self.grazing = []

    def system(self, seed):
        name, kind, graze, _ = seed
        return make_system(self.base, self.families[name], kind, graze, ("eta", "omega"))

    def keep(self, curve) -> list:
        if curve.type == "grazing":
            if any(_same_points(curve, c, self.step) for c in self.grazing):
                return []
            self.grazing.append(curve)
            return [curve]
        fam = self.families[curve.family]
        system = make_system(self.base, fam, curve.type, None, ("eta", "omega"))
        return pieces_of(curve, [_on_family(system, z, fam) for z in curve.z])


def _same_points(a, b, step: float) -> bool:
    """Curve a lies on curve b (of the same family): every point of a within half a step
    of a point of b (e.g. the grazing of two flights that a symmetry of the orbit maps onto
    each other, met at the same parameters)."""
    if a.family != b.family:
        return False
    d = np.hypot(*(a.points[:, None, :] - b.points[None, :, :]).transpose(2, 0, 1))
    return bool(np.all(d.min(axis=1) <= 0.5 * step))


def _on_family(system, z, fam: Family) -> bool:
    o = orbit_of(system, z)
    good = o is not None and o.admissible and o.symmetric == fam.symmetric
    if good and system.kind == "neimark-sacker":
        ev = o.eigenvalues
        good = bool(np.any((np.abs(ev.imag) > 1e-9) & (np.abs(np.abs(ev) - 1.0) <= NS_KEEP_TOL)))
    return good


def sequence_boundaries(p: ModelParams, family: tuple, box, scan: tuple) -> list:
    """Kept curves of the family (walls, periods) in the box at p's F (module docstring);
    scan = (n_scan, ``tracer.CurveSettings``)."""
    n_scan, settings = scan
    kit = _SequenceKit(p, settings.step)
    traced = Traced(kit, box, settings)
    for seed in _seeds(kit, family, box, n_scan):
        traced.add(seed)
    return traced.kept


def _seeds(kit: _SequenceKit, family: tuple, box, n_scan: int):
    """(family name, kind, graze, z0) from continuations through the scan crossings."""
    walls, periods = family
    (e0, e1), (w0, w1) = box
    done = {"eta": [], "omega": []}         # branches followed along each parameter
    for eta in np.linspace(e0, e1, n_scan):
        for omega in np.linspace(w0, w1, n_scan):
            p = with_values(kit.base, {"eta": eta, "omega": omega})
            for o in _starts(p, walls, periods):
                for param, (lo, hi) in (("eta", (e0, e1)), ("omega", (w0, w1))):
                    if _followed(done[param], o, param):
                        continue
                    for stop in (lo, hi):
                        if stop == getattr(p, param):
                            continue
                        br = continue_sequence(p, walls, periods, param, stop, orbit=o,
                                               settings=ContinueSettings(
                                                   step=(hi - lo) / 50.0, max_points=2000,
                                                   max_inadmissible=20))
                        done[param].append(br)
                        for ev in br.events:
                            seed = _event_seed(kit, ev, param)
                            if seed is not None:
                                yield seed


def _starts(p: ModelParams, walls: str, periods: int) -> list:
    """The first admissible symmetric and asymmetric orbits of the sequence at p."""
    try:
        found = find_sequence(p, walls, periods)
    except ParameterError:              # e.g. a near-resonant point the closed form refuses
        return []
    out = []
    for sym in (True, False):
        out += [o for o in found if o.admissible and o.symmetric == sym][:1]
    return out


def _followed(branches, o, param) -> bool:
    """The orbit o lies on a branch already followed along ``param``: Newton from the
    branch point nearest in ``param`` (same other parameter) converges onto o."""
    other = "omega" if param == "eta" else "eta"
    p = o.params
    for br in branches:
        pts = [q for q in br.points if getattr(q.params, other) == getattr(p, other)]
        if not pts:
            continue
        q = min(pts, key=lambda q: abs(getattr(q.params, param) - getattr(p, param)))
        got = solve_sequence(p, o.walls, o.periods, q.states[0], q.flight_times)
        if got is not None and same_orbit(o, got, p.period):
            return True
    return False


def _event_seed(kit: _SequenceKit, ev: dict, param: str):
    """The seed of one continuation event, solved with ``param`` free, or None."""
    o = ev["_orbit"]
    kind = EVENT_KINDS.get(ev["type"])
    fam = family_of(o)
    if kind is None or (kind == "symmetry-breaking") != fam.symmetric and kind in (
            "symmetry-breaking", "flip"):
        return None
    graze, u = None, unknowns(o, fam)
    if kind == "grazing":
        graze, s_g, margin = grazing_guess(o, fam)
        if margin > GRAZE_MARGIN:
            return None
        u = unknowns(o, fam, graze, s_g)
    elif not o.admissible:
        return None
    other = "omega" if param == "eta" else "eta"
    base = with_values(kit.base, {other: getattr(o.params, other)})
    zs = solve(make_system(base, fam, kind, graze, (param,)), u + [getattr(o.params, param)])
    if zs is None:
        return None
    par = {other: getattr(o.params, other), param: float(zs[-1])}
    kit.families[fam.name] = fam
    return fam.name, kind, graze, np.array(list(zs[:-1]) + [par["eta"], par["omega"]])


def family_from_name(name: str, walls: str) -> Family:
    """The family of a curve of ``walls`` from its name ("WALLS/N[-sym|-asym]")."""
    periods = int(name.split("/")[1].split("-")[0])
    return Family(walls, periods, name.endswith("-sym"))


def crossings(curve, walls: str, base: ModelParams, line: tuple) -> list:
    """Exact points (eta, omega) where a curve of the sequence ``walls`` crosses the line
    param = value (line = (param, value), param eta or omega): the square system with the
    other parameter free (``tracer.crossings``), one system for all crossings."""
    param, value = line
    other = "omega" if param == "eta" else "eta"
    fam = family_from_name(curve.family, walls)
    system = make_system(with_values(base, {param: value}), fam, curve.type, curve.graze,
                         (other,))
    return tracer.crossings(curve, line, lambda z: solve(system, z))
