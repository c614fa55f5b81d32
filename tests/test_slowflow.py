"""The averaged slow flow (``vines.slowflow``) against what does not share its algebra: the
ball's motion integrated with the LO prescribed (SIM, fold, symmetry-breaking point), the averaged equations by
quadrature (fixed points, stability) and the exact 1:1 orbits of the impact maps with their
max |z_m| from the closed-form flow (convergence O(eps), stability, the fold)."""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from vines.core.flow import flow, make_osc
from vines.core.params import ParameterError
from vines.core.walls import impact_velocities
from vines.orbits.family.periodic import find_1to1
from vines.slowflow import frc, manifold, optimal_F, response, rho
from vines.slowflow.response import Model, fixed_points

R = 0.65
RHO = rho(R)


# --------------------------------------------------------------------------- helpers

def exact_zm_max(o, eta, W, F, r, d, n=2000) -> float:
    """max |z_m| over a period of a symmetric exact 1:1 orbit: the closed-form flow of the
    LO after the L impact, sampled over the half period (the other half is its mirror)."""
    vm, vb, zb, tL = o.x_L
    zm = zb + 1.0                                   # wall L: w = z_m - z_b = +1
    vmp, _ = impact_velocities(eta, r, vm, vb)
    osc = make_osc(1.0, d, W, F)
    th0 = W * tL
    return max(abs(flow(osc, zm, vmp, math.sin(th0), math.cos(th0), s)[0])
               for s in np.linspace(0.0, o.flight_times[0], n))


def matched(eta, W, F, d, r=R):
    """Rows (branch, slow stable, exact stable, exact lambda_max, X slow - X exact, X slow) of the
    slow flow's fixed points, each matched to the exact symmetric orbit of nearest impact
    phase."""
    fp = fixed_points(Model(eta, F, r, d), np.array([W]))
    exact = [o for o in find_1to1(eta, W, F, r=r, d=d, simulation=False)
             if o.symmetric and o.admissible]
    rows = []
    for j in range(fp.X.size):
        o = min(exact, key=lambda o: abs(np.angle(np.exp(1j * (o.phase_L - fp.phase[j])))))
        assert abs(np.angle(np.exp(1j * (o.phase_L - fp.phase[j])))) < 0.2
        rows.append((int(fp.branch[j]), bool(fp.stable[j]), o.stable, o.lambda_max,
                     fp.X[j] - exact_zm_max(o, eta, W, F, r, d), fp.X[j]))
    return rows


def ball_flight(X, alpha, r):
    """The ball with the LO prescribed as X cos(t) (eta -> 0): from the L impact at t = alpha
    with the restitution law, the time and ball velocity of its next contact (wall R)."""
    zb0 = X * math.cos(alpha) - 1.0
    vm = -X * math.sin(alpha)
    # w'+ = -r w'-: vm - u = -r (vm - u_before), the ball arriving with u_before = -u
    u = vm * (1.0 + r) / (1.0 - r)

    def gap(t):                                         # w + 1: zero at wall R
        return X * math.cos(t) - (zb0 + u * (t - alpha)) + 1.0
    ts = alpha + np.linspace(1e-6, 2.0 * math.pi, 20001)
    g = np.array([gap(t) for t in ts])
    k = int(np.flatnonzero(g <= 0.0)[0])
    t1 = brentq(gap, ts[k - 1], ts[k], xtol=1e-14)
    return t1, u


