"""Which periodic families exist, are admissible and stable at one (eta, omega, F) point.

``atlas_point`` solves every family of ``FAMILIES`` (docs/bifurcation.md, "Families of
periodic orbits") on the maps (``orbits.family.sequence``) from:

* the affine seeds of each sequence (closed form / flight-time scans where they exist);
* one short simulation from rest, shared by all families (its impact record and its
  mirror image searched for each sequence);
* flip seeds: each period-2 family also starts from the admissible orbits of the family it
  doubles that have a real eigenvalue below -0.5, displaced along that eigenvector; a
  mirror family from the mirror images of its partner's orbits; pitchfork seeds: the
  symmetric orbits of a sequence displaced along the eigenvector of their largest positive
  real eigenvalue (the asymmetric orbits born at a symmetry-breaking point);
* optional orbits of a neighbouring point (``seeds``), so that a grid swept in order
  continues every family found at the previous point;
* a second pass from all orbits of the first and of each family's relatives (mirror images
  both ways, flips), so that mirror families end with mirror images of the same orbits.

The answer is a finite search: a family reported absent may exist (no seed reached it).
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ...core.exact import oscillators
from ...core.params import ModelParams, ParameterError, SolverSettings, check_bool
from ..family.family import Family, paper_label
from ..family.sequence import (
    SIM_T_END,
    SequenceOrbit,
    affine_seeds,
    check_sim_t_end,
    flip_seeds,
    mirror_record,
    pitchfork_seeds,
    record_seed,
    solve_seeds,
)

#: family name (docs/bifurcation.md) -> the family (``Family``; symmetric True: the
#: symmetric orbits only, False: the asymmetric ones only, None: both)
FAMILIES = {f.name: f for f in (
    Family("LR", 1, True), Family("LR", 1, False), Family("LLRR", 1, True),
    Family("LLRR", 1, False), Family("LLR", 1), Family("LRR", 1), Family("LLLRR", 1),
    Family("LLRRR", 1), Family("LLLRRR", 1), Family("LRLR", 2), Family("LLRLLR", 2),
    Family("LRRLRR", 2), Family("LLRRLLRR", 2), Family("LLLRRLLLRR", 2),
    Family("LLRRRLLRRR", 2))}
#: the paper's (``core.regime``'s) label of each family
PAPER_LABELS = {key: paper_label(f.walls, f.periods) for key, f in FAMILIES.items()}
#: sequence -> (sequences whose orbits seed it, how): "flip" doubles, "mirror" mirrors
_FLIPS = {"LRLR": "LR", "LLRLLR": "LLR", "LRRLRR": "LRR", "LLRRLLRR": "LLRR",
          "LLLRRLLLRR": "LLLRR", "LLRRRLLRRR": "LLRRR"}
_MIRRORS = (("LLR", "LRR"), ("LLLRR", "LLRRR"), ("LLRLLR", "LRRLRR"),
            ("LLLRRLLLRR", "LLRRRLLRRR"))
_RELATIVES = {}
for _doubled, _single in _FLIPS.items():
    _RELATIVES.setdefault(_doubled, []).append((_single, "flip"))
for _a, _b in _MIRRORS:
    _RELATIVES.setdefault(_a, []).append((_b, "mirror"))
    _RELATIVES.setdefault(_b, []).append((_a, "mirror"))
#: flip seeds come from admissible orbits with a real eigenvalue below -FLIP_FROM (near or
#: past a flip), displaced by FLIP_EPS (far past the flip the doubled orbit is far away)
FLIP_FROM = 0.5
FLIP_EPS = (1e-2, 0.1, 0.3)
_SEQUENCES = tuple(dict.fromkeys(f.walls for f in FAMILIES.values()))
_PERIODS = {f.walls: f.periods for f in FAMILIES.values()}


@dataclass
class FamilyState:
    """One family at one point: any orbit found, any admissible, any stable admissible;
    lambda_max: the smallest lambda_max of its admissible orbits (nan without one)."""

    found: bool
    admissible: bool
    stable: bool
    lambda_max: float
    n_orbits: int

    def to_dict(self) -> dict:
        return {"found": self.found, "admissible": self.admissible, "stable": self.stable,
                "lambda_max": float(self.lambda_max), "n_orbits": self.n_orbits}


def _rest_records(p: ModelParams, t_end: float) -> list:
    from ...core.simulation import simulate_exact
    st = SolverSettings(t_end=t_end, t_transient=0.5 * t_end, max_impacts=200_000)
    res = simulate_exact(p, st)
    return [res.impacts, mirror_record(res.impacts, p.period)]


def sequence_orbits(p: ModelParams, seeds: dict | None = None, simulation: bool = True,
                    sim_t_end: float = SIM_T_END) -> dict:
    """Every orbit found of each sequence of the atlas: {walls: [SequenceOrbit, ...]}.

    ``seeds``: orbits of a neighbouring point ({walls: orbits}, as returned here). Two
    passes: the first from the affine, simulation, neighbour and relatives' seeds (flips and
    mirror images of the sequences already solved), the second from every orbit of the first
    and of all relatives (mirror images both ways), so that a mirror pair ends with mirror
    images of the same orbits.
    """
    osc = oscillators(p)[0]
    if p.F == 0.0:
        return {w: [] for w in _SEQUENCES}
    records = _rest_records(p, sim_t_end) if simulation else []
    seeds = seeds or {}
    first = {}
    for walls in _SEQUENCES:
        starts = affine_seeds(p, osc, walls, _PERIODS[walls])
        for rec in records:
            sd = record_seed(rec, walls)
            if sd is not None:
                starts.append(sd)
        first[walls] = _solve_family(p, osc, walls, starts, list(seeds.get(walls, ())), first)
    out = {}
    for walls in _SEQUENCES:
        out[walls] = _solve_family(p, osc, walls, [], first[walls], out, first)
    return out


def _solve_family(p, osc, walls, starts, extra, *solved) -> list:
    """Orbits of ``walls`` from ``starts`` ((x_0, flights) pairs), ``extra`` (orbits) and
    the orbits of its relatives in the dicts ``solved``, then the pitchfork seeds of the
    symmetric orbits found."""
    periods = _PERIODS[walls]
    starts, extra = list(starts), list(extra)
    for src, how in _RELATIVES.get(walls, ()):
        for o in (q for d in solved for q in d.get(src, ())):
            if how == "mirror":
                extra.append(o)
            elif o.admissible and np.min(o.eigenvalues.real) < -FLIP_FROM:
                starts += flip_seeds(o, eps=FLIP_EPS)
    found = solve_seeds(p, osc, walls, periods, starts, extra)
    sym = [st for o in found if o.symmetric for st in pitchfork_seeds(o)]
    return solve_seeds(p, osc, walls, periods, sym, found) if sym else found


def classify_families(orbits: dict) -> dict:
    """{family key: FamilyState} from ``sequence_orbits``."""
    out = {}
    for key, fam in FAMILIES.items():
        mine = [o for o in orbits.get(fam.walls, ())
                if fam.symmetric is None or o.symmetric == fam.symmetric]
        adm = [o for o in mine if o.admissible]
        out[key] = FamilyState(
            found=bool(mine), admissible=bool(adm), stable=any(o.stable for o in adm),
            lambda_max=min((o.lambda_max for o in adm), default=float("nan")),
            n_orbits=len(mine))
    return out


def _check_atlas_seeds(seeds) -> dict:
    """None or {walls: [SequenceOrbit, ...]} (as ``atlas_point`` returns its orbits)."""
    allowed = "must be None or a dict {walls: [SequenceOrbit, ...]} as atlas_point returns"
    if seeds is None:
        return {}
    if not isinstance(seeds, dict):
        raise ParameterError("seeds", seeds, allowed)
    for orbits in seeds.values():
        if not isinstance(orbits, (list, tuple)) or not all(
                isinstance(o, SequenceOrbit) for o in orbits):
            raise ParameterError("seeds", seeds, allowed)
    return seeds


def atlas_point(params: ModelParams, seeds: dict | None = None, simulation: bool = True,
                sim_t_end: float = SIM_T_END) -> tuple[dict, dict]:
    """(families, orbits): ``classify_families`` of the point and the orbits found (pass
    them as ``seeds`` to the next point of a sweep)."""
    if not isinstance(params, ModelParams):
        raise ParameterError("params", params, "must be a ModelParams")
    seeds = _check_atlas_seeds(seeds)
    simulation = check_bool("simulation", simulation)
    sim_t_end = check_sim_t_end(sim_t_end)
    orbits = sequence_orbits(params, seeds, simulation, sim_t_end)
    return classify_families(orbits), orbits


def atlas_arrays(eta: ArrayLike, omega: ArrayLike, F: float, *, r: float | None = None,
                 d: float | None = None, simulation: bool = True,
                 sim_t_end: float = SIM_T_END,
                 progress: Callable[[int, int], None] | None = None) -> dict:
    """The atlas over an (eta, omega) grid at one F, swept along omega for each eta with
    the previous point's orbits as seeds: arrays (eta, omega) per family key of ``found``,
    ``admissible``, ``stable`` (bool) and ``lambda_max`` (float), under keys
    f"{key}:admissible" etc."""
    eta = np.asarray(eta, float)
    omega = np.asarray(omega, float)
    kw = {k: v for k, v in (("r", r), ("d", d)) if v is not None}
    shape = (eta.size, omega.size)
    out = {}
    for key in FAMILIES:
        out[f"{key}:found"] = np.zeros(shape, bool)
        out[f"{key}:admissible"] = np.zeros(shape, bool)
        out[f"{key}:stable"] = np.zeros(shape, bool)
        out[f"{key}:lambda_max"] = np.full(shape, np.nan)
    for i, e in enumerate(eta):
        prev = None
        for j, w in enumerate(omega):
            p = ModelParams(eta=float(e), omega=float(w), F=float(F), **kw)
            fam, prev = atlas_point(p, prev, simulation, sim_t_end)
            for key, st in fam.items():
                out[f"{key}:found"][i, j] = st.found
                out[f"{key}:admissible"][i, j] = st.admissible
                out[f"{key}:stable"][i, j] = st.stable
                out[f"{key}:lambda_max"][i, j] = st.lambda_max
            if progress:
                progress(i * omega.size + j + 1, eta.size * omega.size)
    return out
