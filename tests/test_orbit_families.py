"""Every family of periodic orbits passes the same checks (issue 38): LR/1-sym, LR/1-asym
(the 1:1 orbits, through ``find_1to1`` and ``continue_branch``), LLRR/1-sym and LRLR/2
(through ``find_sequence`` and ``continue_sequence``).

The expected values come from outside the code under test: each flight is integrated by
scipy from the impact law of SPEC.md (``_impact_flights``), so the orbit must be a fixed
point of those composed flights, its eigenvalues those of a central-difference Jacobian of
them, and its stability flag what a perturbed simulation (``vines.simulate``, the exact
solver: no impact maps) does. The points are where each family has a stable orbit (the
paper's Fig 9 for LLRR/1, the flip of the asymmetric 1:1 orbit for LRLR/2).
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from _impact_flights import RTOL, orbit_flights

import vines
from vines.core.params import ModelParams
from vines.orbits import (
    ContinuationSettings,
    boundaries,
    continue_branch,
    continue_sequence,
    find_1to1,
    find_sequence,
)
from vines.orbits.family.sequence import state_at

#: family -> (eta, omega, F) of a stable orbit, walls, periods, symmetric
FAMILIES = {
    "LR/1-sym": ((0.55, 1.0, 0.4), "LR", 1, True),
    "LR/1-asym": ((0.142, 0.755, 0.2), "LR", 1, False),
    "LLRR/1-sym": ((0.2, 0.8, 0.4), "LLRR", 1, True),
    "LRLR/2": ((0.142, 0.765, 0.2), "LRLR", 2, False),
}
#: family -> (eta, omega, F) of an admissible unstable orbit of it
UNSTABLE = {
    "LR/1-sym": (0.142, 0.755, 0.2),
    "LR/1-asym": (0.142, 0.765, 0.2),
    "LLRR/1-sym": (0.2, 0.8, 0.4),
    "LRLR/2": (0.142, 0.775, 0.2),
}
#: family -> (parameter, stop, step, the event expected): a short branch from the stable
#: orbit through one event (eigenvalue +1 at fold and symmetry-breaking, -1 at flip)
BRANCHES = {
    "LR/1-sym": ("eta", 0.45, 0.005, "symmetry-breaking"),
    "LR/1-asym": ("omega", 0.765, 0.002, "flip"),
    "LLRR/1-sym": ("omega", 0.78, 0.005, "fold"),
    "LRLR/2": ("omega", 0.78, 0.005, "flip"),
}
TARGET = {"fold": 1.0, "symmetry-breaking": 1.0, "flip": -1.0}
#: points where every orbit found (both kinds, admissible or not) is checked: the
#: families' points, for 1:1 omega < 1, = 1 (Fig 6: eta 0.05 symmetric, 0.035 an
#: asymmetric pair) and > 1, and a non-admissible LLRR orbit with lambda_max 0.8 (not
#: stable: stability needs admissibility)
POINTS = [((0.55, 1.0, 0.4), "LR", 1), ((0.142, 0.755, 0.2), "LR", 1),
          ((0.05, 1.0, 0.05), "LR", 1), ((0.035, 1.0, 0.05), "LR", 1),
          ((0.6, 0.9, 0.3077), "LR", 1), ((0.3, 1.1, 0.3077), "LR", 1),
          ((0.2, 0.8, 0.4), "LLRR", 1), ((0.15, 0.95, 0.4), "LLRR", 1),
          ((0.142, 0.765, 0.2), "LRLR", 2)]


def _found(point, walls, periods):
    """Every orbit of walls/periods found at ``point`` (1:1: ``find_1to1``)."""
    if (walls, periods) == ("LR", 1):
        return find_1to1(*point, simulation=False)
    return find_sequence(ModelParams(*point), walls, periods)


def _orbits(name, point):
    """Every orbit of the family at ``point``."""
    _, walls, periods, sym = FAMILIES[name]
    return [o for o in _found(point, walls, periods) if o.symmetric == sym]


@pytest.fixture(scope="module", params=list(FAMILIES))
def family(request):
    """(name, the stable orbit, every orbit of the family found at its point)."""
    name = request.param
    found = _orbits(name, FAMILIES[name][0])
    stable = [o for o in found if o.stable]
    assert stable, f"no stable {name} orbit"
    return name, stable[0], found


@pytest.fixture(scope="module", params=POINTS, ids=lambda c: f"{c[1]}/{c[2]}-{c[0]}")
def every_orbit(request):
    """Every orbit found at one of ``POINTS``."""
    found = _found(*request.param)
    assert found
    return found


def _span(o) -> float:
    return o.periods * o.params.period


def _closure(o):
    """The states after each flight of scipy's integration from the orbit's first state,
    against the orbit's next states (the last one shifted by its period): (walls
    reached, largest difference, tolerance). Tolerance: DOP853 at rtol = atol = 1e-12
    keeps a flight's global error below 100 rtol; an impact time errs by that over the
    relative velocity |w'| at the impact, and the errors add up over the flights."""
    reached, states, _ = orbit_flights(o.params, o.walls, o.states[0], _span(o))
    expect = np.vstack([o.states[1:], o.states[:1] + [0.0, 0.0, 0.0, _span(o)]])
    n = len(o.walls)
    tol = 100.0 * RTOL * n * (1.0 + _span(o)) / min(1.0, np.abs(o.dw).min())
    if len(states) < n or None in reached:
        return "".join(str(w) for w in reached), math.inf, tol
    return "".join(reached), float(np.abs(np.array(states) - expect).max()), tol