def impact_map_growth(X, alpha, r, n=60, delta=1e-7):
    """|deviation of the flight time from pi| / delta after n impacts of the ball (LO
    prescribed as X cos(t)), started at the orbit's L impact delayed by delta."""
    u_orbit = -X * math.sin(alpha) * (1.0 + r) / (1.0 - r)
    t, side, u0 = alpha + delta, 1.0, -u_orbit
    for _ in range(n):
        u = (1.0 + r) * (-X * math.sin(t)) - r * u0            # the impact law, eta -> 0
        t0, zb0, u0 = t, X * math.cos(t) - side, u

        def gap(s, t0=t0, zb0=zb0, u0=u0, side=side):          # distance to the next wall
            return side * (X * math.cos(s) - zb0 - u0 * (s - t0)) + 1.0
        ss = t0 + np.linspace(1e-9, 2.0 * math.pi, 8001)
        g = np.array([gap(x) for x in ss])
        k = int(np.flatnonzero(g <= 0.0)[0])
        t = brentq(gap, ss[k - 1], ss[k], xtol=1e-15)
        side = -side
        if abs(t - t0 - math.pi) > 0.5:
            break
    return abs(t - t0 - math.pi) / delta


# --------------------------------------------------------------------------- rho and SIM

def test_rho_limits():
    assert rho(0.0) == pytest.approx(2.0 / math.pi, rel=1e-15)
    assert rho(1.0) == 0.0
    assert rho(1.0 - 1e-9) == pytest.approx(1e-9 / math.pi, rel=1e-6)
    rs = np.linspace(0.0, 1.0, 11)
    assert np.all(np.diff([rho(x) for x in rs]) < 0)
    assert manifold.xi_min(rho(1.0)) == 0.0
    assert manifold.xi_min(rho(0.0)) == pytest.approx(2.0 / math.sqrt(math.pi ** 2 + 4.0))


@pytest.mark.parametrize("alpha", [-0.05, -0.5, -1.2, -2.0, -2.5])
def test_sim_is_the_ball_flight_of_half_a_period(alpha):
    """On the SIM the ball, launched by the impact law from wall L at phase alpha, reaches
    wall R exactly half a period later (integrated, not from the SIM's formula)."""
    X = float(manifold.amplitude(alpha, RHO))
    if X <= 0 or alpha < -0.5 * math.pi - manifold.beta(RHO):
        pytest.skip("not on the SIM")
    t1, _ = ball_flight(X, alpha, R)
    assert t1 - alpha == pytest.approx(math.pi, abs=1e-9)


def test_fold_and_symmetry_breaking_bound_the_stable_branch():
    """The ball's impact map with the LO prescribed: perturbations decay between the fold
    and the symmetry-breaking point, grow just outside (iterated map, not the trace
    formula)."""
    a_fold, a_flip = -manifold.beta(RHO), manifold.alpha_symmetry_breaking(RHO)
    assert manifold.amplitude(a_fold, RHO) == pytest.approx(manifold.xi_min(RHO))
    for alpha, stable in [(a_fold - 0.1, True), (0.5 * (a_fold + a_flip), True),
                          (a_flip + 0.05, True), (a_fold + 0.1, False),
                          (a_flip - 0.1, False)]:
        X = float(manifold.amplitude(alpha, RHO))
        growth = impact_map_growth(X, alpha, R)
        assert (growth < 0.5) == stable, (alpha, growth)
        assert (manifold.branch_of(alpha, RHO) == manifold.BRANCH_STABLE) == stable


# --------------------------------------------------------------------------- averaging

def averaged_field(m: Model, W, X, chi, branch):
    """(X', chi') of the averaged equations by quadrature of the forcing, damping and
    detuning over a period, plus the two impulses of the exact impact law with the SIM's
    velocities (LO -X W sin(alpha), ball +-2 W (1 - X cos(alpha))/pi)."""
    lo, hi = (-manifold.beta(m.rho), 0.0) if branch == 2 else (
        -0.5 * math.pi - manifold.beta(m.rho) + 1e-12, -manifold.beta(m.rho))
    alpha = brentq(lambda a: manifold.amplitude(a, m.rho) - X, lo, hi, xtol=1e-15)
    th = np.linspace(0.0, 2.0 * math.pi, 257)[:-1]
    psi_rel = chi - math.atan(m.d * W)              # phi - psi
    x, v = X * np.cos(th), -X * W * np.sin(th)
    forcing = m.F * (np.sin(th + psi_rel) + m.d * W * np.cos(th + psi_rel))
    h = forcing - m.d * v + (W * W - 1.0) * x
    hs, hc = np.mean(h * np.sin(th)), np.mean(h * np.cos(th))
    vm = -X * W * math.sin(alpha)
    vb = -2.0 * W * (1.0 - X * math.cos(alpha)) / math.pi      # ball before the L impact
    J = impact_velocities(m.eta, m.r, vm, vb)[0] - vm            # impulse at L; -J at R
    hs += (W / math.pi) * J * math.sin(alpha)        # time averages of the two impulses
    hc += (W / math.pi) * J * math.cos(alpha)
    return -hs / W, (hc / W) / X


