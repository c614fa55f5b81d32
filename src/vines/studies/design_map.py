"""The map of who wins where: the best VI NES against the TMD of the same mass, free and at
equal travel, over mass ratio, band and amplitude span (docs/design.md, "Who wins where").

A cell is (eta, h, S): the ball-to-LO (and TMD-to-LO) mass ratio eta, the band
omega in [1 - h, 1 + h] around the host's natural frequency (a host whose frequency drifts
is modelled as this band: no drift besides it), and the base amplitudes A_max/S ... A_max
(``n_amplitudes`` of them, log-spaced; one for S = 1). Everything is scale-free: the VI NES
depends on A/L only and the TMD is linear, so lengths are in units of A_max and reported in
metres for ``amplitude_max_m``.

Per cell:

* **the best VI NES** by the slow flow (``slowflow.optimal``): for each restitution r of
  the grid ``restitution`` the clearance L minimising the worst x_max/A over the band and
  the amplitudes (``optimal_clearance``), then the best r;
* **the TMD free** (``tmd.optimal_tmd``: band-optimal, unconstrained) with its travel
  |u - x| per unit base amplitude, and **the TMD at equal travel** (travel <= the VI NES's
  clearance L at A_max); their worst ratios are closed form, the same in both models;
* **the ratios** VI NES / TMD (> 1: the TMD wins);
* **the exact check** (``studies.design.Evaluator``: runs from rest on the band's grid,
  peaks refined) at the slow flow's design (eta, L, r), on every cell near the frontier
  (a slow-flow ratio within a factor ``frontier_factor`` of 1 against either TMD) and on a
  seeded sample of the others (a cell is drawn when ``rng(seed, cell index) <
  exact_sample``), and at the slow flow's best clearance for every other r of the grid:
  the best of them is the exact choice of r; with ``exact_refine`` also a local compass
  search of L in the exact model at that r, whose result gives the confirmed verdict.

Each cell depends on its own inputs alone (the exact sample's draw too), so a map cut into
chunks of cells gives the same numbers for any chunk size (``map_cells``). numpy and scipy
only; the exact solver is loaded for confirmed cells alone.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from .. import progress
from ..core.params import (
    D_DEFAULT,
    MAX_IMPACTS_DEFAULT,
    ROOT_TOL_DEFAULT,
    T_END_DEFAULT,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    ParameterError,
    check_bool,
    check_int,
    check_param,
    check_real,
    check_reals,
)

#: defaults of the map (``vines design-map``; the config's ``design_maps`` entries)
ETA_DEFAULT = (0.005, 0.2, 6)              # log-spaced: start, stop, num
HALF_WIDTH_DEFAULT = (0.05, 0.1, 0.2, 0.4)
SPAN_DEFAULT = (1.0, 8.0)
RESTITUTION_DEFAULT = (0.0, 0.3, 0.5, 0.65, 0.8)
N_AMPLITUDES_DEFAULT = 3
AMPLITUDE_MAX_M_DEFAULT = 0.006
N_OMEGA_DEFAULT = 201
N_CLEARANCE_DEFAULT = 41
N_OMEGA_EXACT_DEFAULT = 21
FRONTIER_FACTOR_DEFAULT = 1.5
EXACT_SAMPLE_DEFAULT = 0.1
#: golden-section steps of ``slowflow.optimal._minimise`` besides its grid (design counts)
_EXTRA_DESIGNS = 40 + 2 + 1
#: the exact refinement: first step in log10 L, and its half range around the slow flow's L
REFINE_STEP = 0.05
REFINE_RANGE = 0.3
#: why a cell was checked by the exact solver (dataset flag values)
CONFIRM_NONE, CONFIRM_FRONTIER, CONFIRM_SAMPLE = 0, 1, 2
#: a ratio VI NES/TMD within this relative margin of 1 is a tie (no winner)
TIE = 0.05
#: the slow flow's stated domain (docs/slowflow.md, section 8: no warning)
HALF_WIDTH_MAX = 0.95


@dataclass(frozen=True)
class MapSpec:
    """A validated map (see the module docstring). eta, half_width, span, restitution:
    the axes (tuples); n_amplitudes per cell with S > 1; amplitude_max_m [m]; d: the LO's
    damping c/(M w0); n_omega, n_clearance: the slow flow's band grid and clearance grid;
    the exact check: n_omega_exact, frontier_factor, exact_sample (fraction of the other
    cells), seed, exact_check (False: the slow flow alone), exact_refine, and the runs' t_end, t_transient, v_stick, max_impacts,
    root_tol."""

    eta: tuple
    half_width: tuple
    span: tuple
    restitution: tuple = RESTITUTION_DEFAULT
    n_amplitudes: int = N_AMPLITUDES_DEFAULT
    amplitude_max_m: float = AMPLITUDE_MAX_M_DEFAULT
    d: float = D_DEFAULT
    n_omega: int = N_OMEGA_DEFAULT
    n_clearance: int = N_CLEARANCE_DEFAULT
    n_omega_exact: int = N_OMEGA_EXACT_DEFAULT
    frontier_factor: float = FRONTIER_FACTOR_DEFAULT
    exact_sample: float = EXACT_SAMPLE_DEFAULT
    seed: int = 0
    exact_check: bool = True
    exact_refine: bool = True
    t_end: float = T_END_DEFAULT
    t_transient: float = T_TRANSIENT_DEFAULT
    v_stick: float = V_STICK_DEFAULT
    max_impacts: int = MAX_IMPACTS_DEFAULT
    root_tol: float = ROOT_TOL_DEFAULT

    @property
    def shape(self) -> tuple:
        return (len(self.eta), len(self.half_width), len(self.span))

    @property
    def n_cells(self) -> int:
        return math.prod(self.shape)

    def cell(self, index: int) -> tuple[float, float, float]:
        """(eta, h, S) of the cell ``index`` (C order of eta, half_width, span)."""
        i, j, k = np.unravel_index(int(index), self.shape)
        return self.eta[i], self.half_width[j], self.span[k]

    def amplitudes(self, span: float) -> np.ndarray:
        """Base amplitudes [m] of a span: n_amplitudes log-spaced up to amplitude_max_m."""
        n = 1 if span == 1.0 else self.n_amplitudes
        return self.amplitude_max_m * np.geomspace(1.0 / span, 1.0, n)

    def to_dict(self) -> dict:
        return {k: (list(v) if isinstance(v, tuple) else v) for k, v in asdict(self).items()}


def _axis(name: str, values, lo: float, hi: float, *, lo_open: bool, hi_open: bool = False):
    """A sorted tuple of distinct numbers between lo and hi; ParameterError."""
    if isinstance(values, (int, float, str)):
        values = [values]
    arr = check_reals(name, values, lo=lo, lo_open=lo_open, hi=hi, min_size=1, max_size=1000)
    if hi_open and (arr >= hi).any():
        raise ParameterError(name, float(arr.max()), f"must be < {hi:g}")
    if np.unique(arr).size != arr.size:
        raise ParameterError(name, list(values), "must be distinct numbers")
    return tuple(float(x) for x in np.sort(arr))


def log_axis(name: str, start, stop, num) -> tuple:
    """num log-spaced values from start to stop (both > 0, start < stop unless num = 1)."""
    a = check_real(name, start, lo=0.0, lo_open=True)
    b = check_real(name, stop, lo=0.0, lo_open=True)
    n = check_int(name, num, lo=1, hi=1000)
    if n > 1 and not a < b:
        raise ParameterError(name, f"{start} {stop} {num}",
                             "must be START < STOP (an empty range otherwise)")
    return tuple(float(x) for x in np.geomspace(a, b, n))


def check_map(*, eta, half_width, span, restitution=RESTITUTION_DEFAULT,
              n_amplitudes=N_AMPLITUDES_DEFAULT, amplitude_max_m=AMPLITUDE_MAX_M_DEFAULT,
              d=D_DEFAULT, n_omega=N_OMEGA_DEFAULT, n_clearance=N_CLEARANCE_DEFAULT,
              n_omega_exact=N_OMEGA_EXACT_DEFAULT, frontier_factor=FRONTIER_FACTOR_DEFAULT,
              exact_sample=EXACT_SAMPLE_DEFAULT, seed=0, exact_check=True, exact_refine=True,
              t_end=T_END_DEFAULT, t_transient=T_TRANSIENT_DEFAULT, v_stick=V_STICK_DEFAULT,
              max_impacts=MAX_IMPACTS_DEFAULT, root_tol=ROOT_TOL_DEFAULT) -> MapSpec:
    """A MapSpec from plain values; ParameterError naming the bad one. eta in (0, 0.5]
    (the slow flow's range), half widths in (0, HALF_WIDTH_MAX) (the band must hold the
    host frequency 1 and stay above 0), spans >= 1, restitution in [0, 1)."""
    from ..core.params import SolverSettings
    t_end = check_real("t_end", t_end, lo=0.0, lo_open=True)
    SolverSettings(t_end=t_end, t_transient=t_transient, v_stick=v_stick,
                   max_impacts=max_impacts, root_tol=root_tol)
    return MapSpec(
        eta=_axis("eta", eta, 0.0, 0.5, lo_open=True),
        half_width=_axis("half_width", half_width, 0.0, HALF_WIDTH_MAX, lo_open=True,
                         hi_open=True),
        span=_axis("span", span, 1.0, 1e3, lo_open=False),
        restitution=_axis("restitution", restitution, 0.0, 0.99, lo_open=False),
        n_amplitudes=check_int("n_amplitudes", n_amplitudes, lo=2, hi=20),
        amplitude_max_m=check_real("amplitude_max_m", amplitude_max_m, lo=0.0,
                                   lo_open=True, hi=1.0),
        d=check_param("d", d),
        n_omega=check_int("n_omega", n_omega, lo=3, hi=100_001),
        n_clearance=check_int("n_clearance", n_clearance, lo=3, hi=10_000),
        n_omega_exact=check_int("n_omega_exact", n_omega_exact, lo=2, hi=10_001),
        frontier_factor=check_real("frontier_factor", frontier_factor, lo=1.0, hi=1e3),
        exact_sample=check_real("exact_sample", exact_sample, lo=0.0, hi=1.0),
        seed=check_int("seed", seed, lo=0, hi=2**63 - 1),
        exact_check=check_bool("exact_check", exact_check),
        exact_refine=check_bool("exact_refine", exact_refine),
        t_end=t_end, t_transient=float(t_transient), v_stick=float(v_stick),
        max_impacts=int(max_impacts), root_tol=float(root_tol))


def from_entry(entry: dict, **fixed) -> MapSpec:
    """The MapSpec of a config entry (``design_maps.<name>``): its keys but description
    (eta a list or {start, stop, num} log-spaced) and ``fixed`` (d and the solver's
    v_stick, max_impacts, root_tol); ParameterError naming the bad key."""
    kw = {k: v for k, v in entry.items() if k != "description" and v is not None}
    eta = kw.pop("eta")
    if isinstance(eta, dict):
        eta = log_axis("eta", eta.get("start"), eta.get("stop"), eta.get("num"))
    return check_map(eta=eta, **kw, **fixed)


# --------------------------------------------------------------------------- one cell

def band_of(h: float) -> tuple[float, float]:
    return (1.0 - h, 1.0 + h)


def best_vines(spec: MapSpec, eta: float, h: float, span: float) -> dict:
    """The slow flow's best VI NES of a cell: per r of the grid the best clearance, then
    the best r (the first of equal ones). in_domain: the slow flow's stated domain
    (docs/slowflow.md, section 8): no warning, and r > 0 (a plastic ball sticks to the
    wall, which the slow flow does not describe)."""
    from ..slowflow.optimal import optimal_clearance
    amps = spec.amplitudes(span)
    per_r = [optimal_clearance(eta, amps, band_of(h), r=r, d=spec.d, n_omega=spec.n_omega,
                               n_grid=spec.n_clearance) for r in spec.restitution]
    k = int(np.argmin([o.worst_ratio for o in per_r]))
    best = per_r[k]
    return dict(worst_ratio=best.worst_ratio, worst_omega=best.omega_peak,
                clearance_m=best.clearance_m, restitution=spec.restitution[k],
                worst_ratio_by_restitution=[o.worst_ratio for o in per_r],
                clearance_m_by_restitution=[o.clearance_m for o in per_r],
                warnings=list(best.warnings),
                in_domain=not best.warnings and spec.restitution[k] > 0.0,
                n_designs=len(per_r) * (spec.n_clearance + _EXTRA_DESIGNS))


_TMD_CACHE: dict = {}


def free_tmd(eta: float, d: float, h: float):
    """The band-optimal TMD of mass ratio eta (``tmd.optimal_tmd``, no travel limit),
    cached in the process (cells of one (eta, h) share it; the same numbers either way)."""
    from .tmd import optimal_tmd
    key = (float(eta), float(d), float(h))
    if key not in _TMD_CACHE:
        _TMD_CACHE[key] = optimal_tmd(eta, d, band_of(h))
    return _TMD_CACHE[key]


def tmds(spec: MapSpec, eta: float, h: float, clearance_m: float) -> dict:
    """The TMD free and at equal travel (travel <= clearance_m at A_max: max_travel
    L/A_max per unit base amplitude); the free one where its travel is within the limit."""
    from .tmd import optimal_tmd
    free = free_tmd(eta, spec.d, h)
    limit = clearance_m / spec.amplitude_max_m
    equal = free if free.worst_travel <= limit else optimal_tmd(eta, spec.d, band_of(h),
                                                               max_travel=limit)
    return dict(free=free, equal_travel=equal, max_travel=limit)


def is_sampled(spec: MapSpec, index: int) -> bool:
    """Whether the cell ``index`` is in the exact check's seeded sample (its own draw)."""
    return bool(np.random.default_rng([spec.seed, int(index)]).random() < spec.exact_sample)


