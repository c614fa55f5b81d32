"""The one periodic-orbit result type of every family, ``PeriodicOrbit``: its wall sequence,
pre-impact states, flights, impacts, symmetry, admissibility and stability. The 1:1 names
(``x_L``, ``dw_L``, ``phase_L`` and their R forms) read the impact on a wall hit once per
orbit (both for the family LR/1). ``OrbitBase`` and ``SequenceOrbit`` are former names of
it, kept for one release.

``to_dict`` writes one of two key sets, chosen by whoever made the orbit (``keys``):
``FAMILY_KEYS`` (any family, ``sequence.find_sequence``) or ``KEYS_1TO1`` (the keys the
1:1 solver ``periodic.find_1to1`` always wrote); ``cli.orbit_json`` builds the one public
shape from either.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...core.params import ModelParams
from .names import family_name, paper_label

#: ``PeriodicOrbit.keys``: the dict of any family; the 1:1 solver's dict
FAMILY_KEYS, KEYS_1TO1 = "family", "1:1"


@dataclass(kw_only=True)
class PeriodicOrbit:
    """One periodic orbit and its stability (keyword fields).

    ::

        walls         the wall sequence ("LLRR"), impact k at wall walls[k]
        periods       forcing periods of the orbit (its period is periods * T)
        states        (n, 4) pre-impact states x_k = (z_m', z_b', z_b, t), t_0 in [0, T)
        flight_times  n flight times, flight k from impact k to impact k+1 (cyclically; a list
                      of floats from the 1:1 solver, as it always was)
        dw            relative velocity w' = z_m' - z_b' just before each impact
        phases        impact phases mod(omega t + phi, 2 pi)
        symmetric     invariant under the mirror z -> -z with t -> t + periods T / 2 (flight k
                      as long as flight k + n/2, walls opposite; only for odd periods)
        admissible    every flight is a genuine impact-to-impact flight (``maps``)
        eigenvalues   of the monodromy matrix J_{n-1} ... J_0 (the Jacobians of the maps along
                      the orbit), sorted by decreasing modulus; lambda_max = max |eigenvalue|
        stable        admissible and lambda_max < 1
        residual      the Newton residual at the solution
        jacobians     (n, 4, 4) the map Jacobians J_k along the orbit
        params        the model point of the orbit
        keys          the key set of ``to_dict`` (module docstring)
    """

    walls: str
    periods: int
    states: np.ndarray
    flight_times: list | np.ndarray
    dw: np.ndarray
    phases: np.ndarray
    symmetric: bool
    admissible: bool
    eigenvalues: np.ndarray
    lambda_max: float
    stable: bool
    residual: float = 0.0
    jacobians: np.ndarray | None = field(default=None, repr=False)
    params: ModelParams | None = field(default=None, repr=False)
    keys: str = field(default=FAMILY_KEYS, repr=False)

    @property
    def family(self) -> str:
        """"WALLS/N" (``names.family_name``)."""
        return family_name(self.walls, self.periods)

    @property
    def paper_label(self) -> str:
        return paper_label(self.walls, self.periods)

    def impact_at(self, wall: str) -> int:
        """The index of the one impact on ``wall`` ("L" or "R"); AttributeError when the
        sequence hits it more than once or never (the 1:1 names do not exist then)."""
        if self.walls.count(wall) != 1:
            raise AttributeError(f"walls {self.walls} hit {wall} {self.walls.count(wall)} "
                                 "times: no single impact there")
        return self.walls.index(wall)

    @property
    def x_L(self) -> np.ndarray:
        """Pre-impact state at the one impact on L (``impact_at``)."""
        return self.states[self.impact_at("L")]

    @property
    def x_R(self) -> np.ndarray:
        return self.states[self.impact_at("R")]

    @property
    def dw_L(self) -> float:
        return float(self.dw[self.impact_at("L")])

    @property
    def dw_R(self) -> float:
        return float(self.dw[self.impact_at("R")])

    @property
    def phase_L(self) -> float:
        return float(self.phases[self.impact_at("L")])

    @property
    def phase_R(self) -> float:
        return float(self.phases[self.impact_at("R")])

    def to_dict(self) -> dict:
        """The orbit as JSON-ready values, in the key set ``keys``."""
        return TO_DICT[self.keys](self)


def family_dict(o: PeriodicOrbit) -> dict:
    """The keys of any family (``FAMILY_KEYS``)."""
    return {
        "walls": o.walls,
        "periods": int(o.periods),
        "family": o.family,
        "paper_label": o.paper_label,
        "symmetric": bool(o.symmetric),
        "admissible": bool(o.admissible),
        "stable": bool(o.stable),
        "lambda_max": float(o.lambda_max),
        "eigenvalues": [[float(z.real), float(z.imag)] for z in o.eigenvalues],
        "dw": [float(v) for v in o.dw],
        "phases": [float(v) for v in o.phases],
        "flight_times": [float(v) for v in o.flight_times],
        "states": [[float(v) for v in x] for x in o.states],
    }


def dict_1to1(o: PeriodicOrbit) -> dict:
    """The keys the 1:1 solver always wrote (``KEYS_1TO1``)."""
    return {
        "symmetric": bool(o.symmetric),
        "admissible": bool(o.admissible),
        "stable": bool(o.stable),
        "lambda_max": float(o.lambda_max),
        "eigenvalues": [[float(z.real), float(z.imag)] for z in o.eigenvalues],
        "dw_L": o.dw_L,
        "dw_R": o.dw_R,
        "phase_L": o.phase_L,
        "phase_R": o.phase_R,
        "flight_times": [float(s) for s in o.flight_times],
        "x_L": [float(v) for v in o.x_L],
        "x_R": [float(v) for v in o.x_R],
    }


#: ``PeriodicOrbit.keys`` -> its ``to_dict``
TO_DICT = {FAMILY_KEYS: family_dict, KEYS_1TO1: dict_1to1}

#: the former names of the one orbit type (kept for one release): the base of the two orbit
#: classes, and the orbit of any wall sequence
OrbitBase = SequenceOrbit = PeriodicOrbit
