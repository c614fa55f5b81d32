"""The names of wall sequences: their checks, mirror image, canonical rotation, family name
and the paper's label, the wall codes and the mirror of a pre-impact state (docs/
bifurcation.md, "Families of periodic orbits"). Numpy only: every module of the family
layer, the orbit type included, reads them below ``family.Family``."""
from __future__ import annotations

import numpy as np

from ...core.conventions import WALL_L, WALL_R
from ...core.params import ParameterError, check_int

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


def wall_codes(walls: str) -> np.ndarray:
    """The wall codes of ``walls``, read-only: inside a compiled function a global array is a
    read-only constant, so Python calls passing read-only codes use the same compiled
    specialization instead of compiling a second one."""
    codes = np.array([WALL_CODES[c] for c in walls], dtype=np.int64)
    codes.setflags(write=False)
    return codes
