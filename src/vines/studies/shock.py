"""Shocks and free decay: the LO given an initial velocity, no forcing (F = 0).

Dimensionless as the model (docs/model.md): time w0 t, lengths in units of the clearance L,
velocities in L w0, energies in M (L w0)^2 with M = 1 for the LO. Start: z_m = 0,
z_m' = v0, the ball (or the TMD's mass) at rest at the cavity centre (its rest position).

Energy E = (z_m'^2 + z_m^2 + eta z_b'^2) / 2 (the TMD adds mu y'^2 / 2 and
mu f^2 (y - x)^2 / 2). It leaves by

* LO damping: d times the integral of z_m'^2 (Gauss-Legendre on the closed-form flow of
  each recorded segment, pieces of at most ``PIECE``: exact to round-off);
* impacts (VI NES): the jump of E at each event of the exact solver: (1 - r^2) eta/(1 + eta)
  w'^2 / 2 at an impact, plus the loss to the common velocity when the ball sticks;
* the TMD's damper (2 mu zeta f times the integral of (y' - x')^2), key ``by_absorber``;

and remaining = E at the end. The linear systems (TMD, LO alone) in closed form: the state
by the matrix exponential, the dissipated integrals by Van Loan's block exponential.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import progress as _progress
from .shock_tmd import lo_system, tmd_system

#: default window: natural periods of the LO
N_PERIODS_DEFAULT = 10.0
N_PERIODS_MAX = 1e4
#: reported times per natural period of the LO
SAMPLES_PER_PERIOD = 32
#: energy levels of the decay times t_10 and t_1 (fractions of the initial energy)
LEVELS = (0.1, 0.01)
#: Gauss-Legendre nodes per piece, and the longest piece (dimensionless time)
GAUSS_NODES = 16
PIECE = 0.5
#: a regular gap between impacts is within REGULAR_TOL pi of pi (half a natural period,
#: alternating walls); REGULAR_RUN of them in a row make the two-impact regime
REGULAR_TOL = 0.25
REGULAR_RUN = 6
#: the progress task of ``energy_curve``
TASK = ("shock", "energies")

_X, _W = np.polynomial.legendre.leggauss(GAUSS_NODES)


@dataclass(frozen=True)
class Decay:
    """A free decay sampled at ``times``: remaining energy and the cumulative energies
    dissipated by LO damping, impacts and the absorber's damper (all / E0), impacts so far;
    the decay times to each of LEVELS (NaN: not reached); solver status; the LO amplitude
    where the two-impact regime ends (``two_impact_end``, NaN: not within the window)."""

    times: np.ndarray
    remaining: np.ndarray
    by_damping: np.ndarray
    by_impacts: np.ndarray
    by_absorber: np.ndarray
    n_impacts: np.ndarray
    t_levels: tuple
    status: str = "ok"
    n_sticks: int = 0
    stop_amplitude: float = math.nan

    def summary(self, time_unit: float = 1.0) -> dict:
        """The JSON keys at the end of the window (``t_reached``: the window's end, or where a
    run stopped early, see ``status``); times multiplied by ``time_unit``."""
        t10, t1 = (None if math.isnan(t) else t * time_unit for t in self.t_levels)
        return {"t_reached": float(self.times[-1] * time_unit),
                "dissipated_fraction": float(1.0 - self.remaining[-1]),
                "by_damping": float(self.by_damping[-1]),
                "by_impacts": float(self.by_impacts[-1]),
                "by_absorber": float(self.by_absorber[-1]),
                "remaining_fraction": float(self.remaining[-1]),
                "n_impacts": int(self.n_impacts[-1]), "t_10": t10, "t_1": t1,
                "status": self.status}


def report_times(periods: float) -> np.ndarray:
    """Reported times: SAMPLES_PER_PERIOD per natural period 2 pi, 0 and the end included."""
    n = max(2, int(math.ceil(periods * SAMPLES_PER_PERIOD)) + 1)
    return np.linspace(0.0, 2.0 * math.pi * periods, n)


def activation_velocity(d: float) -> float:
    """Smallest v0 (units of L w0) at which the free LO's first peak reaches the wall
    (|z_m| = 1, the ball at rest at the centre): below it the VI NES never impacts."""
    a = 0.5 * d
    if a < 1.0:
        wd = math.sqrt(1.0 - a * a)
        return math.exp(a * math.atan2(wd, a) / wd)
    if a == 1.0:
        return math.e
    s1, s2 = -a + math.sqrt(a * a - 1.0), -a - math.sqrt(a * a - 1.0)
    t = math.log(s2 / s1) / (s1 - s2)
    return (s1 - s2) / (math.exp(s1 * t) - math.exp(s2 * t))


def xi_min(r: float) -> float:
    """The slow flow's activation threshold (the SIM's fold, units of L) at restitution r."""
    from ..slowflow.manifold import rho
    from ..slowflow.manifold import xi_min as fold
    return float(fold(rho(r)))


def two_impact_end(impacts, t_last: float) -> float:
    """Pre-impact LO amplitude hypot(z_m, z_m') (units of L) where the symmetric two-impact
    regime of a free decay ends: at the last impact before a gap of more than a natural
    period 2 pi (to the next impact, or to ``t_last``) that closes a streak of gaps shorter
    than 2 pi at alternating walls holding REGULAR_RUN regular ones in a row
    (|gap - pi| < REGULAR_TOL pi). NaN if there is none within the window."""
    t, wall = np.asarray(impacts["t"]), np.asarray(impacts["wall"])
    gaps = np.diff(np.append(t, t_last))
    alt = wall[1:] != wall[:-1]
    regular = (np.abs(gaps[:-1] - math.pi) < REGULAR_TOL * math.pi) & alt
    streak = (gaps[:-1] <= 2.0 * math.pi) & alt
    run = best = 0              # regular gaps in a row; most of them in the current streak
    end = -1
    for i in range(gaps.size):
        if gaps[i] > 2.0 * math.pi:
            end = i if best >= REGULAR_RUN else end
            run = best = 0
        elif i == streak.size or not streak[i]:     # the window's end, or a break
            run = best = 0
        else:
            run = run + 1 if regular[i] else 0
            best = max(best, run)
    if end < 0:
        return math.nan
    return float(math.hypot(impacts["z_m"][end], impacts["v_m"][end]))


def _first_below(times, energy_at, remaining, level) -> float:
    """First time the (non-increasing) remaining energy is <= level: the sample bracket,
    then bisection to round-off; NaN if not reached."""
    hit = np.flatnonzero(remaining <= level)
    if hit.size == 0:
        return math.nan
    k = int(hit[0])
    if k == 0:
        return float(times[0])
    lo, hi = float(times[k - 1]), float(times[k])
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if energy_at(mid) <= level:
            hi = mid
        else:
            lo = mid
    return hi


# ----------------------------------------------------------------- VI NES (exact solver)

def _energy(states, eta) -> np.ndarray:
    zm, vm, _, vb = states
    return 0.5 * (vm * vm + zm * zm + eta * vb * vb)


def _damping_integral(traj, cuts, d) -> np.ndarray:
    """d * integral of z_m'^2 over each interval [cuts[i], cuts[i+1]] (cuts sorted, each
    interval inside one segment): Gauss-Legendre on pieces of at most PIECE."""
    lo, hi = cuts[:-1], cuts[1:]
    seg_idx = np.searchsorted(traj.segments[:, 0], lo, side="right") - 1
    n_pc = np.maximum(1, np.ceil((hi - lo) / PIECE).astype(np.int64))
    owner = np.repeat(np.arange(lo.size), n_pc)
    k = np.arange(owner.size) - np.repeat(np.cumsum(n_pc) - n_pc, n_pc)
    h = (hi - lo)[owner] / n_pc[owner]
    a = lo[owner] + k * h
    t = (a[:, None] + 0.5 * h[:, None] * (_X[None, :] + 1.0)).ravel()
    idx = np.repeat(seg_idx[owner], GAUSS_NODES)
    v = traj.on_segments(idx, t)[1].reshape(-1, GAUSS_NODES)
    piece = 0.5 * h * ((v * v) @ _W)
    return d * np.bincount(owner, weights=piece, minlength=lo.size)


def vines_decay(eta: float, r: float, d: float, v0: float, periods: float,
                max_impacts: int | None = None, ball: tuple = (0.0, 0.0)) -> Decay:
    """Free decay of the VI NES from (z_m, z_m', z_b, z_b') = (0, v0, ball) with F = 0 over
    ``periods`` natural periods of the LO, by the exact solver (validated inputs; the
    ball's position |z_b| < 1 in the cavity and velocity, default at rest in the centre;
    fractions of the initial energy of LO and ball)."""
    from ..core.exact import run_exact
    from ..core.params import MAX_IMPACTS_DEFAULT, ModelParams, SolverSettings
    times = report_times(periods)
    t_end = float(times[-1])
    p = ModelParams(eta=eta, omega=1.0, F=0.0, r=r, d=d)   # omega is idle at F = 0
    zb, vb = (float(x) for x in ball)
    st = SolverSettings(t_end=t_end, t_transient=0.0, state0=(0.0, v0, zb, vb),
                        max_impacts=max_impacts or MAX_IMPACTS_DEFAULT)
    raw = run_exact(p, st)
    traj = raw.state_at
    seg = traj.segments
    e0 = 0.5 * v0 * v0 + 0.5 * eta * vb * vb
    t_last = raw.t_last
    times = times[times <= t_last]
    # energy jumps at events: end of segment i against start of segment i + 1
    t_ev = seg[1:, 0]
    before = _energy(traj.on_segments(np.arange(t_ev.size), t_ev), eta)
    after = _energy(seg[1:, 1:5].T, eta)
    jump_cum = np.concatenate([[0.0], np.cumsum(before - after)]) / e0
    by_impacts = jump_cum[np.searchsorted(t_ev, times, side="right")]
    # damping: intervals between segment starts and reported times
    cuts = np.union1d(np.concatenate([seg[:, 0], times]), [t_last])
    damp_cum = np.concatenate([[0.0], np.cumsum(_damping_integral(traj, cuts, d))]) / e0
    by_damping = damp_cum[np.searchsorted(cuts, times)]
    remaining = _energy(traj(times), eta) / e0
    n_imp = np.searchsorted(raw.impacts["t"], times, side="right")

    def energy_at(t):
        return float(_energy(traj(np.array([t])), eta)[0]) / e0

    t_levels = tuple(_first_below(times, energy_at, remaining, lv) for lv in LEVELS)
    return Decay(times, remaining, by_damping, by_impacts, np.zeros_like(times), n_imp,
                 t_levels, raw.status, raw.n_sticks, two_impact_end(raw.impacts, t_last))


# ----------------------------------------------------------------- linear systems

def _gramian(A, Q, t) -> tuple[np.ndarray, np.ndarray]:
    """(expm(A t), integral_0^t expm(A s)^T Q expm(A s) ds) by Van Loan's block exponential."""
    from scipy.linalg import expm
    n = A.shape[0]
    big = np.zeros((2 * n, 2 * n))
    big[:n, :n], big[:n, n:], big[n:, n:] = -A.T, Q, A
    e = expm(big * t)
    phi = e[n:, n:]
    return phi, phi.T @ e[:n, n:]


