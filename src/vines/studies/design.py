"""Design of a VI NES for a frequency band and a set of base amplitudes (numerics only).

A structure (the LO: M, k, c, i.e. d = c/(M w0)) is shaken through its base at amplitudes
A_1..A_n [m] and frequencies omega = w/w0 in a band. A VI NES design is a ball mass ratio
eta = m/M and a clearance L [m] (half the cavity length); at amplitude A it runs the
dimensionless model at F = A/L, and its transmissibility is x_max/A = xmax/F (xmax in units
of L). Its worst case is the largest transmissibility over the band's omega grid and the
amplitudes, in two views:

* ``worst_ratio``: from rest (SPEC 1 default start), x_max over the window
  [t_transient, t_end] (``core.simulation.simulate_batch``);
* ``worst_ratio_any_attractor``: also over every attractor of a census (``VIEWS``) holding
  at least ``basin_min`` of its states, and the one reached from rest; the start from rest
  is one of the starts considered, so this view is >= the first by construction. Periodic
  attractors count with their exact x_max over one period, the others with the largest
  window x_max of their members.

``optimise`` searches (eta, L) globally and deterministically: a brute-force grid (eta
linear in (0, eta_max], L logarithmic over the clearance range), then a compass search in
(eta, log10 L) from the best grid points that accepts only improvements, so the result is
never worse than the grid's best point. Every design's curves are cached. The search
minimises the from-rest view; the attractor view is evaluated at the chosen design.

The LO alone and the optimal TMD of mass ratio eta_max (``studies.tmd``) are the
references; their worst ratios are exact maxima over the continuous band (closed form),
whereas the VI NES's is a maximum over the omega grid (each point one simulation).
"""
from __future__ import annotations

import inspect
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from .. import progress
from ..core.params import (
    C_DAMP_NS_PER_M,
    K_SPRING_N_PER_M,
    L_HALF_M,
    M_LO_KG,
    MAX_IMPACTS_DEFAULT,
    R_DEFAULT,
    ROOT_TOL_DEFAULT,
    T_END_DEFAULT,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    ModelParams,
    ParameterError,
    SolverSettings,
    check_real,
)
from . import design_checks as _chk
from . import tmd as _tmd
from .design_checks import (
    CENSUS_N_DEFAULT,
    DEFAULT_AMPLITUDES_M,
    DEFAULT_BAND,
    DEFAULT_N_OMEGA,
    N_CLEARANCE_DEFAULT,
    N_ETA_DEFAULT,
)

#: default clearance range, relative to the amplitudes: [A_max / 2, 100 A_min], widened to
#: [A_max / 2, 100 A_max] when the amplitudes span more than 200x (the largest amplitude
#: at F <= 2, nearly stuck beyond; the smallest at F >= 0.01, hardly any impact below)
CLEARANCE_RANGE_FACTORS = (0.5, 100.0)   # (x A_max, x A_min)
BASIN_MIN_DEFAULT = 0.01
#: compass search: starts (best distinct grid points) and step halvings below the grid step
N_STARTS = 2
N_HALVINGS = 3
#: rounds of the refinement of each curve's largest value in omega (``Evaluator``)
N_REFINE = 4
N_OMEGA_MAX = 10_001
N_GRID_MAX = 1000
N_AMPLITUDES_MAX = 100
AMPLITUDE_MAX_M = 1e3


# --------------------------------------------------------------------------- problem

@dataclass(frozen=True)
class DesignProblem:
    """What a design is judged on. ``model``: the structure's r, d and phi (its eta, omega
    and F are replaced at every point); ``omega``: the band's grid; ``amplitudes_m``: base
    amplitudes; ``settings``: run length and window of every simulation; the attractor
    view: ``view`` (a key of VIEWS), ``census_n`` states (0: not evaluated),
    ``census_seed``, ``basin_min``; M_kg, k_N_per_m, c_Ns_per_m: the structure in SI (for
    the absorbers' masses, stiffness and damping)."""

    model: ModelParams
    omega: tuple
    amplitudes_m: tuple
    settings: SolverSettings
    M_kg: float = M_LO_KG
    k_N_per_m: float = K_SPRING_N_PER_M
    c_Ns_per_m: float = C_DAMP_NS_PER_M
    view: str = "t_end"
    census_n: int = CENSUS_N_DEFAULT
    census_seed: int = 0
    basin_min: float = BASIN_MIN_DEFAULT

    @property
    def band(self) -> tuple:
        return (self.omega[0], self.omega[-1])

    @property
    def w0_rad_s(self) -> float:
        return math.sqrt(self.k_N_per_m / self.M_kg)


