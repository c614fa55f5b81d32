"""Mistuning: the absorbers of a design on a host whose natural frequency has drifted.

The host's stiffness becomes k (1 + delta)^2, so its natural frequency is s w0 with
s = 1 + delta; the absorbers (ball and clearance, TMD mass, spring and damper) stay as
designed at delta = 0 and the band stays fixed in absolute frequency. In the host's own
scale (time s w0 t_dim) the detuned structure is the dimensionless model again, with

    omega -> omega / s,   d -> d / s,   (TMD) f -> f / s,   t_end, t_transient -> s t,

and eta, F = A/L, r, the TMD's mass ratio and damping ratio zeta unchanged (the impact
law and the ball's free flight have no time scale; the windows keep their length in
seconds). x_max/A is a ratio of lengths, the same in either scale. delta = 0 is s = 1.0:
the same floats as ``vines design``.

``curves`` evaluates one design over delta in [-D, D]: a grid of n_delta points, then the
VI NES's largest worst case refined by N_REFINE_DELTA rounds of bisection hill climbing
in delta (as ``design.Evaluator`` refines omega). The linear systems are evaluated at the
same points in closed form, and their ``worst`` is the maximum over the continuous
interval (a bounded search around the grid's largest value). ``robust`` optimises the
VI NES for the largest worst case over n_search host frequencies (the grid of
``design.optimise`` on ``RobustEvaluator``) and re-tunes the TMD for the same minimax
over a dense delta grid.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from .. import progress
from ..core.params import ParameterError, check_int, check_real

#: largest drift allowed: |delta| <= MISTUNING_MAX (s stays in [0.5, 1.5])
MISTUNING_MAX = 0.5
N_DELTA_DEFAULT = 7
N_DELTA_MAX = 201
N_REFINE_DELTA = 2
#: host frequencies of the robust search (the worst case over them is minimised)
N_SEARCH_DEFAULT = 5
#: delta points and band points of the robust TMD's minimax (then each delta refined)
N_TMD_DELTA = 41
N_TMD_BAND = 801


# --------------------------------------------------------------------------- inputs

def check_mistuning(D, n_delta=N_DELTA_DEFAULT, n_search=N_SEARCH_DEFAULT) -> tuple:
    """(D, n_delta, n_search): 0 <= D <= MISTUNING_MAX; n_delta odd >= 3 (delta = 0 is a
    grid point), n_search odd >= 1."""
    D = check_real("mistuning", D, lo=0.0, hi=MISTUNING_MAX)
    n_delta = check_int("n_delta", n_delta, lo=3, hi=N_DELTA_MAX)
    if n_delta % 2 == 0:
        raise ParameterError("n_delta", n_delta, "must be odd (delta = 0 a grid point)")
    n_search = check_int("n_search", n_search, lo=1, hi=N_DELTA_MAX)
    if n_search % 2 == 0:
        raise ParameterError("n_search", n_search, "must be odd (delta = 0 a grid point)")
    return D, n_delta, n_search


def delta_grid(D: float, n: int) -> np.ndarray:
    """n points evenly over [-D, D]; the middle one exactly 0."""
    g = np.linspace(-D, D, n)
    g[n // 2] = 0.0
    return g


# --------------------------------------------------------------------------- the host

def detuned(problem, delta: float):
    """``design.DesignProblem`` of the host at s = 1 + delta in its own scale (module
    docstring); the SI structure (M, k, c) stays nominal: the absorbers' scale."""
    s = 1.0 + float(delta)
    st = problem.settings
    return replace(problem, model=replace(problem.model, d=problem.model.d / s),
                   omega=tuple(w / s for w in problem.omega),
                   settings=replace(st, t_end=s * st.t_end, t_transient=s * st.t_transient))


def lo_worst(band, d: float, delta: float) -> float:
    """Largest |X/Y| of the detuned LO alone over the band (closed form)."""
    from . import tmd as _tmd
    s = 1.0 + delta
    return _tmd.lo_worst((band[0] / s, band[1] / s), d / s)[0]


def tmd_ratio(omega, d, mu, f, zeta, delta) -> np.ndarray:
    """|X/Y| of the LO of stiffness k (1 + delta)^2 with a TMD tuned to f (nominal scale)."""
    from . import tmd as _tmd
    s = 1.0 + delta
    return _tmd.tmd_ratio(np.asarray(omega) / s, d / s, mu, f / s, zeta)


def tmd_worst(band, d, mu, f, zeta, delta) -> float:
    """Largest ``tmd_ratio`` over the band (``tmd.band_max``: grid and refinement)."""
    from .tmd import band_max
    return band_max(lambda w: tmd_ratio(w, d, mu, f, zeta, delta), band)[0]


