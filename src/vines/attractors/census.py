"""Attractor census at one parameter point: which attractors coexist, and how likely each is.

n initial states (``sampling.sample_states``) run until they settle (``endstate``); their
end states are grouped into attractors:

* 1:1 orbits (polished by the map's Newton solver) are one attractor when their pre-impact
  states at L agree to GROUP_TOL (relative; impact times modulo T);
* other confirmed periodic orbits when they have the same period and their section states
  agree to GROUP_TOL up to a shift by whole forcing periods;
* everything else by regime label ("chatter", "irregular", "no-impact", ...), split where
  the sorted KE ratios of a label jump by more than KE_GAP.

Each attractor gets its basin fraction (members / n) with a 95 % Wilson score interval
(``scipy.stats.binomtest(...).proportion_ci(method="wilson")``), its KE ratio and x_max
(periodic: exact over one period of the orbit; otherwise the mean and [min, max] of the
members' window measures) and one initial state that reaches it. The from-rest start is
classified the same way; if it reaches an attractor no sampled state reached, that
attractor is listed with basin fraction 0. Runs that stopped early are the unsettled
fraction: the fractions of the attractors and the unsettled fraction sum to 1.
"""
from __future__ import annotations

import inspect
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ..core.exact import oscillators
from ..core.params import (
    D_DEFAULT,
    L_HALF_M,
    MAX_IMPACTS_DEFAULT,
    R_DEFAULT,
    ROOT_TOL_DEFAULT,
    T_END_DEFAULT,
    T_END_MAX,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    ModelParams,
    ParameterError,
    SolverSettings,
    as_float_array,
    check_int,
    check_real,
)
from ..core.shortcut import rel_diff
from . import asymptotic as asy
from .endstate import EndState, settle, settle_states
from .orbit import one_period, section_of_1to1
from .sampling import BOX_NAMES, DEFAULT_BOX, N_MAX, SEED_MAX, check_box, sample_states

#: end states closer than this (relative) are the same periodic orbit
GROUP_TOL = 1e-6
#: non-periodic members of one regime label split where sorted KE ratios jump by this
KE_GAP = 0.05
#: confidence level of the basin fractions' intervals
CI_LEVEL = 0.95
CI_METHOD = "wilson"


@dataclass
class Attractor:
    """One attractor of a census. ke_ratio, xmax_m: exact over one period (periodic) or
    the members' mean; ``*_range``: [min, max] over the members (a point for periodic ones);
    ci: Wilson score interval of basin_fraction; example_state: an initial state
    (z_m, z_m', z_b, z_b') that reaches it; section_state: a state of the orbit at
    t = k T (periodic only); orbit: extra facts of a 1:1 orbit (lambda_max, dw_L, ...);
    window_regimes: members by the regime label of their own measurement window (a member
    that settled only inside the window, e.g. after a long chatter transient, keeps the
    label of that transient there)."""

    regime: str
    period: int
    periodic: bool
    ke_ratio: float
    ke_ratio_range: list
    xmax_m: float
    xmax_m_range: list
    count: int
    basin_fraction: float
    ci: list
    example_state: list
    window_regimes: dict
    section_state: list | None = None
    orbit: dict | None = None
    asymptotic: dict | None = None

    def to_dict(self) -> dict:
        """The attributes; with an asymptotic view (``census(t_max=...)``) its keys
        (basin_fraction_asymptotic, ci_asymptotic, status, lyapunov_max, ...) as well."""
        out = dict(self.__dict__)
        extra = out.pop("asymptotic")
        return out | extra if extra is not None else out


@dataclass
class Census:
    """Result of ``census``: attractors sorted by basin fraction (largest first),
    from_rest = index of the attractor reached from rest (None: that run stopped early), unsettled_fraction = share of
    runs that stopped early."""

    params: dict
    settings: dict
    n: int
    seed: int
    box: dict
    attractors: list
    from_rest: int | None
    unsettled_fraction: float
    ci_method: str = f"{CI_METHOD} score interval, {CI_LEVEL:.0%}"
    members: np.ndarray = field(default=None, repr=False)
    t_max: float | None = None
    from_rest_asymptotic: int | None = None
    members_asymptotic: np.ndarray = field(default=None, repr=False)

    def to_dict(self) -> dict:
        out = {"attractors": [a.to_dict() for a in self.attractors],
               "from_rest": self.from_rest, "unsettled_fraction": self.unsettled_fraction,
               "n": self.n, "seed": self.seed, "box": self.box, "ci_method": self.ci_method,
               "params": self.params, "settings": self.settings}
        if self.t_max is not None:
            out |= {"t_max": self.t_max, "from_rest_asymptotic": self.from_rest_asymptotic}
        return out


