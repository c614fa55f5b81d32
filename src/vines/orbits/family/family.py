"""One family of periodic orbits: a wall sequence over a number of forcing periods, and
which of its orbits (symmetric, asymmetric or both); its name, its mirror image, the checks
of its walls and periods (docs/bifurcation.md, "Families of periodic orbits").

The 1:1 orbit is the value LR/1 of it (``ONE_TO_ONE``); ``Family.one_to_one`` is
the one place that tells it apart, and ``Family.engine`` names what follows from it: ``JETS``
for 1:1 (the shooting engine on exact Taylor jets, ``orbits.jets``, with its own seeds, the
compiled stability map, curves seeded from class-map edges and the output formats it
always had), ``MAPS`` for every other family (the impact maps); the code that differs per
family asks ``engine``.
Numba-free (numpy only): the pipeline's config checks read it at parse time.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.conventions import WALL_L, WALL_R
from ...core.params import ModelParams, ParameterError, check_int

#: the engines of a family (``Family.engine``): shooting on exact Taylor jets (1:1), the
#: impact maps (every other family)
JETS, MAPS = "jets", "maps"

#: the mirror z -> -z (positions and velocities) of a pre-impact state (z_m', z_b', z_b, t):
#: as signs (multiply a state) and as a matrix (multiply a Jacobian from the left)
MIRROR_SIGNS = np.array([-1.0, -1.0, -1.0, 1.0])
MIRROR_MATRIX = np.diag(MIRROR_SIGNS)
WALL_CODES = {"L": WALL_L, "R": WALL_R}
WALL_NAMES = {WALL_L: "L", WALL_R: "R"}
MAX_IMPACTS_PER_ORBIT = 64      # longest wall sequence accepted
MAX_PERIODS = 64                # most forcing periods accepted


# --------------------------------------------------------------------------- names

def check_walls(walls: object) -> str:
    """The wall sequence as an upper-case string of L and R; ParameterError otherwise."""
    allowed = (f"must be a sequence of 1 to {MAX_IMPACTS_PER_ORBIT} walls, each L or R "
               "(e.g. LR, LLRR, LLR)")
    if not isinstance(walls, str):
        raise ParameterError("walls", walls, allowed)
    s = walls.strip().upper()
    if not 1 <= len(s) <= MAX_IMPACTS_PER_ORBIT or set(s) - set("LR"):
        raise ParameterError("walls", walls, allowed)
    return s


def check_periods(periods: object) -> int:
    """The number of forcing periods as an int in [1, MAX_PERIODS]; ParameterError otherwise."""
    return check_int("periods", periods, lo=1, hi=MAX_PERIODS)


def mirror_walls(walls: str) -> str:
    """L <-> R."""
    return walls.translate(str.maketrans("LR", "RL"))


def canonical_walls(walls: str) -> str:
    """The rotation of the sequence that is first in alphabetical order (L before R)."""
    return min(walls[k:] + walls[:k] for k in range(len(walls)))


def family_name(walls: str, periods: int) -> str:
    """Family name "WALLS/N" of the canonical rotation (docs/bifurcation.md)."""
    return f"{canonical_walls(walls)}/{int(periods)}"


def paper_label(walls: str, periods: int) -> str:
    """The paper's (and ``core.regime``'s) wording: "p:q" (impacts per period on the wall
    hit more often : on the other) for one period, "period-N" otherwise."""
    if periods > 1:
        return f"period-{periods}"
    nl, nr = walls.count("L"), walls.count("R")
    return f"{max(nl, nr)}:{min(nl, nr)}"


def has_half_symmetry(walls: str) -> bool:
    """True when the second half of the sequence is the mirror image of the first."""
    n = len(walls)
    return n % 2 == 0 and walls[n // 2:] == mirror_walls(walls[:n // 2])


@dataclass(frozen=True)
class Family:
    """Orbits of ``walls`` over ``periods`` forcing periods; ``symmetric``: True the
    symmetric ones only, False the asymmetric ones only, None both."""

    walls: str
    periods: int = 1
    symmetric: bool | None = None

    @property
    def key(self) -> tuple[str, int]:
        return self.walls, int(self.periods)

    @property
    def one_to_one(self) -> bool:
        """The 1:1 family (walls LR, one period): the one place that decides it."""
        return self.key == ONE_TO_ONE.key

    @property
    def engine(self) -> str:
        """``JETS`` for the 1:1 family, ``MAPS`` for every other (module docstring)."""
        return JETS if self.one_to_one else MAPS

    @property
    def name(self) -> str:
        """"WALLS/N", with "-sym"/"-asym" where both kinds exist and ``symmetric`` picks
        one (docs/bifurcation.md)."""
        base = family_name(self.walls, self.periods)
        if self.symmetric is not None and self.has_symmetric:
            return base + ("-sym" if self.symmetric else "-asym")
        return base

    @property
    def has_symmetric(self) -> bool:
        """The family has symmetric orbits: half symmetry of the walls, odd periods."""
        return has_half_symmetry(self.walls) and self.periods % 2 == 1

    @property
    def mirror(self) -> Family:
        """The family of the mirror images (z -> -z, t -> t + T/2): walls L <-> R."""
        return Family(mirror_walls(self.walls), self.periods, self.symmetric)

    @property
    def flights(self) -> int:
        """Flights of the residual: half the sequence when symmetric."""
        n = len(self.walls)
        return n // 2 if self.symmetric else n

    def span(self, p: ModelParams) -> float:
        """Time covered by those flights (N T or N T / 2)."""
        return self.periods * p.period * (0.5 if self.symmetric else 1.0)

    def codes(self) -> np.ndarray:
        """The wall code of every impact."""
        return np.array([WALL_CODES[c] for c in self.walls], dtype=np.int64)

    def full_flights(self, fl) -> np.ndarray:
        """The flight times of the whole sequence from those of the residual's flights."""
        return np.concatenate([fl, fl]) if self.symmetric else np.asarray(fl, float)

    @classmethod
    def checked(cls, walls: object, periods: object = 1,
                symmetric: bool | None = None) -> Family:
        """The family of validated ``walls`` and ``periods`` (ParameterError naming them)."""
        return cls(check_walls(walls), check_periods(periods), symmetric)


#: the 1:1 orbits
ONE_TO_ONE = Family("LR", 1)
