"""Walls and the impact law (the one place both are defined).

w = z_m - z_b is the ball's position relative to the cavity; wall L is w = +1, wall R is
w = -1. An impact changes the velocities by Newton's law with restitution r (paper Eq. 10),
conserving momentum v_m + eta v_b.
"""
from .._jit import njit
from .conventions import WALL_L, WALL_NAMES, WALL_R  # noqa: F401  (the wall codes)


@njit(cache=True, nogil=True)
def impact_velocities(eta, r, vm, vb):
    """Post-impact (v_m+, v_b+) from pre-impact (v_m-, v_b-) (paper Eq. 10)."""
    one = 1.0 + eta
    return ((1.0 - r * eta) * vm + eta * (1.0 + r) * vb) / one, \
        ((1.0 + r) * vm + (eta - r) * vb) / one