def linear_decay(system: tuple, periods: float) -> Decay:
    """Free decay of a linear system (``lo_system``, ``tmd_system``) from x = (0, 1, 0, ...)
    in closed form; its fractions do not depend on the initial velocity."""
    from scipy.linalg import expm
    A, P, Q_d, Q_a = system
    x0 = np.zeros(A.shape[0])
    x0[1] = 1.0
    e0 = 0.5 * x0 @ P @ x0
    times = report_times(periods)
    h = float(times[1] - times[0])
    step, w_d = _gramian(A, Q_d, h)
    w_a = _gramian(A, Q_a, h)[1]
    out = np.zeros((3, times.size))
    x = x0
    for i in range(times.size):     # x(t + h) = expm(A h) x(t); the integrals add up
        out[0, i] = 0.5 * x @ P @ x
        if i + 1 < times.size:
            out[1:, i + 1] = out[1:, i] + (x @ w_d @ x, x @ w_a @ x)
            x = step @ x
    out /= e0

    def energy_at(t):
        x = expm(A * t) @ x0
        return 0.5 * x @ P @ x / e0

    t_levels = tuple(_first_below(times, energy_at, out[0], lv) for lv in LEVELS)
    zero = np.zeros(times.size)
    return Decay(times, out[0], out[1], zero, out[2], zero.astype(np.int64), t_levels)


