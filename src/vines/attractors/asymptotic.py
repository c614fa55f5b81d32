"""The asymptotic view of a census: which motions last, and how long the others do.

The census's t_end view names the state every run has reached at t_end. Runs that have not
settled on a periodic orbit by then (kind "motion": chatter, irregular, ...) continue from
their state at t_end, with the exact solver and the periodic shortcut, until they settle
on a periodic orbit or reach t_max (``continue_state``). Per state:

* **escaped**: it settled on a periodic orbit with impacts (a 1:1 orbit or a confirmed
  orbit, ``endstate.classify_end``); its escape time is the first section time k T after
  which it stays within ESCAPE_TOL (relative, ``shortcut.rel_diff``) of that orbit's
  section states (``escape_time``);
* **settled in place**: it settled on a periodic orbit without impacts (no-impact motion):
  it stays in its class for good;
* **censored**: still not settled at t_max.

Per class of motions (``class_summary``): the share at t_max (``basin_fraction_asymptotic``,
Wilson interval), where its states escape to, the lifetime and the status:

* lifetime: the members are in the class at t_end and are followed to t_max, so their
  residual times min(tau, t_max) - t_end are left-truncated at t_end and right-censored at
  t_max. ``lifetime`` fits an exponential tail (constant escape rate, the law of chaotic
  transients): rate = escapes / total time at risk, mean = 1 / rate (memoryless: the mean
  time the motion lasts measured from any moment), its 95 % interval from the chi-square
  law of 2 rate (time at risk) (2 escapes and 2 escapes + 2 degrees of freedom), and the
  Kaplan-Meier median of the residual time as a check of the exponential law;
* status ``transient``: escapes were seen and either every member escaped before t_max or
  the upper end of the lifetime interval is at most (t_max - t_end) / TRANSIENT_FACTOR (a
  law that slow would have let >= 95 % escape);
  ``persistent``: no escape, and either every member settled in place, or the leading
  Lyapunov exponent of a member over [t_end, t_max] is positive (lower end of its interval
  > 0: chaos that lasted the whole horizon), or the class is **quasi-periodic**: that
  exponent's interval contains 0 and the member's strobe points over the last
  ``torus.N_STROBE`` forcing periods before t_max fill a closed curve
  (``torus.closed_curve``: a motion on a torus, e.g. a strongly modulated response);
  otherwise ``unresolved``, with ``horizon``:
  t_end + TRANSIENT_FACTOR x (upper end of the lifetime interval, or, with no escape,
  the time at risk per member x 10), a t_max that would resolve it.

Periodic classes (1:1 and confirmed orbits) are persistent by construction. lyapunov_max:
periodic classes log(max |multiplier|) / period (1:1: the map's eigenvalues; other orbits:
the monodromy matrix of ``core.variational``); motion classes the mean leading exponent of
up to N_LYAP members over the census window [t_transient, t_end] (the same trajectories, bit
for bit), or, for classes without escapes, of the first member over [t_end, t_max].
"""
from __future__ import annotations

import math
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from .. import progress
from ..core.exact import Oscillators
from ..core.params import ModelParams, SolverSettings, check_int
from ..core.result import RawRun
from ..core.shortcut import rel_diff
from .endstate import EndState, classify_end

#: a state has escaped once it stays this close (relative) to its periodic orbit's sections
ESCAPE_TOL = 1e-3
#: transient: lifetime interval's upper end <= (t_max - t_end) / TRANSIENT_FACTOR
TRANSIENT_FACTOR = 3.0
#: members of a motion class whose window exponent is measured
N_LYAP = 3
#: default t_max of the asymptotic view (see docs/attractors.md for its measured cost)
T_MAX_DEFAULT = 3e5
CI_LEVEL = 0.95


@dataclass
class Continuation:
    """One state's run from t_end on: ``end`` at t_max (kinds of ``endstate``), outcome
    "escaped", "settled" (in place, no impacts) or "censored", and the escape time."""

    end: EndState
    outcome: str
    t_escape: float = math.nan


def asymptotic_settings(st: SolverSettings, t_max: float,
                        t_window: float | None = None) -> SolverSettings:
    """Settings of the continuation runs [t_end, t_max] (window from t_window, default
    t_end)."""
    return SolverSettings(t_end=t_max, t_transient=st.t_end if t_window is None else t_window,
                          v_stick=st.v_stick, max_impacts=st.max_impacts,
                          root_tol=st.root_tol)


