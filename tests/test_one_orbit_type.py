"""One periodic-orbit type, one branch type and one engine registry for every family
(issue 38): the fields mean the same for LR/1-sym, LR/1-asym, LLRR/1-sym and LRLR/2, the
1:1 names are the general values at the wall hit once, a branch's arrays are its orbits'
values, and no module but the registry decides by "is this the 1:1 family" (read from the
sources with ``ast``). Expected values are invariants and independent recomputations from
the orbit's own states (the flow's definition of w' and the forcing phase), not the code's
numbers."""
import ast
import math
import re

import numpy as np
import pytest
from conftest import SRC

from vines.core.params import ModelParams
from vines.orbits.continuation.branch import Branch, SequenceBranch, make_branch
from vines.orbits.family.engine import ENGINES, JETS, MAPS, Engine
from vines.orbits.family.family import ONE_TO_ONE, Family
from vines.orbits.family.orbit import PeriodicOrbit
from vines.orbits.family.periodic import find_1to1
from vines.orbits.family.sequence import SequenceOrbit, find_sequence, flip_seeds

ONE = ModelParams(eta=0.55, omega=1.0, F=0.4)          # symmetric stable 1:1 orbit
ASYM = ModelParams(eta=0.035, omega=1.0, F=0.05)       # a mirror pair of asymmetric ones
FOUR = ModelParams(eta=0.2, omega=0.8, F=0.4)          # LLRR/1-sym
FLIP = ModelParams(eta=0.142, omega=0.765, F=0.2)      # past the flip of the asymmetric 1:1


def _lrlr2():
    one = next(o for o in find_sequence(FLIP, "LR", 1, simulation=False)
               if o.admissible and not o.symmetric)
    return find_sequence(FLIP, "LRLR", 2, simulation=False, seeds=flip_seeds(one))


FAMILIES = {
    "LR/1-sym": (lambda: [o for o in find_1to1(ONE.eta, ONE.omega, ONE.F, simulation=False)
                          if o.symmetric], "LR", 1),
    "LR/1-asym": (lambda: [o for o in find_1to1(ASYM.eta, ASYM.omega, ASYM.F,
                                                simulation=False) if not o.symmetric], "LR", 1),
    "LLRR/1-sym": (lambda: [o for o in find_sequence(FOUR, "LLRR", 1, simulation=False)
                            if o.symmetric], "LLRR", 1),
    "LRLR/2": (_lrlr2, "LRLR", 2),
}


@pytest.fixture(scope="module", params=sorted(FAMILIES))
def family_orbits(request):
    found, walls, periods = FAMILIES[request.param]
    orbits = found()
    assert orbits, request.param
    return request.param, orbits, walls, periods


def test_one_type_same_fields_for_every_family(family_orbits):
    name, orbits, walls, periods = family_orbits
    n = len(walls)
    for o in orbits:
        assert type(o) is PeriodicOrbit and SequenceOrbit is PeriodicOrbit
        assert (o.walls, o.periods) == (walls, periods) and o.family == name.split("-")[0]
        for k in ("states", "dw", "phases", "jacobians", "eigenvalues"):
            assert isinstance(getattr(o, k), np.ndarray), k
        assert o.states.shape == (n, 4) and len(o.flight_times) == len(o.dw) == n
        assert np.shape(o.jacobians) == (n, 4, 4) and len(o.phases) == n
        p = o.params
        # w' = z_m' - z_b' before each impact; the forcing phase of each impact time
        assert np.array_equal(o.dw, o.states[:, 0] - o.states[:, 1])
        ph = np.mod(p.omega * o.states[:, 3] + p.phi, 2.0 * math.pi)
        np.testing.assert_allclose(o.phases, ph, rtol=0, atol=1e-12)
        # the flights cover the orbit's period; the monodromy matrix is the Jacobians' product
        assert sum(o.flight_times) == pytest.approx(periods * p.period, rel=1e-9)
        M = np.eye(4)
        for J in o.jacobians:
            M = J @ M
        ev = np.linalg.eigvals(M)
        np.testing.assert_allclose(np.sort(np.abs(ev)), np.sort(np.abs(o.eigenvalues)),
                                   rtol=1e-9, atol=1e-12)
        assert o.lambda_max == pytest.approx(np.abs(o.eigenvalues).max(), rel=1e-12)
        assert o.stable == (o.admissible and o.lambda_max < 1.0)


