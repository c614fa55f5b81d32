"""Initial states of a census: scrambled Sobol points in a box, seeded.

The box is given in the coordinates (z_m, v_m, w, v_b) = (LO position, LO velocity, ball
position relative to the cavity w = z_m - z_b, ball velocity), so that every point has the
ball inside the cavity (|w| <= 1); states are returned as (z_m, z_m', z_b, z_b') with
z_b = z_m - w, the ``state0`` convention of ``vines.simulate``. The forcing phase at t = 0
is the model's phi (0 by default).
"""
from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np

from ..core.params import STATE_MAX, ParameterError, check_int, check_real

#: box coordinates, in this order
BOX_NAMES = ("z_m", "v_m", "w", "v_b")
#: the default box, z_m, z_m' in [-1.5, 1.5], w in [-1, 1], z_b' in [-1.5, 1.5]
DEFAULT_BOX = ((-1.5, 1.5), (-1.5, 1.5), (-1.0, 1.0), (-1.5, 1.5))
N_MAX = 1_000_000          # initial states of one census
SEED_MAX = 2**63 - 1


def check_box(box: Sequence[Sequence[float]]) -> tuple:
    """``box`` as 4 (lo, hi) float pairs in BOX_NAMES order (lo <= hi, |w| <= 1); raises
    ParameterError naming the bad entry. A mapping {name: (lo, hi)} is accepted too."""
    if isinstance(box, dict):
        unknown = [k for k in box if k not in BOX_NAMES]
        if unknown:
            raise ParameterError("box", unknown[0], f"must be one of {', '.join(BOX_NAMES)}")
        box = tuple(box.get(k, DEFAULT_BOX[i]) for i, k in enumerate(BOX_NAMES))
    try:
        pairs = [tuple(b) for b in box]
    except TypeError:
        raise ParameterError("box", box, "must be 4 (lo, hi) pairs for z_m, v_m, w, v_b") from None
    if len(pairs) != 4 or any(len(b) != 2 for b in pairs):
        raise ParameterError("box", box, "must be 4 (lo, hi) pairs for z_m, v_m, w, v_b")
    out = []
    for name, (lo, hi) in zip(BOX_NAMES, pairs, strict=False):
        bound = 1.0 if name == "w" else STATE_MAX
        lo = check_real(f"box.{name}", lo, lo=-bound, hi=bound)
        hi = check_real(f"box.{name}", hi, lo=lo, hi=bound)
        out.append((lo, hi))
    return tuple(out)


def sample_states(n: int, seed: int = 0,
                  box: Sequence[Sequence[float]] = DEFAULT_BOX) -> np.ndarray:
    """n initial states (n, 4) = (z_m, z_m', z_b, z_b'): the first n points of a scrambled
    Sobol sequence (``scipy.stats.qmc.Sobol``, scramble seed ``seed``) mapped onto ``box``.
    The same (n, seed, box) gives the same states bit for bit; powers of 2 keep the
    sequence's balance."""
    from scipy.stats import qmc
    n = check_int("n", n, lo=1, hi=N_MAX)
    seed = check_int("seed", seed, lo=0, hi=SEED_MAX)
    box = check_box(box)
    sobol = qmc.Sobol(d=4, scramble=True, seed=np.random.default_rng(seed))
    with warnings.catch_warnings():     # n need not be a power of 2
        warnings.simplefilter("ignore", UserWarning)
        u = sobol.random_base2(math.ceil(math.log2(n)))[:n] if n > 1 else sobol.random(1)
    lo = np.array([b[0] for b in box])
    hi = np.array([b[1] for b in box])
    zm, vm, w, vb = (lo + u * (hi - lo)).T
    return np.ascontiguousarray(np.stack([zm, vm, zm - w, vb], axis=1))