def near_frontier(spec: MapSpec, ratios) -> bool:
    """A slow-flow ratio VI NES/TMD within a factor frontier_factor of 1."""
    lim = math.log(spec.frontier_factor)
    return any(abs(math.log(x)) <= lim for x in ratios if np.isfinite(x) and x > 0)


def _problem(spec: MapSpec, h: float, span: float, r: float):
    from ..core.params import ModelParams, SolverSettings
    from .design import DesignProblem
    st = SolverSettings(t_end=spec.t_end, t_transient=spec.t_transient,
                        v_stick=spec.v_stick, max_impacts=spec.max_impacts,
                        root_tol=spec.root_tol)
    omega = tuple(float(w) for w in np.linspace(1.0 - h, 1.0 + h, spec.n_omega_exact))
    return DesignProblem(model=ModelParams(eta=1.0, omega=1.0, F=0.0, r=r, d=spec.d),
                         omega=omega, amplitudes_m=tuple(float(a) for a in
                                                         spec.amplitudes(span)),
                         settings=st)


def exact_check(spec: MapSpec, eta: float, h: float, span: float, vines: dict) -> dict:
    """The exact worst x_max/A (from rest, ``design.Evaluator``) at the slow flow's best
    design of every restitution of the grid (the one at its overall best: the models'
    comparison), the best of them (the exact choice of r), and with exact_refine a compass
    search in log10 L around that one (r and eta fixed; never worse than its start)."""
    by_r = [_exact_worst(spec, eta, h, span, r, L) for r, L in
            zip(spec.restitution, vines["clearance_m_by_restitution"], strict=True)]
    k_slow = spec.restitution.index(vines["restitution"])
    k = int(np.argmin([w for w, _, _ in by_r]))
    best, L_best, n_runs = by_r[k][0], by_r[k][1], sum(n for _, _, n in by_r)
    if spec.exact_refine:
        best, L_best, n = _refine(spec, eta, h, span, spec.restitution[k], L_best, best)
        n_runs += n
    return dict(worst_ratio=by_r[k_slow][0], worst_ratio_by_restitution=[w for w, _, _ in by_r],
                worst_ratio_refined=best, restitution=spec.restitution[k],
                clearance_m_refined=L_best, n_runs=n_runs)


