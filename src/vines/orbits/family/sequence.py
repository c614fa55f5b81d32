"""Periodic orbits of any wall sequence: fixed points of the composed impact maps.

A family is named by its wall sequence and its number of forcing periods (docs/
bifurcation.md, "Families of periodic orbits"): ``walls`` = "LLRR", ``periods`` = 1 is the
orbit with pre-impact states x_0 .. x_{n-1} (x = (z_m', z_b', z_b, t), ``orbits.maps.impact``) at
walls L, L, R, R, in that order, whose maps P(walls[k] -> walls[k+1]) (cyclically) bring
x_0 back to x_0 + (0, 0, 0, periods T). Unknown x_0; Newton on the composed map with the
exact Jacobian J_{n-1} ... J_0 - I (``newton.newton_sequence``, the iteration of
``periodic`` as well). Admissibility flight by flight (``maps.admissible_kernel``), stability
from the eigenvalues of J_{n-1} ... J_0.

Seeds (each polished by that Newton iteration, then deduplicated): those of the family's
engine (``Family.engine``, ``family.seeds``): the affine forms and short simulations; and
caller-supplied seeds (orbits of the same sequence, e.g. from a neighbouring parameter
point, or (x_0, flight times) pairs).

A root whose orbit repeats a shorter sequence (e.g. "LRLR", 2 on a 1:1 orbit) is not an
orbit of this family and is dropped.
"""
from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ...core.exact import oscillators
from ...core.flow import flow
from ...core.params import (
    T_END_MAX,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_bool,
    check_params_arg,
    check_real,
    check_reals,
)
from ...core.walls import impact_velocities
from ..maps.affine import scan_seeds  # noqa: F401 (re-export)
from ..maps.impact import admissible_kernel, impact_map, model_array
from ..maps.newton import monodromy, newton_sequence
from .family import (
    WALL_CODES,
    Family,
    check_periods,
    check_walls,
    has_half_symmetry,
    mirror_walls,
)
from .names import wall_codes
from .orbit import (  # noqa: F401 (SequenceOrbit: re-export, the former name)
    FAMILY_KEYS,
    PeriodicOrbit,
    SequenceOrbit,
)
from .periodic import DEDUP_TOL, SYM_TOL
from .seeds import (  # noqa: F401 (re-exports: the seeds' names as before)
    SIM_STATES,
    SIM_T_END,
    mirror_record,
    record_seed,
    simulation_seeds,
)

# --------------------------------------------------------------------------- orbits

def is_symmetric(walls: str, periods: int, flight_times: ArrayLike) -> bool:
    """The orbit with these flight times has the half-period symmetry
    (``orbit.PeriodicOrbit.symmetric``)."""
    n = len(walls)
    if periods % 2 == 0 or not has_half_symmetry(walls):
        return False
    h = n // 2
    return bool(np.all(np.abs(np.asarray(flight_times[:h]) - flight_times[h:]) <= SYM_TOL))


def _orbit(p: ModelParams, mdl: np.ndarray, walls: str, periods: int, xs: np.ndarray,
           Js: np.ndarray, fl: np.ndarray, res: float) -> PeriodicOrbit:
    n = len(walls)
    codes = wall_codes(walls)
    adm = all(admissible_kernel(mdl, xs[k], (codes[k], codes[(k + 1) % n]), fl[k])
              for k in range(n))
    ev = np.linalg.eigvals(monodromy(list(Js)))
    ev = ev[np.argsort(-np.abs(ev))]
    lam = float(np.hypot(ev.real, ev.imag).max())
    states = xs[:n].copy()
    return PeriodicOrbit(
        walls=walls, periods=periods, states=states, flight_times=fl.copy(),
        symmetric=is_symmetric(walls, periods, fl), admissible=bool(adm), eigenvalues=ev,
        lambda_max=lam, stable=bool(adm and lam < 1.0), dw=states[:, 0] - states[:, 1],
        phases=np.mod(p.omega * states[:, 3] + p.phi, 2.0 * math.pi), residual=float(res),
        jacobians=Js.copy(), params=p, keys=FAMILY_KEYS)