def test_the_1to1_names_are_the_impacts_at_L_and_R(family_orbits):
    name, orbits, walls, _ = family_orbits
    for o in orbits:
        if walls.count("L") != 1:                  # no single impact on L: no 1:1 names
            with pytest.raises(AttributeError):
                o.x_L  # noqa: B018
            assert not hasattr(o, "dw_R")
            continue
        iL, iR = walls.index("L"), walls.index("R")
        assert np.array_equal(o.x_L, o.states[iL]) and np.array_equal(o.x_R, o.states[iR])
        assert (o.dw_L, o.dw_R) == (o.dw[iL], o.dw[iR])
        assert (o.phase_L, o.phase_R) == (o.phases[iL], o.phases[iR])


def test_to_dict_key_sets(family_orbits):
    name, orbits, walls, periods = family_orbits
    o = orbits[0]
    d = o.to_dict()
    if name.startswith("LR/1"):      # found by the 1:1 solver: the keys it always wrote
        assert list(d) == ["symmetric", "admissible", "stable", "lambda_max", "eigenvalues",
                           "dw_L", "dw_R", "phase_L", "phase_R", "flight_times", "x_L", "x_R"]
        assert d["x_L"] == [float(v) for v in o.states[0]] and d["dw_R"] == o.dw[1]
    else:
        assert list(d) == ["walls", "periods", "family", "paper_label", "symmetric",
                           "admissible", "stable", "lambda_max", "eigenvalues", "dw", "phases",
                           "flight_times", "states"]
        assert (d["walls"], d["periods"]) == (walls, periods)
        assert d["states"] == [[float(v) for v in x] for x in o.states]


def test_the_1to1_solver_and_the_sequence_solver_give_one_type():
    ref = find_1to1(ONE.eta, ONE.omega, ONE.F, simulation=False)
    got = find_sequence(ONE, "LR", 1, simulation=False)
    for a, b in zip(ref, got, strict=True):
        assert type(a) is type(b)
        for k in ("states", "dw", "phases", "flight_times", "eigenvalues", "jacobians"):
            assert np.array_equal(getattr(a, k), getattr(b, k)), k
        assert set(b.to_dict()) - set(a.to_dict()) == {"walls", "periods", "family",
                                                        "paper_label", "dw", "phases",
                                                        "states"}


# --------------------------------------------------------------------------- branches

def _points(orbits, param):
    return [(getattr(o.params, param), o) for o in orbits]


def test_one_branch_type_arrays_are_the_orbits_values():
    orbits = find_1to1(ASYM.eta, ASYM.omega, ASYM.F, simulation=False)
    one = make_branch("eta", _points(orbits, "eta"), [], "done", family="asymmetric")
    seq = SequenceBranch(walls="LR", periods=1, param="eta", points=orbits)
    for br in (one, seq):
        assert type(br) is Branch and len(br) == len(orbits) and br.points is br.orbits
        assert np.array_equal(br.values, [o.params.eta for o in orbits])
        for k in ("lambda_max", "stable", "symmetric", "admissible", "dw_L", "dw_R",
                  "phase_L", "phase_R"):
            assert np.array_equal(getattr(br, k), [getattr(o, k) for o in orbits]), k
        for k in ("eta", "omega", "F"):
            assert np.array_equal(getattr(br, k), [getattr(o.params, k) for o in orbits]), k
        mods = br.abs_eigenvalues
        assert mods.shape == (len(orbits), 4) and np.all(np.diff(mods, axis=1) <= 0)
        assert np.array_equal(mods[:, 0], br.lambda_max)
    # the two builders' key sets: the 1:1 continuation's and any family's
    d1, ds = one.to_dict(), seq.to_dict()
    assert list(d1) == ["param", "family", "branch", "events", "stopped", "switched"]
    assert d1["family"] == "asymmetric" and "dw_L" in d1["branch"][0]
    assert list(ds) == ["walls", "periods", "family", "param", "branch", "events", "stopped",
                        "switched"]
    assert ds["family"] == "LR/1" and ds["branch"][0]["dw"] == list(orbits[0].dw)
    assert np.array_equal(one.arclength, np.abs(one.values - one.values[0]))


def test_empty_branches():
    for br in (make_branch("F", [], [], "no orbit"),
               SequenceBranch(walls="LLRR", periods=1, param="F", points=[],
                              stopped="no orbit")):
        assert len(br) == 0 and br.lambda_max.shape == (0,)
        assert br.abs_eigenvalues.shape == (0, 4)
    assert SequenceBranch(walls="LLRR", periods=1, param="F", points=[]).to_dict()[
        "family"] is None


# --------------------------------------------------------------------------- engines

