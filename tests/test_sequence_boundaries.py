"""Boundary curves of families other than 1:1 (``boundaries(..., walls=, periods=)``).

Every check is against quantities the curve tracer does not use: the eigenvalues of the
orbit solved afresh by ``solve_sequence`` at the curve's points, and brute-force scans of
those eigenvalues along a line across the curve. That every flip and symmetry-breaking
curve point of LR/1, LLRR/1 and LRLR/2 lies where an eigenvalue crosses -1 or +1 is checked
in ``test_orbit_families``.
"""
import numpy as np
import pytest

from vines.core.params import ModelParams, ParameterError
from vines.orbits.continuation.arclength import NEWTON_TOL
from vines.orbits.curves.boundaries import boundaries
from vines.orbits.curves.sequence import crossings, family_from_name
from vines.orbits.family.map_systems import make_system, orbit_of
from vines.orbits.family.sequence import orbit_through, pitchfork_seeds, solve_sequence

#: the 2:2 orbits of Fig 9 (eta 0.2, omega 0.8, F 0.4): a fold of the symmetric family
LLRR = dict(F=0.4, box=((0.1, 0.3), (0.7, 0.9)), walls="LLRR", periods=1)
#: period-2 orbits born at the 1:1 flip (F 0.2): their own flip (period 4)
LRLR2 = dict(F=0.2, box=((0.1, 0.2), (0.72, 0.8)), walls="LRLR", periods=2)


def _curves(case):
    return boundaries(case["F"], *case["box"], walls=case["walls"], periods=case["periods"],
                      n_scan=2).curves


@pytest.fixture(scope="module")
def llrr():
    return _curves(LLRR)


@pytest.fixture(scope="module")
def lrlr2():
    return _curves(LRLR2)


def _system(curve, case):
    fam = family_from_name(curve.family, case["walls"])
    base = ModelParams(eta=0.1, omega=1.0, F=case["F"])
    return make_system(base, fam, curve.type, curve.graze, ("eta", "omega"))


def _eigen_tolerance(system, z, A, target):
    """How far the eigenvalue of A (the half map's for a symmetric family) may lie from
    ``target`` at a point the tracer accepted: the condition det(A - target I) is zero to
    |grad| x the corrector's step tolerance; an eigenvalue moves by that over the product
    of the other eigenvalues' distances to ``target`` (x 10 for the orbit's own Newton
    stop and rounding)."""
    _, Gz = system(z)
    g_err = np.linalg.norm(Gz[-1]) * NEWTON_TOL * (1.0 + np.abs(z).max())
    mu = np.linalg.eigvals(A)
    i = int(np.argmin(np.abs(mu - target)))
    others = np.prod(np.abs(np.delete(mu, i) - target))
    return abs(mu[i] - target), 10.0 * g_err / others


def _half_map(o, symmetric):
    """A of ``sequence_curves``: the monodromy, or the mirrored half map."""
    n = len(o.walls) // (2 if symmetric else 1)
    A = o.jacobians[0]
    for J in o.jacobians[1:n]:
        A = J @ A
    return np.diag([-1.0, -1.0, -1.0, 1.0]) @ A if symmetric else A


def test_fold_curve_points_have_eigenvalue_one(llrr):
    folds = [c for c in llrr if c.type == "fold"]
    assert folds and all(c.family == "LLRR/1-sym" for c in folds)
    for c in folds:
        system = _system(c, LLRR)
        for z in c.z:
            o = orbit_of(system, z)
            assert o is not None and o.admissible and o.symmetric
            err, tol = _eigen_tolerance(system, z, _half_map(o, True), 1.0)
            assert err <= tol, (z[-2:], err, tol)
            # the monodromy matrix (the half map squared) has the eigenvalue +1 too
            assert np.min(np.abs(o.eigenvalues - 1.0)) <= 3.0 * tol