# --------------------------------------------------------------------------- views

def _census_t_end(model: ModelParams, settings: SolverSettings, n: int, seed: int,
                  n_threads) -> tuple[list, float]:
    """Attractors of ``attractors.census`` (end state at t_end, measures over the window):
    [(basin_fraction, worst xmax in units of L, reached_from_rest)], unsettled fraction."""
    from ..attractors.census import census
    st = settings
    c = census(model.eta, model.omega, model.F, r=model.r, d=model.d, n=n, seed=seed,
               t_end=st.t_end, t_transient=st.t_transient, v_stick=st.v_stick,
               max_impacts=st.max_impacts, root_tol=st.root_tol, n_threads=n_threads)
    out = [(a.basin_fraction, (a.xmax_m if a.periodic else a.xmax_m_range[1]) / L_HALF_M,
            i == c.from_rest) for i, a in enumerate(c.attractors)]
    return out, c.unsettled_fraction


#: attractor views: name -> function(model, settings, n, seed, n_threads) ->
#: ([(basin_fraction, xmax, reached_from_rest)], unsettled_fraction)
VIEWS = {"t_end": _census_t_end}       # keys: design_checks.VIEW_NAMES (a test checks)
VIEW_DESCRIPTIONS = {"t_end": "census at t_end: attractors reached by t_end, x_max over the "
                              "window [t_transient, t_end] (a finite-time view)"}


# --------------------------------------------------------------------------- evaluation

@dataclass
class Response:
    """From-rest response of one design. curves (n_amplitudes, n_omega): x_max/A on the
    band's grid; peak, peak_omega (n_amplitudes,): the largest x_max/A found per amplitude
    (grid and refinement points) and where."""

    curves: np.ndarray
    peak: np.ndarray
    peak_omega: np.ndarray

    @property
    def worst(self) -> float:
        return float(self.peak.max())


