"""The state a sweep carries from one point to the next stays inside the cavity in floating
point (a ball resting on a wall far from the origin can end a run 1 ulp outside)."""
import math

import pytest

from vines.core.params import SolverSettings
from vines.core.sweep import inside_cavity


def test_round_off_outside_is_moved_onto_the_wall():
    # the final state of a chatter run of the paper's Fig 14 sweep (F = 0.4), 1 ulp outside
    s = (-7.368235572371556, 11.140681567382709, -8.368235572371557, 11.140681567382709)
    assert abs(s[0] - s[2]) > 1.0
    z_m, v_m, z_b, v_b = inside_cavity(*s)
    assert abs(z_m - z_b) <= 1.0
    assert (z_m, v_m, v_b) == s[:2] + s[3:]
    assert abs(z_b - s[2]) <= 2 * math.ulp(s[2])
    SolverSettings(t_end=1.0, t_transient=0.0, state0=(z_m, v_m, z_b, v_b))   # accepted


@pytest.mark.parametrize("state", [(0.3, 0.1, -0.2, 0.0), (2.0, 0.0, 1.0, 0.0),
                                   (-5.0, 1.0, -4.0, 1.0)])
def test_states_inside_are_unchanged(state):
    assert inside_cavity(*state) == state


def test_a_real_excess_is_left_for_the_validation_to_refuse():
    s = (0.0, 0.0, -1.001, 0.0)
    assert inside_cavity(*s) == s
    with pytest.raises(ValueError, match="state0"):
        SolverSettings(t_end=1.0, t_transient=0.0, state0=s)