def solve_sequence(p: ModelParams, walls: str, periods: int, x0: ArrayLike,
                   flight_times: ArrayLike | None = None,
                   osc: np.ndarray | None = None) -> PeriodicOrbit | None:
    """Newton from x0 (pre-impact state at walls[0]) with optional flight-time guesses.

    The orbit found (any admissibility), or None when Newton fails, a flight time is not
    positive, the flights do not add up to periods T, or the orbit repeats a shorter
    sequence.
    """
    mdl = model_array(p, osc)
    n = len(walls)
    codes = wall_codes(walls)
    T = p.period
    NT = periods * T
    s = np.full(n, -1.0) if flight_times is None else np.array(flight_times, dtype=float)
    xs = np.empty((n + 1, 4))
    Js = np.empty((n, 4, 4))
    P = np.empty((4, 4))
    x0 = np.asarray(x0, dtype=float).copy()
    res = newton_sequence(mdl, codes, NT, x0, s, xs, Js, P)
    if not math.isfinite(res) or not np.all(np.isfinite(xs[0])):
        return None
    if not np.all(s > 0.0) or abs(s.sum() - NT) > 1e-8 * (1.0 + NT):
        return None
    k = math.floor(xs[0, 3] / T)
    if k != 0:
        xs[:, 3] -= k * T
    if not _primitive(walls, periods, xs, s, T):
        return None
    return _orbit(p, mdl, walls, periods, xs, Js, s, res)


def orbit_through(p: ModelParams, walls: str, periods: int, x0: ArrayLike,
                  flight_times: ArrayLike) -> PeriodicOrbit | None:
    """The orbit through x0 (pre-impact state at walls[0]) as it stands, classified without
    Newton: for a point an augmented system has already solved (a curve point). A fresh
    Newton on the orbit residual alone is ill-conditioned there: at a fold or branch point
    its Jacobian is singular and a solve from the point drifts by about the square root of
    the corrector's tolerance, enough to flip a marginal admissibility. flight_times:
    guesses of the maps' flight times. None where a map fails, a flight time is not
    positive, the flights do not add up to periods T or the orbit repeats a shorter
    sequence (as ``solve_sequence``)."""
    mdl = model_array(p)
    n, codes, T = len(walls), wall_codes(walls), p.period
    xs, Js, fl = np.empty((n + 1, 4)), np.empty((n, 4, 4)), np.empty(n)
    xs[0] = np.asarray(x0, dtype=float)
    for k in range(n):
        fl[k] = impact_map(mdl, xs[k], (codes[k], codes[(k + 1) % n]), flight_times[k],
                           xs[k + 1], Js[k])
        if not (fl[k] > 0.0):           # nan (a map failed) or not a flight
            return None
    if abs(fl.sum() - periods * T) > 1e-8 * (1.0 + periods * T):
        return None
    res = float(np.max(np.abs(xs[n] - xs[0] - np.array([0.0, 0.0, 0.0, periods * T]))))
    xs[:, 3] -= math.floor(xs[0, 3] / T) * T
    if not _primitive(walls, periods, xs, fl, T):
        return None
    return _orbit(p, mdl, walls, periods, xs, Js, fl, res)


def _primitive(walls, periods, xs, fl, T) -> bool:
    """False when the orbit repeats itself after m < n impacts (a shorter family)."""
    n = len(walls)
    for m in range(1, n):
        if n % m or walls[m:] + walls[:m] != walls:
            continue
        tau = float(np.sum(fl[:m]))
        j = round(tau / T)
        if j >= 1 and abs(tau - j * T) <= 1e-6 * (1.0 + T) and np.all(
                np.abs(xs[m, :3] - xs[0, :3]) <= 1e-6 * (1.0 + np.abs(xs[0, :3]))):
            return False
    return True


def same_orbit(a: PeriodicOrbit, b: PeriodicOrbit, T: float) -> bool:
    """a and b are the same orbit (b possibly started at another impact of the same
    wall pattern), to DEDUP_TOL."""
    if a.walls != b.walls or a.periods != b.periods:
        return False
    n = len(a.walls)
    for k in range(n):
        if b.walls[k:] + b.walls[:k] != a.walls:
            continue
        dt = abs(a.states[0, 3] - b.states[k, 3]) % T
        dt = min(dt, T - dt)
        if dt <= DEDUP_TOL * (1.0 + T) and np.all(
                np.abs(a.states[0, :3] - b.states[k, :3])
                <= DEDUP_TOL * (1.0 + np.abs(a.states[0, :3]))):
            return True
    return False