def tmd_travel_worst(band, d, mu, f, zeta, delta) -> float:
    """Largest travel |U - X|/|Y| of the TMD over the band on the detuned host (a ratio of
    lengths: the same in either scale)."""
    from .tmd import band_max, tmd_travel
    s = 1.0 + delta
    return band_max(lambda w: tmd_travel(np.asarray(w) / s, d / s, mu, f / s, zeta), band)[0]


def tmd_over_delta(problem, tuned, delta, D: float, n_delta: int) -> dict:
    """A TMD (``tmd.TunedMassDamper``) over the host's drift: its worst |X/Y| at each
    delta, the largest over [-D, D] and where, and its stroke [m]: the largest band travel
    over the drift at the largest base amplitude."""
    band, d, grid = problem.band, problem.model.d, delta_grid(D, n_delta)
    mu, f, z = tuned.eta, tuned.frequency_ratio, tuned.damping_ratio
    worst, where = _sup(lambda x: tmd_worst(band, d, mu, f, z, x), grid, D)
    travel = _sup(lambda x: tmd_travel_worst(band, d, mu, f, z, x), grid, D)[0]
    return dict(design=dict(eta=mu, frequency_ratio=f, damping_ratio=z),
                tmd=[tmd_worst(band, d, mu, f, z, x) for x in delta], worst=worst,
                worst_delta=where, stroke_m=travel * max(problem.amplitudes_m))


def _sup(fun, grid: np.ndarray, D: float) -> tuple[float, float]:
    """(max, argmax) of a cheap fun(delta) over [-D, D]: the grid's best, then a bounded
    search between its neighbours."""
    from scipy.optimize import minimize_scalar
    vals = np.array([fun(x) for x in grid])
    i = int(vals.argmax())
    top, arg = float(vals[i]), float(grid[i])
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    if hi > lo:
        res = minimize_scalar(lambda x: -fun(x), bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-10})
        if -res.fun > top:
            top, arg = float(-res.fun), float(res.x)
    return top, arg


# --------------------------------------------------------------------------- VI NES

def vines_worst(problem, eta: float, clearance_m: float, delta: float,
                n_threads=None) -> tuple[float, float | None, int]:
    """(worst x_max/A from rest, over the attractors (None when census_n = 0), runs) of
    a VI NES design on the detuned host, as ``design.solve`` takes them."""
    from .design import Evaluator, attractor_curves
    pb = detuned(problem, delta)
    ev = Evaluator(pb, n_threads)
    with progress.task(None, "runs from rest", "runs"):
        rest = ev.responses([(eta, clearance_m)])[0]
    any_, runs = None, ev.n_runs
    if pb.census_n > 0:
        with progress.task(None, "censuses", "points"):
            curves, _ = attractor_curves(pb, eta, clearance_m, rest.curves, n_threads)
        any_ = float(max(curves.max(), rest.worst))
        runs += (pb.census_n + 1) * curves.size
    return rest.worst, any_, runs


@dataclass
class Curves:
    """One pair of designs over the host's drift: ``delta`` (sorted), the worst x_max/A
    over band and amplitudes at each delta of the LO alone, the TMD (f, zeta) and the
    VI NES (eta, clearance_m) from rest and over attractors (None: no census);
    ``worst``/``worst_delta``: the maximum over delta of each and where."""

    D: float
    delta: np.ndarray
    lo_alone: np.ndarray
    tmd: np.ndarray
    vines: np.ndarray
    vines_any_attractor: np.ndarray | None
    worst: dict
    worst_delta: dict
    design: dict
    n_runs: int = 0

    def to_dict(self) -> dict:
        any_ = self.vines_any_attractor
        return dict(D=self.D, delta=self.delta.tolist(), lo_alone=self.lo_alone.tolist(),
                    tmd=self.tmd.tolist(), vines=self.vines.tolist(),
                    vines_any_attractor=None if any_ is None else any_.tolist(),
                    worst=self.worst, worst_delta=self.worst_delta, design=self.design,
                    n_runs=self.n_runs)