def test_orbit_is_a_fixed_point_of_independent_flights_iff_admissible(every_orbit):
    """Impact law and free flight by scipy from x_0: for an admissible orbit every
    flight ends first on the next wall of the sequence at the orbit's next pre-impact
    state, and the last at x_0 one orbit period later; a non-admissible one is not so
    reproduced (an earlier wall contact, or an "impact" moving away from its wall)."""
    for o in every_orbit:
        reached, err, tol = _closure(o)
        closes = reached == o.walls[1:] + o.walls[0] and err <= tol
        assert closes == o.admissible, (o.walls, o.admissible, reached, err, tol)


def test_flights_cover_the_period_and_the_flags_agree(every_orbit):
    """Every orbit reads the same, whatever its family: one flight time, dw and phase
    per impact, t_0 in [0, T), flights adding up to periods T, eigenvalues by decreasing
    modulus, lambda_max the largest, stable iff admissible with lambda_max < 1, the dw
    and phases those of its states (SPEC.md: w' = z_m' - z_b', phase = mod(omega t +
    phi, 2 pi)). The flights add up to the period to Newton's accuracy in the impact
    times (1e-9 relative: the unstable LLRR orbit, lambda_max ~ 8e3, is the least
    accurate, ~2e-12)."""
    for o in every_orbit:
        n = len(o.walls)
        p = o.params
        assert len(o.flight_times) == n == len(o.dw) == len(o.phases) == len(o.states)
        assert 0.0 <= o.states[0, 3] < p.period
        assert sum(o.flight_times) == pytest.approx(_span(o), rel=1e-9)
        assert np.all(np.asarray(o.flight_times) > 0.0)
        mods = np.abs(o.eigenvalues)
        assert np.all(np.diff(mods) <= 1e-12 * mods.max())
        assert o.lambda_max == pytest.approx(mods.max(), rel=1e-12)
        assert o.stable == (o.admissible and o.lambda_max < 1.0)
        np.testing.assert_allclose(o.dw, o.states[:, 0] - o.states[:, 1], rtol=0, atol=1e-15)
        ph = np.mod(p.omega * o.states[:, 3] + p.phi, 2 * math.pi)
        d = np.abs(ph - o.phases)
        assert np.all(np.minimum(d, 2 * math.pi - d) <= 1e-12)


def test_state_along_the_orbit_is_the_integrated_one_and_inside_the_cavity(family):
    """``state_at`` along one period equals scipy's dense solution of the flights (to
    its tolerance, 1e3 rtol over a flight), and |w| = |z_m - z_b| <= 1 everywhere
    (SPEC.md: the invariant that must never break)."""
    _, o, _ = family
    _, _, sols = orbit_flights(o.params, o.walls, o.states[0], _span(o), dense=True)
    worst_w, worst = 0.0, 0.0
    for k, sol in enumerate(sols):
        t0, s = o.states[k, 3], o.flight_times[k]
        for t in t0 + s * np.linspace(0.0, 1.0, 41)[1:-1]:
            y = sol.sol(t)                              # (z_m, z_m', z_b, z_b')
            x = state_at(o, t)
            worst = max(worst, float(np.abs(x - y).max()))
            worst_w = max(worst_w, abs(x[0] - x[2]))
    assert worst <= 1e3 * RTOL * (1.0 + _span(o)), worst
    assert worst_w <= 1.0 + 1e-12, worst_w


