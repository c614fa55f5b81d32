"""Pseudo-arclength continuation of 1:1 branches (issue 14, steps 1-2): derivatives of the
shooting systems, fold passing, events, asymmetric branches and branch switching.

Oracles: the independent map solver (``periodic.find_1to1``, ``maps.impact_map``), the
closed-form symmetric seeds (a line-circle intersection: two orbits on one side of a fold,
none on the other), central finite differences, analytic derivatives."""
import math

import numpy as np
import pytest

from vines.core.params import D_DEFAULT, R_DEFAULT, ModelParams
from vines.orbits.continuation.follower import orbit_at
from vines.orbits.continuation.one_to_one import continue_branch
from vines.orbits.family.family import MIRROR_MATRIX
from vines.orbits.family.periodic import find_1to1, symmetric_seeds
from vines.orbits.jets import shooting as sh
from vines.orbits.jets import taylor as jets
from vines.orbits.maps.impact import model_array

MODEL = sh.Model(R_DEFAULT, D_DEFAULT)


def test_jets_match_analytic_derivatives():
    x, y = jets.variables([0.7, -1.3], order=2)
    f = jets.sin(x * y) / jets.exp(x) + jets.sqrt(x) * jets.cos(y) - 2.0 / y
    a, b = 0.7, -1.3
    # f = sin(ab) e^-a + sqrt(a) cos b - 2/b
    fa = b * math.cos(a * b) * math.exp(-a) - math.sin(a * b) * math.exp(-a) \
        + 0.5 / math.sqrt(a) * math.cos(b)
    fb = a * math.cos(a * b) * math.exp(-a) - math.sqrt(a) * math.sin(b) + 2.0 / b ** 2
    fbb = -a * a * math.sin(a * b) * math.exp(-a) - math.sqrt(a) * math.cos(b) - 4.0 / b ** 3
    fab = (math.cos(a * b) - a * b * math.sin(a * b)) * math.exp(-a) \
        - a * math.cos(a * b) * math.exp(-a) - 0.5 / math.sqrt(a) * math.sin(b)
    assert f.g == pytest.approx([fa, fb], rel=1e-13)
    assert f.H[1, 1] == pytest.approx(fbb, rel=1e-13)
    assert f.H[0, 1] == pytest.approx(fab, rel=1e-13) and f.H[1, 0] == f.H[0, 1]