@pytest.mark.parametrize("fam", [ONE_TO_ONE, Family("LR", 1, True), Family("LR", 1, False),
                                 Family("LLRR", 1, True), Family("LRLR", 2), Family("RL", 1),
                                 Family("LR", 3), Family("LLR", 1)])
def test_every_family_gets_an_engine(fam):
    engine = fam.engine
    assert isinstance(engine, Engine) and ENGINES[engine.name] is engine
    assert (engine.name == JETS) == (fam.key == ONE_TO_ONE.key)
    # the 1:1 outputs keep their form; every other names its family
    keys = engine.output_keys(fam)
    assert keys == ({} if engine.name == JETS else {"walls": fam.walls,
                                                   "periods": fam.periods})


def test_registry_implements_the_contract():
    assert set(ENGINES) == {JETS, MAPS}
    for engine in ENGINES.values():
        for op in ("affine_seeds", "simulation_seeds"):
            assert getattr(type(engine), op) is not getattr(Engine, op), (engine.name, op)


def test_the_engines_seeds():
    """JETS: the 1:1 solver's seeds; MAPS: the affine forms of the sequence (LLRR/1-sym has
    the half symmetry: its seeds are symmetric, flight k as long as flight k + 2)."""
    from vines.orbits.maps.impact import model_array
    jets = ONE_TO_ONE.engine.affine_seeds(ONE, model_array(ONE), "LR", 1)
    assert jets and all(len(fl) == 2 and sum(fl) == pytest.approx(ONE.period)
                        for _, fl in jets)
    maps = Family("LLRR", 1).engine.affine_seeds(FOUR, model_array(FOUR), "LLRR", 1)
    assert maps and all(fl[0] == fl[2] and fl[1] == fl[3] for _, fl in maps)


#: the registry (family.py picks the engine, engine.py is it) and the curve layer's table of
#: each engine's tracer
REGISTRY = {"orbits/family/family.py", "orbits/family/engine.py"}
TABLES = {"orbits/curves/boundaries.py"}


def _sources():
    pkg = SRC / "vines"
    yield from ((str(f.relative_to(pkg)), f.read_text()) for f in pkg.rglob("*.py"))
    workflow = SRC.parent / "workflow"
    yield from ((str(f.relative_to(workflow)), f.read_text()) for f in workflow.rglob("*.smk"))


def _engine_comparisons(text: str) -> list:
    """Comparisons (==, !=, is, in) with an operand ``<x>.engine`` or ``JETS``/``MAPS``,
    and reads of an attribute ``one_to_one``, in Python source."""
    hits = []
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Compare) and any(
                (isinstance(op, ast.Attribute) and op.attr == "engine")
                or (isinstance(op, ast.Name) and op.id in ("JETS", "MAPS"))
                for op in [node.left, *node.comparators]):
            hits.append(ast.unparse(node))
        if isinstance(node, ast.Attribute) and node.attr == "one_to_one":
            hits.append(ast.unparse(node))
    return hits


def test_the_checker_sees_a_comparison():
    assert _engine_comparisons("if fam.engine == JETS: pass") == ["fam.engine == JETS"]
    assert _engine_comparisons("x = 1 if f.one_to_one else 2")
    assert not _engine_comparisons("if fam.engine.class_map_seeds: pass")


def test_only_the_registry_decides_by_the_family():
    """No module outside the registry compares an engine or asks whether a family is 1:1;
    JETS and MAPS are imported by the registry and the curve layer's table only."""
    hits = []
    for name, text in _sources():
        if name in REGISTRY:
            continue
        if name.endswith(".py"):
            hits += [f"{name}: {h}" for h in _engine_comparisons(text)]
        elif re.search(r"engine\s*[!=]=|\.one_to_one\b", text):
            hits.append(name)
        if name not in TABLES and re.search(r"import[^\n]*\b(JETS|MAPS)\b", text):
            hits.append(f"{name}: imports JETS/MAPS")
    assert not hits, hits


def test_continue_branch_takes_the_orbits_of_its_family_only():
    """One orbit type for every family: the 1:1 continuation refuses an LLRR orbit with
    the one-line error naming ``orbit`` (not an AttributeError on x_L)."""
    from vines.core.params import ParameterError
    from vines.orbits.continuation.one_to_one import continue_branch
    llrr = next(o for o in find_sequence(FOUR, "LLRR", 1, simulation=False) if o.symmetric)
    with pytest.raises(ParameterError, match=r"^invalid orbit = .LLRR/1.: must be None or a 1:1"):
        continue_branch("omega", FOUR.omega, FOUR.omega + 0.01,
                        fixed={"eta": FOUR.eta, "F": FOUR.F}, orbit=llrr)
