"""1:1 periodic orbits: fixed points of P2∘P1 with the time shifted by T = 2 pi / omega.

Unknowns x_L = (z_m', z_b', z_b, t_L), the pre-impact state at wall L. The orbit solves
P2(P1(x_L)) = x_L + (0, 0, 0, T): the sequence "LR", 1 of ``newton.newton_sequence`` (exact
Jacobian J_P2(x_R) J_P1(x_L) - I).

Seeds (every seed is polished by that Newton iteration on the true maps, then deduplicated):

* symmetric ansatz: P1(x_L) = mirror(x_L) + (0, 0, 0, T/2), mirror flipping the signs of
  positions and velocities (the model is invariant under z -> -z, t -> t + T/2). With the
  flight time fixed at T/2 every condition is affine in (z_m', z_b', z_b, sin theta_L,
  cos theta_L) (``affine``), so the symmetric orbits are the intersections of a line with
  the unit circle: zero or two per parameter point, in closed form. This replaces a scan of
  t_L over [0, T).
* asymmetric scan: with the L->R flight time s1 fixed (R->L flight T - s1) the five
  conditions (arrival at R, arrival at L, periodicity of z_m', z_b', z_b) are again affine in
  those five unknowns; the orbit exists where the solution has sin^2 + cos^2 = 1. s1 is
  scanned over (0, T) and sign changes of sin^2 + cos^2 - 1 are refined by bisection.
* a short simulation (t_end ~ 600) from rest: its last L impact followed by R and L.
* caller-supplied seeds (continuation): x_L arrays, optionally with flight times.

One solver serves both interfaces: ``orbit_solve``/``orbit_classify``/``seed_kernel`` (end
of the module) work nogil on float rows, for threaded per-point drivers
(``stability_map``); ``solve_orbit``/``seed_orbits`` wrap the same compiled Newton and seeds
into ``PeriodicOrbit`` objects (``orbit``, the one orbit type of every family; eigenvalues
by numpy; the compiled ones by scipy's dgeev, ``lapack``: the same bits where numpy and
scipy share a LAPACK build).
"""
from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike

from ..._jit import njit
from ...core.flow import I_F, I_W
from ...core.params import (
    D_DEFAULT,
    R_DEFAULT,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_bool,
    check_reals,
)
from ...core.walls import WALL_L, WALL_R
from ..maps.affine import N_SEEDS_MAX, closed_form_kernel, closed_form_seeds, scan_seeds
from ..maps.affine import scan as affine_scan
from ..maps.impact import M_PHI, admissible_kernel, model_array
from ..maps.lapack import lambda_max_4
from ..maps.newton import monodromy, newton_sequence
from .orbit import KEYS_1TO1, PeriodicOrbit

SYM_TOL = 1e-6          # flight times equal to this: symmetric
DEDUP_TOL = 1e-8
#: the wall codes of a 1:1 orbit: flight L -> R, then R -> L
LR = np.array([WALL_L, WALL_R], dtype=np.int64)
# read-only like every wall-code array passed to the kernels (``sequence._codes``): inside a
# compiled function a global array is a read-only constant, so Python calls then use the
# same compiled specialization instead of compiling a second one
LR.setflags(write=False)


# --------------------------------------------------------------------------- seeds

def symmetric_seeds(mdl: np.ndarray) -> list:
    """The (0 or 2) symmetric 1:1 candidates (z_m', z_b', z_b, theta_L) of the model mdl
    (``maps.pack_model``): flight L -> R of time T/2 onto the mirror image."""
    return closed_form_seeds(mdl, LR, 0.5 * (2.0 * math.pi / mdl[I_W]), -1)


def asymmetric_seeds(mdl: np.ndarray) -> np.ndarray:
    """Rows (z_m', z_b', z_b, theta_L, s1) of the scan of the L -> R flight time s1 (R -> L:
    T - s1; the second flight starts where the first one ends)."""
    return affine_scan(mdl, LR, 2.0 * math.pi / mdl[I_W], 1, carry=True)


# --------------------------------------------------------------------------- orbits

def solve_orbit(p: ModelParams, x0: ArrayLike, s1: float = -1.0, s2: float = -1.0,
                osc: np.ndarray | None = None) -> PeriodicOrbit | None:
    """Newton from x0 (flight-time guesses s1, s2, <= 0: first contact); the orbit, or None
    (``orbit_solve``). osc: the free oscillator of p, if already built."""
    mdl = model_array(p, osc)
    ws = orbit_workspace()
    ws[0][:] = np.asarray(x0, dtype=float)
    res = orbit_solve(mdl, (float(s1), float(s2)), np.empty(N_ROW), ws)
    if not math.isfinite(res):
        return None
    xs, Js, fl = ws[1], ws[2], ws[3]
    return classify_orbit(p, mdl, xs[0], xs[1], (Js[0], Js[1]), fl, res)


