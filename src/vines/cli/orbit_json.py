"""One JSON shape for the periodic orbits of every family: ``vines periodic``, ``continue``
and ``boundaries`` print the same keys for the 1:1 orbits and with ``--walls SEQ
--periods N`` (``--walls LR --periods 1`` prints exactly the keys of the 1:1 output).

Every object names its family (``walls``, ``periods``, ``family``); an orbit or branch
point gives its impacts as lists in sequence order (``dw``, ``phases``, ``flight_times``);
an event says which family meets the branch there (``meets``, or null); a branch says
where it was born (``born_at``: the event of the branch it was switched from, or null).

The old 1:1 keys stay for one release as aliases (deprecated, ``ALIASES``): on the orbits
of a family with one impact on each wall (walls ``LR``) ``dw_L``/``dw_R`` = ``dw``,
``phase_L``/``phase_R`` = ``phases`` (impacts at L and R), and ``connects`` = ``meets``
where it is not null. The 1:1 branches keep ``family`` = symmetric / asymmetric.
"""
from __future__ import annotations

from ..orbits.family.family import ONE_TO_ONE as ONE_TO_ONE_FAMILY
from ..orbits.family.family import family_name, paper_label

#: keys of an orbit of ``vines periodic`` (``solutions``), in order
SOLUTION_KEYS = ("walls", "periods", "family", "paper_label", "symmetric", "admissible",
                 "stable", "lambda_max", "eigenvalues", "dw", "phases", "flight_times")
#: keys of a point of a continued branch
POINT_KEYS = ("eta", "omega", "F", "lambda_max", "stable", "symmetric", "admissible", "dw",
              "phases", "flight_times")
#: keys of an event of a continued branch
EVENT_KEYS = ("type", "at", "eta", "omega", "F", "index", "meets")
#: keys of a continued branch (``switched``: branches with these same keys)
BRANCH_KEYS = ("walls", "periods", "family", "param", "branch", "events", "stopped",
               "switched", "born_at")
#: deprecated 1:1 key -> (its key in this shape, index into that list or None)
ALIASES = {"dw_L": ("dw", 0), "dw_R": ("dw", 1), "phase_L": ("phases", 0),
           "phase_R": ("phases", 1), "connects": ("meets", None)}
#: the aliases each kind of object carried in the 1:1 output
ALIASES_OF = {"solution": ("dw_L", "dw_R", "phase_L", "phase_R"), "point": ("dw_L",),
              "event": ("connects",)}
#: the wall sequence whose orbits carry the aliases (one impact at L, one at R)
ALIAS_WALLS = "LR"
#: (walls, periods) of the 1:1 orbits
ONE_TO_ONE = (ONE_TO_ONE_FAMILY.walls, ONE_TO_ONE_FAMILY.periods)
#: the model parameters of a branch point
PARAMS = ("eta", "omega", "F")


def family_keys(walls: str, periods: int) -> dict:
    """``walls``, ``periods`` and ``family`` (``WALLS/N``, ``vines.orbits.family``)."""
    return {"walls": walls, "periods": int(periods), "family": family_name(walls, periods)}


def with_aliases(d: dict, kind: str, walls: str) -> dict:
    """``d`` (an object of this shape) with the deprecated 1:1 keys of ``kind``
    (``ALIASES_OF``) when the family's walls are ``ALIAS_WALLS``."""
    if walls != ALIAS_WALLS:
        return d
    out = dict(d)
    for old in ALIASES_OF[kind]:
        new, k = ALIASES[old]
        if d.get(new) is not None:
            out[old] = d[new] if k is None else d[new][k]
    return out


# ---------------------------------------------------------------------------- periodic

def periodic_json(solutions: list[dict], walls: str, periods: int, params: dict) -> dict:
    """The object of ``vines periodic``: the family, its ``solutions`` (orbit dicts of
    either solver: ``PeriodicOrbit.to_dict`` in the keys of any family or in the 1:1
    solver's) and the model ``params``."""
    fam = family_keys(walls, periods)
    base = dict(fam, paper_label=paper_label(walls, periods))
    sols = [with_aliases(_pick({**base, **_impacts(s)}, SOLUTION_KEYS), "solution", walls)
            for s in solutions]
    return dict(fam, solutions=sols, params=params)