@pytest.mark.parametrize("eta, W, F", [(0.02, 1.0, 0.02), (0.05, 0.97, 0.04),
                                       (0.01, 1.02, 0.015), (0.03, 0.95, 0.03)])
def test_fixed_points_and_stability_of_the_averaged_equations(eta, W, F):
    m = Model(eta, F, R, 0.6 * eta)
    fp = fixed_points(m, np.array([W]))
    assert fp.X.size >= 1
    for j in range(fp.X.size):
        X, branch = fp.X[j], int(fp.branch[j])
        b = 2 if branch == 2 else 1
        chi = (fp.phase[j] - fp.alpha[j] + math.atan(m.d * W))
        f0 = np.array(averaged_field(m, W, X, chi, b))
        assert np.abs(f0).max() < 1e-12 * max(1.0, X)
        h = 1e-6
        J = np.column_stack([
            (np.array(averaged_field(m, W, X + h, chi, b))
             - np.array(averaged_field(m, W, X - h, chi, b))) / (2 * h),
            (np.array(averaged_field(m, W, X, chi + h, b))
             - np.array(averaged_field(m, W, X, chi - h, b))) / (2 * h)])
        tr, det = np.trace(J), np.linalg.det(J)
        assert tr == pytest.approx(fp.trace[j], rel=1e-4, abs=1e-8)
        assert det == pytest.approx(fp.det[j], rel=1e-4, abs=1e-8)


# --------------------------------------------------------------------------- exact orbits

EPS = (0.04, 0.02, 0.01, 0.005)
KAPPA = 0.5


@pytest.mark.parametrize("r, f, sigma, branches", [
    (0.8, 1.0, 0.0, {1}), (0.8, 1.5, 1.0, {1, 2}), (0.8, 1.0, -1.0, {2, 3}),
    (0.8, 2.0, 0.0, {3}),
    (0.65, 1.0, 0.0, {1}), (0.65, 1.5, 1.0, {1, 2}), (0.65, 1.0, 1.0, {1, 2}),
    (0.65, 2.0, 0.0, {3})])
def test_converges_to_the_exact_orbits(r, f, sigma, branches):
    """eta = eps, d = kappa eps, F = f eps, Omega = 1 + sigma eps: the slow flow's
    amplitudes differ from the exact orbits' max |z_m| by O(eps): each halving of eps
    divides the difference by 1.6 to 3.5, on every branch (stable, unstable,
    symmetry-breaking); the
    stability agrees."""
    diffs = {}
    for eps in EPS:
        rows = matched(eps, 1.0 + sigma * eps, f * eps, KAPPA * eps, r=r)
        assert {b for b, *_ in rows} == branches
        for b, s_slow, s_exact, _, diff, _ in rows:
            assert s_slow == s_exact
            diffs.setdefault(b, []).append(diff)
    for b, ds in diffs.items():
        ratios = np.abs(ds[:-1]) / np.abs(ds[1:])
        assert np.all((ratios >= 1.6) & (ratios <= 3.5)), (b, ds)


