"""Exact derivatives of the map residual of any family (``jets.chain``) against three
references: the pure-Python Taylor jets of the same flights with the flight times
eliminated by hand (the implicit function theorem on the shooting form), central
differences of the impact maps (``map_systems.orbit_residual``), and the 1:1 kernels
(``kernels.codim1``) where they compute the same numbers; then the systems that use them
(``derivatives="jets"`` against ``"differences"``).

Tolerances. Jets against jets: both exact, they differ by rounding only (1e-10 relative to
the largest entry). Jets against central differences with step h = 1e-6 (1 + |z_i|): the
truncation error is h^2 |f'''| / 6 ~ 1e-12 (1 + |z|)^2 |f'''|, the rounding error
eps |f| / h ~ 1e-10 |f| amplified by the flight time's sensitivity 1 / |w'| (w' >= 0.1 at
these orbits); 1e-6 relative to the largest entry leaves a margin of 100 over both, while a
wrong sign or a missing chain-rule term changes an entry by O(1).
"""
import numpy as np
import pytest

from vines.core.params import ModelParams
from vines.orbits.continuation.sequence import _System
from vines.orbits.family import map_systems as ms
from vines.orbits.family.sequence import find_sequence, flip_seeds
from vines.orbits.family.systems import compound2
from vines.orbits.jets import chain, kernels
from vines.orbits.jets import shooting as sh
from vines.orbits.jets import taylor as jets

KINDS = ("fold", "det(A+I)", "neimark-sacker")
H = 1e-6
FD_REL = 1e-6
JET_REL = 1e-10


@pytest.fixture(scope="module")
def orbits():
    """LR/1-sym, LR/1-asym, LLRR/1-sym and LRLR/2 (born at the asymmetric 1:1 orbit's flip)."""
    p1 = ModelParams(eta=0.55, omega=1.0, F=0.4)
    p2 = ModelParams(eta=0.142, omega=0.765, F=0.2)
    asym = next(o for o in find_sequence(p2, "LR", 1, simulation=False)
                if o.admissible and not o.symmetric)
    got = {"LR/1-sym": find_sequence(p1, "LR", 1, simulation=False)[0], "LR/1-asym": asym,
           "LLRR/1-sym": find_sequence(ModelParams(eta=0.2, omega=0.8, F=0.4), "LLRR", 1,
                                       simulation=False)[0],
           "LRLR/2": find_sequence(p2, "LRLR", 2, simulation=False, seeds=flip_seeds(asym))[0]}
    for name, o in got.items():
        assert ms.family_of(o).name == name
    return got


def _kind(fam, kind):
    return ("symmetry-breaking" if fam.symmetric else "flip") if kind == "det(A+I)" else kind


def _chain(o, kind=None):
    """(fam, R, dR, g, dg) of the compiled chain at the orbit o."""
    fam, p = ms.family_of(o), o.params
    model = chain.model_of(p.r, p.d, p.phi)
    out = chain.residual_derivatives(model, fam.codes()[:fam.flights], fam.symmetric,
                                     fam.span(p), (p.eta, p.omega, p.F), o.states[0],
                                     o.flight_times[:fam.flights], kind)
    return (fam, *out)


def _close(a, b, rel):
    np.testing.assert_allclose(a, b, rtol=0, atol=rel * np.abs(b).max())


# ------------------------------------------------------------- pure-Python reference

def _reference(o, kind):
    """(dR, g, dg) from ``taylor`` jets: the shooting form over (x_0, s, eta, omega, F)
    gives the gaps' and R's gradients; the flight times are eliminated by the implicit
    function theorem (s_z = -Gap_s^-1 Gap_z); the map Jacobians (``map_jacobian_jets``)
    with those inner gradients, multiplied, give A and the condition as jets."""
    fam, p = ms.family_of(o), o.params
    m, codes = fam.flights, fam.codes()
    model = sh.Model(p.r, p.d, p.phi)
    z = jets.variables([*o.states[0], *o.flight_times[:m], p.eta, p.omega, p.F])
    par = z[4 + m:]
    x, xs, gaps = z[:4], [], []
    for k in range(m):
        xs.append(x)
        x, gap, _ = sh.flight(model, x, z[4 + k], *par, codes[k])
        gaps.append(gap)
    mirror = ms.MIRROR_SIGNS if fam.symmetric else np.ones(4)
    R = [mirror[i] * x[i] - z[i] for i in range(4)]
    R[3] = R[3] - fam.periods * (0.5 if fam.symmetric else 1.0) * sh.period(par[1])
    keep = [*range(4), *range(4 + m, 7 + m)]            # the globals (x_0, eta, omega, F)
    G = jets.jacobian(gaps, 7 + m)
    s_z = -np.linalg.solve(G[:, 4:4 + m], G[:, keep])
    dR = jets.jacobian(R, 7 + m)

    def reduced(f):
        g = jets.gradient(f, 7 + m)
        return g[keep] + g[4:4 + m] @ s_z

    A = None
    for k in range(m):
        inner = np.array([*(reduced(q) for q in xs[k]), s_z[k], *np.eye(7)[4:]])
        J = sh.map_jacobian_jets(model, xs[k], z[4 + k], *par, codes[k], inner)
        A = J if A is None else sh.matmul(J, A)
    A = [[q * mirror[i] for q in row] for i, row in enumerate(A)]
    if kind == "neimark-sacker":
        A = compound2(A)
    c = jets.det(sh.shifted(A, 1.0 if kind == "det(A+I)" else -1.0))
    return dR[:, keep] + dR[:, 4:4 + m] @ s_z, c.v, c.g