def monodromy_eigenvalues(J1: np.ndarray, J2: np.ndarray) -> np.ndarray:
    """Eigenvalues of the monodromy matrix J2 J1 by numpy (product and ``eigvals``); the
    compiled ``orbit_classify`` forms it with numba's np.dot and scipy's dgeev (the same
    numbers to round-off; ``lapack.monodromy_eigvals`` is that path for tests)."""
    return np.linalg.eigvals(monodromy((J1, J2)))


def classify_orbit(p: ModelParams, mdl: np.ndarray, x: np.ndarray, xR: np.ndarray, jacobians: tuple,
           fl: np.ndarray, res: float) -> PeriodicOrbit:
    """The 1:1 PeriodicOrbit (walls LR, one period; ``to_dict`` in the 1:1 solver's keys)
    with pre-impact states x (at L), xR (at R), map Jacobians (J_P1(x), J_P2(xR)), flight
    times fl and Newton residual res."""
    J1, J2 = jacobians
    adm = bool(admissible_kernel(mdl, x, (WALL_L, WALL_R), fl[0])
               and admissible_kernel(mdl, xR, (WALL_R, WALL_L), fl[1]))
    ev = monodromy_eigenvalues(J1, J2)
    ev = ev[np.argsort(-np.abs(ev))]
    lam = float(np.hypot(ev.real, ev.imag).max())      # as ``lapack.lambda_max_4``
    two_pi = 2.0 * math.pi
    dw_L, dw_R = float(x[0] - x[1]), float(xR[0] - xR[1])
    phase_L = float(np.mod(p.omega * x[3] + p.phi, two_pi))
    phase_R = float(np.mod(p.omega * xR[3] + p.phi, two_pi))
    return PeriodicOrbit(
        walls="LR", periods=1, states=np.array([x, xR]),
        flight_times=[float(fl[0]), float(fl[1])], dw=np.array([dw_L, dw_R]),
        phases=np.array([phase_L, phase_R]), symmetric=bool(abs(fl[0] - fl[1]) <= SYM_TOL),
        admissible=adm, eigenvalues=ev, lambda_max=lam, stable=bool(adm and lam < 1.0),
        residual=float(res), jacobians=np.array([J1, J2]), params=p, keys=KEYS_1TO1)


def _dedup(orbits: list, T: float) -> list:
    """The orbits without None and repeats (``same_rows``), first occurrences kept."""
    out = []
    for o in orbits:
        if o is not None and not any(same_rows(o.x_L, q.x_L, T) for q in out):
            out.append(o)
    return out


def theta_to_t(theta: float, p: ModelParams) -> float:
    """The time in [0, T) of the forcing phase theta (omega t + phi = theta mod 2 pi)."""
    return float(np.mod((theta - p.phi) / p.omega, p.period))


def seed_orbits(p: ModelParams, osc: np.ndarray | None = None, simulation: bool = True,
                scan: bool = True) -> list[PeriodicOrbit]:
    """Every distinct 1:1 orbit reachable from the built-in seeds (not yet sorted)."""
    mdl = model_array(p, osc)
    T = p.period
    if p.F == 0.0:
        return []
    found = []
    for vm, vb, zb, th in symmetric_seeds(mdl):
        found.append(solve_orbit(p, [vm, vb, zb, theta_to_t(th, p)], 0.5 * T, 0.5 * T, mdl))
    if scan:
        for vm, vb, zb, th, s1 in asymmetric_seeds(mdl):
            found.append(solve_orbit(p, [vm, vb, zb, theta_to_t(th, p)], s1, T - s1, mdl))
    if simulation:
        found.extend(simulation_seed(p, mdl))
    return _dedup(found, T)


def simulation_seed(p: ModelParams, osc: np.ndarray, t_end: float = 600.0) -> list:
    from ...core.simulation import simulate_exact
    try:
        st = SolverSettings(t_end=t_end, t_transient=0.5 * t_end, max_impacts=200_000)
        res = simulate_exact(p, st)
    except Exception:                        # pragma: no cover - a seed is optional
        return []
    imp = res.impacts
    w = imp["wall"]
    idx = np.nonzero((w[:-2] == WALL_L) & (w[1:-1] == WALL_R) & (w[2:] == WALL_L))[0]
    if idx.size == 0:
        return []
    k = idx[-1]
    x0 = [imp["v_m"][k], imp["v_b"][k], imp["z_b"][k], imp["t"][k]]
    return [solve_orbit(p, x0, imp["t"][k + 1] - imp["t"][k], imp["t"][k + 2] - imp["t"][k + 1],
                        osc)]


def _sort_key(o: PeriodicOrbit) -> tuple:
    return (not o.admissible, not o.stable, not o.symmetric, o.lambda_max)