def _exact_worst(spec: MapSpec, eta, h, span, r, clearance_m) -> tuple[float, float, int]:
    """(exact worst x_max/A, its clearance as the compass search spells it, runs) of the
    design (eta, clearance_m, r)."""
    from .design import Evaluator
    L = 10.0 ** float(math.log10(clearance_m))   # as design.compass maps log10 L to L
    ev = Evaluator(_problem(spec, h, span, r), n_threads=1)
    return ev.worst([(eta, L)])[0], L, ev.n_runs


def _refine(spec: MapSpec, eta, h, span, r, L, value) -> tuple[float, float, int]:
    """Compass search in log10 L (+- REFINE_RANGE decades, first step REFINE_STEP) from the
    design (eta, L, r) of exact worst ``value``: (best value, its L, runs)."""
    from .design import Evaluator, compass
    ev = Evaluator(_problem(spec, h, span, r), n_threads=1)
    u = math.log10(L)
    lo_u = max(u - REFINE_RANGE, math.log10(spec.amplitude_max_m / 2.0))
    x, best = compass(ev, (eta, u), value, (0.0, REFINE_STEP), (eta, lo_u),
                      (eta, u + REFINE_RANGE))
    return best, 10.0 ** float(x[1]), ev.n_runs


def map_cell(spec: MapSpec, index: int) -> dict:
    """Everything of the cell ``index`` (module docstring): plain numbers and lists."""
    eta, h, span = spec.cell(index)
    vines = best_vines(spec, eta, h, span)
    t = tmds(spec, eta, h, vines["clearance_m"])
    free, equal = t["free"], t["equal_travel"]
    ratios = [vines["worst_ratio"] / free.worst_ratio, vines["worst_ratio"] / equal.worst_ratio]
    frontier = near_frontier(spec, ratios)
    reason = (CONFIRM_NONE if not spec.exact_check else CONFIRM_FRONTIER if frontier else
              CONFIRM_SAMPLE if is_sampled(spec, index) else CONFIRM_NONE)
    exact = None
    if reason != CONFIRM_NONE:
        exact = exact_check(spec, eta, h, span, vines)
        # the exact design's clearance is the TMD's travel limit of its verdict
        exact["tmd_equal_travel"] = _tmd_dict(
            tmds(spec, eta, h, exact["clearance_m_refined"])["equal_travel"])
    return dict(index=int(index), eta=eta, half_width=h, span=span, vines=vines,
                tmd=_tmd_dict(free), tmd_equal_travel=_tmd_dict(equal),
                max_travel=t["max_travel"], ratio=ratios[0], ratio_equal_travel=ratios[1],
                confirm=reason, exact=exact)