def ball_starts(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """n ball states at the moment of the shock (numpy Generator seeded by ``seed``):
    positions uniform over the cavity (-1, 1) (units of L, the LO at its centre) and
    velocities uniform in (-1, 1) as fractions of the LO's initial velocity v0."""
    rng = np.random.default_rng(seed)
    draws = rng.uniform(-1.0, 1.0, size=(2, n))
    return draws[0], draws[1]


def start_distribution(eta: float, r: float, d: float, v0s, periods: float,
                       positions, velocity_fractions) -> np.ndarray:
    """Dissipated fraction of the VI NES (shape (len(v0s), n)) from each ball start
    (``ball_starts``) at each initial LO velocity v0 (units of L w0)."""
    out = np.empty((len(v0s), len(positions)))
    pairs = [(i, j) for i in range(len(v0s)) for j in range(len(positions))]
    for i, j in _progress.track(pairs, len(pairs), "shock", "ball starts"):
        v0 = float(v0s[i])
        dec = vines_decay(eta, r, d, v0, periods,
                          ball=(positions[j], velocity_fractions[j] * v0))
        out[i, j] = 1.0 - dec.remaining[-1]
    return out


def energy_curve(eta: float, r: float, d: float, v0s, periods: float) -> list[Decay]:
    """``vines_decay`` at each initial velocity of ``v0s`` (progress task TASK)."""
    return [vines_decay(eta, r, d, float(v), periods)
            for v in _progress.track(v0s, len(v0s), *TASK)]


# ----------------------------------------------------------------- the study (SI inputs)

#: largest initial velocity in units of L w0 (beyond it the run is all impacts)
V0_MAX = 1e6
#: most energies of one curve
N_ENERGIES_MAX = 10_000
#: most ball starts per energy, and the quantiles of their dissipated fractions reported
N_STARTS_MAX = 4096
QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)
#: JSON keys of one system's decay, in order
KEYS = ("t_reached", "dissipated_fraction", "by_damping", "by_impacts", "by_absorber",
        "remaining_fraction", "n_impacts", "t_10", "t_1", "status")