def test_stability_agrees_away_from_the_boundary():
    """Over a grid at eta = 0.01: wherever the exact multiplier is not within 5 % of the unit
    circle and the slow flow's amplitude not within 5 % of the SIM's fold or
    symmetry-breaking point (where
    the averaging is singular: the ball's own dynamics slows down), a fixed point called
    stable is a stable exact orbit and vice versa."""
    n = 0
    ends = (manifold.xi_min(RHO), manifold.x_symmetry_breaking(RHO))
    for f in (0.5, 1.0, 2.0, 3.0):
        for sigma in (-2.0, -1.0, 0.0, 1.0, 2.0):
            eps = 0.01
            for _, s_slow, s_exact, lam, _, X in matched(eps, 1.0 + sigma * eps, f * eps,
                                                         KAPPA * eps):
                if abs(lam - 1.0) > 0.05 and min(abs(X / e - 1.0) for e in ends) > 0.05:
                    assert s_slow == s_exact, (f, sigma, lam)
                    n += 1
    assert n >= 20


def test_symmetry_breaking_amplitude_is_the_exact_orbits_limit():
    """eta = eps, d = eps/2, Omega = 1: the exact symmetric 1:1 orbit continued in F
    (``continue_branch``, natural mode) meets a multiplier +1 of its full period (the
    half map composed with the mirror: -1), a symmetry-breaking pitchfork; its max |z_m|
    there tends to the slow flow's x_symmetry_breaking as eps -> 0 at first order: each
    halving divides the difference by 1.6 to 2.5 (first order: -> 2), and it stays below
    2.5 eps (its O(eps) coefficient, ~1.9 here, settles within 10 %)."""
    from vines.orbits import continue_branch
    xs = manifold.x_symmetry_breaking(RHO)

    def upper_X(F, eta, d):
        fp = fixed_points(Model(eta, F, R, d), np.array([1.0]))
        return fp.X[fp.branch != manifold.BRANCH_UNSTABLE].max() - xs

    errors = []
    for eps in (0.04, 0.02, 0.01, 0.005):
        eta, d = eps, KAPPA * eps
        F_slow = brentq(upper_X, 1.2 * eps, 2.0 * eps, args=(eta, d), xtol=1e-15)
        br = continue_branch("F", 0.95 * F_slow, F_slow, step=0.05 * F_slow / 20,
                             fixed={"eta": eta, "omega": 1.0}, r=R, d=d, event_tol=1e-12,
                             method="natural")
        (sb,) = [e["at"] for e in br.events if e["type"] == "symmetry-breaking"]
        (o,) = [o for o in find_1to1(eta, 1.0, sb, r=R, d=d, simulation=False)
                if o.symmetric and o.admissible]
        assert np.min(np.abs(o.eigenvalues - 1.0)) < 1e-8        # full period: +1
        errors.append(xs - exact_zm_max(o, eta, 1.0, sb, R, d))
    errors = np.array(errors)
    ratios = errors[:-1] / errors[1:]
    assert np.all((ratios >= 1.6) & (ratios <= 2.5)), errors
    scaled = errors / np.array([0.04, 0.02, 0.01, 0.005])
    assert np.all(scaled <= 2.5) and np.ptp(scaled) < 0.1 * scaled[-1], scaled


@pytest.mark.parametrize("eta", [0.02, 0.01, 0.005])
def test_fold_is_the_smallest_exact_amplitude(eta):
    """Along the exact symmetric orbits at Omega = 1 as F varies (every orbit of a fine F
    scan around the slow flow's F at the fold), the smallest max |z_m| tends to xi_min:
    within 0.12 eta."""
    d, W = KAPPA * eta, 1.0
    m = Model(eta, 1.0, R, d)
    a = -manifold.beta(RHO)
    k = m.e * m.K * W * W
    G = manifold.xi_min(RHO) * math.hypot(W * d + 2 * k * math.sin(a) ** 2,
                                          2 * k * math.sin(a) * math.cos(a))
    F_fold = G / math.sqrt(1.0 + (d * W) ** 2)
    amps = [exact_zm_max(o, eta, W, F, R, d, n=600)
            for F in F_fold * np.linspace(0.7, 1.3, 25)
            for o in find_1to1(eta, W, F, r=R, d=d, simulation=False)
            if o.symmetric and o.admissible]
    assert abs(min(amps) - manifold.xi_min(RHO)) < 0.12 * eta


# --------------------------------------------------------------------------- API