@pytest.mark.parametrize("name", ["LR/1-sym", "LR/1-asym", "LLRR/1-sym", "LRLR/2"])
@pytest.mark.parametrize("kind", KINDS)
def test_chain_matches_python_jets(orbits, name, kind):
    fam, R, dR, g, dg = _chain(orbits[name], _kind(ms.family_of(orbits[name]), kind))
    ref_dR, ref_g, ref_dg = _reference(orbits[name], kind)
    _close(dR, ref_dR, JET_REL)
    assert g == pytest.approx(ref_g, rel=JET_REL, abs=JET_REL)
    _close(dg, ref_dg, JET_REL)


# ------------------------------------------------------------- central differences

def _map_values(o, kind, z):
    fam = ms.family_of(o)
    p = ms.with_values(o.params, dict(zip(("eta", "omega", "F"), z[4:], strict=True)))
    R, A, _ = ms.orbit_residual(p, fam, z[:4], o.flight_times[:fam.flights])
    return np.append(R, ms.condition(kind, A))


@pytest.mark.parametrize("name", ["LR/1-sym", "LR/1-asym", "LLRR/1-sym", "LRLR/2"])
@pytest.mark.parametrize("kind", KINDS)
def test_chain_matches_central_differences_of_the_maps(orbits, name, kind):
    o = orbits[name]
    fam = ms.family_of(o)
    kind = _kind(fam, kind)
    _, R, dR, g, dg = _chain(o, kind)
    z = np.array([*o.states[0], o.params.eta, o.params.omega, o.params.F])
    fd = np.empty((5, 7))
    for i in range(7):
        e = np.zeros(7)
        e[i] = H * (1.0 + abs(z[i]))
        fd[:, i] = (_map_values(o, kind, z + e) - _map_values(o, kind, z - e)) / (2 * e[i])
    at = _map_values(o, kind, z)
    np.testing.assert_allclose(np.append(R, g), at, rtol=0, atol=1e-10 * np.abs(at).max())
    _close(dR, fd[:4], FD_REL)
    _close(dg, fd[4], FD_REL)


# ------------------------------------------------------------- the 1:1 kernels

@pytest.mark.parametrize("name", ["LR/1-sym", "LR/1-asym"])
def test_chain_monodromy_and_conditions_equal_the_one_to_one_kernels(orbits, name):
    """Same A (x_0 columns of dR + I, against the maps' Jacobians) and the same fold,
    det(A + I), Neimark-Sacker values as ``kernels.codim1`` on the 1:1 shooting system."""
    o = orbits[name]
    fam, p = ms.family_of(o), o.params
    u = list(o.states[0]) + ([] if fam.symmetric else [o.flight_times[0]])
    model = sh.Model(p.r, p.d, p.phi)
    _, A, _ = ms.orbit_residual(p, fam, o.states[0], o.flight_times[:fam.flights])
    for cond, kind in enumerate(KINDS):
        _, _, dR, g, _ = _chain(o, _kind(fam, kind))
        G, _ = kernels.codim1(model.tape, 1 - int(fam.symmetric), cond, 1, 0,
                              np.array(u), (p.eta, p.omega, p.F), 0.0)
        assert g == pytest.approx(G[-1], rel=1e-10, abs=1e-12)
        _close(dR[:, :4] + np.eye(4), A, 1e-12)


# ------------------------------------------------------------- the systems

@pytest.mark.parametrize("name,kind,graze", [
    ("LLRR/1-sym", "symmetry-breaking", None), ("LRLR/2", "neimark-sacker", None),
    ("LLRR/1-sym", "grazing", (2, "R")), ("LRLR/2", "grazing", (1, "arrival"))])
def test_systems_jets_equal_differences(orbits, name, kind, graze):
    o = orbits[name]
    fam = ms.family_of(o)
    sg = None if graze is None or graze[1] == "arrival" else 0.5 * o.flight_times[1]
    z = np.array(ms.unknowns(o, fam, graze, sg) + [o.params.omega, o.params.F])
    G, Gz = ms.make_system(o.params, fam, kind, graze, ("omega", "F"))(z)
    G0, Gz0 = ms.make_system(o.params, fam, kind, graze, ("omega", "F"), "differences")(z)
    np.testing.assert_array_equal(G, G0)
    _close(Gz, Gz0, FD_REL)
    assert not np.array_equal(Gz, Gz0)          # the jets were used


def test_continuation_system_parameter_column(orbits):
    o = orbits["LRLR/2"]
    sys_ = _System(o.params, "omega", o.walls, o.periods)
    sys_.s = o.flight_times.copy()
    z = np.append(o.states[0], o.params.omega)
    R, Rz = sys_(z)
    sys_.derivatives = "differences"
    R0, Rz0 = sys_(z)
    np.testing.assert_array_equal(R, R0)
    np.testing.assert_array_equal(Rz[:, :4], Rz0[:, :4])
    _close(Rz[:, 4], Rz0[:, 4], FD_REL)


def test_differences_where_the_jets_do_not_apply():
    """d outside (0, 2) (overdamped): no jets, the systems use differences."""
    assert chain.model_of(0.6, 2.5, 0.0) is None
    p = ModelParams(eta=0.2, omega=0.8, F=0.4, d=2.5)
    fam = ms.Family("LLRR", 1, True)
    z = np.array([0.3, -0.2, 0.1, 0.5, 0.8])
    a = ms.MapSystem(p, fam, "fold", ("omega",))(z)
    b = ms.MapSystem(p, fam, "fold", ("omega",), "differences")(z)
    for x, y in zip(a, b, strict=True):
        np.testing.assert_array_equal(x, y)


def test_unknown_derivative_method_is_refused():
    p = ModelParams(eta=0.2, omega=0.8, F=0.4)
    with pytest.raises(ValueError, match="derivatives"):
        ms.MapSystem(p, ms.Family("LLRR", 1, True), "fold", ("omega",), "exact")