def check_initial(velocity_m_s, energy_J, energy_range) -> str:
    """Which initial condition is given: exactly one of 'velocity', 'energy', 'range'."""
    from ..core.params import ParameterError
    given = [k for k, v in (("velocity", velocity_m_s), ("energy", energy_J),
                            ("energy_range", energy_range)) if v is not None]
    if len(given) != 1:
        name = given[1] if len(given) > 1 else "velocity"
        raise ParameterError(name, None if not given else "given with " + given[0],
                             "give exactly one of velocity, energy, energy_range")
    return given[0]


def check_energy_range(rng, M: float, v_unit: float) -> np.ndarray:
    """Energies [J] of a curve: (A, B, N), 0 < A < B, 2 <= N <= N_ENERGIES_MAX,
    geometric; each initial velocity <= V0_MAX L w0."""
    from ..core.params import ParameterError, check_int, check_real
    try:
        a, b, n = rng
    except (TypeError, ValueError):
        raise ParameterError("energy_range", rng, "must be three values A B N") from None
    hi = 0.5 * M * (V0_MAX * v_unit) ** 2
    a = check_real("energy_range", a, lo=0.0, lo_open=True, hi=hi)
    b = check_real("energy_range", b, lo=0.0, lo_open=True, hi=hi)
    if not a < b:
        raise ParameterError("energy_range", list(rng), "must be A B N with 0 < A < B")
    n = check_int("energy_range", n, lo=2, hi=N_ENERGIES_MAX)
    return np.geomspace(a, b, n)


def check_energy(name: str, energy_J, M: float, v_unit: float) -> float:
    """An initial energy [J]: > 0, its initial velocity <= V0_MAX L w0."""
    from ..core.params import check_real
    return check_real(name, energy_J, lo=0.0, lo_open=True,
                      hi=0.5 * M * (V0_MAX * v_unit) ** 2)


def _initial_velocity(velocity_m_s, energy_J, M: float, v_unit: float) -> float:
    """Initial LO velocity [m/s] from velocity or energy E = M V^2 / 2 (one is given)."""
    from ..core.params import check_real
    if velocity_m_s is not None:
        return check_real("velocity", velocity_m_s, lo=0.0, lo_open=True,
                          hi=V0_MAX * v_unit)
    return math.sqrt(2.0 * check_energy("energy", energy_J, M, v_unit) / M)