def _impacts(d: dict) -> dict:
    """An orbit dict with ``dw`` and ``phases``: a 1:1 orbit's ``dw_L``, ``dw_R``,
    ``phase_L``, ``phase_R`` as lists."""
    if "dw" in d:
        return d
    return dict(d, dw=[d["dw_L"], d["dw_R"]], phases=[d["phase_L"], d["phase_R"]])


def _pick(d: dict, keys: tuple) -> dict:
    return {k: d[k] for k in keys}


# ---------------------------------------------------------------------------- continue

def branch_json(br, walls: str = ONE_TO_ONE[0], periods: int = ONE_TO_ONE[1]) -> dict:
    """The object of ``vines continue`` for a continued branch: a ``Branch`` of the 1:1
    continuation or of a wall sequence's (or its ``to_dict()``), and recursively the
    branches switched to."""
    if isinstance(br, dict):
        d, subs, orbits = br, br["switched"], []
    else:
        d, subs, orbits = br.to_dict(), br.switched, list(getattr(br, "orbits", ()))
    walls, periods = d.get("walls", walls), d.get("periods", periods)
    pts = [_point(p, orbits[i] if orbits else None) for i, p in enumerate(d["branch"])]
    switched = [branch_json(s, walls, periods) for s in subs]
    born = d.get("born_at", _born_at(br))
    fam = family_keys(walls, periods)
    out = dict(fam, param=d["param"], family=d.get("family") or fam["family"],
               branch=[with_aliases(p, "point", walls) for p in pts],
               events=[with_aliases(e, "event", walls)
                       for e in _events(d, [p[d["param"]] for p in pts], switched)],
               stopped=d["stopped"], switched=switched, born_at=born)
    return _pick(out, BRANCH_KEYS)


def _point(p: dict, orbit) -> dict:
    """A branch point of this shape; a 1:1 point takes ``dw`` and ``phases`` from its
    orbit."""
    if "dw" not in p and orbit is not None:
        p = dict(p, dw=[float(orbit.dw_L), float(orbit.dw_R)],
                 phases=[float(orbit.phase_L), float(orbit.phase_R)])
    return _pick(p, POINT_KEYS)


def _born_at(br) -> dict | None:
    """The event a switched 1:1 branch was born at (``continuation`` sets ``born_at``)."""
    ev = getattr(br, "born_at", None)
    if ev is None:
        return None
    return {k: ev[k] if k == "type" else float(ev[k]) for k in ("type", "at", *PARAMS)}


def _events(d: dict, values: list, switched: list) -> list:
    """The events with every key of ``EVENT_KEYS``: the parameter point and ``index`` where
    the continuation did not give them (natural mode), ``meets`` from the 1:1 ``connects``
    or from the branch switched to there."""
    born = {(s["born_at"]["type"], s["born_at"]["at"]): s["family"] for s in switched
            if s["born_at"] is not None}
    out = []
    for e in d["events"]:
        full = dict(e)
        if any(k not in e for k in PARAMS):
            full.update(_fixed(d, e["at"]))
        if "index" not in e:
            full["index"] = _index(values, e["at"])
        full["meets"] = e.get("connects") or born.get((e["type"], e["at"]))
        out.append(_pick(full, EVENT_KEYS))
    return out


def _fixed(d: dict, at: float) -> dict:
    """eta, omega, F of an event at ``at`` (the fixed ones are those of every point; None
    without points)."""
    first = d["branch"][0] if d["branch"] else dict.fromkeys(PARAMS)
    return {q: float(at) if q == d["param"] else first[q] for q in PARAMS}


def _index(values: list, at: float) -> int | None:
    """The first point at or past ``at`` in continuation order (the last one if none)."""
    if not values:
        return None
    sign = 1.0 if values[-1] >= values[0] else -1.0
    for i, v in enumerate(values):
        if sign * (v - at) >= 0:
            return i
    return len(values) - 1


# -------------------------------------------------------------------------- boundaries

def boundaries_json(d: dict, walls: str, periods: int) -> dict:
    """The object of ``vines boundaries``: ``Boundaries.to_dict()`` with the family."""
    fam = family_keys(walls, periods)
    return {"F": d["F"], "eta_range": d["eta_range"], "omega_range": d["omega_range"],
            **fam, "curves": d["curves"]}
