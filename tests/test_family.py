"""The family object (``orbits.family.family.Family``): names, mirror images, symmetry,
checks. Expected names from docs/bifurcation.md ("Families of periodic orbits")."""
import pytest

from vines.core.params import ModelParams, ParameterError
from vines.orbits.family.family import JETS, MAPS, ONE_TO_ONE, Family

# (family, name, has symmetric orbits, flights of its residual)
CASES = [
    (Family("LR", 1, True), "LR/1-sym", True, 1),
    (Family("LR", 1, False), "LR/1-asym", True, 2),
    (Family("LLRR", 1, True), "LLRR/1-sym", True, 2),
    (Family("LRLR", 2), "LRLR/2", False, 4),
    (Family("RLL", 1), "LLR/1", False, 3),          # the canonical rotation names it
]


@pytest.mark.parametrize("fam,name,sym,flights", CASES, ids=[c[1] for c in CASES])
def test_name_symmetry_flights(fam, name, sym, flights):
    assert fam.name == name
    assert fam.has_symmetric is sym
    assert fam.flights == flights
    p = ModelParams(eta=0.2, omega=1.0, F=0.3)
    assert fam.span(p) == pytest.approx(fam.periods * p.period * (0.5 if fam.symmetric else 1))
    assert len(fam.codes()) == len(fam.walls)


@pytest.mark.parametrize("fam", [c[0] for c in CASES], ids=[c[1] for c in CASES])
def test_mirror_is_an_involution_swapping_the_walls(fam):
    m = fam.mirror
    assert m.mirror == fam
    assert m.walls.count("L") == fam.walls.count("R")
    assert all(a != b for a, b in zip(m.walls, fam.walls, strict=True))
    assert (m.periods, m.symmetric) == (fam.periods, fam.symmetric)


def test_only_lr_over_one_period_is_one_to_one():
    assert ONE_TO_ONE.engine.name == JETS == Family("LR", 1, True).engine.name
    assert Family("LR", 3).engine.name == MAPS == Family("LRLR", 2).engine.name
    assert Family.checked(" lr ", 1) == ONE_TO_ONE
    assert Family("RL", 1).engine.name == MAPS  # a rotation: the sequence solver's business


@pytest.mark.parametrize("fam, engine", [(ONE_TO_ONE, JETS), (Family("LR", 1, True), JETS),
                                         (Family("LR", 1, False), JETS), (Family("RL", 1), MAPS),
                                         (Family("LLRR", 1, True), MAPS),
                                         (Family("LRLR", 2), MAPS), (Family("LR", 3), MAPS)])
def test_engine_follows_the_family(fam, engine):
    assert fam.engine.name == engine


@pytest.mark.parametrize("walls,periods,name", [("LXR", 1, "walls"), ("", 1, "walls"),
                                                ("L" * 65, 1, "walls"), ("LR", 0, "periods"),
                                                ("LR", 65, "periods"), (3, 1, "walls")])
def test_checked_refuses_bad_walls_and_periods(walls, periods, name):
    with pytest.raises(ParameterError) as err:
        Family.checked(walls, periods)
    assert err.value.name == name