def check_inputs(*, eta, clearance_m, periods=N_PERIODS_DEFAULT, M_kg=None, k_N_per_m=None,
                 c_Ns_per_m=None, d=None, r=None, omega_band=None) -> dict:
    """The validated inputs of ``shock`` besides the initial condition (keys eta,
    clearance_m, periods, M_kg, k_N_per_m, c_Ns_per_m, d, r, omega_band, w0, v_unit: the
    natural frequency [rad/s] and the velocity unit L w0 [m/s]); ParameterError."""
    from ..core.params import R_DEFAULT, check_param, check_real
    from .design_checks import DEFAULT_BAND, check_band, check_eta, check_structure
    M, k, c, d = check_structure(M_kg, k_N_per_m, c_Ns_per_m, d)
    r = check_param("r", R_DEFAULT if r is None else r)
    eta = check_eta("eta", eta)
    L = check_real("clearance", clearance_m, lo=0.0, lo_open=True, hi=1e6)
    periods = check_real("periods", periods, lo=0.0, lo_open=True, hi=N_PERIODS_MAX)
    band = check_band(DEFAULT_BAND if omega_band is None else omega_band)
    w0 = math.sqrt(k / M)
    return {"eta": eta, "clearance_m": L, "periods": periods, "M_kg": M, "k_N_per_m": k,
            "c_Ns_per_m": c, "d": d, "r": r, "omega_band": band, "w0": w0,
            "v_unit": L * w0}


def _series(decays: list[Decay], key: str, time_unit: float) -> list:
    return [dec.summary(time_unit)[key] for dec in decays]


