"""The results of continued branches: what every branch holds, ``BranchBase`` (the
continued parameter, events, why it stopped, the branches switched onto and where it was
born), and its two forms: ``Branch`` (1:1, ``one_to_one.continue_branch``: per-point
arrays) and ``SequenceBranch`` (any wall sequence, ``sequence.continue_sequence``: the
orbits); the event types of both."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ...core.params import PARAM_NAMES

#: every event type a continuation reports (branch-point: the wall-sequence continuation only,
#: det(B - I) changing sign on an asymmetric orbit without a fold)
EVENT_TYPES = ("fold", "flip", "neimark-sacker", "admissibility-loss", "symmetry-breaking",
               "branch-point")


@dataclass(kw_only=True)
class BranchBase:
    """What every continued branch holds (keyword fields).

    param       the continued parameter (eta, omega or F)
    events      dicts {type (``EVENT_TYPES``), at (parameter value), eta, omega, F, index
                (the branch point where it was located), ...}
    stopped     why the continuation ended
    switched    branches started at this branch's switching points (``switch``)
    born_at     the event of the parent branch where this one was switched onto, or None
    """

    param: str
    events: list = field(default_factory=list)
    stopped: str = "done"
    switched: list = field(default_factory=list)
    born_at: dict | None = None


@dataclass(kw_only=True)
class Branch(BranchBase):
    """A continued 1:1 branch: one entry per point, in continuation order.

    family      "symmetric" or "asymmetric" (the orbit family followed)
    arclength   pseudo-arclength of each point from the start (natural mode: |param - start|)
    events      also connects (the family met there, symmetry-breaking)
    switched    the asymmetric branches born at its symmetry-breaking points
    """

    values: np.ndarray
    eta: np.ndarray
    omega: np.ndarray
    F: np.ndarray
    lambda_max: np.ndarray
    abs_eigenvalues: np.ndarray          # (n, 4), sorted decreasing
    stable: np.ndarray
    symmetric: np.ndarray
    admissible: np.ndarray
    dw_L: np.ndarray
    dw_R: np.ndarray
    phase_L: np.ndarray
    phase_R: np.ndarray
    orbits: list = field(default_factory=list, repr=False)
    family: str = "symmetric"
    arclength: np.ndarray | None = None

    def __len__(self):
        return len(self.values)

    def to_dict(self) -> dict:
        pts = [{"eta": float(self.eta[i]), "omega": float(self.omega[i]), "F": float(self.F[i]),
                "lambda_max": float(self.lambda_max[i]), "stable": bool(self.stable[i]),
                "symmetric": bool(self.symmetric[i]), "admissible": bool(self.admissible[i]),
                "dw_L": float(self.dw_L[i]),
                "flight_times": [float(s) for s in self.orbits[i].flight_times]}
               for i in range(len(self.values))]
        return {"param": self.param, "family": self.family, "branch": pts,
                "events": [_event_dict(e) for e in self.events], "stopped": self.stopped,
                "switched": [b.to_dict() for b in self.switched]}


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


def make_branch(param: str, pts: list, events: list, stopped: str, family: str = "symmetric",
                arclength: ArrayLike | None = None) -> Branch:
    """Branch from [(parameter value, PeriodicOrbit)] in continuation order."""
    n = len(pts)
    vals = np.array([v for v, _ in pts], float)
    orbits = [o for _, o in pts]
    par = {q: np.empty(n) for q in PARAM_NAMES}
    for i, (_, o) in enumerate(pts):
        p = o.params
        par["eta"][i], par["omega"][i], par["F"][i] = p.eta, p.omega, p.F
    absev = np.array([np.sort(np.abs(o.eigenvalues))[::-1] for o in orbits]).reshape(n, 4)

    def get(name, dt=float):
        return np.array([getattr(o, name) for o in orbits], dtype=dt)

    if arclength is None:
        arclength = np.abs(vals - vals[0]) if n else np.empty(0)
    return Branch(param=param, values=vals, eta=par["eta"], omega=par["omega"], F=par["F"],
                  lambda_max=get("lambda_max"), abs_eigenvalues=absev,
                  stable=get("stable", bool), symmetric=get("symmetric", bool),
                  admissible=get("admissible", bool), dw_L=get("dw_L"), dw_R=get("dw_R"),
                  phase_L=get("phase_L"), phase_R=get("phase_R"), events=events,
                  orbits=orbits, stopped=stopped, family=family,
                  arclength=np.asarray(arclength, float))


@dataclass(kw_only=True)
class SequenceBranch(BranchBase):
    """A continued family of any wall sequence: its points (``SequenceOrbit``s with their
    parameter point); switched: the branches born at its flip and symmetry-breaking
    points."""

    walls: str
    periods: int
    points: list

    def to_dict(self) -> dict:
        pts = []
        for o in self.points:
            p = o.params
            d = o.to_dict()
            pts.append({"eta": p.eta, "omega": p.omega, "F": p.F,
                        **{k: d[k] for k in ("lambda_max", "stable", "symmetric", "admissible",
                                             "dw", "phases", "flight_times")}})
        out = {"walls": self.walls, "periods": self.periods,
               "family": self.points[0].family if self.points else None,
               "param": self.param, "branch": pts,
               "events": [{k: v for k, v in e.items() if k != "_orbit"} for e in self.events],
               "stopped": self.stopped,
               "switched": [b.to_dict() for b in self.switched]}
        if self.born_at is not None:
            out["born_at"] = self.born_at
        return out