class _Group:
    def __init__(self, first: int, end: EndState):
        self.first, self.end, self.members = first, end, []


def _same_1to1(a, b, T) -> bool:
    dt = abs(a.x_L[3] - b.x_L[3]) % T
    return min(dt, T - dt) <= GROUP_TOL * (1.0 + T) and bool(
        np.all(np.abs(a.x_L[:3] - b.x_L[:3]) <= GROUP_TOL * (1.0 + np.abs(a.x_L[:3]))))


def _same_orbit(a: EndState, b: EndState) -> bool:
    pp = a.section.shape[0]
    if b.section.shape[0] != pp:
        return False
    for shift in range(pp):
        if all(rel_diff(a.section[i], b.section[(i + shift) % pp]) <= GROUP_TOL
               and a.modes[i] == b.modes[(i + shift) % pp] for i in range(pp)):
            return True
    return False


def _matches(g: _Group, e: EndState, T: float) -> bool:
    """Same periodic orbit (kinds 1:1, orbit); motions match by regime label here and are
    split by KE ratio later (``_split_motions``)."""
    if g.end.kind != e.kind:
        return False
    if e.kind == "1:1":
        return _same_1to1(g.end.orbit, e.orbit, T)
    if e.kind == "orbit":
        return _same_orbit(g.end, e)
    return g.end.regime == e.regime


def _group(ends: list, T: float) -> tuple[list, int]:
    """Groups in order of first appearance, and the number of unsettled runs."""
    groups, unsettled = [], 0
    for i, e in enumerate(ends):
        if e.kind == "unsettled":
            unsettled += 1
            continue
        g = next((g for g in groups if _matches(g, e, T)), None)
        if g is None:
            g = _Group(i, e)
            groups.append(g)
        g.members.append(i)
    return _split_motions(groups, ends), unsettled


def _split_motions(groups: list, ends: list) -> list:
    """Split each non-periodic group where its sorted KE ratios jump by more than KE_GAP."""
    out = []
    for g in groups:
        if g.end.kind != "motion":
            out.append(g)
            continue
        order = sorted(g.members, key=lambda i: (ends[i].ke_ratio, i))
        cur = [order[0]]
        for a, b in zip(order[:-1], order[1:], strict=False):
            if ends[b].ke_ratio - ends[a].ke_ratio > KE_GAP:
                out.append(_subgroup(cur, ends))
                cur = []
            cur.append(b)
        out.append(_subgroup(cur, ends))
    return sorted(out, key=lambda g: g.first)


def _subgroup(members: list, ends: list) -> _Group:
    first = min(members)
    g = _Group(first, ends[first])
    g.members = sorted(members)
    return g


def _wilson(k: int, n: int) -> list:
    from scipy.stats import binomtest
    if n == 0:
        return [0.0, 1.0]
    ci = binomtest(k, n).proportion_ci(confidence_level=CI_LEVEL, method=CI_METHOD)
    return [float(ci.low), float(ci.high)]


def _periodic_summary(p, st, oscs, e: EndState) -> dict:
    """Exact measures over one period of the orbit of end state e (kinds 1:1, orbit)."""
    if e.kind == "1:1":
        one = section_of_1to1(p, st, oscs, e.orbit)
        o = e.orbit
        extra = {"lambda_max": o.lambda_max, "stable": o.stable, "symmetric": o.symmetric,
                 "dw_L": o.dw_L, "dw_R": o.dw_R, "phase_L": o.phase_L, "phase_R": o.phase_R,
                 "x_L": [float(v) for v in o.x_L]}
        return dict(regime="1:1", period=1, ke=one["ke_ratio"], xmax=one["xmax"],
                    section=one["section_state"], orbit=extra)
    pp = e.section.shape[0]
    one = one_period(p, st, oscs, e.section[0], e.t_section, pp * p.period, int(e.modes[0]))
    return dict(regime=one["regime"], period=pp, ke=one["ke_ratio"], xmax=one["xmax"],
                section=e.section[0], orbit=None)