def continue_state(p: ModelParams, st: SolverSettings, st_max: SolverSettings,
                   oscs: Oscillators, e: EndState) -> Continuation:
    """Run the end state e of the t_end view (kind "motion") on to st_max.t_end."""
    from ..core.exact import run_exact
    t0 = st.t_end
    raw = run_exact(p, st_max, record_from=t0, state0=tuple(e.final_state), t0=t0,
                    periodic_shortcut=True)
    end = classify_end(p, st_max, oscs, raw, e.regime)
    if end.kind in ("1:1", "orbit"):
        return Continuation(end, "escaped", escape_time(p, st, oscs, raw, end))
    if end.kind == "motion" and raw.shortcut_period > 0:
        return Continuation(end, "settled")
    return Continuation(end, "censored")


def orbit_sections(p: ModelParams, st: SolverSettings, oscs: Oscillators,
                   end: EndState) -> np.ndarray:
    """States (pp, 4) of the periodic orbit of ``end`` on the sections t = k T."""
    if end.kind == "orbit":
        return np.asarray(end.section, float)
    from .orbit import section_of_1to1
    return np.asarray(section_of_1to1(p, st, oscs, end.orbit)["section_state"],
                      float)[None, :]


def escape_time(p: ModelParams, st: SolverSettings, oscs: Oscillators, raw: RawRun,
                end: EndState) -> float:
    """First section time k T >= t_end after which the run stays within ESCAPE_TOL of the
    orbit of ``end`` (the run's records from t_end, up to its shortcut plus a period)."""
    T = p.period
    sections = orbit_sections(p, st, oscs, end)
    t_stop = raw.t_last
    if math.isfinite(raw.shortcut_time):
        t_stop = min(t_stop, raw.shortcut_time + max(raw.shortcut_period, 1) * T)
    k = np.arange(math.ceil(st.t_end / T), math.floor(t_stop / T) + 1)
    if k.size == 0:
        return float(st.t_end)
    times = k * T
    x = raw.state_at(times)
    dist = np.array([min(rel_diff(x[:, i], s) for s in sections) for i in range(k.size)])
    far = np.flatnonzero(dist > ESCAPE_TOL)
    if far.size == 0:
        return float(times[0])
    return float(times[min(far[-1] + 1, k.size - 1)])


def continue_states(p: ModelParams, st: SolverSettings, oscs: Oscillators, ends: list,
                    t_max: float, n_threads: int | None = None) -> dict:
    """{index: Continuation} for every end state of kind "motion", on threads (results by
    index: independent of the thread count)."""
    n_threads = check_int("n_threads", n_threads if n_threads is not None
                          else (os.cpu_count() or 1), lo=1)
    st_max = asymptotic_settings(st, t_max)
    idx = [i for i, e in enumerate(ends) if e.kind == "motion"]

    def work(i):
        return continue_state(p, st, st_max, oscs, ends[i])

    if n_threads == 1 or len(idx) <= 1:
        out = list(progress.track(map(work, idx), len(idx), "asymptotic view", "states"))
    else:
        with ThreadPoolExecutor(max_workers=n_threads) as ex:
            out = list(progress.track(ex.map(work, idx), len(idx), "asymptotic view", "states"))
    return dict(zip(idx, out, strict=True))


def lifetime(residual: np.ndarray, escaped: np.ndarray, level: float = CI_LEVEL) -> dict:
    """Exponential-tail lifetime from residual times (after t_end) with the escaped ones
    marked (the others censored): mean = time at risk / escapes, its chi-square interval,
    the counts, and the Kaplan-Meier median of the residual time (None when the survival
    stays above 1/2)."""
    from scipy.stats import chi2
    residual = np.asarray(residual, float)
    escaped = np.asarray(escaped, bool)
    n_esc = int(escaped.sum())
    at_risk = float(residual.sum())
    a = 1.0 - level
    if at_risk > 0.0:
        # rate interval: chi2(a/2, 2 n) / (2 at_risk) .. chi2(1 - a/2, 2 n + 2) / (2 at_risk)
        rate_lo = chi2.ppf(a / 2, 2 * n_esc) / (2 * at_risk) if n_esc > 0 else 0.0
        rate_hi = chi2.ppf(1 - a / 2, 2 * n_esc + 2) / (2 * at_risk)
    else:
        rate_lo, rate_hi = 0.0, math.inf
    return {"mean": at_risk / n_esc if n_esc > 0 else math.inf,
            "ci": [_inverse(rate_hi), _inverse(rate_lo)],
            "escaped": n_esc, "censored": int(escaped.size - n_esc),
            "km_median_residual": _km_median(residual, escaped),
            "method": "exponential tail: escapes after t_end over the time at risk "
                      "[t_end, min(escape, t_max)], chi-square 95 % interval"}


def _inverse(rate: float) -> float:
    return float(1.0 / rate) if rate > 0.0 else math.inf