def _mirrored(o, t, shift):
    """The mirror image of the orbit at time t: -x(t + shift); an orbit whenever shift is
    an odd multiple of T/2 (the forcing changes sign, SPEC.md section 1)."""
    return -state_at(o, t + shift)


def test_mirror_image(every_orbit):
    """The mirror image (z -> -z, T/2 later) of every orbit is an orbit found at the same
    point: itself half its period later where it is symmetric (and only there, whatever
    the shift T/2 + k T), else the other orbit of its pair, with the same eigenvalues
    (the mirror conjugates the monodromy)."""
    for o in every_orbit:
        T = o.params.period
        ts = o.states[0, 3] + _span(o) * (np.arange(23) + 0.37) / 23   # no impact instant

        def distance(q, shift, o=o, ts=ts):
            return max(float(np.abs(_mirrored(o, t, shift) - state_at(q, t)).max())
                       for t in ts)

        if o.symmetric:
            assert distance(o, 0.5 * _span(o)) <= 1e-10
            continue
        shifts = [(k + 0.5) * T for k in range(o.periods)]
        assert min(distance(o, sh) for sh in shifts) > 1e-3
        twin = min(every_orbit, key=lambda q: min(distance(q, sh) for sh in shifts))
        assert twin is not o and min(distance(twin, sh) for sh in shifts) <= 1e-9
        _assert_same_spectrum(twin.eigenvalues, o.eigenvalues, 1e-9 * max(1.0, o.lambda_max))


def _return_map(o, x):
    """x_0 -> the state after one period of scipy flights, less the period in t."""
    reached, states, _ = orbit_flights(o.params, o.walls, x, _span(o))
    assert "".join(str(w) for w in reached) == o.walls[1:] + o.walls[0]
    return states[-1] - [0.0, 0.0, 0.0, _span(o)]


def fd_monodromy(o, h=1e-5):
    """(eigenvalues of the central-difference Jacobian of the return map at x_0 with step
    h, tolerance on them). The error of that Jacobian is estimated by its difference to
    the one with step 2h (truncation ~ h^2 and the integration noise ~ rtol / h both
    show there); an eigenvalue moves by at most cond(V) times that (Bauer-Fike, V the
    eigenvectors), x 3 for the estimate."""
    J = {}
    for step in (h, 2 * h):
        J[step] = np.empty((4, 4))
        for k in range(4):
            e = np.zeros(4)
            e[k] = step
            J[step][:, k] = (_return_map(o, o.states[0] + e)
                             - _return_map(o, o.states[0] - e)) / (2 * step)
    ev, V = np.linalg.eig(J[h])
    tol = 3.0 * np.linalg.cond(V) * np.linalg.norm(J[h] - J[2 * h], 2)
    return ev, tol


def _assert_same_spectrum(ev, ref, tol):
    ref = list(ref)
    for z in sorted(ev, key=abs, reverse=True):     # pair each to the nearest one left
        w = min(ref, key=lambda q: abs(q - z))
        assert abs(z - w) <= tol, (ev, ref, tol)
        ref.remove(w)


def test_eigenvalues_are_those_of_the_integrated_return_map(family):
    _, o, _ = family
    ev, tol = fd_monodromy(o)
    assert tol < 1e-4                       # the check is sharp enough to mean something
    _assert_same_spectrum(o.eigenvalues, ev, tol)


def _distance_after(o, delta, n_periods):
    """|x(n_periods orbit periods) - x(0)| of the exact simulation from the orbit's state
    at t = 0 displaced by delta (the orbit returns to x(0) after each of its periods)."""
    p = o.params
    s0 = state_at(o, 0.0)
    t_end = n_periods * _span(o)
    run = vines.simulate(p.eta, p.omega, p.F, r=p.r, d=p.d, phi=p.phi, t_end=t_end,
                         t_transient=0.5 * t_end, state0=tuple(s0 + delta),
                         periodic_shortcut=False)
    return float(np.abs(run.state_at(t_end)[:, 0] - s0).max())