def _attractor(p, st, oscs, g: _Group, ends: list, states: np.ndarray, n: int) -> Attractor:
    k = len(g.members)
    example = states[g.first] if g.first >= 0 else np.zeros(4)
    labels = [ends[i].regime for i in g.members]
    common = dict(count=k, basin_fraction=k / n, ci=_wilson(k, n),
                  example_state=[float(v) for v in example],
                  window_regimes={lab: labels.count(lab) for lab in sorted(set(labels))})
    if g.end.kind in ("1:1", "orbit"):
        s = _periodic_summary(p, st, oscs, g.end)
        return Attractor(regime=s["regime"], period=s["period"], periodic=True,
                         ke_ratio=s["ke"], ke_ratio_range=[s["ke"], s["ke"]],
                         xmax_m=s["xmax"] * L_HALF_M,
                         xmax_m_range=[s["xmax"] * L_HALF_M] * 2,
                         section_state=[float(v) for v in s["section"]], orbit=s["orbit"],
                         **common)
    mem = [ends[i] for i in g.members] or [g.end]
    ke = np.array([e.ke_ratio for e in mem])
    xm = np.array([e.xmax for e in mem]) * L_HALF_M
    return Attractor(regime=g.end.regime, period=0, periodic=False, ke_ratio=float(ke.mean()),
                     ke_ratio_range=[float(ke.min()), float(ke.max())],
                     xmax_m=float(xm.mean()), xmax_m_range=[float(xm.min()), float(xm.max())],
                     **common)


def _place_from_rest(groups: list, rest: EndState, T: float) -> _Group | None:
    """The group the from-rest end state belongs to (a motion: the label's group with the
    nearest mean KE ratio within KE_GAP), or a new empty group; None if unsettled."""
    if rest.kind == "unsettled":
        return None
    if rest.kind != "motion":
        g = next((g for g in groups if _matches(g, rest, T)), None)
    else:
        cands = [g for g in groups if g.end.kind == "motion" and g.end.regime == rest.regime]
        g = None
        if cands:
            g = min(cands, key=lambda c: abs(c.end.ke_ratio - rest.ke_ratio))
            g = g if abs(g.end.ke_ratio - rest.ke_ratio) <= KE_GAP else None
    if g is None:
        g = _Group(-1, rest)
        groups.append(g)
    return g


def _check_states(states) -> np.ndarray:
    """Given initial states as an (n, 4) array, each a valid ``state0``."""
    arr = as_float_array("states", states)
    if arr.ndim != 2 or arr.shape[1] != 4 or arr.shape[0] == 0:
        raise ParameterError("states", f"shape {arr.shape}", "must be an (n, 4) array, n >= 1")
    for row in arr:
        SolverSettings(state0=tuple(row))       # raises ParameterError for a bad state
    return arr


def census(eta: float, omega: float, F: float, *, r: float = R_DEFAULT, d: float = D_DEFAULT,
           n: int = 256, seed: int = 0, box: Sequence[Sequence[float]] = DEFAULT_BOX,
           states: ArrayLike | None = None, t_end: float = T_END_DEFAULT,
           t_transient: float = T_TRANSIENT_DEFAULT, v_stick: float = V_STICK_DEFAULT,
           max_impacts: int = MAX_IMPACTS_DEFAULT, root_tol: float = ROOT_TOL_DEFAULT,
           n_threads: int | None = None, t_max: float | None = None) -> Census:
    """Attractor census at (eta, omega, F) from n Sobol initial states in ``box``
    (``sampling``; forcing phase 0 at t = 0), or from the given ``states`` (n, 4) =
    (z_m, z_m', z_b, z_b') (then n, seed and box are not used), each run to t_end with the
    measures over [t_transient, t_end] (module docstring). ``members`` of the result: the
    attractor index of every state (-1: unsettled).

    ``t_max`` (> t_end; ``asymptotic.T_MAX_DEFAULT`` is the documented choice): also the
    asymptotic view (``asymptotic``): states not settled at t_end run on until they settle
    on a periodic orbit or reach t_max; every attractor gains basin_fraction_asymptotic,
    ci_asymptotic, status, lyapunov_max (and motion classes their lifetime and where their
    states escape to), the result ``t_max``, ``from_rest_asymptotic`` and
    ``members_asymptotic``. Without t_max the result is the t_end view alone, unchanged.
    Raises ParameterError for bad input."""
    p, st, t_max, box, seed, states = _inputs(dict(locals()))
    return _census(p, st, states, settle_states(p, st, states, n_threads), box, seed,
                   t_max, n_threads)


def _inputs(a: dict) -> tuple:
    """(model, settings, t_max, box, seed, states) of ``census``'s arguments, validated."""
    p = ModelParams(eta=a["eta"], omega=a["omega"], F=a["F"], r=a["r"], d=a["d"])
    st = SolverSettings(t_end=a["t_end"], t_transient=a["t_transient"], v_stick=a["v_stick"],
                        max_impacts=a["max_impacts"], root_tol=a["root_tol"])
    t_max = a["t_max"]
    if t_max is not None:
        t_max = check_real("t_max", t_max, lo=st.t_end, lo_open=True, hi=T_END_MAX)
    box = check_box(a["box"])
    n = check_int("n", a["n"], lo=1, hi=N_MAX)
    seed = check_int("seed", a["seed"], lo=0, hi=SEED_MAX)
    states = sample_states(n, seed, box) if a["states"] is None else _check_states(a["states"])
    return p, st, t_max, box, seed, states