def _km_median(residual: np.ndarray, escaped: np.ndarray) -> float | None:
    """Kaplan-Meier median of right-censored times (None: survival never <= 1/2)."""
    order = np.lexsort((~escaped, residual))        # escapes before censorings at ties
    surv, at_risk = 1.0, residual.size
    for i in order:
        if escaped[i]:
            surv *= 1.0 - 1.0 / at_risk
            if surv <= 0.5:
                return float(residual[i])
        at_risk -= 1
    return None


def class_status(life: dict, n_settled: int, n_members: int, lam_long: tuple | None,
                 t_end: float, t_max: float,
                 quasi_periodic: bool = False) -> tuple[str, float | None]:
    """(status, horizon) of a motion class (module docstring); quasi_periodic: its
    continuation was recognised as quasi-periodic (``is_quasi_periodic``)."""
    span = t_max - t_end
    if n_members == 0:                      # reached from rest only: nothing sampled
        return "unresolved", None
    if life["escaped"] > 0 and (life["censored"] == 0
                                or life["ci"][1] <= span / TRANSIENT_FACTOR):
        return "transient", None
    if life["escaped"] == 0 and (n_settled == n_members or quasi_periodic
                                 or (lam_long is not None and lam_long[1][0] > 0.0)):
        return "persistent", None
    hi = life["ci"][1]
    horizon = t_end + TRANSIENT_FACTOR * hi if math.isfinite(hi) else t_end + 10.0 * span
    return "unresolved", float(horizon)


def may_be_quasi_periodic(life: dict, n_settled: int, n_members: int,
                          lam_long: tuple | None) -> bool:
    """Whether a motion class gets the quasi-periodic test: no escape, not every member
    settled in place (so ``lam_long`` was measured) and no positive exponent (lower end of
    its interval > 0: chaos)."""
    return (n_members > 0 and life["escaped"] == 0 and n_settled < n_members
            and lam_long is not None and lam_long[1][0] <= 0.0)


def is_quasi_periodic(modulation: dict | None) -> bool:
    """Quasi-periodic: over the strobe window of the continuation (``torus.modulation``)
    the interval of lambda_1 contains 0 and the strobe points fill a closed curve."""
    if modulation is None or not modulation["closed"]:
        return False
    lo, hi = modulation["lambda_1_ci"]
    return lo <= 0.0 <= hi


def window_lambda(p: ModelParams, st: SolverSettings, states: np.ndarray, members: list,
                  n_threads: int | None = None) -> tuple[float, list, list]:
    """Mean leading exponent of up to N_LYAP members over [t_transient, t_end] from their
    initial states (the census's trajectories) and the mean of their interval ends."""
    from .lyapunov import spectrum
    chosen = members[:N_LYAP]
    res = _threaded(lambda i: spectrum(p, st, tuple(states[i]), with_regime=False), chosen,
                    n_threads)
    lam = float(np.mean([r.exponents[0] for r in res]))
    ci = [float(np.mean([r.ci[0][0] for r in res])), float(np.mean([r.ci[0][1] for r in res]))]
    return lam, ci, [st.t_transient, st.t_end]


def long_lambda(p: ModelParams, st: SolverSettings, t_max: float,
                e: EndState) -> tuple[float, list, list]:
    """Leading exponent of the continuation of e over [t_end, t_max] (the same trajectory
    as ``continue_state``'s run, bit for bit) and its interval."""
    from .lyapunov import spectrum
    st_max = asymptotic_settings(st, t_max)
    r = spectrum(p, st_max, tuple(e.final_state), t0=st.t_end, with_regime=False)
    return float(r.exponents[0]), [float(r.ci[0][0]), float(r.ci[0][1])], [st.t_end, t_max]


def _threaded(fn, items, n_threads):
    n_threads = n_threads if n_threads is not None else (os.cpu_count() or 1)
    if n_threads == 1 or len(items) <= 1:
        return list(progress.track(map(fn, items), len(items), "lyapunov exponents", "runs"))
    with ThreadPoolExecutor(max_workers=n_threads) as ex:
        return list(progress.track(ex.map(fn, items), len(items), "lyapunov exponents", "runs"))


def periodic_lambda(p: ModelParams, st: SolverSettings, oscs: Oscillators,
                    end: EndState) -> float:
    """log(max |multiplier|) / period of a periodic end state (1:1: the map's eigenvalues;
    other orbits: the monodromy matrix over pp periods from its first section state)."""
    if end.kind == "1:1":
        return float(math.log(end.orbit.lambda_max) / p.period)
    from ..core.variational import monodromy
    pp = end.section.shape[0]
    M, _ = monodromy(p, st, oscs, end.section[0], end.t_section, pp * p.period,
                     int(end.modes[0]))
    mu = np.abs(np.linalg.eigvals(M)).max()
    return float(math.log(mu) / (pp * p.period)) if mu > 0.0 else -math.inf