def test_frc_rows_are_the_responses():
    W = np.linspace(0.85, 1.15, 61)
    out = frc(0.02, W, 0.03)
    assert np.all(np.isfinite(out.amplitude)) and np.all(np.isfinite(out.phase))
    assert np.all((out.phase >= 0) & (out.phase < 2 * math.pi))
    for w in W[::10]:
        res = response(0.02, w, 0.03)
        rows = np.flatnonzero(out.omega == w)
        assert sorted(o.amplitude for o in res.orbits) == pytest.approx(
            sorted(out.amplitude[rows]))
        assert res.fixed_point_regime == out.regime[np.flatnonzero(w == W)[0]]
    d = out.to_dict()
    assert {"omega", "amplitude", "ball_amplitude", "phase", "stable", "branch"} <= set(
        d["frc"][0])


def test_regimes():
    assert response(0.02, 1.0, 0.005).regime == "no impact"      # linear response < 1
    r = response(0.02, 1.0, 0.02)
    assert r.regime == "two-impact" and r.orbits[0].stable and r.smr is None
    r = response(0.05, 1.0, 0.02)
    assert r.regime == "SMR" and r.smr[0] <= manifold.xi_min(RHO) and r.smr[1] == 1.0
    assert not any(o.stable for o in r.orbits) and r.linear_amplitude > 1.0
    c = r.smr_cycle
    assert c.period == pytest.approx(c.time_impacting + c.time_free) and c.time_free > 0
    assert r.to_dict()["smr"]["period"] == c.period


@pytest.mark.parametrize("eta, W, F, regime, decided_by, exact", [
    # the jump at X = 1 lands in the fixed point's basin (exact: the 1:1 orbit)
    (0.02, 1.0, 0.02, "two-impact", "slow flow", "1:1"),
    # a fixed point attracts, but from rest the LO stays inside the clearance
    (0.02, 0.975, 0.03, "no impact", "slow flow", "no-impact"),
    # the linear amplitude is below 1, but the start-up beat reaches the clearance: SMR
    (0.1, 0.975, 0.05, "SMR", "slow flow", "chatter"),
    # the jump reaches the fold while a fixed point attracts: the exact solver decides
    (0.05, 1.025, 0.05, "two-impact", "exact solver: 1:1", "1:1"),
])
def test_regime_from_rest_is_followed(eta, W, F, regime, decided_by, exact):
    """The regime from rest is decided by following the slow flow through the jump at
    X = 1 (or by the exact solver where it cannot), not by assuming that an attracting
    fixed point is reached; the exact run from rest agrees."""
    from vines.core.simulation import simulate_batch
    r = response(eta, W, F)
    assert (r.regime, r.from_rest.decided_by) == (regime, decided_by)
    assert str(simulate_batch(eta, W, F, n_threads=1)["regime"]) == exact
    d = r.to_dict()["from_rest"]
    assert d["regime"] == regime and d["fixed_point_regime"] == r.fixed_point_regime
    if regime == "two-impact":
        assert r.from_rest.jumps >= 1 and any(
            o.amplitude == r.from_rest.amplitude for o in r.orbits) == (
            decided_by == "slow flow")
    if regime == "no impact":
        assert r.from_rest.jumps == 0 and r.from_rest.amplitude == r.linear_amplitude
        assert r.fixed_point_regime == "two-impact"


def test_flip_names_are_deprecated_aliases():
    res = response(0.02, 1.0, 0.02)
    with pytest.warns(DeprecationWarning, match="x_symmetry_breaking"):
        assert res.x_flip == res.x_symmetry_breaking == manifold.x_symmetry_breaking(RHO)
    for old, new in (("alpha_flip", "alpha_symmetry_breaking"),
                     ("x_flip", "x_symmetry_breaking"),
                     ("BRANCH_FLIP", "BRANCH_SYMMETRY_BREAKING")):
        with pytest.warns(DeprecationWarning, match=new):
            assert getattr(manifold, old) is getattr(manifold, new)
    d = res.to_dict()
    assert d["x_flip"] == d["x_symmetry_breaking"]
    assert manifold.BRANCH_NAMES[manifold.BRANCH_SYMMETRY_BREAKING] == "symmetry-breaking"


