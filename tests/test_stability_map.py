"""Compiled stability map: same bits as the Python orbit solvers (given the same BLAS/LAPACK
routines), any thread count; the compiled pieces (seeds, residual of the asymmetric scan,
dgeev) against their references."""
import math

import numpy as np
import pytest
import scipy.linalg
from scipy.optimize import linear_sum_assignment

import vines
from vines.core.exact import oscillators
from vines.core.flow import I_NRES, I_W, flow, flow_zv, make_osc, s_factors
from vines.core.params import ModelParams
from vines.core.walls import WALL_L, WALL_R
from vines.orbits.atlas.stability_map import stability_map, stability_map_python
from vines.orbits.family import periodic as P
from vines.orbits.maps.affine import _chain, _lr_chain, affine_chain, chain_workspace
from vines.orbits.maps.impact import map_jacobian, model_array, pack_model
from vines.orbits.maps.lapack import eigvals, lambda_max_4, monodromy_eigvals

KEYS = ("lambda_max", "cls", "dw_L", "symmetric")
ETA = np.linspace(0.02, 0.9, 12)
OMEGA = np.linspace(0.6, 1.4, 6)


def _equal(a, b):
    return all(np.array_equal(a[k], b[k], equal_nan=True) for k in KEYS)


@pytest.fixture
def same_dgeev(monkeypatch):
    """The Python orbit solvers' monodromy eigenvalues (numpy's product and ``eigvals``) as
    the compiled kernels compute them (numba's np.dot, scipy's dgeev), so that a reference
    and a kernel run the same routines: numpy and scipy may ship different BLAS/LAPACK
    builds, whose results differ in the last bits (``test_compiled_dgeev_is_numpys``
    bounds by how much)."""
    monkeypatch.setattr(P, "monodromy_eigenvalues", monodromy_eigvals)


@pytest.mark.parametrize("F", [0.3077, 0.4])
def test_compiled_map_equals_python_reference(F, same_dgeev):
    fast = stability_map(ETA, OMEGA, F, n_threads=1)
    ref = stability_map_python(ETA, OMEGA, F)
    assert _equal(fast, ref)
    # the grid exercises every class
    assert set(np.unique(fast["cls"])) == {0, 1, 2, 3}


def test_threads_give_identical_arrays():
    m1 = stability_map(ETA, OMEGA, 0.3077, n_threads=1)
    for nt in (2, 3):
        assert _equal(m1, stability_map(ETA, OMEGA, 0.3077, n_threads=nt))
    assert m1["F"] == 0.3077 and np.array_equal(m1["eta"], ETA)


def test_progress_unforced_and_conditioning():
    calls = []
    m = stability_map(ETA[:3], OMEGA[:4], 0.0, n_threads=2,
                      progress=lambda done, total: calls.append((done, total)))
    assert calls[-1] == (4, 4) and len(calls) == 4
    assert np.all(m["cls"] == 0) and np.all(np.isnan(m["lambda_max"]))
    # weakly damped, at the stuck body's natural frequency: refused like oscillators()
    eta = 0.44
    w = 1.0 / math.sqrt(1.0 + eta)
    with pytest.raises(vines.ParameterError):
        oscillators(ModelParams(eta, w, 0.3, d=1e-6))
    with pytest.raises(vines.ParameterError):
        stability_map([0.1, eta], [0.9, w], 0.3, d=1e-6)


def _points(n, seed=0):
    rng = np.random.default_rng(seed)
    return [(rng.uniform(0.01, 1.0), rng.uniform(0.5, 1.5), rng.uniform(0.1, 0.5))
            for _ in range(n)]