def test_jet_determinant_and_its_gradient():
    rng = np.random.default_rng(3)
    M0 = rng.normal(size=(4, 4))
    v = jets.variables(M0.ravel().tolist())
    M = [[v[4 * i + j] for j in range(4)] for i in range(4)]
    d = jets.det(M)
    assert d.v == pytest.approx(np.linalg.det(M0), rel=1e-12)
    # d det / d M = det(M) M^-T (Jacobi's formula)
    ref = np.linalg.det(M0) * np.linalg.inv(M0).T
    np.testing.assert_allclose(d.g.reshape(4, 4), ref, rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("eta, omega, F", [(0.12, 1.1, 0.3077), (0.2, 1.0, 0.2),
                                           (0.6, 0.9, 0.3077)])
def test_shooting_system_on_the_maps_orbits(eta, omega, F):
    """Orbits of the map solver solve the shooting systems; the monodromy matrices from the
    jets equal the maps' Jacobians; dE/d(u, eta, omega, F) equals central differences."""
    p = ModelParams(eta, omega, F)
    orbits = find_1to1(eta, omega, F, simulation=False)
    assert orbits
    for o in orbits:
        fam = "symmetric" if o.symmetric else "asymmetric"
        u = list(o.x_L) + ([] if o.symmetric else [o.flight_times[0]])
        par = {"eta": eta, "omega": omega, "F": F}
        E, Ez = sh.residual_jacobian(MODEL, fam, u, par, ("eta", "omega", "F"))
        assert np.abs(E).max() < 1e-10
        z0 = np.array(u + [eta, omega, F])
        for k in range(len(z0)):
            h = 1e-6 * max(1.0, abs(z0[k]))
            zp, zm = z0.copy(), z0.copy()
            zp[k] += h
            zm[k] -= h
            fd = (np.array(sh.residual(MODEL, fam, zp[:-3], *zp[-3:]))
                  - np.array(sh.residual(MODEL, fam, zm[:-3], *zm[-3:]))) / (2 * h)
            np.testing.assert_allclose(Ez[:, k], fd, rtol=1e-6, atol=1e-7)
        ref = orbit_at(p, fam, u)
        A = sh.jacobian_float(sh.monodromy_jets(MODEL, fam, u, eta, omega, F))
        mono = MIRROR_MATRIX @ ref.jacobians[0] if o.symmetric else ref.jacobians[1] @ ref.jacobians[0]
        np.testing.assert_allclose(A, mono, atol=1e-10 * np.abs(mono).max())
        assert np.abs(np.linalg.eigvals(mono @ mono if o.symmetric else mono)).max() == \
            pytest.approx(o.lambda_max, rel=1e-9)


@pytest.fixture(scope="module")
def fold_branch():
    return continue_branch("F", 0.3, 0.01, None, {"eta": 0.2, "omega": 1.0})


def test_fold_is_passed(fold_branch):
    """Acceptance: the fold at F = 0.01199 +- 1e-4 is reported and passed (F back > 0.05)."""
    br = fold_branch
    folds = [e for e in br.events if e["type"] == "fold"]
    assert len(folds) == 1
    F_fold = folds[0]["at"]
    # 1e-4 is the precision of the quoted acceptance value (4 digits), not of the solver: the
    # closed-form check below brackets F_fold to a relative 1e-6, independently
    assert abs(F_fold - 0.01199) < 1e-4
    assert br.values.min() == pytest.approx(F_fold, abs=1e-12)
    assert br.values[folds[0]["index"]:].max() > 0.05
    # independent: the closed-form symmetric orbits exist just above the fold, not below
    mdl = lambda F: model_array(ModelParams(0.2, 1.0, F))            # noqa: E731
    assert len(symmetric_seeds(mdl(F_fold * (1 + 1e-6)))) == 2
    assert symmetric_seeds(mdl(F_fold * (1 - 1e-6))) == []
    # every point is an orbit of the maps (the non-admissible sheet has |lambda| up to 1e7)
    assert max(o.residual / (1.0 + o.lambda_max) for o in br.orbits) < 1e-10


def test_events_along_the_arclength(fold_branch):
    """Stable window of the symmetric branch at (eta, omega) = (0.2, 1): symmetry-breaking
    (half-map multiplier -1) above, Neimark-Sacker (complex pair on the unit circle) below;
    the stable flags change exactly there."""
    br = fold_branch
    ev = {e["type"]: e for e in br.events}
    sb, ns = ev["symmetry-breaking"], ev["neimark-sacker"]
    assert sb["connects"] == "asymmetric"
    mu = np.linalg.eigvals(MIRROR_MATRIX @ orbit_at(br.orbits[sb["index"]].params, "symmetric",
                                                br.orbits[sb["index"]].x_L).jacobians[0])
    assert np.min(np.abs(mu + 1.0)) < 1e-6
    o = br.orbits[ns["index"]]
    ev_ns = o.eigenvalues[np.argmin(np.abs(np.abs(o.eigenvalues) - 1.0))]
    assert abs(abs(ev_ns) - 1.0) < 1e-6 and abs(ev_ns.imag) > 1e-3
    stable = br.stable
    inside = (br.values < sb["at"] - 1e-6) & (br.values > ns["at"] + 1e-6) \
        & (np.arange(len(br)) < ns["index"])
    outside = (np.arange(len(br)) < sb["index"]) | (
        (np.arange(len(br)) > ns["index"]) & (np.arange(len(br)) < len(br)))
    assert stable[inside].all() and not stable[outside].any()


def test_asymmetric_branch_ends_on_the_symmetric_one():
    """Acceptance: (0.12, 1.1, 0.3077) --branch asymmetric starts on the stable asymmetric
    orbit and ends at the symmetry-breaking point the symmetric branch reports."""
    fixed = {"omega": 1.1, "F": 0.3077}
    asym = continue_branch("eta", 0.12, 0.3, None, fixed, branch="asymmetric")
    assert asym.family == "asymmetric" and not asym.symmetric[0]
    # the published values have 3 decimals: half a unit of the last one (the solver's own
    # error, ~1e-12, is far below)
    assert asym.lambda_max[0] == pytest.approx(0.821, abs=5e-4)
    assert sorted(asym.orbits[0].flight_times) == pytest.approx([1.971, 3.741], abs=5e-4)
    assert asym.stopped.startswith("reached the symmetric branch")
    end = asym.events[-1]
    assert end["type"] == "symmetry-breaking" and end["connects"] == "symmetric"
    sym = continue_branch("eta", 0.12, 0.3, None, fixed, switch=True)
    sb = [e for e in sym.events if e["type"] == "symmetry-breaking"]
    assert len(sb) == 1 and abs(sb[0]["at"] - 0.1496) < 1e-4
    assert end["at"] == pytest.approx(sb[0]["at"], abs=1e-9)
    # the branch switched to at that point is the same asymmetric family
    sw = sym.switched[0]
    assert sw.family == "asymmetric" and sw.values[0] == pytest.approx(sb[0]["at"], abs=1e-4)
    k = int(np.argmin(np.abs(sw.values - 0.13)))
    ref = [o for o in find_1to1(sw.values[k], 1.1, 0.3077, simulation=False)
           if not o.symmetric and o.admissible]
    assert any(abs(o.lambda_max - sw.lambda_max[k]) < 1e-8 for o in ref)


def test_natural_method_is_kept():
    br = continue_branch("eta", 0.05, 0.03, 0.005, {"omega": 1.0, "F": 0.05},
                         method="natural")
    assert len(br) == 5 and br.values[-1] == pytest.approx(0.03)
    arc = continue_branch("eta", 0.05, 0.03, 0.005, {"omega": 1.0, "F": 0.05})
    assert arc.values[-1] == pytest.approx(0.03, abs=1e-12)
    assert arc.stopped == "left the parameter interval"
    # both methods see the same events (to the natural method's 1e-6)
    for e in br.events:
        assert min(abs(e["at"] - a["at"]) for a in arc.events if a["type"] == e["type"]) < 2e-6


@pytest.mark.parametrize("kwargs, name", [
    (dict(method="secant"), "method"), (dict(branch="both"), "branch"),
    (dict(switch="yes"), "switch"), (dict(max_inadmissible=0), "max_inadmissible")])
def test_new_options_are_checked(kwargs, name):
    from vines.core.params import ParameterError
    with pytest.raises(ParameterError) as err:
        continue_branch("eta", 0.05, 0.03, None, {"omega": 1.0, "F": 0.05}, **kwargs)
    assert err.value.name == name


def test_max_points_ends_the_branch():
    br = continue_branch("F", 0.3, 0.01, 0.05, {"eta": 0.2, "omega": 1.0}, max_points=7)
    assert len(br) == 7 and br.stopped == "max_points = 7 reached"


def test_map_solve_stores_the_asymmetric_branch():
    """The branch dataset holds the continued symmetric branch (row 0) and the asymmetric
    branch born at its symmetry-breaking point; at eta = 0.12 the latter is the stable
    asymmetric orbit the map solver finds there (issue 14: lambda_max 0.821)."""
    from vines.data.builders import ragged_rows
    from vines.pipeline import stages
    spec = {"param": "eta", "start": 0.1, "stop": 0.2, "step": 0.01,
            "fixed": {"omega": 1.1, "F": 0.3077}}
    ds = stages.map_solve(spec, model={"r": R_DEFAULT, "d": D_DEFAULT}, code="t", title="t")
    assert ds["family"].values.tolist() == ["symmetric", "asymmetric"]
    assert ds["symmetric"].values.tolist() == [1] * int(ds["row_size"][0]) + [0] * int(
        ds["row_size"][1])
    assert abs(float(ds["born_at"][1]) - 0.1496) < 5e-4 and np.isnan(float(ds["born_at"][0]))
    sb = ds["event_at"].values[ds["event_type"].values == "symmetry-breaking"]
    # the natural-mode event is the midpoint of a bracket narrower than BRANCH_EVENT_TOL =
    # 1e-12 (error <= 5e-13); the sign of det(A + I) it bisects is wrong only within
    # ~eps |A| / |d det/d eta| ~ 1e-15 of the root, and born_at (regula falsi along the
    # arclength on the same simple root) is as close: 1e-12 holds on any CPU
    assert abs(sb[0] - float(ds["born_at"][1])) < stages.BRANCH_EVENT_TOL
    eta, lam = ragged_rows(ds, "eta")[1], ragged_rows(ds, "lambda_max")[1]
    ref = [o for o in find_1to1(0.12, 1.1, 0.3077) if not o.symmetric and o.stable][0]
    assert abs(ref.lambda_max - 0.821) < 5e-4        # the 3 decimals of the issue's value
    assert abs(np.interp(0.12, *zip(*sorted(zip(eta, lam, strict=True)), strict=True)) - ref.lambda_max) < 5e-3


def test_map_solve_switches_beyond_a_non_admissible_start():
    """Fig 6 at F = 0.1: the symmetric orbit is not admissible at the branch's start (it
    becomes so at eta ~ 0.0185), yet the asymmetric branch born at the symmetry-breaking
    point eta ~ 0.0789 is stored: the switching run starts at the first admissible point.
    Oracle: the map solver's asymmetric orbit at eta = 0.077 (admissible, lambda_max 2.43)."""
    from vines.data.builders import ragged_rows
    from vines.pipeline import stages
    spec = {"param": "eta", "start": 0.01, "stop": 0.1, "step": 0.01,
            "fixed": {"omega": 1.0, "F": 0.1}}
    ds = stages.map_solve(spec, model={"r": R_DEFAULT, "d": D_DEFAULT}, code="t", title="t")
    assert not bool(ragged_rows(ds, "admissible")[0][0])
    assert ds["family"].values.tolist() == ["symmetric", "asymmetric"]
    sb = ds["event_at"].values[ds["event_type"].values == "symmetry-breaking"]
    assert abs(sb[0] - float(ds["born_at"][1])) < stages.BRANCH_EVENT_TOL
    eta, lam = ragged_rows(ds, "eta")[1], ragged_rows(ds, "lambda_max")[1]
    near = np.abs(eta - 0.077) < 2e-3
    ref = [o for o in find_1to1(0.077, 1.0, 0.1) if not o.symmetric and o.admissible]
    assert ref and near.any()
    order = np.argsort(eta[near])
    # linear interpolation between points <= 4e-5 apart in eta, on a stretch where
    # lambda_max falls from 2.4 to 1 over 2e-3 (measured error 7e-6): 1e-3 bounds it
    assert abs(np.interp(0.077, eta[near][order], lam[near][order]) - ref[0].lambda_max) < 1e-3


def test_switch_start_is_the_first_admissible_point():
    """The switching run keeps the spec's start (and the preferred orbit there) when the
    branch starts admissible or never is, else starts at its first admissible point."""
    from types import SimpleNamespace

    from vines.pipeline.stages import switch_start

    def branch(flags):
        return SimpleNamespace(admissible=np.array(flags), values=np.arange(len(flags)) + 0.5,
                               orbits=[f"orbit{i}" for i in range(len(flags))])
    assert switch_start(branch([True, False]), 0.25) == (0.25, None)
    assert switch_start(branch([False, False]), 0.25) == (0.25, None)
    assert switch_start(branch([]), 0.25) == (0.25, None)
    assert switch_start(branch([False, False, True, True]), 0.25) == (2.5, "orbit2")