def find_1to1(eta: float, omega: float, F: float, r: float = R_DEFAULT, d: float = D_DEFAULT,
              phi: float = 0.0, seeds: Iterable | None = None,
              simulation: bool = True) -> list[PeriodicOrbit]:
    """Every distinct 1:1 orbit found (admissible or not), stable admissible ones first.

    ``seeds``: extra starting points, each an x_L = (z_m', z_b', z_b, t_L) or a pair
    (x_L, (s1, s2)) with flight-time guesses; ``simulation=False`` skips the short
    simulation seed.
    """
    p = ModelParams(eta=eta, omega=omega, F=F, r=r, d=d, phi=phi)
    return orbits_1to1(p, seeds=check_seeds(seeds),
                       simulation=check_bool("simulation", simulation))


SEEDS_ALLOWED = ("must be None or a list of seeds, each a PeriodicOrbit of walls LR, an x_L = "
                 "(z_m', z_b', z_b, t_L) of 4 finite numbers or a pair (x_L, (s1, s2))")


def check_seeds(seeds: Iterable | None) -> list:
    """The seeds of ``find_1to1`` as a list of PeriodicOrbit or (x_L, (s1, s2)) (s <= 0: first
    contact, as ``solve_orbit``); ParameterError naming ``seeds`` otherwise."""
    if seeds is None:
        return []
    if isinstance(seeds, (str, bytes, dict)) or not hasattr(seeds, "__iter__"):
        raise ParameterError("seeds", seeds, SEEDS_ALLOWED)
    out = []
    for sd in seeds:
        if isinstance(sd, PeriodicOrbit):
            if sd.walls != "LR":        # an orbit of another sequence seeds no 1:1 orbit
                raise ParameterError("seeds", seeds, SEEDS_ALLOWED)
            out.append(sd)
            continue
        try:
            pair = len(sd) == 2 and not isinstance(sd, str)
            x_L, flights = (sd[0], sd[1]) if pair else (sd, (-1.0, -1.0))
            out.append((check_reals("seeds", x_L, min_size=4, max_size=4),
                        tuple(check_reals("seeds", flights, min_size=2, max_size=2))))
        except (TypeError, ParameterError):
            raise ParameterError("seeds", seeds, SEEDS_ALLOWED) from None
    return out


def orbits_1to1(p: ModelParams, *, seeds: list | None = None,
                simulation: bool = True) -> list[PeriodicOrbit]:
    """``find_1to1`` at the validated model ``p``."""
    mdl = model_array(p)
    found = seed_orbits(p, mdl, simulation=simulation)
    for sd in seeds or ():
        if isinstance(sd, PeriodicOrbit):
            found.append(solve_orbit(p, sd.x_L, *sd.flight_times, osc=mdl))
        elif len(sd) == 2:      # (x_L, (s1, s2)), as ``check_seeds`` returns them
            found.append(solve_orbit(p, sd[0], sd[1][0], sd[1][1], mdl))
        else:
            found.append(solve_orbit(p, sd, osc=mdl))
    out = _dedup(found, p.period)
    out.sort(key=_sort_key)
    return out


# --------------------------------------------------------------------------- compiled candidates
# nogil versions of solve_orbit / seed_orbits(simulation=False) for per-point drivers that
# run on threads (``stability_map``). An orbit is a row of floats (ROW_* columns); the
# arithmetic is that of the Python functions above, so the rows equal their PeriodicOrbits
# (lambda_max of admissible orbits: scipy's dgeev, numpy's to round-off; see ``lapack``).

ROW_X, ROW_FL, ROW_ADM, ROW_LAM, ROW_SYM, ROW_DWL = 0, 4, 6, 7, 8, 9
N_ROW = 10                  # callers may append their own columns after these
N_SEED_MAX = 2 + N_SEEDS_MAX        # symmetric + asymmetric seeds of one parameter point


@njit(cache=True, nogil=True)
def orbit_workspace():
    """Scratch of ``orbit_solve``/``orbit_classify``: (x0, xs, Js, fl, P, M, a, wr, wi,
    work); x0 is the starting point, the solve fills xs (x_L, x_R, P2(x_R)), Js (J_P1(x_L),
    J_P2(x_R)) and fl (flight times)."""
    return (np.empty(4), np.empty((3, 4)), np.empty((2, 4, 4)), np.empty(2), np.empty((4, 4)),
            np.empty((4, 4)), np.empty(16), np.empty(4), np.empty(4), np.empty(64))