def shock(*, eta, clearance_m, velocity_m_s=None, energy_J=None, energy_range=None,
          periods=N_PERIODS_DEFAULT, M_kg=None, k_N_per_m=None, c_Ns_per_m=None, d=None,
          r=None, omega_band=None, starts=0, seed=0) -> dict:
    """Free decay after an impulse: the VI NES (eta, clearance) by the exact solver, the
    equal-mass TMD tuned for ``omega_band`` as ``vines.design`` tunes it, the LO alone.

    Give one of velocity_m_s (LO's initial velocity), energy_J (E0 = M V0^2 / 2) or
    energy_range (A, B, N: N energies from A to B J, geometric). Window: ``periods``
    natural periods of the LO. Structure as ``vines.design`` (Table 1 by default).
    Besides the band-tuned TMD (``tmd``): the TMD decaying fastest (``tmd_fastest``) and
    the fastest whose travel stays within the clearance at the largest shock
    (``tmd_equal_travel``), each with its stroke (``shock_tmd``). ``starts`` > 0: that
    many ball states at the moment of the shock (``ball_starts``, seeded by ``seed``) and
    the distribution of the VI NES's dissipated fraction over them (key ``starts``; the
    ball at rest in the centre stays the VI NES's own result). Returns a JSON-ready dict
    (keys inputs, scales, activation, vines, tmd, tmd_fastest, tmd_equal_travel, lo_alone,
    stroke, starts and, for one shock, history and the VI NES's impacts_stop_amplitude
    beside the slow flow's xi_min; for a range, curve and optimal). ParameterError on bad
    input.
    """
    import time

    from ..core.params import check_int
    from .tmd import optimal_tmd
    t0 = time.perf_counter()
    inp = check_inputs(eta=eta, clearance_m=clearance_m, periods=periods, M_kg=M_kg,
                       k_N_per_m=k_N_per_m, c_Ns_per_m=c_Ns_per_m, d=d, r=r,
                       omega_band=omega_band)
    eta, L, periods, M, k, c, d, r, band, w0, v_unit = (
        inp[key] for key in ("eta", "clearance_m", "periods", "M_kg", "k_N_per_m",
                             "c_Ns_per_m", "d", "r", "omega_band", "w0", "v_unit"))
    mode = check_initial(velocity_m_s, energy_J, energy_range)
    if mode == "energy_range":
        energies = check_energy_range(energy_range, M, v_unit)
        velocities = np.sqrt(2.0 * energies / M)
    else:
        velocities = np.array([_initial_velocity(velocity_m_s, energy_J, M, v_unit)])
    starts = check_int("starts", starts, lo=0, hi=N_STARTS_MAX)
    seed = check_int("seed", seed, lo=0, hi=2**63 - 1)
    tmd = optimal_tmd(eta, d, band)
    tunings = _shock_tunings(eta, d, tmd, v_unit / float(velocities.max()))
    lin = {"tmd": linear_decay(tmd_system(d, eta, tmd.frequency_ratio, tmd.damping_ratio),
                               periods),
           "lo_alone": linear_decay(lo_system(d), periods)}
    lin.update({name: linear_decay(tmd_system(d, eta, t["f"], t["zeta"]), periods)
                for name, t in tunings.items() if t is not None and name != "tmd"})
    decays = energy_curve(eta, r, d, velocities / v_unit, periods)
    v_act = activation_velocity(d) * v_unit
    out = {
        "inputs": {"mode": mode, "eta": eta, "clearance_m": L, "M_kg": M, "k_N_per_m": k,
                   "c_Ns_per_m": c, "d": d, "r": r, "periods": periods,
                   "omega_band": list(band)},
        "scales": {"w0_rad_s": w0, "natural_period_s": 2.0 * math.pi / w0,
                   "window_s": 2.0 * math.pi * periods / w0, "velocity_unit_m_s": v_unit,
                   "energy_unit_J": M * v_unit * v_unit},
        "activation": {"velocity_m_s": v_act, "energy_J": 0.5 * M * v_act * v_act},
        "tmd": {**lin["tmd"].summary(1.0 / w0), "design": tmd.to_dict(),
                **_stroke(tunings["tmd"], velocities, w0)},
        "lo_alone": {**lin["lo_alone"].summary(1.0 / w0),
                     "x_max_m": _lo_peak(d) * float(velocities.max()) / w0},
    }
    for name in ("tmd_fastest", "tmd_equal_travel"):
        t = tunings[name]
        out[name] = None if t is None else {
            **lin[name].summary(1.0 / w0),
            "design": {"eta": eta, "frequency_ratio": t["f"], "damping_ratio": t["zeta"]},
            **_stroke(t, velocities, w0)}
    if out["tmd_equal_travel"] is not None:
        out["tmd_equal_travel"].update(max_stroke_m=L,
                                       binding=tunings["tmd_equal_travel"]["binding"])
    out["stroke"] = STROKE_DESCRIPTION
    if mode == "energy_range":
        out["curve"] = _curve(decays, energies, velocities, lin, 1.0 / w0)
        frac = np.array(out["curve"]["vines"]["dissipated_fraction"])
        best = int(np.argmax(frac))
        out["optimal"] = {"energy_J": float(energies[best]),
                          "velocity_m_s": float(velocities[best]),
                          "dissipated_fraction": float(frac[best])}
        out["vines"] = {"n_sticks": [dec.n_sticks for dec in decays], "stroke_m": L}
    else:
        dec = decays[0]
        out["inputs"].update(velocity_m_s=float(velocities[0]),
                             energy_J=float(0.5 * M * velocities[0] ** 2))
        stop = dec.stop_amplitude
        out["vines"] = {**dec.summary(1.0 / w0), "n_sticks": dec.n_sticks,
                        "impacts_stop_amplitude": None if math.isnan(stop) else stop,
                        "xi_min": xi_min(r), "stroke_m": L}
        out["history"] = _history(dec, lin, 1.0 / w0)
    out["starts"] = None
    if starts > 0:
        pos, frac = ball_starts(starts, seed)
        dist = start_distribution(eta, r, d, velocities / v_unit, periods, pos, frac)
        out["starts"] = {
            "n": starts, "seed": seed, "ball_position": pos.tolist(),
            "ball_velocity_fraction": frac.tolist(),
            "dissipated_fraction": dist.tolist() if mode == "energy_range" else dist[0].tolist(),
            "quantiles": list(QUANTILES),
            "dissipated_fraction_quantiles": (
                np.quantile(dist, QUANTILES, axis=1).T.tolist() if mode == "energy_range"
                else np.quantile(dist[0], QUANTILES).tolist()),
            "description": STARTS_DESCRIPTION}
    out["cost"] = {"wall_s": time.perf_counter() - t0,
                   "n_runs": len(decays) + starts * len(velocities)}
    return out