def _symmetric_seeds_numpy(mdl):
    """The closed-form symmetric 1:1 seeds by numpy's svd and lstsq (the reference of the
    compiled ``affine.closed_form_kernel``), each with a bound on how far another LAPACK
    build may move it (first order): the min-norm solution p and the null vector q of the
    4 x 5 system A u = -b within kappa = sv_max / sv_min times 2 n^2 eps (two solvers),
    the root lam of |p + lam q|_(3,4) = 1 within the change of that quadratic's
    coefficients over its slope sqrt(disc), u = p + lam q within the sum."""
    T = 2.0 * math.pi / mdl[I_W]
    A, b = np.empty((4, 5)), np.empty(4)
    affine_chain(mdl, (P.LR, np.array([0.5 * T]), (-1, False)), A, b, chain_workspace(1))
    _, sv, Vt = np.linalg.svd(A)
    if sv[-1] <= 1e-14 * sv[0]:
        return []
    q = Vt[-1]
    p = np.linalg.lstsq(A, -b, rcond=None)[0]
    a2 = q[3] * q[3] + q[4] * q[4]
    a1 = 2.0 * (p[3] * q[3] + p[4] * q[4])
    a0 = p[3] * p[3] + p[4] * p[4] - 1.0
    disc = a1 * a1 - 4.0 * a2 * a0
    if a2 == 0.0 or disc < 0.0:
        return []
    rel = 2.0 * 25 * np.finfo(float).eps * sv[0] / sv[-1]
    dp, dq = rel * max(1.0, np.abs(p).max()), rel
    p34, q34 = np.hypot(p[3], p[4]), np.hypot(q[3], q[4])
    out = []
    for lam in ((-a1 - math.sqrt(disc)) / (2.0 * a2), (-a1 + math.sqrt(disc)) / (2.0 * a2)):
        u = p + lam * q
        da = (2 * q34 * dq * lam * lam + 2 * (p34 * dq + q34 * dp) * abs(lam)
              + 2 * p34 * dp)
        du = dp + abs(lam) * dq + da / math.sqrt(disc)
        out.append(((u[0], u[1], u[2], math.atan2(u[3], u[4])), du))
    return out


def _seeds_agree(got, ref):
    """The compiled seeds are the reference's to within each one's bound (the phase too,
    modulo 2 pi: (u3, u4) is a unit vector, its angle moves by at most its change)."""
    if len(got) != len(ref):
        return False
    for g, (r, du) in zip(got, ref, strict=True):
        d = np.array(g) - np.array(r)
        d[3] = (d[3] + math.pi) % (2.0 * math.pi) - math.pi
        if not np.all(np.abs(d) <= du):
            return False
    return True


@pytest.mark.parametrize("eta, w, F", _points(25))
def test_seed_kernel_rows_equal_seed_orbits(eta, w, F, same_dgeev):
    p = ModelParams(eta, w, F)
    mdl = model_array(p)
    orbits = P.seed_orbits(p, mdl, simulation=False)
    rows = np.zeros((P.N_SEED_MAX, P.N_ROW))
    n = P.seed_kernel(mdl, rows, P.orbit_workspace())
    assert n == len(orbits)
    for row, o in zip(rows[:n], orbits, strict=False):
        assert np.array_equal(row[P.ROW_X:P.ROW_X + 4], o.x_L)
        assert list(row[P.ROW_FL:P.ROW_FL + 2]) == o.flight_times
        assert bool(row[P.ROW_ADM]) == o.admissible and bool(row[P.ROW_SYM]) == o.symmetric
        assert row[P.ROW_DWL] == o.dw_L
        if o.admissible:
            assert row[P.ROW_LAM] == o.lambda_max
    assert _seeds_agree(P.symmetric_seeds(mdl), _symmetric_seeds_numpy(mdl))


@pytest.mark.parametrize("d, w", [(0.011998, 0.9), (0.0, 1.0), (0.0, 0.8), (0.0, 0.9999),
                                  (2.5, 1.2)])
def test_flight_chains_are_affine_in_the_start(d, w):
    """E(u) of the chains (walls restarted or carried) is A u + b to round-off, A and b from
    ``affine_chain`` (damped, resonant, undamped, near-resonant, overdamped oscillators)."""
    rng = np.random.default_rng(1)
    T = 2.0 * math.pi / w
    A, b, E, ws = np.empty((5, 5)), np.empty(5), np.empty(5), chain_workspace(2)
    for _ in range(20):
        mdl = pack_model(make_osc(1.0, d, w, 0.3), rng.uniform(0.01, 1.0), 0.65, 0.0)
        s1 = rng.uniform(0.0, T)
        s = np.array([s1, T - s1])
        for carry in (False, True):
            chain = (P.LR, s, (1, carry))
            affine_chain(mdl, chain, A, b, ws)
            u = rng.normal(size=5)
            f1, f2 = s_factors(mdl, s[0]), s_factors(mdl, s[1])
            if mdl[I_NRES] > 0.5:
                f1 = f2 = None
            _chain(mdl, u, (2, P.LR[0], P.LR[1], s[0], s[1], 1, carry), f1, f2, E)
            scale = np.abs(A).sum(axis=1) * np.abs(u).max() + np.abs(b) + 1.0
            assert np.all(np.abs(A @ u + b - E) <= 1e-9 * scale)
            if carry and f1 is not None:     # the 1:1 scan's written-out chain: same bits
                E1 = np.empty(5)
                _lr_chain(mdl, u, s[0], s[1], f1, f2, E1)
                assert np.array_equal(E1, E)


