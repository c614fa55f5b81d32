"""One orbit base, ``OrbitBase``, for the 1:1 orbit and the orbit of any wall sequence:
the same fields mean the same for every family (invariants, not the code's numbers)."""
import numpy as np
import pytest

from vines.core.params import ModelParams
from vines.orbits.family.orbit import OrbitBase
from vines.orbits.family.periodic import find_1to1
from vines.orbits.family.sequence import find_sequence

ONE = ModelParams(eta=0.55, omega=1.0, F=0.4)
FOUR = ModelParams(eta=0.2, omega=0.8, F=0.4)


@pytest.mark.parametrize("orbits, walls", [
    (lambda: find_1to1(ONE.eta, ONE.omega, ONE.F), "LR"),
    (lambda: find_sequence(ONE, "LR", 1), "LR"),
    (lambda: find_sequence(FOUR, "LLRR", 1), "LLRR"),
], ids=["1:1", "LR/1", "LLRR/1"])
def test_every_orbit_reads_the_same(orbits, walls):
    found = orbits()
    assert found
    for o in found:
        assert isinstance(o, OrbitBase) and o.walls == walls
        assert len(o.flight_times) == len(walls) == len(o.dw) == len(o.phases)
        mods = np.abs(o.eigenvalues)
        assert o.lambda_max == pytest.approx(mods.max(), rel=1e-12)
        assert np.all(np.diff(mods) <= 1e-12 * mods.max())          # decreasing modulus
        assert o.stable == (o.admissible and o.lambda_max < 1.0)
        # the flights cover the orbit's period (periods forcing periods)
        assert sum(o.flight_times) == pytest.approx(o.periods * o.params.period, rel=1e-9)