#: what ``stroke_m`` and ``x_max_m`` mean in a shock's JSON (key ``stroke``)
STROKE_DESCRIPTION = {
    "tmd": "peak |y - x| after the shock: the TMD mass's largest displacement relative to "
           "the LO over all later time (closed form, linear in the initial velocity; at the "
           "largest velocity of a range); stroke_per_velocity_s: the same per m/s",
    "vines": "the ball's travel relative to the LO: +-L, the clearance",
    "x_max_m": "the LO's own peak |x| after the shock (linear systems, largest velocity)",
    "tmd_fastest": "the tuning maximising the slowest decay rate of LO + TMD: the two "
                   "modes coalesce (docs/design.md)",
    "tmd_equal_travel": "the fastest-decaying tuning whose stroke stays within the "
                        "clearance L at the largest shock (binding: whether the limit "
                        "changes it; null when no tuning meets it)"}
#: what the ``starts`` block holds
STARTS_DESCRIPTION = (
    "the ball's state at the moment of the shock drawn at random (numpy Generator, seed): "
    "position uniform over the cavity (units of L, LO at the centre), velocity uniform "
    "within +-v0 (fractions of the LO's initial velocity); dissipated_fraction: of the "
    "initial energy of LO and ball, per start (per energy for a range); the VI NES's own "
    "keys keep the ball at rest in the centre")


def _lo_peak(d: float) -> float:
    """Peak |x| of the LO alone after the unit shock x'(0) = 1."""
    from .shock_tmd import peak_response
    A, P, _, _ = lo_system(d)
    return peak_response(A, P, np.array([1.0, 0.0]), np.array([0.0, 1.0]))[0]


def _shock_tunings(eta, d, tmd, max_travel) -> dict:
    """(f, zeta, binding) of the band-tuned TMD, the fastest and the fastest within
    ``max_travel`` (units of L per unit initial velocity; None when none meets it), with
    their peaks after the unit shock (``shock_tmd.shock_peaks``)."""
    from ..core.params import ParameterError
    from . import shock_tmd as st
    out = {"tmd": dict(f=tmd.frequency_ratio, zeta=tmd.damping_ratio)}
    f, z, _ = st.tmd_fastest(eta, d)
    out["tmd_fastest"] = dict(f=f, zeta=z)
    try:
        f, z, _ = st.tmd_equal_travel(eta, d, max_travel)
        out["tmd_equal_travel"] = dict(f=f, zeta=z, binding=(f, z) != (
            out["tmd_fastest"]["f"], out["tmd_fastest"]["zeta"]))
    except ParameterError:
        out["tmd_equal_travel"] = None
    for t in out.values():
        if t is not None:
            t.update(st.shock_peaks(d, eta, t["f"], t["zeta"]))
    return out


def _stroke(t: dict, velocities, w0: float) -> dict:
    """Stroke, LO peak and decay rate of a tuning (``_shock_tunings``) in SI units, at the
    largest initial velocity."""
    v = float(velocities.max())
    return {"stroke_m": t["travel"] * v / w0, "x_max_m": t["x_max"] * v / w0,
            "stroke_per_velocity_s": t["travel"] / w0,
            "slowest_decay_rate_per_s": t["rate"] * w0}


def _curve(decays, energies, velocities, lin, time_unit) -> dict:
    """The curve against initial energy: the VI NES per energy, the linear ones repeated
    (their fractions do not depend on the energy)."""
    n = len(decays)
    return {"energy_J": energies.tolist(), "velocity_m_s": velocities.tolist(),
            "vines": {key: _series(decays, key, time_unit) for key in KEYS},
            **{name: {key: [dec.summary(time_unit)[key]] * n for key in KEYS}
               for name, dec in lin.items()}}


def _history(dec: Decay, lin: dict, time_unit: float) -> dict:
    """The energies in time (fractions of E0) at the reported times [s]."""
    def one(x: Decay) -> dict:
        return {"remaining_fraction": x.remaining.tolist(),
                "by_damping": x.by_damping.tolist(), "by_impacts": x.by_impacts.tolist(),
                "by_absorber": x.by_absorber.tolist(), "n_impacts": x.n_impacts.tolist()}
    return {"t_s": (dec.times * time_unit).tolist(), "vines": one(dec),
            **{name: one(x) for name, x in lin.items()}}