def test_curve_points_are_classified_as_they_stand(llrr):
    """``orbit_of`` classifies the curve point itself (``orbit_through``, no second Newton:
    at a fold the residual's Jacobian A - I is singular and a fresh solve from the point
    drifts by about the square root of its tolerance, enough to flip a marginal
    admissibility): its start is the point's, its residual the point's own; a start 1e-7
    off the orbit stays off (a Newton solve would return to the orbit)."""
    (fold,) = [c for c in llrr if c.type == "fold"]
    z = fold.z[len(fold.z) // 2]
    o = orbit_of(_system(fold, LLRR), z)
    assert np.array_equal(o.states[0, :3], z[:3]) and o.residual < 1e-9
    p = ModelParams(eta=z[4], omega=z[5], F=LLRR["F"])
    x_off = z[:4] + np.array([1e-7, 0.0, 0.0, 0.0])
    off = orbit_through(p, "LLRR", 1, x_off, o.flight_times)
    assert np.array_equal(off.states[0, :3], x_off[:3]) and off.residual > 1e-9


def test_fold_is_where_two_orbits_meet(llrr):
    """Brute force across the fold at fixed eta: two orbits on one side whose eigenvalues
    approach +1 like the square root of the distance, none on the other."""
    (fold,) = [c for c in llrr if c.type == "fold"]
    i = len(fold.points) // 2
    eta = float(fold.points[i:i + 2, 0].mean())         # between two curve points
    base = ModelParams(eta=eta, omega=0.8, F=LLRR["F"])
    (pt,) = crossings(fold, "LLRR", base, ("eta", eta))
    p0 = ModelParams(eta=eta, omega=pt[1], F=LLRR["F"])
    z = fold.z[np.argmin(np.hypot(*(fold.points - pt).T))]
    o0 = solve_sequence(p0, "LLRR", 1, z[:4], _system(fold, LLRR).flights(z))
    sides = {}
    for sign in (1.0, -1.0):
        gaps = []
        for k in (1, 4):
            dw = sign * k * 1e-8
            p = ModelParams(eta=eta, omega=pt[1] + dw, F=LLRR["F"])
            found = [solve_sequence(p, "LLRR", 1, x0, fl) for x0, fl in pitchfork_seeds(o0)]
            near = [o for o in found if o is not None
                    and np.linalg.norm(o.states[0] - o0.states[0]) < 0.1]
            distinct = {round(float(o.states[0, 0]), 8): o for o in near}
            gaps.append([abs(np.min(np.abs(o.eigenvalues - 1.0)))
                         for o in distinct.values()])
        sides[sign] = gaps
    exist = [s for s, g in sides.items() if all(len(x) == 2 for x in g)]
    assert len(exist) == 1, sides
    assert all(len(x) == 0 for x in sides[-exist[0]])
    # |lambda - 1| ~ c sqrt(delta): four times the distance, twice the gap (to 15 %)
    near, far = (np.mean(x) for x in sides[exist[0]])
    assert 1.7 < far / near < 2.3


def test_flip_curve_agrees_with_a_brute_force_eigenvalue_scan(lrlr2):
    """Along omega = const across the flip curve: the real eigenvalue through -1 of the
    orbits solved on a grid of eta, linearly interpolated, crosses where the curve does,
    to the interpolation error h^2 max|lambda''| / (8 |lambda'|) of the scan."""
    (flip,) = [c for c in lrlr2 if c.type == "flip"]
    i = len(flip.points) // 2
    omega = float(flip.points[i:i + 2, 1].mean())       # between two curve points
    base = ModelParams(eta=0.15, omega=omega, F=LRLR2["F"])
    (pt,) = crossings(flip, "LRLR", base, ("omega", omega))
    z = flip.z[np.argmin(np.hypot(*(flip.points - pt).T))]
    x0, fl = z[:4], _system(flip, LRLR2).flights(z)
    h = 5e-4
    etas = pt[0] + h * (np.arange(-6, 7) + 0.37)      # the crossing between grid points
    lam = np.empty(etas.size)
    for order in (range(6, etas.size), range(5, -1, -1)):    # outwards from the curve
        x0, fl = z[:4], _system(flip, LRLR2).flights(z)
        for j in order:
            p = ModelParams(eta=etas[j], omega=omega, F=LRLR2["F"])
            o = solve_sequence(p, "LRLR", 2, x0, fl)
            assert o is not None, etas[j]
            x0, fl = o.states[0], o.flight_times
            real = o.eigenvalues[np.abs(o.eigenvalues.imag) < 1e-12].real
            lam[j] = real[np.argmin(np.abs(real + 1.0))]
    i = int(np.nonzero(np.sign(lam[:-1] + 1.0) != np.sign(lam[1:] + 1.0))[0][0])
    eta_scan = etas[i] + (-1.0 - lam[i]) / (lam[i + 1] - lam[i]) * h
    d1 = np.abs(np.diff(lam)).min() / h
    d2 = np.abs(np.diff(lam, 2)).max() / h ** 2
    tol = h * h * d2 / (8.0 * d1) + 1e-9
    assert abs(eta_scan - pt[0]) <= tol, (eta_scan, pt[0], tol)


def test_default_family_is_1to1_and_bad_families_are_refused():
    with pytest.raises(ParameterError, match="walls"):
        boundaries(0.2, (0.1, 0.2), (0.8, 0.9), walls="LXR")
    with pytest.raises(ParameterError, match="periods"):
        boundaries(0.2, (0.1, 0.2), (0.8, 0.9), walls="LR", periods=0)
    with pytest.raises(ParameterError, match="class_map"):
        boundaries(0.2, (0.1, 0.2), (0.8, 0.9), walls="LLRR",
                   class_map=([0.1, 0.2], [0.8, 0.9], np.zeros((2, 2))))


def test_continuation_switches_onto_the_asymmetric_pair_at_symmetry_breaking(llrr):
    """LLRR/1-sym at eta 0.2, F 0.4: the symmetry-breaking point the continuation locates
    (det(B - I) along the branch) is where the symmetry-breaking curve (det(H + I) with
    eta and omega free) crosses eta = 0.2; the branch switched onto there is asymmetric,
    comes with its mirror image, and leaves the symmetric orbit like a square root."""
    from vines.orbits.continuation.sequence import ContinueSettings, continue_sequence
    from vines.orbits.family.sequence import find_sequence
    (curve,) = [c for c in llrr if c.type == "symmetry-breaking"]
    p = ModelParams(eta=0.2, omega=0.8, F=0.4)
    (pt,) = crossings(curve, "LLRR", p, ("eta", 0.2))
    # start 0.01 above the point, on the symmetric orbit through it
    z = curve.z[np.argmin(np.hypot(*(curve.points - pt).T))]
    p = ModelParams(eta=0.2, omega=pt[1] + 0.01, F=0.4)
    sym = solve_sequence(p, "LLRR", 1, z[:4], _system(curve, LLRR).flights(z))
    assert sym is not None and sym.symmetric and sym.admissible
    br = continue_sequence(p, "LLRR", 1, "omega", pt[1] - 0.02, orbit=sym,
                           settings=ContinueSettings(step=0.002, switch=True))
    (sb,) = [e for e in br.events if e["type"] == "symmetry-breaking"]
    assert abs(sb["at"] - pt[1]) < 1e-8
    mu = np.linalg.eigvals(_half_map(sb["_orbit"], True))
    assert np.min(np.abs(mu + 1.0)) < 1e-6
    (sub,) = br.switched
    assert sub.born_at["type"] == "symmetry-breaking" and sub.walls == "LLRR"
    assert len(sub.points) > 5 and not any(o.symmetric for o in sub.points)
    pair = find_sequence(sub.points[3].params, "LLRR", 1, simulation=False,
                         seeds=[sub.points[3]])
    twins = [o for o in pair if not o.symmetric
             and abs(o.lambda_max - sub.points[3].lambda_max) < 1e-9]
    assert len(twins) == 2
    # distance to the symmetric orbit ~ sqrt(|omega - omega_sb|)
    dist = []
    for o in sub.points[1:40]:
        s = solve_sequence(o.params, "LLRR", 1, sb["_orbit"].states[0],
                           sb["_orbit"].flight_times)
        assert s is not None and s.symmetric
        dist.append((abs(o.params.omega - sb["at"]),
                     np.linalg.norm(o.states[0, :3] - s.states[0, :3])))
    (d1, a1), (d2, a2) = dist[0], dist[-1]
    assert d2 > 4.0 * d1
    assert 0.6 < (a2 / a1) / np.sqrt(d2 / d1) < 1.4