@pytest.mark.parametrize("d, w", [(0.011998, 0.9), (0.0, 1.0), (0.0, 0.8), (2.5, 1.2)])
def test_flow_zv_is_flow_bitwise(d, w):
    """``flow_zv`` (z, z' with shared s-factors, written out) equals ``flow`` bit for bit
    (damped, resonant, undamped, overdamped oscillators)."""
    osc = make_osc(1.0, d, w, 0.3)
    rng = np.random.default_rng(3)
    for _ in range(50):
        x0, v0, th, s = rng.normal(), rng.normal(), rng.uniform(0, 6.3), rng.uniform(0, 20.0)
        start = (x0, v0, math.sin(th), math.cos(th))
        z, v, _, _, _ = flow(osc, *start, s)
        assert flow_zv(osc, start, s, s_factors(osc, s)) == (z, v)


def _eigen_bounds(M, E=None):
    """Eigenvalues of M and, for each, how far two backward-stable solvers (dgeev of two
    LAPACK builds) may put it apart, to first order: kappa (2 n^2 eps ||B||_F + ||E_B||_F),
    B the balanced matrix dgeev reduces (T^-1 M T, T a scaled permutation), n^2 eps ||B||
    the normwise backward error of its Householder reductions (once per solver), kappa =
    1 / |y^H x| for unit left and right eigenvectors of B (the eigenvalue's condition
    number), E_B = T^-1 E T for an elementwise bound E on how far the two inputs M differ."""
    B, T = scipy.linalg.matrix_balance(M)
    lam, vl, vr = scipy.linalg.eig(B, left=True, right=True)
    kappa = 1.0 / np.abs(np.sum(vl.conj() * vr, axis=0))
    n = M.shape[0]
    err = 2.0 * n * n * np.finfo(float).eps * np.linalg.norm(B)
    if E is not None:
        err += np.linalg.norm(np.linalg.solve(T, E) @ T)
    return lam, err * kappa


def _paired(lam, z):
    """z reordered so that z[i] is the one closest to lam[i] (a one-to-one assignment)."""
    return z[linear_sum_assignment(np.abs(lam[:, None] - z[None, :]))[1]]


def _jacobians(n_points=12):
    """(J_P1, J_P2) of the admissible seed orbits at a few random parameter points."""
    out = []
    for eta, w, F in _points(n_points, seed=5):
        p = ModelParams(eta, w, F)
        for o in P.seed_orbits(p, simulation=False):
            if o.admissible:
                out.append((map_jacobian(p, o.x_L, WALL_L, WALL_R, o.x_L[3] + o.flight_times[0]),
                            map_jacobian(p, o.x_R, WALL_R, WALL_L, o.x_R[3] + o.flight_times[1])))
    return out


def test_compiled_dgeev_is_numpys():
    """The compiled dgeev's eigenvalues and lambda_max are numpy's to within the bound of
    ``_eigen_bounds`` (bit for bit where numpy and scipy share a LAPACK build), on random
    matrices and on the monodromy matrices of 1:1 orbits."""
    rng = np.random.default_rng(2)
    a, wr, wi, work = np.empty(16), np.empty(4), np.empty(4), np.empty(64)
    mats = [rng.normal(size=(4, 4)) * rng.uniform(0.01, 10.0) for _ in range(500)]
    orbits = [J2 @ J1 for J1, J2 in _jacobians()]
    assert len(orbits) > 10
    for M in mats + orbits:
        lam, bound = _eigen_bounds(M)
        ev, got = np.linalg.eigvals(M), eigvals(M)
        assert np.all(np.abs(_paired(lam, got) - _paired(lam, ev)) <= bound)
        # max |z| moves by at most the largest move of an eigenvalue
        assert abs(lambda_max_4(M, a, wr, wi, work) - np.abs(ev).max()) <= bound.max()
        assert np.hypot(got.real, got.imag).max() == lambda_max_4(M, a, wr, wi, work)
    M = mats[-1].copy()
    M[1, 2] = math.inf
    assert math.isnan(lambda_max_4(M, a, wr, wi, work))


def test_compiled_monodromy_eigenvalues_are_numpys():
    """The monodromy eigenvalues of 1:1 orbits as the kernels compute them (numba's np.dot,
    scipy's dgeev) and as the Python solvers do (numpy): within ``_eigen_bounds`` with the
    two products' difference bounded by 2 n eps |J2| |J1| (the product's error bound)."""
    eps = np.finfo(float).eps
    for J1, J2 in _jacobians():
        M = J2 @ J1
        lam, bound = _eigen_bounds(M, 2 * 4 * eps * (np.abs(J2) @ np.abs(J1)))
        got, ev = monodromy_eigvals(J1, J2), P.monodromy_eigenvalues(J1, J2)
        assert np.all(np.abs(_paired(lam, got) - _paired(lam, ev)) <= bound)
