"""Two-parameter curves of codimension-one points (issue 14, step 3): exact Jacobians of
the augmented systems against finite differences, agreement with one-parameter
continuation and with the stability map's classes."""
import json

import numpy as np
import pytest
from conftest import run_vines

from vines.core.params import D_DEFAULT, R_DEFAULT, ParameterError
from vines.orbits.atlas.stability_map import stability_map
from vines.orbits.continuation.one_to_one import continue_branch
from vines.orbits.curves.boundaries import boundaries
from vines.orbits.curves.one_to_one import crossings
from vines.orbits.family import augmented as ag
from vines.orbits.family.family import MIRROR_MATRIX
from vines.orbits.family.periodic import find_1to1
from vines.orbits.family.systems import KINDS
from vines.orbits.jets import shooting as sh

MODEL = sh.Model(R_DEFAULT, D_DEFAULT)
F = 0.3077
BOX = ((0.05, 1.0), (0.7, 1.4))


def _fd_jacobian(system, z):
    out = np.empty((len(system(z)[0]), len(z)))
    for k in range(len(z)):
        h = 1e-6 * max(1.0, abs(z[k]))
        e = np.zeros(len(z))
        e[k] = h
        out[:, k] = (system(z + e)[0] - system(z - e)[0]) / (2.0 * h)
    return out


CASES = [(fam, kind, None) for fam in ("symmetric", "asymmetric") for kind in KINDS[fam == "symmetric"]
         if kind != "grazing"]
CASES += [(fam, "grazing", (k, wall)) for fam in ("symmetric", "asymmetric")
          for k in ((1,) if fam == "symmetric" else (1, 2)) for wall in ag.GRAZE_WALLS]


def augmented_point(family, kind, graze, free):
    """(system, z, n_orbit_unknowns): the augmented system of this case at a 1:1 orbit of
    the family at (eta, omega, F) = (0.12, 1.1, F), free parameters ``free``."""
    o = [o for o in find_1to1(0.12, 1.1, F, simulation=False)
         if o.symmetric == (family == "symmetric")][0]
    u = list(o.x_L) + ([] if o.symmetric else [o.flight_times[0]])
    fixed = {q: v for q, v in (("eta", 0.12), ("omega", 1.1), ("F", F)) if q not in free}
    system = ag.Codim1System(MODEL, family, kind, free, fixed, graze)
    sg = [0.4 * o.flight_times[graze[0] - 1]] if system.has_sg else []
    z = np.array(u + sg + [{"eta": 0.12, "omega": 1.1, "F": F}[q] for q in free])
    return system, z, len(u)


@pytest.mark.parametrize("family, kind, graze", CASES)
@pytest.mark.parametrize("free", [("eta", "omega"), ("F",)])
def test_augmented_jacobians_match_finite_differences(family, kind, graze, free):
    system, z, n_u = augmented_point(family, kind, graze, free)
    G, Gz = system(z)
    assert G.shape == (n_u + (2 if system.has_sg else 1),) and Gz.shape == (len(G), len(z))
    fd = _fd_jacobian(system, z)
    np.testing.assert_allclose(Gz, fd, rtol=1e-6, atol=1e-6 * max(1.0, np.abs(fd).max()))


@pytest.fixture(scope="module")
def curves():
    return boundaries(F, *BOX, n_scan=4)


def test_curves_reproduce_the_stable_windows_at_omega_1(curves):
    """Where the curves cross omega = 1 they give the edges of the stable windows of the
    symmetric branch found by one-parameter continuation, to 1e-4 in eta."""
    br = continue_branch("eta", 0.05, 1.0, None, {"omega": 1.0, "F": F})
    # the events where the stable flag of the branch changes (located along the arclength)
    edges = [e["at"] for e in br.events if 0 < e["index"] < len(br) - 1
             and br.stable[e["index"] - 1] != br.stable[e["index"] + 1]]
    n_changes = sum(br.stable[i] != br.stable[i - 1] for i in range(1, len(br)))
    assert len(edges) >= 2 and n_changes == len(edges)      # no change without an event
    cross = [x for c in curves.curves if c.family == "symmetric"
             for x in crossings(c, MODEL, F, 1.0)]
    for e in edges:
        assert min(abs(np.array(cross) - e)) < 1e-4, (e, sorted(cross))


def test_class_changes_of_a_coarse_map_lie_on_curves(curves):
    eta = np.linspace(*BOX[0], 8)
    omega = np.linspace(*BOX[1], 10)
    cls = stability_map(eta, omega, F)["cls"]
    pts = np.concatenate([c.points for c in curves.curves])
    de, dw = eta[1] - eta[0], omega[1] - omega[0]
    n = 0
    for i in range(len(eta)):
        for j in range(len(omega)):
            for i2, j2 in ((i + 1, j), (i, j + 1)):
                if i2 < len(eta) and j2 < len(omega) and cls[i, j] != cls[i2, j2]:
                    mid = ((eta[i] + eta[i2]) / 2, (omega[j] + omega[j2]) / 2)
                    dist = np.min(np.hypot((pts[:, 0] - mid[0]) / de, (pts[:, 1] - mid[1]) / dw))
                    assert dist <= 1.5, (mid, cls[i, j], cls[i2, j2], dist)
                    n += 1
    assert n >= 10