def _arguments(kwargs: dict) -> dict:
    """``census``'s arguments: its defaults updated by ``kwargs``."""
    return {k: v.default for k, v in inspect.signature(census).parameters.items()} | kwargs


def census_part(eta: float, omega: float, F: float, start: int, stop: int,
                **kwargs) -> dict:
    """The runs of the initial states [start, stop) of ``census(eta, omega, F, **kwargs)``:
    their end states at t_end (``ends``) and, with ``t_max``, the continuations of their
    motions (``conts``, by index into all states). ``census_of_parts`` makes the census of
    all parts, the same as ``census`` itself."""
    a = _arguments(dict(kwargs, eta=eta, omega=omega, F=F))
    p, st, t_max, _, _, states = _inputs(a)
    ends = settle_states(p, st, states[start:stop], a["n_threads"])
    conts = {}
    if t_max is not None:
        local = asy.continue_states(p, st, oscillators(p), ends, t_max, a["n_threads"])
        conts = {start + i: c for i, c in local.items()}
    return {"ends": ends, "conts": conts}


def census_of_parts(eta: float, omega: float, F: float, parts: list, **kwargs) -> Census:
    """``census(eta, omega, F, **kwargs)`` from the ``census_part`` results ``parts`` that
    cover its states in order (their runs are not repeated)."""
    a = _arguments(dict(kwargs, eta=eta, omega=omega, F=F))
    p, st, t_max, box, seed, states = _inputs(a)
    ends = [e for part in parts for e in part["ends"]]
    if len(ends) != len(states):
        raise ValueError(f"parts hold {len(ends)} runs, the census {len(states)} states")
    conts = {i: c for part in parts for i, c in part["conts"].items()}
    return _census(p, st, states, ends, box, seed, t_max, a["n_threads"], conts)


def _census(p, st, states, ends, box, seed, t_max, n_threads, conts=None) -> Census:
    """The census of the runs ``ends`` of ``states`` (``conts``: their continuations to
    t_max when known, else run here)."""
    groups, n_unsettled = _group(ends, p.period)
    oscs = oscillators(p)
    rest_end = settle(p, st, oscs, (0.0, 0.0, 0.0, 0.0))
    rest = _place_from_rest(groups, rest_end, p.period)
    groups.sort(key=lambda g: (-len(g.members), g.first if g.first >= 0 else len(ends)))
    attractors = [_attractor(p, st, oscs, g, ends, states, len(ends)) for g in groups]
    members = np.full(len(ends), -1, dtype=np.int64)
    for j, g in enumerate(groups):
        members[g.members] = j
    out = Census(params=p.as_dict(), settings=st.as_dict() | {"state0": None}, n=len(ends),
                 seed=int(seed), box=dict(zip(BOX_NAMES, map(list, box), strict=False)),
                 attractors=attractors,
                 from_rest=groups.index(rest) if rest is not None else None,
                 unsettled_fraction=n_unsettled / len(ends), members=members)
    if t_max is not None:
        runs = _Runs(p, st, oscs, states, ends, t_max, n_threads)
        _asymptotic_view(out, runs, groups, (rest, rest_end), conts)
    return out


# ------------------------------------------------------------------ asymptotic view

def _group_of(groups: list, e: EndState, T: float, first: int) -> int:
    """Index of the periodic group e belongs to; a new (empty) group if none."""
    for j, g in enumerate(groups):
        if g.end.kind in ("1:1", "orbit") and _matches(g, e, T):
            return j
    g = _Group(first, e)
    groups.append(g)
    return len(groups) - 1


@dataclass(frozen=True)
class _Runs:
    """The runs of one census that its asymptotic view continues: model, settings and
    oscillators, the initial states (n, 4) and their end states at t_end, the horizon
    t_max (dimensionless time) and the worker threads (None: all cores)."""

    p: ModelParams
    st: SolverSettings
    oscs: tuple
    states: np.ndarray
    ends: list
    t_max: float
    n_threads: int | None