@pytest.mark.parametrize("name", list(FAMILIES))
@pytest.mark.parametrize("kind", ["stable", "unstable"])
def test_stability_is_what_a_perturbed_simulation_does(name, kind):
    """A small displacement of the orbit's state decays (stable) or grows (unstable)
    over the periods that multiply it by lambda_max^n = 1e-3 (1e3): by more than a
    factor 10 either way (a non-normal transient is worth at most the eigenvector
    matrix's condition number, ~20 at these orbits)."""
    if kind == "stable":
        o = next(q for q in _orbits(name, FAMILIES[name][0]) if q.stable)
        delta = 1e-6
    else:
        o = next(q for q in _orbits(name, UNSTABLE[name]) if q.admissible and not q.stable)
        delta = 1e-9                        # stays linear while it grows 1e3 times
    lam = max(abs(fd_monodromy(o)[0]))      # independent of the orbit's eigenvalues
    assert (lam < 1.0) == o.stable
    n = math.ceil(3.0 * math.log(10.0) / abs(math.log(lam)))
    d = _distance_after(o, delta * np.array([1.0, -0.5, 0.7, 0.3]), n)
    if o.stable:
        assert d < 0.1 * delta, (n, d)
    else:
        assert d > 10.0 * delta, (n, d)


# --------------------------------------------------------------------------- continuation

@pytest.fixture(scope="module")
def branch(family):
    """(the branch's orbits in continuation order, its events, param): a short branch from
    the family's stable orbit along ``BRANCHES``."""
    name, o, _ = family
    param, stop, step, _ = BRANCHES[name]
    p = o.params
    if (o.walls, o.periods) == ("LR", 1):
        fixed = {q: getattr(p, q) for q in ("eta", "omega", "F") if q != param}
        br = continue_branch(param, getattr(p, param), stop, step, fixed, orbit=o,
                             branch="symmetric" if o.symmetric else "asymmetric")
    else:
        br = continue_sequence(p, o.walls, o.periods, param, stop, orbit=o,
                               settings=ContinuationSettings(step=step))
    points = br.points if hasattr(br, "points") else br.orbits     # any branch type
    return points, br.events, param