def test_curve_points_solve_their_conditions(curves):
    """Every kept point is a genuine codimension-one point of an orbit of the maps."""
    from vines.core.params import ModelParams
    from vines.orbits.continuation.follower import orbit_at
    types = {c.type for c in curves.curves}
    assert {"symmetry-breaking", "neimark-sacker", "grazing"} <= types
    for c in curves.curves:
        system = ag.Codim1System(MODEL, c.family, c.type, ("eta", "omega"), {"F": F}, c.graze)
        for z in c.z[:: max(1, len(c.z) // 5)]:
            assert np.abs(system(z)[0]).max() < 1e-8
            if c.type == "symmetry-breaking":
                o = orbit_at(ModelParams(z[-2], z[-1], F), "symmetric", z[:4])
                assert np.min(np.abs(np.linalg.eigvals(MIRROR_MATRIX @ o.jacobians[0]) + 1.0)) < 1e-6


def test_boundaries_cli_json():
    proc = run_vines("boundaries", "--F", "0.3077", "--eta-range", "0.1", "0.4",
                     "--omega-range", "0.9", "1.2", "--json")
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["curves"] and all({"type", "points"} <= set(c) for c in out["curves"])
    for c in out["curves"]:
        pts = np.array(c["points"])
        assert pts.shape[1] == 2
        assert (pts[:, 0] >= 0.1 - 1e-9).all() and (pts[:, 0] <= 0.4 + 1e-9).all()
        assert (pts[:, 1] >= 0.9 - 1e-9).all() and (pts[:, 1] <= 1.2 + 1e-9).all()


@pytest.mark.parametrize("args, fragments", [
    (["--F", "abc"], ["--F", "abc"]),
    (["--F", "0.3", "--eta-range", "0.3", "0.2"], ["--eta-range", "lo < hi"]),
    (["--F", "0.3", "--omega-range", "0", "1"], ["--omega-range", "> 0"]),
    (["--F", "0.3", "--eta-range", "0.1"], ["--eta-range"]),
    (["--eta-range", "0.1", "0.2"], ["--F"]),
])
def test_boundaries_bad_input(args, fragments):
    proc = run_vines("boundaries", *args, "--json")
    assert proc.returncode == 2 and proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("vines boundaries: error: "), proc.stderr
    assert all(f in lines[0] for f in fragments), lines[0]


def test_api_refuses_bad_ranges():
    with pytest.raises(ParameterError) as err:
        boundaries(0.3, (0.2, 0.1), (0.9, 1.0))
    assert err.value.name == "eta_range"


def test_curve_points_lie_in_the_box(curves):
    """A curve ends on the box side it crosses first; no point lies outside the box."""
    (e0, e1), (w0, w1) = BOX
    for c in curves.curves:
        e, w = c.points.T
        assert ((e >= e0) & (e <= e1) & (w >= w0) & (w <= w1)).all(), (c.type, c.stopped)


def _arrival_omega(F_, lo, hi):
    """W where the free LO's steady amplitude is 1 (half the clearance): F^2 (1 + d^2 W^2)
    = (1 - W^2)^2 + d^2 W^2 (forcing F sin + d W F cos, SPEC section 1)."""
    from scipy.optimize import brentq
    d = D_DEFAULT
    return brentq(lambda w: (1 - w * w) ** 2 + (d * w) ** 2 - F_ * F_ * (1 + (d * w) ** 2),
                  lo, hi, xtol=1e-15)


def test_arrival_grazing_line_found_from_the_map_and_matches_the_closed_form():
    """A symmetric orbit with zero relative velocity at its impacts has the ball at rest
    and the LO in its free steady state touching both walls: amplitude 1, the same W for
    every eta. No scan line of this box meets the family; the class change of the coarse
    stability map seeds it."""
    box = ((0.5, 1.0), (0.85, 0.95))
    W = _arrival_omega(0.2, 0.8, 0.95)
    arrival = [c for c in boundaries(0.2, *box, n_scan=1, n_map=6).curves
               if c.type == "grazing" and c.graze[1] == "arrival"]
    assert len(arrival) == 1
    e, w = arrival[0].points.T
    np.testing.assert_allclose(w, W, rtol=0, atol=1e-9)
    assert e.min() == box[0][0] and e.max() == box[0][1]
    assert not [c for c in boundaries(0.2, *box, n_scan=1, n_map=0).curves
                if c.type == "grazing" and c.graze[1] == "arrival"]


def test_admissibility_loss_at_a_grazing_arrival_is_an_event():
    """The maps have a pole where the arrival velocity vanishes; the event is solved on the
    shooting system with the grazing-arrival condition (explicit flight times: no pole there)
    and lies at the closed-form W. Tolerance 1e-9: Newton stops when its step is below
    1e-11 (1 + |z|) ~ 3e-11 and the Jacobian of that square system is well conditioned
    (condition number ~ 30), so the error is ~1e-14 whatever the round-off of the CPU; a
    bisection of the admissibility flag could not get closer than where the corrector
    fails near the pole (~1e-6)."""
    br = continue_branch("omega", 0.896, 0.85, 0.001, {"eta": 0.7, "F": 0.2},
                         max_inadmissible=5)
    ev = [e for e in br.events if e["type"] == "admissibility-loss"]
    assert len(ev) == 1
    W = _arrival_omega(0.2, 0.8, 0.95)
    assert abs(ev[0]["at"] - W) < 1e-9
    assert ev[0]["omega"] == ev[0]["at"] and ev[0]["eta"] == 0.7
    # the branch point of the event is the nearest one where the maps are defined
    assert abs(br.values[ev[0]["index"]] - W) < 1e-5