def dedup(orbits: Iterable[PeriodicOrbit | None], T: float) -> list[PeriodicOrbit]:
    """The orbits without None and repeats (``same_orbit``), first occurrences kept."""
    out = []
    for o in orbits:
        if o is not None and not any(same_orbit(o, q, T) for q in out):
            out.append(o)
    return out


# --------------------------------------------------------------------------- seeds

def affine_seeds(p: ModelParams, osc: np.ndarray | None, walls: str, periods: int) -> list:
    """Seeds (x_0, flight times) from the affine forms of the family's engine
    (``family.seeds``)."""
    mdl = model_array(p, osc)
    return Family(walls, periods).engine.affine_seeds(p, mdl, walls, periods)


def _sort_key(o: PeriodicOrbit):
    return (not o.admissible, not o.stable, not o.symmetric, o.lambda_max)


def find_sequence(params: ModelParams, walls: str, periods: int = 1, *,
                  seeds: list | None = None, simulation: bool = True,
                  sim_states: Sequence = SIM_STATES) -> list[PeriodicOrbit]:
    """Every distinct orbit of the sequence found (admissible or not), stable admissible
    ones first (the order of ``find_1to1``).

    ``seeds``: extra starting points, each a ``PeriodicOrbit`` of the same sequence (or of
    its mirror image, mirrored) or a pair (x_0, flight times). ``simulation``: also seed from
    short simulations from ``sim_states`` (for "LR", 1: from rest only, as ``find_1to1``).
    Raises ParameterError on a bad ``walls`` or ``periods``.
    """
    p = check_params_arg("params", params)
    walls = check_walls(walls)
    periods = check_periods(periods)
    seeds = check_sequence_seeds(seeds, walls)
    simulation = check_bool("simulation", simulation)
    sim_states = check_states("sim_states", sim_states)
    mdl = model_array(p)
    if p.F == 0.0:
        return []
    engine = Family(walls, periods).engine
    starts = engine.affine_seeds(p, mdl, walls, periods)
    if simulation:
        starts += engine.simulation_seeds(p, mdl, walls, sim_states)
    return solve_seeds(p, mdl, walls, periods, starts, seeds)


def _check_list(name, values) -> list:
    """``values`` as a list (None: empty); ParameterError if it is not a list or tuple."""
    if values is None:
        return []
    if not isinstance(values, (list, tuple)):
        raise ParameterError(name, values, "must be a list or tuple")
    return list(values)


def check_sequence_seeds(seeds: object, walls: str) -> list:
    """The seeds of ``find_sequence``: PeriodicOrbits or pairs (x_0, flight times) with x_0
    4 finite numbers and one flight time per wall of ``walls``; ParameterError otherwise."""
    allowed = ("must be None or a list of seeds, each a PeriodicOrbit or a pair (x_0, flight "
               f"times): x_0 4 finite numbers, {len(walls)} finite flight times")
    out = []
    for sd in _check_list("seeds", seeds):
        if isinstance(sd, PeriodicOrbit):
            out.append(sd)
            continue
        if not isinstance(sd, (list, tuple)) or len(sd) != 2:
            raise ParameterError("seeds", seeds, allowed)
        try:
            out.append((check_reals("seeds", sd[0], min_size=4, max_size=4),
                        check_reals("seeds", sd[1], min_size=len(walls), max_size=len(walls))))
        except ParameterError:
            raise ParameterError("seeds", seeds, allowed) from None
    return out


def check_states(name: str, states: object) -> list:
    """Initial states (z_m, z_m', z_b, z_b') as ``SolverSettings.state0`` accepts them."""
    out = []
    for s0 in _check_list(name, states):
        try:
            out.append(SolverSettings(t_end=1.0, t_transient=0.0, state0=s0).state0)
        except ParameterError as err:
            raise ParameterError(name, states, f"each state {err.allowed}") from None
    return out


def check_sim_t_end(value: object) -> float:
    """Length of a seeding simulation (0 < sim_t_end <= T_END_MAX)."""
    return check_real("sim_t_end", value, lo=0.0, lo_open=True, hi=T_END_MAX)