def test_refuses_and_warns_outside_the_assumptions():
    for kw in (dict(eta=0.6), dict(d=0.6), dict(r=1.0), dict(eta=0.0), dict(F=-1.0)):
        args = dict(eta=0.02, omega=1.0, F=0.02) | kw
        with pytest.raises(ParameterError) as err:
            response(args.pop("eta"), args.pop("omega"), args.pop("F"), **args)
        assert err.value.name == next(iter(kw))
    assert response(0.02, 1.0, 0.02).warnings == []
    w = response(0.2, 1.5, 0.3, d=0.2).warnings
    assert len(w) == 4 and all(("eta" in x) or ("d =" in x) or ("F =" in x) or ("omega" in x)
                               for x in w)
    with pytest.raises(ParameterError):
        frc(0.02, [1.0, float("nan")], 0.02)


def test_optimal_F_is_the_band_minimum():
    """The optimum is no worse than any F of an independent coarse scan (same model)."""
    from vines.slowflow.optimal import worst_ratio
    W = np.linspace(0.8, 1.2, 801)
    opt = optimal_F(0.02)
    scan = [worst_ratio(0.02, [F], W, R, response(0.02, 1.0, 0.02).d)
            for F in np.geomspace(1e-3, 2.0, 37)]
    assert opt.worst_ratio <= min(scan) + 1e-9
    assert 0.8 <= opt.omega_peak <= 1.2


@pytest.mark.slow
def test_optimal_clearance_against_the_exact_design():
    """At eta = 0.02 (one base amplitude, 0.75 mm): the exact worst case (``vines.design``)
    at the slow flow's best clearance is within a factor 1.3 of the exact optimum's
    (``vines.design`` optimising (eta <= 0.02, clearance)), and the slow flow's own peak
    within that factor of the exact value at its design."""
    from vines.slowflow import optimal_clearance
    from vines.studies.design import design
    A = [0.75e-3]
    sf = optimal_clearance(0.02, A)
    at_sf = design(eta=0.02, clearance_m=sf.clearance_m, amplitudes_m=A, census_n=0)
    best = design(eta_max=0.02, n_eta=1, amplitudes_m=A, census_n=0)
    assert at_sf.worst_ratio <= 1.3 * best.worst_ratio
    assert 1 / 1.3 <= sf.worst_ratio / at_sf.worst_ratio <= 1.3


@pytest.mark.slow
@pytest.mark.parametrize("eta, W, F", [(0.05, 1.0, 0.02), (0.1, 1.0, 0.03),
                                       (0.05, 0.995, 0.025)])
def test_smr_against_the_exact_run(eta, W, F):
    """Where the slow flow predicts SMR the exact run from rest is modulated: its LO
    amplitude per forcing period over [4000, 7000] swings by more than half its largest
    value, its smallest value is within 0.05 of the predicted cycle's smallest, its largest
    below the predicted 1; the predicted period is an overestimate by at most 3x (the ball
    re-engages before the LO reaches the clearance, docs/slowflow.md section 6)."""
    import vines
    r = response(eta, W, F)
    assert r.regime == "SMR"
    res = vines.simulate(eta=eta, omega=W, F=F)
    T = 2 * math.pi / W
    t = np.arange(4000.0, 7000.0, T / 64)
    n = len(t) // 64
    env = np.abs([res.state_at(x)[0] for x in t[: 64 * n]]).reshape(n, 64).max(axis=1)
    spec = np.abs(np.fft.rfft(env - env.mean()))
    period = n * T / (int(np.argmax(spec[1:])) + 1)
    assert env.max() - env.min() > 0.5 * env.max()
    assert abs(env.min() - r.smr[0]) < 0.05 and env.max() < r.smr[1]
    assert 1.0 <= r.smr_cycle.period / period <= 3.0