@njit(cache=True, nogil=True)
def orbit_solve(mdl, flights, row, ws):
    """Newton (``newton.newton_sequence`` on L, R) from ws[0] = x0 with flight-time guesses
    flights = (s1, s2) (<= 0: first contact); mdl: ``maps.pack_model``.

    Returns the residual and fills row's x_L (t_L in [0, T)) and flight times; inf where
    Newton fails, a flight time is not positive or they do not add up to T.
    ``orbit_classify`` completes the row."""
    x0, xs, Js, fl, P = ws[0], ws[1], ws[2], ws[3], ws[4]
    T = 2.0 * math.pi / mdl[I_W]
    fl[0], fl[1] = flights
    res = newton_sequence(mdl, LR, T, x0, fl, xs, Js, P)
    if not math.isfinite(res):
        return math.inf
    for i in range(4):
        if not math.isfinite(xs[0, i]):
            return math.inf
    if not (fl[0] > 0.0 and fl[1] > 0.0) or abs(fl[0] + fl[1] - T) > 1e-8 * (1.0 + T):
        return math.inf
    # t_L into [0, T) (the maps commute with t -> t + T)
    k = math.floor(xs[0, 3] / T)
    if k != 0:
        xs[0, 3] -= k * T
        xs[1, 3] -= k * T
    for i in range(4):
        row[ROW_X + i] = xs[0, i]
    row[ROW_FL] = fl[0]
    row[ROW_FL + 1] = fl[1]
    return res


@njit(cache=True, nogil=True)
def orbit_classify(mdl, row, ws):
    """Admissibility, symmetry, dw_L and, for admissible orbits only, lambda_max (nan
    otherwise) of the orbit the last ``orbit_solve`` with ws found (as ``classify_orbit``).

    An admissible orbit whose monodromy matrix is not finite (numpy's eigvals would raise)
    is marked non-admissible.
    """
    xs, Js, fl, _, M, a, wr, wi, work = ws[1:]
    x, xR = xs[0], xs[1]
    adm = (admissible_kernel(mdl, x, (WALL_L, WALL_R), fl[0])
           and admissible_kernel(mdl, xR, (WALL_R, WALL_L), fl[1]))
    lam = math.nan
    if adm:
        np.dot(Js[1], Js[0], M)
        lam = lambda_max_4(M, a, wr, wi, work)
        adm = math.isfinite(lam)
    row[ROW_ADM] = 1.0 if adm else 0.0
    row[ROW_LAM] = lam
    row[ROW_SYM] = 1.0 if abs(fl[0] - fl[1]) <= SYM_TOL else 0.0
    row[ROW_DWL] = x[0] - x[1]


@njit(cache=True, nogil=True)
def same_rows(a, b, T):
    """The orbit of row a is the one of row b (same t_L mod T to DEDUP_TOL (1 + T), same
    velocities and position to DEDUP_TOL relative): x_L arrays work as rows."""
    dt = abs(a[ROW_X + 3] - b[ROW_X + 3]) % T
    dt = min(dt, T - dt)
    if not dt <= DEDUP_TOL * (1.0 + T):
        return False
    for i in range(3):
        if not abs(a[ROW_X + i] - b[ROW_X + i]) <= DEDUP_TOL * (1.0 + abs(a[ROW_X + i])):
            return False
    return True


@njit(cache=True, nogil=True)
def seed_kernel(mdl, rows, ws):
    """Compiled ``seed_orbits(simulation=False)``: distinct orbits into rows[:n]; returns n.

    rows needs N_SEED_MAX rows (of >= N_ROW columns). Duplicates are dropped before
    ``orbit_classify`` (their admissibility and eigenvalues are never needed).
    """
    if mdl[I_F] == 0.0:
        return 0
    omega, phi = mdl[I_W], mdl[M_PHI]
    T = 2.0 * math.pi / omega
    x0 = ws[0]
    buf = np.empty((2 + N_SEEDS_MAX, 5))
    n = 0
    # np.int64 / np.bool_: typed like the Python callers' arguments (a literal constant would
    # compile a second specialization of each kernel)
    ns = closed_form_kernel(mdl, LR, 0.5 * T, np.int64(-1), buf)
    na = scan_seeds(mdl, LR, T, np.int64(1), np.bool_(True), buf[ns:ns + N_SEEDS_MAX])
    for k in range(ns + na):
        x0[0], x0[1], x0[2] = buf[k, 0], buf[k, 1], buf[k, 2]
        x0[3] = np.mod((buf[k, 3] - phi) / omega, T)
        s1 = 0.5 * T if k < ns else buf[k, 4]
        if math.isfinite(orbit_solve(mdl, (s1, T - s1), rows[n], ws)) and _is_new(rows, n, T):
            orbit_classify(mdl, rows[n], ws)
            n += 1
    return n


@njit(cache=True, nogil=True)
def _is_new(rows, n, T):
    """rows[n] is not ``same_rows`` as any of rows[:n]."""
    for q in range(n):  # noqa: SIM110 (numba: no generator in all())
        if same_rows(rows[n], rows[q], T):
            return False
    return True
