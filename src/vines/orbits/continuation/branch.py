"""The one result type of every continuation, ``Branch``: the orbits of a family in
continuation order (``PeriodicOrbit``), the continued parameter, events, why it stopped, the
branches switched onto and where it was born, with per-point arrays read from its orbits
(the 1:1 dataset builder's included); and the event types of every continuation.

``make_branch`` (the 1:1 continuation, ``one_to_one``) and ``SequenceBranch`` (any wall
sequence, ``sequence``; the former class name, kept for one release) build it.
``to_dict`` writes one of two key sets, chosen by whoever built the branch (``keys``):
that of the 1:1 continuation or that of any family (``orbit.KEYS_1TO1``,
``orbit.FAMILY_KEYS``); ``cli.orbit_json`` builds the one public shape from either.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ..family.orbit import FAMILY_KEYS, KEYS_1TO1, family_dict

#: every event type a continuation reports (branch-point: the wall-sequence continuation only,
#: det(B - I) changing sign on an asymmetric orbit without a fold)
EVENT_TYPES = ("fold", "flip", "neimark-sacker", "admissibility-loss", "symmetry-breaking",
               "branch-point")


@dataclass(kw_only=True)
class Branch:
    """A continued branch of one family (keyword fields).

    ::

        param       the continued parameter (eta, omega or F)
        orbits      the ``PeriodicOrbit`` of every point, in continuation order (``points``)
        values      the continued parameter at each point
        walls, periods  the family of the orbits
        family      the 1:1 continuation: "symmetric" or "asymmetric" (the orbits followed);
                    None for any other
        events      dicts {type (``EVENT_TYPES``), at (parameter value), eta, omega, F, index
                    (the branch point where it was located), ...}; the 1:1 ones also connects
                    (the family met there, symmetry-breaking)
        stopped     why the continuation ended
        switched    branches started at this branch's switching points (flip,
                    symmetry-breaking)
        born_at     the event of the parent branch where this one was switched onto, or None
        arclength   pseudo-arclength of each point from the start (natural mode: |param -
                    start|), where the continuation gives it
        keys        the key set of ``to_dict`` (module docstring)
    """

    param: str
    orbits: list = field(default_factory=list, repr=False)
    values: np.ndarray = field(default_factory=lambda: np.empty(0))
    walls: str = "LR"
    periods: int = 1
    family: str | None = None
    events: list = field(default_factory=list)
    stopped: str = "done"
    switched: list = field(default_factory=list)
    born_at: dict | None = None
    arclength: np.ndarray | None = None
    keys: str = field(default=FAMILY_KEYS, repr=False)

    def __len__(self):
        return len(self.values)

    @property
    def points(self) -> list:
        """The orbits (the former ``SequenceBranch`` name)."""
        return self.orbits

    # ------------------------------------------------------------- per-point arrays
    def _params(self, name: str) -> np.ndarray:
        out = np.empty(len(self.orbits))
        for i, o in enumerate(self.orbits):
            out[i] = getattr(o.params, name)
        return out

    def _get(self, name: str, dt=float) -> np.ndarray:
        return np.array([getattr(o, name) for o in self.orbits], dtype=dt)

    eta = property(lambda self: self._params("eta"), doc="eta of every point")
    omega = property(lambda self: self._params("omega"), doc="omega of every point")
    F = property(lambda self: self._params("F"), doc="F of every point")
    lambda_max = property(lambda self: self._get("lambda_max"))
    stable = property(lambda self: self._get("stable", bool))
    symmetric = property(lambda self: self._get("symmetric", bool))
    admissible = property(lambda self: self._get("admissible", bool))
    # the impacts on a wall hit once per orbit (the 1:1 names, ``PeriodicOrbit.x_L``)
    dw_L = property(lambda self: self._get("dw_L"))
    dw_R = property(lambda self: self._get("dw_R"))
    phase_L = property(lambda self: self._get("phase_L"))
    phase_R = property(lambda self: self._get("phase_R"))

    @property
    def abs_eigenvalues(self) -> np.ndarray:
        """(n, 4) moduli of the eigenvalues of every point, sorted decreasing."""
        n = len(self.orbits)
        return np.array([np.sort(np.abs(o.eigenvalues))[::-1]
                         for o in self.orbits]).reshape(n, 4)

    def to_dict(self) -> dict:
        """The branch as JSON-ready values, in the key set ``keys``."""
        return TO_DICT[self.keys](self)


def dict_1to1(br: Branch) -> dict:
    """The keys the 1:1 continuation always wrote (``orbit.KEYS_1TO1``)."""
    eta, omega, F = br.eta, br.omega, br.F
    lam, stable, sym, adm, dw_L = (br.lambda_max, br.stable, br.symmetric, br.admissible,
                                   br.dw_L)
    pts = [{"eta": float(eta[i]), "omega": float(omega[i]), "F": float(F[i]),
            "lambda_max": float(lam[i]), "stable": bool(stable[i]),
            "symmetric": bool(sym[i]), "admissible": bool(adm[i]),
            "dw_L": float(dw_L[i]),
            "flight_times": [float(s) for s in br.orbits[i].flight_times]}
           for i in range(len(br.values))]
    return {"param": br.param, "family": br.family, "branch": pts,
            "events": [_event_dict(e) for e in br.events], "stopped": br.stopped,
            "switched": [b.to_dict() for b in br.switched]}


def _event_dict(e: dict) -> dict:
    out = {"type": e["type"], "at": float(e["at"])}
    for key in ("eta", "omega", "F"):
        if key in e:
            out[key] = float(e[key])
    if "index" in e:
        out["index"] = int(e["index"])
    if e.get("connects"):
        out["connects"] = e["connects"]
    return out


def family_branch_dict(br: Branch) -> dict:
    """The keys of any family (``orbit.FAMILY_KEYS``)."""
    pts = []
    for o in br.orbits:
        p = o.params
        d = family_dict(o)
        pts.append({"eta": p.eta, "omega": p.omega, "F": p.F,
                    **{k: d[k] for k in ("lambda_max", "stable", "symmetric", "admissible",
                                         "dw", "phases", "flight_times")}})
    out = {"walls": br.walls, "periods": br.periods,
           "family": br.orbits[0].family if br.orbits else None,
           "param": br.param, "branch": pts,
           "events": [{k: v for k, v in e.items() if k != "_orbit"} for e in br.events],
           "stopped": br.stopped,
           "switched": [b.to_dict() for b in br.switched]}
    if br.born_at is not None:
        out["born_at"] = br.born_at
    return out


#: ``Branch.keys`` -> its ``to_dict``
TO_DICT = {FAMILY_KEYS: family_branch_dict, KEYS_1TO1: dict_1to1}


def make_branch(param: str, pts: list, events: list, stopped: str, family: str = "symmetric",
                arclength: ArrayLike | None = None) -> Branch:
    """The branch of the 1:1 continuation from [(parameter value, PeriodicOrbit)] in
    continuation order."""
    vals = np.array([v for v, _ in pts], float)
    if arclength is None:
        arclength = np.abs(vals - vals[0]) if len(pts) else np.empty(0)
    return Branch(param=param, orbits=[o for _, o in pts], values=vals, family=family,
                  events=events, stopped=stopped, arclength=np.asarray(arclength, float),
                  keys=KEYS_1TO1)


def SequenceBranch(*, walls: str, periods: int, param: str, points: list,  # noqa: N802
                   **fields) -> Branch:
    """The branch of a wall sequence's continuation (the former class name, kept for one
    release): ``points`` its orbits; ``fields`` the other ``Branch`` fields."""
    values = np.array([getattr(o.params, param) for o in points], float)
    return Branch(walls=walls, periods=periods, param=param, orbits=list(points),
                  values=values, **fields)


#: the former names of the one branch type (kept for one release)
BranchBase = Branch