def _asymptotic_view(out: Census, runs: _Runs, groups: list, rest: tuple,
                     conts: dict | None = None) -> None:
    """Add the asymptotic view to ``out`` (``asymptotic`` module docstring); rest = (group,
    end state) of the start from rest; conts: the continuations of the motions, if known."""
    p, st, oscs, ends, t_max = runs.p, runs.st, runs.oscs, runs.ends, runs.t_max
    n, T = len(ends), p.period
    if conts is None:
        conts = asy.continue_states(p, st, oscs, ends, t_max, runs.n_threads)
    n_old = len(groups)
    members = out.members.copy()
    for i, c in sorted(conts.items()):
        if c.outcome == "escaped":
            members[i] = _group_of(groups, c.end, T, i)
    for g in groups[n_old:]:            # attractors reached only asymptotically
        a = _attractor(p, st, oscs, g, ends, runs.states, n)
        a.window_regimes = {}
        out.attractors.append(a)
    for j, (g, a) in enumerate(zip(groups, out.attractors, strict=True)):
        k = int(np.count_nonzero(members == j))
        view = {"basin_fraction_asymptotic": k / n, "ci_asymptotic": _wilson(k, n)}
        if g.end.kind == "motion":
            view |= _motion_view(runs, g, conts, members)
        else:
            view |= {"status": "persistent", "regime_asymptotic": a.regime,
                     "lyapunov_max": asy.periodic_lambda(p, st, oscs, g.end),
                     "lyapunov_window": None}
        a.asymptotic = view
    out.t_max, out.members_asymptotic = t_max, members
    out.from_rest_asymptotic = _rest_asymptotic(out, runs, groups, rest)


def _motion_view(runs: _Runs, g: _Group, conts: dict, members: np.ndarray) -> dict:
    """Lifetime, escapes, status and leading exponent of a class of motions (conts: the
    continuations by state index; members: attractor index of every state at t_max)."""
    p, st, t_max = runs.p, runs.st, runs.t_max
    mem = g.members
    cs = [conts[i] for i in mem]
    escaped = np.array([c.outcome == "escaped" for c in cs], bool)
    t_out = np.array([c.t_escape if c.outcome == "escaped" else t_max for c in cs])
    life = asy.lifetime(t_out - st.t_end, escaped)
    n_settled = sum(c.outcome == "settled" for c in cs)
    dest = [int(members[i]) for i, c in zip(mem, cs, strict=True) if c.outcome == "escaped"]
    lam_long = None
    if mem and life["escaped"] == 0 and n_settled < len(mem):
        first = next(i for i, c in zip(mem, cs, strict=True) if c.outcome == "censored")
        lam_long = asy.long_lambda(p, st, t_max, runs.ends[first])
    mod = None
    if asy.may_be_quasi_periodic(life, n_settled, len(mem), lam_long):
        from .torus import modulation
        mod = modulation(p, st, t_max, runs.ends[first].final_state)
    qp = asy.is_quasi_periodic(mod)
    status, horizon = asy.class_status(life, n_settled, len(mem), lam_long, st.t_end,
                                       t_max, quasi_periodic=qp)
    if lam_long is not None:
        lam, ci, win = lam_long
    elif mem:
        lam, ci, win = asy.window_lambda(p, st, runs.states, mem, runs.n_threads)
    else:
        lam, ci, win = math.nan, [math.nan, math.nan], None
    view = {"status": status, "regime_asymptotic": "quasi-periodic" if qp else g.end.regime,
            "lyapunov_max": lam, "lyapunov_max_ci": ci,
            "lyapunov_window": win, "lifetime": life,
            "escape_to": {str(j): dest.count(j) for j in sorted(set(dest))}}
    if mod is not None:
        view["modulation"] = mod
    if horizon is not None:
        view["horizon"] = horizon
    return view


def _rest_asymptotic(out: Census, runs: _Runs, groups: list, rest: tuple) -> int | None:
    """Attractor the start from rest is in at t_max (None: its run stopped early)."""
    p, st, oscs = runs.p, runs.st, runs.oscs
    g, e = rest
    if g is None:
        return None
    if e.kind != "motion":
        return out.from_rest
    c = asy.continue_state(p, st, asy.asymptotic_settings(st, runs.t_max), oscs, e)
    if c.outcome != "escaped":
        return out.from_rest
    n_old = len(groups)
    j = _group_of(groups, c.end, p.period, -1)
    if j >= n_old:                      # reached from rest only, and only asymptotically
        a = _attractor(p, st, oscs, groups[j], [], np.zeros((0, 4)), out.n)
        a.window_regimes = {}
        a.asymptotic = {"basin_fraction_asymptotic": 0.0, "ci_asymptotic": _wilson(0, out.n),
                        "status": "persistent", "regime_asymptotic": a.regime,
                        "lyapunov_max": asy.periodic_lambda(p, st, oscs, c.end),
                        "lyapunov_window": None}
        out.attractors.append(a)
    return j