def test_every_branch_point_is_a_fixed_point_of_independent_flights(family, branch):
    """Points spread along the branch close under scipy's flights (``_closure``) and lie
    in the parameter interval; the last one may lie past its end by less than a step
    (the wall-sequence continuation keeps the first point outside, the 1:1 one ends on
    the end)."""
    name, o, _ = family
    points, _, param = branch
    assert len(points) > 5
    _, stop, step, _ = BRANCHES[name]
    lo, hi = sorted((getattr(o.params, param), stop))
    for k, q in enumerate(points):
        v = getattr(q.params, param)
        slack = step if k == len(points) - 1 else 1e-12
        assert lo - slack <= v <= hi + slack, (k, v)
    for q in points[:: max(1, len(points) // 6)] + points[-1:]:
        assert q.walls == o.walls
        if q.admissible:
            reached, err, tol = _closure(q)
            assert reached == o.walls[1:] + o.walls[0] and err <= tol, (err, tol)


#: how close in its parameter an event is located, at most (``ContinuationSettings``'s
#: default event_tol: the 1:1 natural mode's bisection; the arclength modes locate to 1e-10)
EVENT_TOL = 1e-6


def _gap(o, target):
    """(the real eigenvalue of the integrated return map nearest target, less target;
    that eigenvalue's tolerance)."""
    mu, tol = fd_monodromy(o)
    real = mu[np.abs(mu.imag) <= tol].real
    return real[np.argmin(np.abs(real - target))] - target, tol


def test_branch_events_satisfy_their_defining_condition(family, branch):
    """The expected event is found, once, and
    * an eigenvalue of the integrated return map (``fd_monodromy``) crosses its value
      (+1 or -1) between the branch points on either side of it, and the event lies
      between them in the parameter (a fold: the branch turns there, both on one side);
    * the orbit solved afresh at the event's parameter has that eigenvalue, to the
      return map's tolerance plus how far it moves over ``EVENT_TOL``: linearly with the
      slope between the neighbours (flip, symmetry-breaking), like the square root of
      the distance to a fold (the neighbour before it gives the factor)."""
    name = family[0]
    points, events, param = branch
    typ = BRANCHES[name][3]
    found = [e for e in events if e["type"] == typ]
    assert len(found) == 1, events
    ev = found[0]
    i = ev["index"]
    a, b = points[i - 1], points[i + 1]          # the event lies between them
    target = TARGET[typ]
    (ga, _), (gb, _) = _gap(a, target), _gap(b, target)
    assert ga * gb < 0.0, (ga, gb)
    at = ev["at"]
    va, vb = getattr(a.params, param), getattr(b.params, param)
    if typ == "fold":
        assert (va - at) * (vb - at) >= 0.0, (va, at, vb)
        moves = abs(ga) * math.sqrt(EVENT_TOL / abs(va - at))
    else:
        assert min(va, vb) <= at <= max(va, vb), (va, at, vb)
        moves = abs(gb - ga) / abs(vb - va) * EVENT_TOL
    p = a.params
    here = ModelParams(**{q: (at if q == param else getattr(p, q)) for q in ("eta", "omega", "F")})
    again = find_sequence(here, a.walls, a.periods, simulation=False,
                          seeds=[(a.states[0], a.flight_times)])
    o = min(again, key=lambda q: np.abs(q.states[0] - a.states[0]).max())
    g, tol = _gap(o, target)
    assert abs(g) <= tol + moves, (g, tol, moves)


# --------------------------------------------------------------------------- curves

#: family -> F, (eta, omega) box and scan lines of a ``boundaries`` run whose box holds a
#: curve of the family's codimension-one point
CURVES = {
    "LR/1-sym": (0.4, ((0.45, 0.52), (0.97, 1.03)), 1, "symmetry-breaking"),
    "LR/1-asym": (0.2, ((0.12, 0.16), (0.74, 0.78)), 1, "flip"),
    "LLRR/1-sym": (0.4, ((0.2, 0.26), (0.77, 0.83)), 2, "symmetry-breaking"),
    "LRLR/2": (0.2, ((0.12, 0.16), (0.76, 0.78)), 2, "flip"),
}
#: an eigenvalue crosses its value within this distance of a curve point (in eta or omega)
CURVE_DELTA = 1e-8


def _real_gap(o, target):
    """The real eigenvalue of the orbit nearest target, less target (inf: none)."""
    ev = o.eigenvalues
    real = ev[np.abs(ev.imag) <= 1e-9 * max(1.0, np.abs(ev).max())].real
    return float(real[np.argmin(np.abs(real - target))] - target) if real.size else math.inf


def _crossing_near(walls, periods, point, F, target):
    """True when an orbit at (eta, omega) = ``point`` has a real eigenvalue through
    ``target`` within ``CURVE_DELTA`` of it along eta or omega: orbits solved afresh
    (``find_sequence``), the one with the eigenvalue nearest target, then continued to
    point +- CURVE_DELTA along each axis."""
    found = find_sequence(ModelParams(*point, F), walls, periods)
    o = min(found, key=lambda q: abs(_real_gap(q, target)))
    for axis in (0, 1):
        gaps = []
        for sign in (-1.0, 1.0):
            x = np.array(point, float)
            x[axis] += sign * CURVE_DELTA
            near = find_sequence(ModelParams(*x, F), walls, periods, simulation=False,
                                 seeds=[(o.states[0], o.flight_times)])
            q = min(near, key=lambda r: np.abs(r.states[0] - o.states[0]).max())
            gaps.append(_real_gap(q, target))
        if gaps[0] * gaps[1] < 0.0:
            return True
    return False


@pytest.mark.parametrize("name", list(CURVES))
def test_curve_points_are_where_an_eigenvalue_crosses(name):
    """``boundaries`` in a box around the family's point finds its curve; at every point
    of every flip (-1) and symmetry-breaking (+1: the monodromy is the half map squared)
    curve there, an eigenvalue of the orbit solved afresh crosses its value within
    ``CURVE_DELTA`` (the tracer solves augmented systems, not these eigenvalues)."""
    _, walls, periods, _ = FAMILIES[name]
    F, box, n_scan, kind = CURVES[name]
    curves = boundaries(F, *box, walls=walls, periods=periods, n_scan=n_scan).curves
    assert any(c.type == kind for c in curves), [c.type for c in curves]
    checked = 0
    for c in curves:
        if c.type not in TARGET or c.type == "fold":
            continue
        for pt in c.points:
            assert _crossing_near(walls, periods, tuple(pt), F, TARGET[c.type]), (c.type, pt)
            checked += 1
    assert checked >= 5