def solve_seeds(p: ModelParams, osc: np.ndarray | None, walls: str, periods: int,
                starts: Iterable, seeds: Iterable = ()) -> list[PeriodicOrbit]:
    """Newton from every (x_0, flights) in ``starts`` and every seed of ``seeds`` (see
    ``find_sequence``); distinct orbits, stable admissible ones first."""
    starts = list(starts)
    for sd in seeds or ():
        starts += _user_seed(sd, walls, p.period)
    found = [solve_sequence(p, walls, periods, x0, fl, osc) for x0, fl in starts]
    out = dedup(found, p.period)
    out.sort(key=_sort_key)
    return out


def _user_seed(sd, walls: str, T: float) -> list:
    """(x_0, flights) from a seed: a pair, or an orbit of the same sequence or of its mirror
    image, started at any impact whose rotation of the sequence is ``walls``."""
    if not isinstance(sd, PeriodicOrbit):
        x0, fl = sd
        return [(x0, fl)]
    out = []
    n = len(sd.walls)
    for mirrored, w in ((False, sd.walls), (True, mirror_walls(sd.walls))):
        for k in range(n):
            if w[k:] + w[:k] != walls:
                continue
            x = np.array(sd.states[k], dtype=float)
            if mirrored:
                x = np.array([-x[0], -x[1], -x[2], x[3] + 0.5 * T])
            out.append((x, np.roll(sd.flight_times, -k)))
    return out


# --------------------------------------------------------------------------- flips, states

def _real_eigenvector(orbit: PeriodicOrbit, negative: bool):
    """Unit eigenvector of the most negative (negative) or largest positive real eigenvalue
    of the orbit's monodromy matrix, or None."""
    ev, V = np.linalg.eig(monodromy(list(orbit.jacobians)))
    real = [k for k in range(4) if abs(ev[k].imag) <= 1e-9 * max(1.0, abs(ev[k]))
            and (ev[k].real < 0.0) == negative and ev[k].real != 0.0]
    if not real:
        return None
    k = min(real, key=lambda j: ev[j].real) if negative else max(real, key=lambda j: ev[j].real)
    return V[:, k].real / np.linalg.norm(V[:, k].real)


def flip_seeds(orbit: PeriodicOrbit, eps: Sequence[float] = (1e-3, 1e-2, 3e-2)) -> list:
    """Seeds of the period-doubled sequence (walls twice, 2 periods) near ``orbit``: its
    start displaced by +- eps along the eigenvector of its most negative real eigenvalue
    (a flip point of the family gives birth to that branch). Empty without such an
    eigenvalue."""
    v = _real_eigenvector(orbit, True)
    if v is None:
        return []
    fl = np.concatenate([orbit.flight_times, orbit.flight_times])
    return [(orbit.states[0] + sg * e * v, fl) for e in eps for sg in (1.0, -1.0)]


def pitchfork_seeds(orbit: PeriodicOrbit, eps: Sequence[float] = (1e-2, 5e-2)) -> list:
    """Seeds of asymmetric orbits of the same sequence near a symmetric ``orbit``: its start
    displaced by +- eps along the eigenvector of its largest positive real eigenvalue (a
    symmetry-breaking point gives birth to the asymmetric pair there)."""
    v = _real_eigenvector(orbit, False)
    if v is None:
        return []
    return [(orbit.states[0] + sg * e * v, orbit.flight_times) for e in eps for sg in (1.0, -1.0)]


def state_at(orbit: PeriodicOrbit, t: float) -> np.ndarray:
    """State (z_m, z_m', z_b, z_b') of the orbit at absolute time t (any t: the orbit is
    periodic with period periods T), by the closed-form flight from the impact before t."""
    p = orbit.params
    osc = oscillators(p)[0]
    n = len(orbit.walls)
    P = orbit.periods * p.period
    t0 = orbit.states[0, 3]
    tau = (t - t0) % P
    k = int(np.searchsorted(np.cumsum(orbit.flight_times), tau, side="right"))
    k = min(k, n - 1)
    x = orbit.states[k]
    s = tau - (x[3] - t0)
    vp, vbp = impact_velocities(p.eta, p.r, x[0], x[1])
    th0 = p.omega * x[3] + p.phi
    z, v, _, _, _ = flow(osc, x[2] + WALL_CODES[orbit.walls[k]], vp, math.sin(th0),
                         math.cos(th0), s)
    return np.array([z, v, x[2] + vbp * s, vbp])
