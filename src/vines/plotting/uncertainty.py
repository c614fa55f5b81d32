"""Sampling uncertainty of the basin fractions of the robust-TET maps (a census of n initial
states per grid point): the Wilson score interval of a binomial proportion."""
from __future__ import annotations

import numpy as np

#: normal quantile of a two-sided 95 % interval
Z95 = 1.959963984540054
#: intervals wider than this are hatched on the robust-TET figure
WIDE_INTERVAL = 0.2


def wilson_interval(fraction, n: int, z: float = Z95):
    """(low, high) Wilson score interval of a proportion ``fraction`` observed on ``n``
    trials (arrays broadcast)."""
    p = np.asarray(fraction, dtype=float)
    if n < 1:
        raise ValueError(f"n = {n}: a Wilson interval needs at least one trial")
    den = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z / den * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return centre - half, centre + half


def wilson_width(fraction, n: int, z: float = Z95) -> np.ndarray:
    """Width of the Wilson score interval (see ``wilson_interval``)."""
    lo, hi = wilson_interval(fraction, n, z)
    return hi - lo