def _tmd_dict(t) -> dict:
    return dict(frequency_ratio=t.frequency_ratio, damping_ratio=t.damping_ratio,
                worst_ratio=t.worst_ratio, worst_omega=t.worst_omega,
                worst_travel=t.worst_travel)


def map_cells(spec: MapSpec, start: int = 0, stop: int | None = None,
              n_workers: int = 1) -> list[dict]:
    """``map_cell`` of the cells [start, stop) in order (a chunk of the map), in
    ``n_workers`` processes (spawned; the numbers do not depend on them)."""
    stop = spec.n_cells if stop is None else stop
    cells = range(start, stop)
    n_workers = check_int("n_workers", n_workers, lo=1, hi=4096)
    if n_workers == 1 or len(cells) < 2:
        return [map_cell(spec, i)
                for i in progress.track(cells, len(cells), "design map", "cells")]
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor
    from functools import partial
    ctx = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(min(n_workers, len(cells)), mp_context=ctx) as pool:
        try:
            return list(progress.track(pool.map(partial(map_cell, spec), cells),
                                       len(cells), "design map", "cells"))
        except BaseException:
            pool.shutdown(wait=False, cancel_futures=True)
            raise


# --------------------------------------------------------------------------- the map

def _grid(cells: list, shape: tuple, get, fill=np.nan, dtype="f8") -> np.ndarray:
    out = np.full(shape, fill, dtype=dtype)
    for c in cells:
        v = get(c)
        out[np.unravel_index(c["index"], shape)] = fill if v is None else v
    return out


