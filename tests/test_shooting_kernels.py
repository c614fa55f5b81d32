"""Compiled derivatives of the shooting systems (``shooting_kernels``, ``tape``) against
the pure-Python Taylor jets (``jets``) and finite differences."""
import math

import numpy as np
import pytest
from test_boundaries import CASES, MODEL, F, augmented_point

from vines.orbits.curves import boundaries as bnd
from vines.orbits.curves import one_to_one
from vines.orbits.curves.one_to_one import class_edges
from vines.orbits.curves.tracer import in_box
from vines.orbits.family.periodic import find_1to1
from vines.orbits.jets import kernels as sk
from vines.orbits.jets import shooting as sh
from vines.orbits.jets import taylor as jets
from vines.orbits.jets.tape import record


def _formula(x, y, c):
    """Every operation a tape records: + - * / (both orders), negation, sin cos exp sqrt."""
    a = jets.sin(x * y) / jets.exp(x) + jets.sqrt(x) * jets.cos(y) - 2.0 / y
    b = (1.5 - x) * (y + 0.25) - (-x) / 3.0 + c * x
    return [a, b, 0.5 + 2.0 * y - a * b]


def _jet_rows(vals, size):
    """The tape's outputs for inputs (x, y, c) = vals, as jets of length size."""
    tp = record(_formula, 3)
    return sk.run_tape(tp, np.asarray(vals, float), size)


@pytest.mark.parametrize("vals", [(0.7, -1.3, 0.4), (2.1, 0.6, -3.0)])
def test_tape_matches_python_jets_to_second_order(vals):
    out = _jet_rows(vals, sk.N2)
    ref = _formula(*jets.variables(vals, order=2))
    for row, f in zip(out, ref, strict=False):
        assert row[0] == pytest.approx(f.v, rel=1e-14, abs=1e-14)
        np.testing.assert_allclose(row[1:4], f.g, rtol=1e-13, atol=1e-13)
        H = row[sk.N1:].reshape(sk.NL, sk.NL)
        np.testing.assert_allclose(H[:3, :3], f.H, rtol=1e-12, atol=1e-12)
        # the unused local variables carry no derivative
        assert not row[4:sk.N1].any() and not H[3:].any() and not H[:, 3:].any()


def test_tape_inputs_beyond_the_local_variables_are_constants():
    """Input NL (the flight's from_wall) has no derivative slot."""
    tp = record(lambda *v: [v[0] * v[sk.NL] + v[sk.NL]], sk.NL + 1)
    row = sk.run_tape(tp, np.arange(1.0, sk.NL + 2.0), sk.N2)[0]
    assert row[0] == 1.0 * (sk.NL + 1.0) + (sk.NL + 1.0)
    assert row[1] == sk.NL + 1.0 and not row[2:].any()


def test_tape_gradient_matches_finite_differences():
    vals = np.array([0.7, -1.3, 0.4])
    g = _jet_rows(vals, sk.N1)[:, 1:4]
    h = 1e-6
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        fd = (_jet_rows(vals + e, sk.N1)[:, 0] - _jet_rows(vals - e, sk.N1)[:, 0]) / (2 * h)
        np.testing.assert_allclose(g[:, k], fd, rtol=1e-7, atol=1e-8)


@pytest.mark.parametrize("family, kind, graze", CASES)
@pytest.mark.parametrize("free", [("eta", "omega"), ("F",)])
def test_compiled_augmented_systems_match_python_jets(family, kind, graze, free):
    system, z, _ = augmented_point(family, kind, graze, free)
    G, Gz = system(z)
    G_ref, Gz_ref = system.evaluate_jets(z)
    scale = max(1.0, np.abs(Gz_ref).max())
    np.testing.assert_allclose(G, G_ref, rtol=0, atol=1e-13 * max(1.0, np.abs(G_ref).max()))
    np.testing.assert_allclose(Gz, Gz_ref, rtol=0, atol=1e-13 * scale)


@pytest.mark.parametrize("family", sh.ORBIT_KINDS)
def test_compiled_residual_jacobian_matches_python_jets(family):
    o = [o for o in find_1to1(0.3, 0.9, 0.2, simulation=False)
         if o.symmetric == (family == "symmetric")][0]
    u = list(o.x_L) + ([] if o.symmetric else [o.flight_times[0]])
    par = {"eta": 0.3, "omega": 0.9, "F": 0.2}
    for free in [("eta",), ("omega", "F"), ("F", "eta", "omega")]:
        E, Ez = sh.residual_jacobian(MODEL, family, u, par, free)
        E_ref, Ez_ref = sh.residual_jacobian_jets(MODEL, family, u, par, free)
        assert Ez.shape == Ez_ref.shape == (len(u), len(u) + len(free))
        np.testing.assert_allclose(E, E_ref, rtol=0, atol=1e-14)
        np.testing.assert_allclose(Ez, Ez_ref, rtol=0, atol=1e-13 * np.abs(Ez_ref).max())


@pytest.mark.parametrize("singular", [False, True])
def test_det_gradient_matches_python_jets(singular):
    rng = np.random.default_rng(3)
    M0 = rng.normal(size=(4, 4))
    if singular:
        M0[3] = M0[0] - 2.0 * M0[1]
    v = jets.variables(M0.ravel().tolist())
    ref = jets.det([[v[4 * i + j] for j in range(4)] for i in range(4)])
    dM = np.eye(16).reshape(4, 4, 16)
    d, grad = sk.det_gradient(M0, dM)
    assert d == pytest.approx(ref.v, abs=1e-12)
    np.testing.assert_allclose(grad, ref.g, rtol=1e-12, atol=1e-12)
    # the gradient of det is the adjugate (transposed): finite and non-zero at rank 3
    adj = np.array([[(-1) ** (i + j) * np.linalg.det(np.delete(np.delete(M0, i, 0), j, 1))
                     for j in range(4)] for i in range(4)])
    np.testing.assert_allclose(grad.reshape(4, 4), adj, rtol=1e-9, atol=1e-9)
    assert math.isfinite(d) and np.abs(grad).max() > 0.1


def test_class_changes_outside_the_box_seed_nothing(monkeypatch):
    """An edge of the class map with both cells outside the box is not continued (its
    events cannot lie in the box); an edge with a cell in the box is."""
    calls = []
    monkeypatch.setattr(one_to_one, "_edge_seeds", lambda model, F_, edge: calls.append(edge) or [])
    box = ((0.1, 0.4), (0.9, 1.2))
    eta, omega = np.array([0.8, 0.9]), np.array([1.0, 1.1])        # eta outside the box
    cls = np.array([[1, 3], [3, 1]])
    bnd.boundaries(F, *box, n_scan=1, class_map=(eta, omega, cls))
    assert calls == []
    eta_in = np.array([0.35, 0.45])                                 # one cell inside
    res = bnd.boundaries(F, *box, n_scan=1, class_map=(eta_in, omega, cls))
    inside = [e for e in class_edges(eta_in, omega, cls)
              if in_box(e[0], box) or in_box(e[1], box)]
    explained = [e for e in inside if _near(res.curves, e)]
    assert len(calls) == len(inside) - len(explained) and len(inside) == 3


def _near(curves, edge) -> bool:
    if not curves:
        return False
    pts = np.concatenate([c.points for c in curves])
    mid = 0.5 * (np.asarray(edge[0]) + np.asarray(edge[1]))
    return float(np.min(np.hypot(*((pts - mid) / edge[2]).T))) <= 1.5