def _vines_over_delta(problem, eta, clearance_m, D, n_delta, n_threads) -> tuple:
    """({delta: (worst from rest, worst over attractors)}, runs) of a VI NES design on
    the delta grid, then N_REFINE_DELTA rounds of hill climbing at its largest value (the
    points at +- h around the best so far, h = grid step / 2, / 4, ...)."""
    grid = delta_grid(D, n_delta)
    seen: dict = {}
    n_runs = 0

    def at(x):
        nonlocal n_runs
        x = float(x)
        if x not in seen:
            w, a, n = vines_worst(problem, eta, clearance_m, x, n_threads)
            seen[x], n_runs = (w, a), n_runs + n
        progress.advance()
        return seen[x][0]

    with progress.task(n_delta + 2 * N_REFINE_DELTA, "mistuning: host frequencies",
                       "frequencies"):
        vals = [at(x) for x in grid]
        k = int(np.argmax(vals))
        best, x0, h = vals[k], float(grid[k]), (grid[1] - grid[0]) / 2 if D > 0 else 0.0
        for _ in range(N_REFINE_DELTA):
            for x in (x0 - h, x0 + h):
                if not (h > 0 and -D <= x <= D):
                    progress.advance()          # a candidate outside [-D, D]: skipped
                elif at(x) > best:
                    best, x0 = seen[x][0], x
            h /= 2
    return seen, n_runs


def curves(problem, mu: float, f: float, zeta: float, eta: float, clearance_m: float,
           D: float, n_delta: int = N_DELTA_DEFAULT, n_threads=None) -> Curves:
    """The LO alone, the TMD (mass ratio mu, tuning f, zeta) and the VI NES (eta,
    clearance_m) over delta in [-D, D] (module docstring; validated problem and D)."""
    band, d = problem.band, problem.model.d
    grid = delta_grid(D, n_delta)
    seen, n_runs = _vines_over_delta(problem, eta, clearance_m, D, n_delta, n_threads)
    delta = np.array(sorted(seen))
    vines = np.array([seen[x][0] for x in delta])
    any_ = (None if problem.census_n == 0
            else np.array([seen[x][1] for x in delta]))
    lo = np.array([lo_worst(band, d, x) for x in delta])
    tm = np.array([tmd_worst(band, d, mu, f, zeta, x) for x in delta])
    worst, where = {}, {}
    for key, fun in (("lo_alone", lambda x: lo_worst(band, d, x)),
                     ("tmd", lambda x: tmd_worst(band, d, mu, f, zeta, x))):
        worst[key], where[key] = _sup(fun, grid, D)
    for key, v in (("vines", vines), ("vines_any_attractor", any_)):
        worst[key] = None if v is None else float(v.max())
        where[key] = None if v is None else float(delta[int(v.argmax())])
    design = dict(tmd=dict(eta=mu, frequency_ratio=f, damping_ratio=zeta),
                  vines=dict(eta=eta, clearance_m=clearance_m))
    return Curves(D=D, delta=delta, lo_alone=lo, tmd=tm, vines=vines,
                  vines_any_attractor=any_, worst=worst, worst_delta=where, design=design,
                  n_runs=n_runs)


# --------------------------------------------------------------------------- robust

class RobustEvaluator:
    """``design.Evaluator``'s ``worst`` for the largest worst case over host drifts
    ``deltas``: one Evaluator (with its cache) per detuned host."""

    def __init__(self, problem, deltas, n_threads=None):
        from .design import Evaluator
        self.evaluators = [Evaluator(detuned(problem, x), n_threads) for x in deltas]

    @property
    def cache(self) -> dict:
        return self.evaluators[0].cache

    @property
    def n_runs(self) -> int:
        return sum(ev.n_runs for ev in self.evaluators)

    def worst(self, designs) -> list[float]:
        per = np.array([ev.worst(designs) for ev in self.evaluators])
        return per.max(axis=0).tolist()


def robust_tmd(mu: float, d: float, band, D: float, start: tuple) -> tuple[float, float]:
    """(f, zeta) of the TMD of mass ratio mu minimising its largest |X/Y| over the band
    and delta in [-D, D] (N_TMD_DELTA x N_TMD_BAND points), Nelder-Mead in
    (log f, log zeta) from ``start`` (the nominal tuning)."""
    from scipy.optimize import minimize
    w = np.linspace(band[0], band[1], N_TMD_BAND)
    s = 1.0 + np.linspace(-D, D, N_TMD_DELTA)[:, None]

    def worst(x):
        f, z = math.exp(x[0]), math.exp(x[1])
        from .tmd import tmd_ratio as ratio
        return float(ratio(w / s, d / s, mu, f / s, z).max())

    x0 = [math.log(start[0]), math.log(start[1])]
    res = minimize(worst, x0, method="Nelder-Mead",
                   options={"xatol": 1e-7, "fatol": 1e-10, "maxiter": 2000,
                            "initial_simplex": [x0, [x0[0] + 0.05, x0[1]],
                                                [x0[0], x0[1] + 0.2]]})
    return math.exp(res.x[0]), math.exp(res.x[1])