def assemble(spec: MapSpec, cells: list) -> dict:
    """The map's arrays (eta, half_width, span) from every cell's dict, in cell order
    (refused unless the cells are exactly 0 .. n_cells - 1). Exact values NaN where a cell
    was not checked. ``verdict_*``: the ratio VI NES/TMD of the exact refined design where
    checked, else the slow flow's; ``verdict_differs``: the exact and the slow flow name
    different winners against either TMD."""
    if [c["index"] for c in cells] != list(range(spec.n_cells)):
        raise ValueError(f"the map needs its {spec.n_cells} cells in order, got "
                         f"{len(cells)}")
    s, n_r = spec.shape, len(spec.restitution)
    g = {}
    v = lambda key: _grid(cells, s, lambda c: c["vines"][key])  # noqa: E731
    for key in ("worst_ratio", "worst_omega", "clearance_m", "restitution"):
        g[f"vines_{key}"] = v(key)
    g["vines_in_domain"] = _grid(cells, s, lambda c: c["vines"]["in_domain"], 0, "i1")
    by_r = np.full(s + (n_r,), np.nan)
    for c in cells:
        by_r[np.unravel_index(c["index"], s)] = c["vines"]["worst_ratio_by_restitution"]
    g["vines_worst_ratio_by_restitution"] = by_r
    ex_r = np.full(s + (n_r,), np.nan)
    for c in cells:
        if c["exact"]:
            ex_r[np.unravel_index(c["index"], s)] = c["exact"]["worst_ratio_by_restitution"]
    g["vines_worst_ratio_exact_by_restitution"] = ex_r
    for prefix in ("tmd", "tmd_equal_travel"):
        for key in ("frequency_ratio", "damping_ratio", "worst_ratio", "worst_omega",
                    "worst_travel"):
            g[f"{prefix}_{key}"] = _grid(cells, s, lambda c, p=prefix, k=key: c[p][k])
    g["ratio"] = _grid(cells, s, lambda c: c["ratio"])
    g["ratio_equal_travel"] = _grid(cells, s, lambda c: c["ratio_equal_travel"])
    g["confirm"] = _grid(cells, s, lambda c: c["confirm"], 0, "i1")
    ex = lambda key: _grid(cells, s, lambda c: c["exact"] and c["exact"][key])  # noqa: E731
    g["vines_worst_ratio_exact"] = ex("worst_ratio")
    g["vines_worst_ratio_exact_refined"] = ex("worst_ratio_refined")
    g["vines_clearance_m_exact_refined"] = ex("clearance_m_refined")
    g["vines_restitution_exact"] = ex("restitution")
    g["tmd_equal_travel_exact_worst_ratio"] = _grid(
        cells, s, lambda c: c["exact"] and c["exact"]["tmd_equal_travel"]["worst_ratio"])
    g["exact_runs"] = _grid(cells, s, lambda c: c["exact"] and c["exact"]["n_runs"], 0,
                            "i8")
    g.update(derived(g, spec.amplitude_max_m))
    return g