class Evaluator:
    """From-rest responses of designs (eta, L), cached.

    ``responses(designs)`` runs every design not seen yet in one ``simulate_batch`` call
    on the band's grid, then refines each amplitude's largest value by N_REFINE rounds of
    bisection hill climbing in omega (the two points at +- h around the best omega so far,
    h = grid step / 2, / 4, ...; one batch per round), because resonance peaks of width
    ~d fall between grid points. Results depend only on the design, not on the batch or
    the threads."""

    def __init__(self, problem: DesignProblem, n_threads: int | None = None):
        self.problem = problem
        self.n_threads = n_threads
        self.cache: dict = {}
        self.n_runs = 0

    def responses(self, designs: Sequence[tuple[float, float]]) -> list[Response]:
        keys = [(float(e), float(L)) for e, L in designs]
        new = list(dict.fromkeys(k for k in keys if k not in self.cache))
        if new:
            self._run(new)
        return [self.cache[k] for k in keys]

    def worst(self, designs: Sequence[tuple[float, float]]) -> list[float]:
        return [r.worst for r in self.responses(designs)]

    def _ratio(self, eta, omega, F) -> np.ndarray:
        """x_max/A from rest at broadcast (eta, omega, F)."""
        from ..core.simulation import simulate_batch
        p, st = self.problem.model, self.problem.settings
        out = simulate_batch(eta, omega, F, r=p.r, d=p.d, phi=p.phi, t_end=st.t_end,
                             t_transient=st.t_transient, v_stick=st.v_stick,
                             max_impacts=st.max_impacts, root_tol=st.root_tol,
                             n_threads=self.n_threads)
        self.n_runs += out["xmax"].size
        progress.advance(out["xmax"].size)
        return out["xmax"] / np.broadcast_to(F, out["xmax"].shape)

    def _climb(self, eta, F, peak, at, h) -> tuple:
        """One round of the refinement: x_max/A at at - h and at + h (inside the band) for
        every (design, amplitude) in one batch; move where larger (ties: the lower)."""
        band = self.problem.band
        cand = np.stack([at - h, at + h])
        ok = (cand >= band[0]) & (cand <= band[1])
        vals = np.full(cand.shape, -np.inf)
        if ok.any():
            vals[ok] = self._ratio(np.broadcast_to(eta, cand.shape)[ok], cand[ok],
                                   np.broadcast_to(F, cand.shape)[ok])
        k = vals.argmax(axis=0)[None]
        best = np.take_along_axis(vals, k, 0)[0]
        better = best > peak
        return (np.where(better, best, peak),
                np.where(better, np.take_along_axis(cand, k, 0)[0], at))

    def _run(self, new: list) -> None:
        pb = self.problem
        eta = np.array([e for e, _ in new])[:, None]
        F = np.asarray(pb.amplitudes_m)[None, :] / np.array([L for _, L in new])[:, None]
        omega = np.asarray(pb.omega)
        curves = self._ratio(eta[..., None], omega, F[..., None])
        idx = curves.argmax(axis=-1)
        peak, at = np.take_along_axis(curves, idx[..., None], -1)[..., 0], omega[idx]
        h = 0.5 * (omega[1] - omega[0])
        for _ in range(N_REFINE):
            peak, at = self._climb(eta, F, peak, at, h)
            h *= 0.5
        for k, key in enumerate(new):
            self.cache[key] = Response(curves=curves[k], peak=peak[k], peak_omega=at[k])


def attractor_curves(problem: DesignProblem, eta: float, clearance_m: float,
                     from_rest: np.ndarray,
                     n_threads: int | None = None) -> tuple[np.ndarray, float]:
    """Worst x_max/A over the attractors of ``problem.view`` at every (amplitude, omega)
    of a design: those holding >= basin_min of the census's states and the one reached
    from rest, and the from-rest run itself (``from_rest``: its curves). Also the largest
    unsettled fraction met."""
    view = VIEWS[problem.view]
    out = np.array(from_rest, dtype=float, copy=True)
    unsettled = 0.0
    for j, A in enumerate(problem.amplitudes_m):
        F = A / clearance_m
        for i, w in enumerate(problem.omega):
            model = replace(problem.model, eta=eta, omega=w, F=F)
            atts, u = view(model, problem.settings, problem.census_n, problem.census_seed,
                           n_threads)
            unsettled = max(unsettled, u)
            progress.advance()
            xs = [x for frac, x, rest in atts if rest or frac >= problem.basin_min]
            if xs:
                out[j, i] = max(out[j, i], max(xs) / F)
    return out, unsettled


# --------------------------------------------------------------------------- search

def search_grid(eta_max: float, clearance_range_m: tuple[float, float], n_eta: int,
                n_clearance: int) -> tuple[np.ndarray, np.ndarray]:
    """(eta grid eta_max k/n_eta, k = 1..n_eta; clearance grid 10**v, v evenly spaced over
    log10 of the range: the compass search maps log10 L to L the same way, so a grid
    design is the same float wherever it is met)."""
    etas = eta_max * np.arange(1, n_eta + 1) / n_eta
    logs = _log_clearances(clearance_range_m, n_clearance)
    return etas, np.array([_clearance(v) for v in logs])


def _log_clearances(clearance_range_m, n: int) -> np.ndarray:
    return np.linspace(math.log10(clearance_range_m[0]), math.log10(clearance_range_m[1]), n)


def _clearance(log10_L) -> float:
    """L from log10 L, one scalar path for the grid and the compass search."""
    return 10.0 ** float(log10_L)