def robust_vines(problem, search, D: float, n_search: int, nominal: tuple,
                 n_threads=None) -> dict:
    """The VI NES (eta, clearance_m) minimising the largest worst case from rest over
    n_search host drifts in [-D, D]: ``design.optimise`` on a ``RobustEvaluator``, and a
    compass search from the ``nominal`` design (eta, L) too, so that the robust design is
    never worse than the nominal one on this objective; ``search``: the nominal
    ``design.DesignSearch`` (eta_max, range, grid)."""
    from .design import compass, optimise, search_grid
    ev = RobustEvaluator(problem, delta_grid(D, n_search) if n_search > 1 else [0.0],
                         n_threads)
    with progress.task(None, "robust design: runs from rest", "runs"):
        best = optimise(ev, search.eta_max, search.clearance_range_m, search.n_eta,
                        search.n_clearance)
        etas, Ls = search_grid(search.eta_max, search.clearance_range_m, search.n_eta,
                               search.n_clearance)
        logs = np.log10(Ls)
        steps = [0.5 * (etas[1] - etas[0]) if len(etas) > 1 else 0.0,
                 0.5 * (logs[1] - logs[0])]
        x0 = (nominal[0], math.log10(nominal[1]))
        x, v = compass(ev, x0, ev.worst([nominal])[0], steps, [etas[0], logs[0]],
                        [etas[-1], logs[-1]])
    if v < best["worst_ratio"]:
        moved = tuple(x) != x0
        best = best | dict(eta=float(x[0]) if moved else nominal[0],
                           clearance_m=10.0 ** float(x[1]) if moved else nominal[1],
                           worst_ratio=v)
    return best | dict(n_runs=ev.n_runs, n_designs=len(ev.cache))


# --------------------------------------------------------------------------- driver

def mistuning(result, D, *, n_delta: int = N_DELTA_DEFAULT, robust: bool = False,
              n_search: int = N_SEARCH_DEFAULT, n_threads=None) -> dict:
    """The JSON block ``mistuning`` of a ``design.DesignResult``: its designs over the
    host's drift (``curves``: keys delta, lo_alone, tmd, vines, vines_any_attractor,
    worst, worst_delta, design), and with ``robust`` (an optimised design only) the
    robust VI NES and the re-tuned TMD over the same drift (key ``robust``)."""
    D, n_delta, n_search = check_mistuning(D, n_delta, n_search)
    if robust and result.search is None:
        raise ParameterError("robust", True, "optimises a design: give eta_max with it")
    pb, t = result.problem, result.tmd
    t0, c0 = time.perf_counter(), time.process_time()
    out = curves(pb, t.eta, t.frequency_ratio, t.damping_ratio, result.eta,
                 result.clearance_m, D, n_delta, n_threads).to_dict()
    out["n_delta"] = n_delta
    out["tmd_stroke_m"] = tmd_over_delta(pb, t, out["delta"], D, n_delta)["stroke_m"]
    eq = result.tmd_equal_travel
    out["tmd_equal_travel"] = (None if eq is None else
                               tmd_over_delta(pb, eq, out["delta"], D, n_delta)
                               | dict(max_stroke_m=result.clearance_m))
    out["robust"] = None
    if robust:
        from .design import DesignSearch
        g = result.search
        search = DesignSearch(eta_max=result.inputs["eta_max"],
                              clearance_range_m=tuple(result.inputs["clearance_range_m"]),
                              n_eta=len(g["eta"]), n_clearance=len(g["clearance_m"]))
        best = robust_vines(pb, search, D, n_search, (result.eta, result.clearance_m),
                            n_threads)
        f, z = robust_tmd(t.eta, pb.model.d, pb.band, D,
                          (t.frequency_ratio, t.damping_ratio))
        rob = curves(pb, t.eta, f, z, best["eta"], best["clearance_m"], D, n_delta,
                     n_threads)
        out["robust"] = rob.to_dict() | dict(
            search=dict(delta=delta_grid(D, n_search).tolist() if n_search > 1 else [0.0],
                        worst_ratio=best["worst_ratio"], n_designs=best["n_designs"],
                        n_runs=best["n_runs"]),
            tmd_search=dict(n_delta=N_TMD_DELTA, n_omega=N_TMD_BAND))
    out["host"] = ("stiffness k (1 + delta)^2, natural frequency (1 + delta) w0; absorbers "
                   "and band fixed in absolute terms; the detuned host is the model at "
                   "omega/(1 + delta), d/(1 + delta), TMD f/(1 + delta), times "
                   "(1 + delta) t")
    out["cost"] = dict(wall_s=time.perf_counter() - t0, cpu_s=time.process_time() - c0)
    return out
