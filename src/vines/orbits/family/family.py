"""One family of periodic orbits: a wall sequence over a number of forcing periods, and
which of its orbits (symmetric, asymmetric or both); its name, its mirror image, the checks
of its walls and periods (``names``; docs/bifurcation.md, "Families of periodic orbits").

The 1:1 orbit is the value LR/1 of it (``ONE_TO_ONE``); ``Family.engine`` is the one place
that decides anything by it: it returns the family's engine from the registry of
``engine`` (``JETS`` for 1:1, ``MAPS`` for every other family), which the code that
differs per family asks (seeds, curves, output formats) instead of comparing families.
Numba-free (numpy only): the pipeline's config checks read it at parse time.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.params import ModelParams
from .engine import ENGINES, JETS, MAPS, Engine
from .names import (  # noqa: F401 (the names of a family, read from here as well)
    MAX_IMPACTS_PER_ORBIT,
    MAX_PERIODS,
    MIRROR_MATRIX,
    MIRROR_SIGNS,
    WALL_CODES,
    WALL_NAMES,
    canonical_walls,
    check_periods,
    check_walls,
    family_name,
    has_half_symmetry,
    mirror_walls,
    paper_label,
)


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
    def engine(self) -> Engine:
        """The family's engine (``engine.ENGINES``): ``JETS`` for the 1:1 family (walls LR,
        one period), ``MAPS`` for every other; the one place that tells 1:1 apart."""
        return ENGINES[JETS if self.key == ONE_TO_ONE.key else MAPS]

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