def winner(ratio):
    """-1 where the VI NES wins (ratio VI NES/TMD below 1/(1 + TIE)), +1 where the TMD
    wins (above 1 + TIE), 0 for a tie (within TIE of each other)."""
    r = np.asarray(ratio, dtype=float)
    return np.where(r < 1.0 / (1.0 + TIE), -1, np.where(r > 1.0 + TIE, 1, 0))


def derived(g: dict, amplitude_max_m: float) -> dict:
    """The map's comparisons from its arrays ``g``: the slow flow's relative error at its
    design, the verdict ratios (where checked: the exact refined VI NES over the TMD free
    and limited to the exact design's clearance), whether the two models name different
    winners, and the free TMD's travel against the VI NES's clearance."""
    slow, exact = g["vines_worst_ratio"], g["vines_worst_ratio_exact"]
    refined = g["vines_worst_ratio_exact_refined"]
    checked = np.isfinite(exact)
    out = {"slowflow_relative_error": (slow - exact) / exact}
    for key, exact_tmd in (("", g["tmd_worst_ratio"]),
                           ("_equal_travel", g["tmd_equal_travel_exact_worst_ratio"])):
        tmd = g[f"tmd{key}_worst_ratio"]
        verdict = np.where(checked, refined / exact_tmd, slow / tmd)
        out[f"verdict_ratio{key}"] = verdict
        differs = checked & (winner(slow / tmd) * winner(verdict) < 0)
        out[f"verdict_differs{key}"] = differs.astype("i1")
    out["tmd_travel_over_clearance"] = (g["tmd_worst_travel"] * amplitude_max_m
                                        / g["vines_clearance_m"])
    return out


def summary(spec: MapSpec, g: dict) -> dict:
    """Counts of the map: cells, designs evaluated by the slow flow, exact checks (frontier,
    sample), runs, where each absorber wins (verdict ratios), where the models disagree
    and the largest slow-flow error inside and outside its stated domain."""
    conf = g["confirm"]
    err = np.abs(g["slowflow_relative_error"])
    dom = g["vines_in_domain"] == 1

    def worst(mask):
        m = mask & np.isfinite(err)
        return float(err[m].max()) if m.any() else None
    return dict(n_cells=spec.n_cells,
                n_frontier=int((conf == CONFIRM_FRONTIER).sum()),
                n_sample=int((conf == CONFIRM_SAMPLE).sum()),
                n_exact_runs=int(g["exact_runs"].sum()),
                vines_wins=int((winner(g["verdict_ratio"]) < 0).sum()),
                vines_wins_equal_travel=int((winner(g["verdict_ratio_equal_travel"]) < 0)
                                            .sum()),
                verdict_differs=int(g["verdict_differs"].sum()),
                verdict_differs_equal_travel=int(g["verdict_differs_equal_travel"].sum()),
                ties_equal_travel=int((winner(g["verdict_ratio_equal_travel"]) == 0).sum()),
                slowflow_error_max_in_domain=worst(dom),
                slowflow_error_max_outside_domain=worst(~dom))
