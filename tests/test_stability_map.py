"""Compiled stability map: same bits as the Python orbit solvers, any thread count; the
compiled pieces (seeds, residual of the asymmetric scan, dgeev) against their references."""
import math

import numpy as np
import pytest

import vines
from vines.core.exact import oscillators
from vines.core.flow import I_NRES, flow, make_osc
from vines.core.params import ModelParams
from vines.orbits import periodic as P
from vines.orbits._lapack import eigvals, lambda_max_4
from vines.orbits.stability_map import stability_map, stability_map_python

KEYS = ("lambda_max", "cls", "dw_L", "symmetric")
ETA = np.linspace(0.02, 0.9, 12)
OMEGA = np.linspace(0.6, 1.4, 6)


def _equal(a, b):
    return all(np.array_equal(a[k], b[k], equal_nan=True) for k in KEYS)


@pytest.mark.parametrize("F", [0.3077, 0.4])
def test_compiled_map_equals_python_reference(F):
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


@pytest.mark.parametrize("eta, w, F", _points(25))
def test_seed_kernel_rows_equal_seed_orbits(eta, w, F):
    p = ModelParams(eta, w, F)
    osc = oscillators(p)[0]
    orbits = P.seed_orbits(p, osc, simulation=False)
    rows = np.zeros((P.N_SEED_MAX, P.N_ROW))
    n = P.seed_kernel(osc, p.eta, p.r, p.omega, p.phi, p.F, rows, P.orbit_workspace())
    assert n == len(orbits)
    for row, o in zip(rows[:n], orbits, strict=False):
        assert np.array_equal(row[P.ROW_X:P.ROW_X + 4], o.x_L)
        assert list(row[P.ROW_FL:P.ROW_FL + 2]) == o.flight_times
        assert bool(row[P.ROW_ADM]) == o.admissible and bool(row[P.ROW_SYM]) == o.symmetric
        assert row[P.ROW_DWL] == o.dw_L
        if o.admissible:
            assert row[P.ROW_LAM] == o.lambda_max
    buf = np.empty((2, 4))
    ns = P.symmetric_seeds_kernel(osc, p.eta, p.r, p.omega, buf)
    assert [tuple(b) for b in buf[:ns]] == P.symmetric_seeds(osc, p.eta, p.r, p.omega)


@pytest.mark.parametrize("d, w", [(0.011998, 0.9), (0.0, 1.0), (0.0, 0.8), (0.0, 0.9999),
                                  (2.5, 1.2)])
def test_cached_flow_and_scan_residual_are_bitwise_the_originals(d, w):
    osc = make_osc(1.0, d, w, 0.3)   # damped, resonant, undamped, near-resonant, overdamped
    rng = np.random.default_rng(1)
    T = 2.0 * math.pi / w
    ws = (np.empty((5, 5)), np.empty(5), np.empty(5), np.empty((5, 5)), np.empty(5))
    for _ in range(50):
        x0, v0, th, s = rng.normal(), rng.normal(), rng.uniform(0, 6.3), rng.uniform(0, T)
        z, v, _, _, _ = flow(osc, x0, v0, math.sin(th), math.cos(th), s)
        assert osc[I_NRES] > 0.5 or P._flow_zv(osc, x0, v0, math.sin(th), math.cos(th), s,
                          P._s_factors(osc, s)) == (z, v)
        eta = rng.uniform(0.01, 1.0)
        A, b, u = np.empty((5, 5)), np.empty(5), np.empty(5)
        P._affine(osc, eta, 0.65, w, s, T - s, False, A, b)      # the original formulation
        ok = P._solve(A, -b, u)
        h_ref = u[3] * u[3] + u[4] * u[4] - 1.0 if ok else math.nan
        h = P._circle_residual(osc, eta, 0.65, w, s, T, np.empty(5), ws)
        assert h == h_ref or (math.isnan(h) and math.isnan(h_ref))


def test_compiled_dgeev_is_numpys():
    rng = np.random.default_rng(2)
    a, wr, wi, work = np.empty(16), np.empty(4), np.empty(4), np.empty(64)
    for _ in range(500):
        M = rng.normal(size=(4, 4)) * rng.uniform(0.01, 10.0)
        ev = np.linalg.eigvals(M)
        assert np.array_equal(eigvals(M), ev)
        assert lambda_max_4(M, a, wr, wi, work) == np.hypot(ev.real, ev.imag).max()
    M[1, 2] = math.inf
    assert math.isnan(lambda_max_4(M, a, wr, wi, work))