def compass(ev: Evaluator, start, value, steps, lower, upper) -> tuple:
    """Compass search in x = (eta, log10 L) from ``start``: try x +- step along each axis
    (inside [lower, upper]), move to the best strict improvement, else halve the steps,
    N_HALVINGS times. Returns (x, value)."""
    x, h = np.array(start, float), np.array(steps, float)
    for _ in range(N_HALVINGS + 1):
        while True:
            cands = []
            for axis in range(2):
                for sign in (-1.0, 1.0):
                    y = x.copy()
                    y[axis] = min(max(x[axis] + sign * h[axis], lower[axis]), upper[axis])
                    if y[axis] != x[axis]:
                        cands.append(y)
            vals = ev.worst([(y[0], _clearance(y[1])) for y in cands])
            k = int(np.argmin(vals)) if vals else -1
            if k < 0 or vals[k] >= value:
                break
            x, value = cands[k], vals[k]
        h = h / 2.0
    return x, value


def optimise(ev: Evaluator, eta_max: float, clearance_range_m: tuple[float, float],
             n_eta: int, n_clearance: int) -> dict:
    """Best (eta, L) of the brute-force grid, then compass searches from the N_STARTS best
    grid points (steps half the grid's). Returns eta, clearance_m, worst_ratio and the
    grid (eta, clearance_m, worst_ratio (n_eta, n_clearance))."""
    etas, Ls = search_grid(eta_max, clearance_range_m, n_eta, n_clearance)
    grid = [(e, L) for e in etas for L in Ls]
    worst = np.array(ev.worst(grid)).reshape(n_eta, n_clearance)
    logs = _log_clearances(clearance_range_m, n_clearance)
    steps = [0.5 * (etas[1] - etas[0]) if n_eta > 1 else 0.0,
             0.5 * (logs[1] - logs[0])]
    lower, upper = [etas[0], logs[0]], [etas[-1], logs[-1]]
    order = np.argsort(worst, axis=None, kind="stable")[:N_STARTS]
    best = (float(worst.flat[order[0]]), etas[order[0] // n_clearance],
            Ls[order[0] % n_clearance])
    for flat in order:
        i, j = divmod(int(flat), n_clearance)
        x, v = compass(ev, (etas[i], logs[j]), float(worst[i, j]), steps, lower, upper)
        if v < best[0]:
            best = (v, float(x[0]), _clearance(x[1]))
    return dict(eta=float(best[1]), clearance_m=float(best[2]), worst_ratio=best[0],
                grid=dict(eta=etas, clearance_m=Ls, worst_ratio=worst))


# --------------------------------------------------------------------------- result

#: what ``stroke_m`` and ``x_max_m`` are (the JSON key ``stroke``)
STROKE_DESCRIPTION = dict(
    tmd="largest displacement of the TMD's mass relative to the LO, |u - x|, over the "
        "continuous band at the largest base amplitude (closed form, linear in A)",
    vines="the ball's travel relative to the LO: +-L, the clearance (half the cavity "
          "length), whatever the response",
    x_max_m="the LO's own largest displacement relative to the base: worst x_max/A times "
            "A (LO alone, TMD: at the largest amplitude; VI NES: the largest over the "
            "amplitudes, from rest)",
    tmd_equal_travel="the TMD of the same mass minimising the same worst case with its "
                     "stroke at most the VI NES's clearance (binding: whether the limit "
                     "changes the tuning; null when no tuning meets it)")


def _finite(x):
    """A float for JSON: None where not finite."""
    x = float(x)
    return x if math.isfinite(x) else None


@dataclass
class DesignResult:
    """Curves and worst cases of the LO alone, the optimal TMD and the VI NES design
    (``to_dict``: the JSON of ``vines design``). rest: the from-rest response (curves on
    the grid, refined peaks); vines_any_attractor: x_max/A per (amplitude, omega) over the
    attractors (None when census_n = 0); search: the grid of an optimisation (None for an
    evaluated design)."""

    problem: DesignProblem
    inputs: dict
    lo_alone: np.ndarray
    lo_alone_worst: tuple
    tmd: _tmd.TunedMassDamper
    tmd_curve: np.ndarray
    eta: float
    clearance_m: float
    rest: Response
    vines_any_attractor: np.ndarray | None
    unsettled_fraction: float | None
    search: dict | None
    cost: dict = field(default_factory=dict)
    tmd_equal_travel: _tmd.TunedMassDamper | None = None

    @property
    def worst_ratio(self) -> float:
        return self.rest.worst

    @property
    def worst_any_per_amplitude(self) -> np.ndarray | None:
        """Attractor view per amplitude: its grid maxima and the from-rest peaks."""
        a = self.vines_any_attractor
        return None if a is None else np.maximum(a.max(axis=1), self.rest.peak)

    @property
    def worst_ratio_any_attractor(self) -> float | None:
        a = self.worst_any_per_amplitude
        return None if a is None else float(a.max())

    def _tmd_dict(self, t: _tmd.TunedMassDamper | None = None) -> dict:
        """A TMD's JSON object (default: the free optimum ``tmd``); its stroke and LO
        amplitude in metres at the largest base amplitude (the system is linear)."""
        pb, t = self.problem, self.tmd if t is None else t
        m = t.eta * pb.M_kg
        w_a = t.frequency_ratio * pb.w0_rad_s
        a_max = max(pb.amplitudes_m)
        curve = np.asarray(t.ratio(np.asarray(pb.omega), pb.model.d), dtype=float)
        return dict(eta=t.eta, frequency_ratio=t.frequency_ratio,
                    damping_ratio=t.damping_ratio, worst_ratio=_finite(t.worst_ratio),
                    worst_omega=t.worst_omega,
                    worst_ratio_grid=_finite(curve.max()), mass_kg=m,
                    stiffness_N_per_m=m * w_a ** 2,
                    damping_Ns_per_m=2.0 * t.damping_ratio * m * w_a,
                    worst_travel=_finite(t.worst_travel),
                    stroke_m=_finite(t.worst_travel * a_max),
                    x_max_m=_finite(t.worst_ratio * a_max))

    def _tmd_equal_travel_dict(self) -> dict | None:
        """The TMD of the same mass whose band travel at the largest amplitude stays
        within the VI NES's clearance (None when no tuning keeps it there)."""
        t = self.tmd_equal_travel
        if t is None:
            return None
        return self._tmd_dict(t) | dict(max_stroke_m=self.clearance_m,
                                        binding=t != self.tmd)

    def _vines_dict(self) -> dict:
        pb, any_ = self.problem, self.vines_any_attractor
        return dict(eta=self.eta, clearance_m=self.clearance_m,
                    worst_ratio=self.worst_ratio,
                    worst_ratio_any_attractor=self.worst_ratio_any_attractor,
                    view=pb.view if any_ is not None else None,
                    view_description=VIEW_DESCRIPTIONS[pb.view] if any_ is not None else None,
                    mass_kg=self.eta * pb.M_kg,
                    F=[A / self.clearance_m for A in pb.amplitudes_m],
                    worst_ratio_per_amplitude=self.rest.peak.tolist(),
                    worst_omega_per_amplitude=self.rest.peak_omega.tolist(),
                    worst_ratio_any_attractor_per_amplitude=(
                        None if any_ is None else self.worst_any_per_amplitude.tolist()),
                    unsettled_fraction_max=self.unsettled_fraction,
                    stroke_m=self.clearance_m,
                    x_max_m=float(np.max(self.rest.peak * np.asarray(pb.amplitudes_m))))

    def to_dict(self) -> dict:
        pb = self.problem
        curves = dict(omega=list(pb.omega), amplitude_m=list(pb.amplitudes_m),
                      lo_alone=[_finite(v) for v in self.lo_alone],
                      tmd=self.tmd_curve.tolist(), vines=self.rest.curves.tolist(),
                      vines_any_attractor=(None if self.vines_any_attractor is None
                                           else self.vines_any_attractor.tolist()))
        search = None
        if self.search is not None:
            g = self.search
            search = dict(eta=g["eta"].tolist(), clearance_m=g["clearance_m"].tolist(),
                          worst_ratio=g["worst_ratio"].tolist(), n_starts=N_STARTS,
                          n_halvings=N_HALVINGS)
        worst_lo, w_lo = self.lo_alone_worst
        return dict(inputs=self.inputs, curves=curves,
                    lo_alone=dict(worst_ratio=_finite(worst_lo), worst_omega=w_lo,
                                  worst_ratio_grid=_finite(np.max(self.lo_alone)),
                                  x_max_m=_finite(worst_lo * max(pb.amplitudes_m))),
                    tmd=self._tmd_dict(), tmd_equal_travel=self._tmd_equal_travel_dict(),
                    vines=self._vines_dict(), search=search,
                    worst_case=dict(
                        lo_alone="exact maximum over the continuous band (closed form)",
                        tmd="maximum over the continuous band (closed form, refined grid)",
                        vines="maximum of x_max/A over the amplitudes and the omega grid, "
                              "each amplitude's largest value refined by bisection hill "
                              f"climbing in omega ({N_REFINE} rounds); x_max over the "
                              "window [t_transient, t_end]: a lower bound of the band "
                              "maximum"),
                    stroke=STROKE_DESCRIPTION,
                    cost=self.cost)


# --------------------------------------------------------------------------- driver

@dataclass(frozen=True)
class DesignSearch:
    """What ``solve`` does with a problem (validated by ``design``): evaluate the design
    (eta, clearance_m [m], half the cavity length) or, when eta_max is set, optimise one
    with eta <= eta_max and the clearance in clearance_range_m (lo, hi) [m] on an
    n_eta x n_clearance grid plus a compass search (``optimise``)."""

    eta: float | None = None
    clearance_m: float | None = None
    eta_max: float | None = None
    clearance_range_m: tuple | None = None
    n_eta: int = N_ETA_DEFAULT
    n_clearance: int = N_CLEARANCE_DEFAULT


def solve(problem: DesignProblem, search: DesignSearch, *, n_threads: int | None = None,
          inputs: dict | None = None, known: dict | None = None) -> DesignResult:
    """Evaluate or optimise a design as ``search`` says (validated inputs; ``design`` is
    the checked entry; ``inputs``: the inputs as the result reports them)."""
    eta, clearance_m, eta_max = search.eta, search.clearance_m, search.eta_max
    t0, c0 = time.perf_counter(), time.process_time()
    d = problem.model.d
    mu = eta if eta_max is None else eta_max
    tuned = _tmd.optimal_tmd(mu, d, problem.band)
    omega = np.asarray(problem.omega)
    lo_curve = np.asarray(_tmd.lo_ratio(omega, d), dtype=float)
    t1, c1 = time.perf_counter(), time.process_time()
    ev = Evaluator(problem, n_threads)
    if known is not None:             # responses computed by grid_responses elsewhere
        ev.cache.update(known["responses"])
        ev.n_runs += known["n_runs"]
    grid = None
    with progress.task(None, "design: runs from rest", "runs"):
        if eta_max is not None:
            best = optimise(ev, eta_max, search.clearance_range_m, search.n_eta,
                            search.n_clearance)
            eta, clearance_m, grid = best["eta"], best["clearance_m"], best["grid"]
        rest = ev.responses([(eta, clearance_m)])[0]
    t2, c2 = time.perf_counter(), time.process_time()
    any_, unsettled = None, None
    n_points = len(problem.omega) * len(problem.amplitudes_m)
    if problem.census_n > 0:
        with progress.task(n_points, "design: attractor censuses", "points"):
            any_, unsettled = attractor_curves(problem, eta, clearance_m, rest.curves,
                                               n_threads)
    t3, c3 = time.perf_counter(), time.process_time()
    equal_travel = equal_travel_tmd(tuned, d, problem, clearance_m)
    t4, c4 = time.perf_counter(), time.process_time()
    cost = dict(wall_s=t4 - t0, tmd_s=t1 - t0 + t4 - t3, search_s=t2 - t1, census_s=t3 - t2,
                cpu_s=c4 - c0, search_cpu_s=c2 - c1, census_cpu_s=c3 - c2,
                n_designs=len(ev.cache), n_runs_from_rest=ev.n_runs,
                n_runs_census=(problem.census_n + 1) * n_points if any_ is not None else 0,
                n_threads=n_threads)
    return DesignResult(problem=problem, inputs=inputs or {}, lo_alone=lo_curve,
                        lo_alone_worst=_tmd.lo_worst(problem.band, d), tmd=tuned,
                        tmd_curve=np.asarray(tuned.ratio(omega, d), dtype=float),
                        eta=float(eta), clearance_m=float(clearance_m), rest=rest,
                        vines_any_attractor=any_, unsettled_fraction=unsettled,
                        search=grid, cost=cost, tmd_equal_travel=equal_travel)


def equal_travel_tmd(tuned: _tmd.TunedMassDamper, d: float, problem: DesignProblem,
                     clearance_m: float) -> _tmd.TunedMassDamper | None:
    """The TMD of ``tuned``'s mass minimising the band worst case with its travel at the
    largest base amplitude at most ``clearance_m`` (``tuned`` itself when it already is);
    None when no tuning keeps it there."""
    try:
        return _tmd.limit_travel(tuned, d, problem.band,
                                 clearance_m / max(problem.amplitudes_m))
    except ParameterError:
        return None


def design(*, omega_band: Sequence[float] = DEFAULT_BAND, n_omega: int = DEFAULT_N_OMEGA,
           amplitudes_m: float | Sequence[float] = DEFAULT_AMPLITUDES_M,
           M_kg: float | None = None, k_N_per_m: float | None = None,
           c_Ns_per_m: float | None = None, d: float | None = None, r: float = R_DEFAULT,
           eta: float | None = None, clearance_m: float | None = None,
           eta_max: float | None = None, clearance_range_m: Sequence[float] | None = None,
           n_eta: int = N_ETA_DEFAULT, n_clearance: int = N_CLEARANCE_DEFAULT,
           view: str = "t_end", census_n: int = CENSUS_N_DEFAULT, census_seed: int = 0,
           basin_min: float = BASIN_MIN_DEFAULT, t_end: float = T_END_DEFAULT,
           t_transient: float = T_TRANSIENT_DEFAULT, v_stick: float = V_STICK_DEFAULT,
           max_impacts: int = MAX_IMPACTS_DEFAULT, root_tol: float = ROOT_TOL_DEFAULT,
           n_threads: int | None = None) -> DesignResult:
    """Choose (or judge) a VI NES for a structure shaken through its base over a band.

    omega_band (lo, hi) of omega = w/w0 with n_omega grid points; amplitudes_m: base
    amplitudes [m]; the structure: M_kg, k_N_per_m and c_Ns_per_m (Table 1 by default) or
    the dimensionless damping d = c/(M w0) instead of c; r: restitution. Evaluate the
    design (eta, clearance_m [m], half the cavity length) or optimise one with
    eta <= eta_max and the clearance in clearance_range_m (default
    [A_min/2, 100 A_max]) on an n_eta x n_clearance grid plus a compass search (module
    docstring). The attractor view ``view`` (a key of VIEWS) uses census_n states
    (0: skip it) seeded by census_seed and keeps attractors with basin fraction >=
    basin_min. t_end ... root_tol: every simulation's settings (``SolverSettings``).
    Results do not depend on n_threads. Raises ParameterError naming the bad argument.
    """
    problem, search, inputs, n_threads = _prepare(dict(locals()))
    return solve(problem, search, n_threads=n_threads, inputs=inputs)


def _arguments(kwargs: dict) -> dict:
    """``design``'s arguments: its defaults updated by ``kwargs``."""
    return {k: p.default for k, p in inspect.signature(design).parameters.items()} | kwargs


def complete(known: dict, **kwargs) -> DesignResult:
    """``design(**kwargs)`` with the responses of ``known`` (the merged ``grid_responses``
    of parts of its search grid, computed elsewhere) not run again: the same result."""
    problem, search, inputs, n_threads = _prepare(_arguments(kwargs))
    return solve(problem, search, n_threads=n_threads, inputs=inputs, known=known)


def grid_responses(start: int, stop: int, **kwargs) -> dict:
    """What ``design(**kwargs)`` computes for the designs [start, stop) of its search grid
    (grid order, ``grid_designs``): their responses from rest and the runs they took; pass
    the merged dicts of all parts to ``complete``."""
    problem, search, _, n_threads = _prepare(_arguments(kwargs))
    ev = Evaluator(problem, n_threads)
    ev.responses(grid_designs(search)[start:stop])
    return {"responses": ev.cache, "n_runs": ev.n_runs}


def grid_designs(search: DesignSearch) -> list:
    """The (eta, clearance_m) of the search grid in the order ``optimise`` runs them (none
    when a design is evaluated, not optimised)."""
    if search.eta_max is None:
        return []
    etas, Ls = search_grid(search.eta_max, search.clearance_range_m, search.n_eta,
                           search.n_clearance)
    return [(float(e), float(L)) for e in etas for L in Ls]


def _prepare(a: dict) -> tuple:
    """(problem, search, inputs, n_threads) from ``design``'s arguments ``a``, validated."""
    mode = _chk.check_mode(a["eta"], a["clearance_m"], a["eta_max"], a["clearance_range_m"])
    band = _chk.check_band(a["omega_band"])
    n_omega = _chk.check_count("n_omega", a["n_omega"], 2, N_OMEGA_MAX)
    amps = _chk.check_amplitudes(a["amplitudes_m"], AMPLITUDE_MAX_M, N_AMPLITUDES_MAX)
    M, k, c, d = _chk.check_structure(a["M_kg"], a["k_N_per_m"], a["c_Ns_per_m"], a["d"])
    model = ModelParams(eta=1.0, omega=1.0, F=0.0, r=a["r"], d=d)
    settings = SolverSettings(t_end=a["t_end"], t_transient=a["t_transient"],
                              v_stick=a["v_stick"], max_impacts=a["max_impacts"],
                              root_tol=a["root_tol"])
    view = a["view"]
    if not isinstance(view, str) or view not in VIEWS:
        raise ParameterError("view", view, f"must be one of {', '.join(VIEWS)}")
    census_n = _chk.check_count("census_n", a["census_n"], 0, 1_000_000)
    census_seed = _chk.check_count("census_seed", a["census_seed"], 0, 2**63 - 1)
    basin_min = check_real("basin_min", a["basin_min"], lo=0.0, hi=1.0)
    n_threads = a["n_threads"]
    if n_threads is not None:
        n_threads = _chk.check_count("n_threads", n_threads, 1, 4096)
    if mode == "evaluate":
        search = dict(eta=_chk.check_eta("eta", a["eta"]),
                      clearance_m=_chk.check_clearance("clearance", a["clearance_m"], amps))
    else:
        eta_max = _chk.check_eta("eta_max", a["eta_max"])
        rng = _chk.check_clearance_range(a["clearance_range_m"], amps, CLEARANCE_RANGE_FACTORS)
        search = dict(eta_max=eta_max, clearance_range_m=rng,
                      n_eta=_chk.check_count("n_eta", a["n_eta"], 1, N_GRID_MAX),
                      n_clearance=_chk.check_count("n_clearance", a["n_clearance"], 2,
                                                   N_GRID_MAX))
    omega = tuple(float(w) for w in np.linspace(band[0], band[1], n_omega))
    problem = DesignProblem(model=model, omega=omega, amplitudes_m=amps, settings=settings,
                            M_kg=M, k_N_per_m=k, c_Ns_per_m=c, view=view, census_n=census_n,
                            census_seed=census_seed, basin_min=basin_min)
    inputs = dict(mode=mode, omega_band=list(band), n_omega=n_omega, amplitude_m=list(amps),
                  M_kg=M, k_N_per_m=k, c_Ns_per_m=c, d=d, r=model.r,
                  **{k_: (list(v) if isinstance(v, tuple) else v) for k_, v in search.items()},
                  view=view, census_n=census_n, census_seed=census_seed,
                  basin_min=basin_min, settings=settings.as_dict() | {"state0": None})
    return problem, DesignSearch(**search), inputs, n_threads
