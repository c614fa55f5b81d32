"""The orbit atlas's per-point answer (``vines.orbits.atlas.atlas``) against simulations from rest.

At points where the simulation from rest (the Fig 12 run: t_end 7000) ends on a periodic
orbit, the family of its last period's wall sequence must be stable and admissible in the
atlas (which sees only a 600-unit run from rest, plus its own seeds).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from vines.core.params import ModelParams, ParameterError
from vines.orbits.atlas.atlas import FAMILIES, PAPER_LABELS, atlas_arrays, atlas_point
from vines.orbits.family.family import canonical_walls, has_half_symmetry
from vines.solvers import simulate

# (eta, omega, F): regimes 2:2 (Fig 9), 2:2 asymmetric, 2:1, 3:2, period-2 of 2:1, of 2:2
# and of 3:2, 1:1 (points of coarse simulation scans)
POINTS = [(0.2, 0.8, 0.4), (0.3, 0.82, 0.2), (0.16, 0.62, 0.4), (0.23, 0.74, 0.3077),
          (0.16, 0.74, 0.3077), (0.58, 0.66, 0.4), (0.79, 0.62, 0.4), (0.55, 1.0, 0.4)]


def _family_of_run(p: ModelParams) -> str:
    run = simulate(p.eta, p.omega, p.F, r=p.r, d=p.d)
    assert run.period >= 1, run.regime
    last = run.impacts[run.impacts["t"] > run.settings.t_end - run.period * p.period]
    walls = canonical_walls("".join("L" if w > 0 else "R" for w in last["wall"]))
    key = f"{walls}/{run.period}"
    if key not in FAMILIES:         # the families split by symmetry
        t = last["t"]
        fl = np.diff(np.append(t, t[0] + run.period * p.period))
        h = len(walls) // 2
        sym = has_half_symmetry(walls) and run.period % 2 == 1 and \
            np.allclose(fl[:h], fl[h:], atol=1e-6)
        key += "-sym" if sym else "-asym"
    assert PAPER_LABELS[key] == run.regime or run.regime.startswith("period")
    return key


@pytest.mark.parametrize("eta, omega, F", POINTS)
def test_the_family_the_simulation_settles_on_is_stable_in_the_atlas(eta, omega, F):
    p = ModelParams(eta=eta, omega=omega, F=F)
    key = _family_of_run(p)
    fam, _ = atlas_point(p)
    assert fam[key].stable and fam[key].admissible and fam[key].lambda_max < 1.0, key


def test_fig9_point_and_mirror_families():
    fam, orbits = atlas_point(ModelParams(eta=0.2, omega=0.8, F=0.4))
    assert fam["LLRR/1-sym"].stable and abs(fam["LLRR/1-sym"].lambda_max - 0.88209) < 1e-5
    assert fam["LR/1-sym"].admissible and not fam["LR/1-sym"].stable
    # mirror images: the same existence, stability and multipliers
    for a, b in (("LLR/1", "LRR/1"), ("LLRLLR/2", "LRRLRR/2"), ("LLLRR/1", "LLRRR/1")):
        assert (fam[a].admissible, fam[a].stable) == (fam[b].admissible, fam[b].stable)
        if fam[a].admissible:
            assert math.isclose(fam[a].lambda_max, fam[b].lambda_max, rel_tol=1e-8)
    assert set(orbits) == {f.walls for f in FAMILIES.values()}


def test_sweep_equals_points_with_the_same_seeds_and_bad_input():
    eta, omega = [0.2], [0.78, 0.8]
    out = atlas_arrays(eta, omega, 0.4)
    fam0, orb0 = atlas_point(ModelParams(eta=0.2, omega=0.78, F=0.4))
    fam1, _ = atlas_point(ModelParams(eta=0.2, omega=0.8, F=0.4), orb0)
    for j, fam in enumerate((fam0, fam1)):
        for key, st in fam.items():
            assert out[f"{key}:stable"][0, j] == st.stable
            assert out[f"{key}:admissible"][0, j] == st.admissible
    with pytest.raises(ParameterError, match="params"):
        atlas_point({"eta": 0.2})
