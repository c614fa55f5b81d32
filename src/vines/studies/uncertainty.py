"""Uncertain parts: a design judged over distributions of its parts (numerics only).

A design of ``studies.design`` (a VI NES (eta, L) and the TMD of the same mass tuned to the
band) is built once; its parts are then not exact. Four parameters may be uncertain
(``PARAMETERS``):

* ``frequency``: the host's natural frequency is (1 + delta) w0 (stiffness k (1 + delta)^2,
  M and c unchanged), the band fixed in absolute frequency: in the host's own dimensionless
  terms omega -> omega / (1 + delta), d -> d / (1 + delta), the TMD's f -> f / (1 + delta);
* ``clearance``: L -> L (1 + e) (a relative deviation);
* ``mass``: the absorber's mass m -> m (1 + e): eta -> eta (1 + e) for both absorbers; the
  TMD's spring and damper are the built ones, so its f -> f / sqrt(1 + e) and
  zeta -> zeta / sqrt(1 + e);
* ``r``: the restitution itself (a value in [0, 1], not a deviation).

Each is ``uniform`` on [LO, HI] or ``normal`` (MEAN, SD) truncated at +-3 SD
(``Uncertain``). LO = HI (SD = 0) is a part known exactly: the nominal value, bit for bit.

Sampling (``sobol_blocks``): the pick-freeze design on a scrambled, seeded Sobol sequence
(``scipy.stats.qmc.Sobol`` in 2k dimensions, n points, n a power of 2): A = its first k
coordinates, B the last k, AB_i = A with column i from B; the design is evaluated at the
n (k + 2) points (distinct points once). Every block is a low-discrepancy sample of the
joint distribution, so the statistics (mean, 95 % quantile, regime shares) are over all
n (k + 2) points; the first-order and total Sobol indices come from
``scipy.stats.sobol_indices`` on these evaluations (its default method,
``saltelli_2010``) with bootstrap confidence intervals (``sobol_analysis``). The numbers
depend on the seed only, not on the threads.

Per point the VI NES's worst ratio is ``design.Evaluator``'s (from rest, over the band's
grid and the amplitudes, peaks refined) and its regime the one of the run from rest at
its worst (omega, amplitude); the TMD's is its closed form's maximum over the band
(``tmd.band_max``).
"""
from __future__ import annotations

import inspect
import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from .. import progress
from ..core.params import ParameterError, check_int
from .uncertainty_checks import (
    N_SAMPLES_DEFAULT,
    PARAMETERS,
    Uncertain,
    check_parameters,
    check_samples,
)

__all__ = ["PARAMETERS", "Uncertain", "UncertaintyResult", "evaluate", "sobol_analysis",
           "uncertainty", "uncertainty_part"]

#: bootstrap of the Sobol indices: confidence level, resamples, and the widest 95 %
#: interval (absolute) of an index still called reliable
CONFIDENCE = 0.95
N_BOOTSTRAP = 999
CI_WIDTH_MAX = 0.1
#: regimes of a sample's worst point, grouped (``regime_group``); the efficient one is 1:1
REGIME_GROUPS = ("no-impact", "1:1", "other periodic", "chatter", "irregular")
EFFICIENT = "1:1"


# --------------------------------------------------------------------------- sampling

def _rng_keyword(fun) -> str:
    """'rng' (scipy >= 1.15) or 'seed'/'random_state' (older): the seed's keyword."""
    params = inspect.signature(fun).parameters
    return next(k for k in ("rng", "seed", "random_state") if k in params)


def sobol_blocks(k: int, n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Unit-cube points (k, n) of A and B: a scrambled Sobol sequence in 2k dimensions
    seeded by ``seed`` (A its first k coordinates, B the last k)."""
    from scipy.stats import qmc
    eng = qmc.Sobol(d=2 * k, scramble=True, **{_rng_keyword(qmc.Sobol): seed})
    u = eng.random(n)
    return u[:, :k].T, u[:, k:].T


def pick_freeze_points(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Points (k, n (k + 2)): the blocks A, B, AB_1 .. AB_k (AB_i: A with row i of B)."""
    k = A.shape[0]
    blocks = [A, B]
    for i in range(k):
        ab = A.copy()
        ab[i] = B[i]
        blocks.append(ab)
    return np.concatenate(blocks, axis=1)


def pick_freeze_estimators(f_A, f_B, f_AB) -> tuple[np.ndarray, np.ndarray]:
    """First-order and total indices (s, k) from f_A, f_B (s, n) and f_AB (k, s, n): the
    estimators of ``scipy.stats.sobol_indices``'s default method ``saltelli_2010``
    (variance from A and B; S_i = mean(f_B (f_AB_i - f_A)) / var,
    S_Ti = mean((f_A - f_AB_i)^2) / (2 var)), written out so that the bootstrap can be
    seeded (scipy's own bootstrap of the indices is not). Centre the values first."""
    var = np.var([f_A, f_B], axis=(0, -1))
    first = np.mean(f_B * (f_AB - f_A), axis=-1) / var
    total = 0.5 * np.mean((f_A - f_AB) ** 2, axis=-1) / var
    return first.T, total.T


def _bootstrap(f: dict, n: int, seed: int, n_resamples: int):
    """BCa bootstrap intervals (low, high), each (2, k) for (first, total), of the indices
    over resamples of the n rows, seeded."""
    from scipy.stats import bootstrap

    def statistic(idx):
        s1, sT = pick_freeze_estimators(f["f_A"][:, idx], f["f_B"][:, idx],
                                        f["f_AB"][..., idx])
        return np.concatenate([s1[0], sT[0]])

    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")     # degenerate resamples (a part without effect)
        res = bootstrap([np.arange(n)], statistic, vectorized=False, method="BCa",
                        n_resamples=n_resamples, confidence_level=CONFIDENCE,
                        **{_rng_keyword(bootstrap): np.random.default_rng(seed)})
    ci = res.confidence_interval
    return np.reshape(ci.low, (2, -1)), np.reshape(ci.high, (2, -1))


def sobol_analysis(values: np.ndarray, k: int, n: int, seed: int, names: Sequence[str],
                   n_bootstrap: int = N_BOOTSTRAP) -> dict | None:
    """First-order and total Sobol indices of ``values`` (n (k + 2), in the block order of
    ``pick_freeze_points``) by ``scipy.stats.sobol_indices`` (``pick_freeze_estimators``),
    with BCa bootstrap intervals (CONFIDENCE, n_bootstrap resamples seeded by ``seed``);
    an index is ``reliable`` when both its intervals are at most CI_WIDTH_MAX wide; a
    parameter that changes no value (AB_i's values are A's) gets exactly 0 and [0, 0].
    None when the values do not vary or are not all finite (the indices are then
    undefined)."""
    from scipy.stats import sobol_indices
    v = np.asarray(values, dtype=float)
    if not np.all(np.isfinite(v)) or np.ptp(v) == 0.0:
        return None
    v = v - np.mean(v[:2 * n])      # centred by the mean of A and B, as scipy does: the
    f = dict(f_A=v[:n][None], f_B=v[n:2 * n][None],   # first-order estimator is not
             f_AB=v[2 * n:].reshape(k, 1, n))        # shift-invariant under resampling
    if k == 1:      # scipy cannot take one parameter: a second one without effect
        f["f_AB"] = np.concatenate([f["f_AB"], f["f_A"][None]])
    res = sobol_indices(func=f, n=n, method=pick_freeze_estimators)
    low, high = _bootstrap(f, n, seed, n_bootstrap)
    out = {}
    for i, name in enumerate(names):
        c1 = [_finite(low[0, i]), _finite(high[0, i])]
        cT = [_finite(low[1, i]), _finite(high[1, i])]
        s1, sT = float(np.ravel(res.first_order)[i]), float(np.ravel(res.total_order)[i])
        if np.array_equal(f["f_AB"][i, 0], f["f_A"][0]):    # no effect at all: exactly 0
            s1 = sT = 0.0
            c1, cT = [0.0, 0.0], [0.0, 0.0]
        out[name] = dict(first_order=s1, total_order=sT, first_order_ci=c1,
                         total_order_ci=cT, reliable=None not in c1 + cT and bool(
                             c1[1] - c1[0] <= CI_WIDTH_MAX and cT[1] - cT[0] <= CI_WIDTH_MAX))
    return out


def _finite(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


# --------------------------------------------------------------------------- one point

def regime_group(label: str) -> str:
    """The REGIME_GROUPS entry of a regime label of ``core.regime``."""
    if label in ("no-impact", "chatter", "1:1"):
        return label
    if label.startswith("period-") or ":" in label:
        return "other periodic"
    return "irregular"          # irregular, and runs that did not finish


def _deviated(values: Mapping[str, float], nominal_r: float) -> tuple:
    """(delta, clearance factor, mass factor, r) of one point (the nominal where absent)."""
    return (values.get("frequency", 0.0), 1.0 + values.get("clearance", 0.0),
            1.0 + values.get("mass", 0.0), values.get("r", nominal_r))


def vines_point(problem, eta: float, clearance_m: float, values: Mapping[str, float],
                n_threads=None) -> tuple[float, str]:
    """(worst x_max/A from rest, regime of its worst point) of the VI NES (eta, L) when
    its parts are ``values`` (module docstring)."""
    from ..core.simulation import simulate_batch
    from .design import Evaluator
    delta, cL, cm, r = _deviated(values, problem.model.r)
    g = 1.0 + delta
    model = replace(problem.model, r=r, d=problem.model.d / g)
    pb = replace(problem, model=model, omega=tuple(w / g for w in problem.omega))
    e, L = eta * cm, clearance_m * cL
    with progress.task(None, "uncertainty: runs of one point", "runs"):
        resp = Evaluator(pb, n_threads).responses([(e, L)])[0]
    j = int(np.argmax(resp.peak))
    st = pb.settings
    out = simulate_batch(e, resp.peak_omega[j], pb.amplitudes_m[j] / L, r=model.r, d=model.d,
                         phi=model.phi, t_end=st.t_end, t_transient=st.t_transient,
                         v_stick=st.v_stick, max_impacts=st.max_impacts,
                         root_tol=st.root_tol, n_threads=1)
    return resp.worst, str(out["regime"])


def tmd_point(tmd, d: float, band: Sequence[float], values: Mapping[str, float]) -> float:
    """Worst |X/Y| over the band of the built TMD when its parts are ``values``
    (closed form; the nominal TMD's own worst ratio when they are nominal)."""
    from .tmd import band_max, tmd_ratio
    delta, _, cm, _ = _deviated(values, 0.0)
    g, s = 1.0 + delta, math.sqrt(cm)
    mu, f, z = tmd.eta * cm, tmd.frequency_ratio / (g * s), tmd.damping_ratio / s
    return band_max(lambda w: tmd_ratio(w, d / g, mu, f, z), (band[0] / g, band[1] / g))[0]


# --------------------------------------------------------------------------- study

def _summary(values: np.ndarray, nominal: float) -> dict:
    return dict(nominal=float(nominal), mean=float(np.mean(values)),
                q95=float(np.quantile(values, 0.95)), min=float(np.min(values)),
                max=float(np.max(values)))


@dataclass
class UncertaintyResult:
    """Samples and statistics of one design with uncertain parts (``to_dict``: the JSON
    key ``uncertainty`` of ``vines design``)."""

    parameters: tuple
    n: int
    seed: int
    points: np.ndarray            # (k, n (k + 2)) parameter values, pick-freeze blocks
    vines_worst: np.ndarray
    vines_regime: list
    tmd_worst: np.ndarray
    nominal: dict                 # vines, tmd: the nominal design's worst ratios
    design: dict                  # eta, clearance_m of the VI NES, tmd_eta
    cost: dict = field(default_factory=dict)

    @property
    def names(self) -> list[str]:
        return [p.name for p in self.parameters]

    def regime_shares(self) -> dict:
        groups = [regime_group(x) for x in self.vines_regime]
        return {g: groups.count(g) / len(groups) for g in REGIME_GROUPS}

    def sensitivity(self) -> dict:
        k = len(self.parameters)
        return {key: sobol_analysis(v, k, self.n, self.seed, self.names)
                for key, v in (("vines", self.vines_worst), ("tmd", self.tmd_worst))}

    def to_dict(self) -> dict:
        shares = self.regime_shares()
        sens = self.sensitivity()
        mixed = max(shares.values()) < 0.95
        return dict(
            design=self.design,
            parameters=[p.to_dict() for p in self.parameters], n_base=self.n,
            n_points=int(self.points.shape[1]), seed=self.seed,
            sampler="scrambled Sobol (scipy.stats.qmc.Sobol), pick-freeze blocks A, B, AB_i",
            samples={name: self.points[i].tolist() for i, name in enumerate(self.names)},
            vines=dict(**_summary(self.vines_worst, self.nominal["vines"]),
                       worst_ratio=self.vines_worst.tolist(), regime=list(self.vines_regime),
                       regime_shares=shares, efficient_probability=shares[EFFICIENT]),
            tmd=dict(**_summary(self.tmd_worst, self.nominal["tmd"]),
                     worst_ratio=self.tmd_worst.tolist()),
            vines_better_probability=float(np.mean(self.vines_worst < self.tmd_worst)),
            sensitivity=sens,
            sensitivity_notes=_notes(sens, mixed),
            cost=self.cost)


def _notes(sens: dict, mixed: bool) -> list[str]:
    notes = []
    if mixed:
        notes.append("the VI NES's worst point changes regime between samples (no regime "
                     "holds 95 % of them): its worst ratio jumps, and its indices describe "
                     "a discontinuous response")
    for key, s in sens.items():
        if s is None:
            notes.append(f"{key}: no variance, indices undefined")
            continue
        bad = [n for n, v in s.items() if not v["reliable"]]
        if bad:
            notes.append(f"{key}: indices of {', '.join(bad)} unreliable (a 95 % bootstrap "
                         f"interval wider than {CI_WIDTH_MAX:g})")
    return notes


def sample_points(parameters: Sequence[Uncertain], n: int, seed: int) -> np.ndarray:
    """The parameter values (k, n (k + 2)) of ``sobol_blocks``/``pick_freeze_points``."""
    A, B = sobol_blocks(len(parameters), n, seed)
    units = pick_freeze_points(A, B)
    return np.stack([p.ppf(units[i]) for i, p in enumerate(parameters)])


def point_keys(points: np.ndarray) -> list[tuple]:
    """One key (the parameter values) per point, in point order."""
    return [tuple(points[:, j]) for j in range(points.shape[1])]


def point_rows(result, names: Sequence[str], keys: Sequence[tuple], n_threads=None) -> dict:
    """{key: (VI NES worst ratio, its regime, TMD worst ratio)} of the distinct ``keys``
    (parameter values in ``names`` order) of the design of ``result``, spread over
    ``n_threads`` threads (each point's runs on one): a point's row depends on it alone."""
    import os
    from concurrent.futures import ThreadPoolExecutor
    pb = result.problem
    distinct = list(dict.fromkeys(keys))
    n_threads = n_threads or os.cpu_count() or 1

    def work(key):
        vals = dict(zip(names, map(float, key), strict=True))
        worst, regime = vines_point(pb, result.eta, result.clearance_m, vals, 1)
        return worst, regime, tmd_point(result.tmd, pb.model.d, pb.band, vals)

    with ThreadPoolExecutor(max_workers=n_threads) as ex:
        rows = ex.map(work, distinct) if n_threads > 1 else map(work, distinct)
        return dict(zip(distinct, progress.track(rows, len(distinct), "uncertainty: samples",
                                                 "points"), strict=True))


def evaluate(result, parameters: Sequence[Uncertain], n: int, seed: int,
             n_threads=None, known: dict | None = None) -> UncertaintyResult:
    """The design of ``result`` (a ``design.DesignResult``) at the n (k + 2) points of
    ``sample_points`` for validated ``parameters``; each distinct point is evaluated once
    (``point_rows``), those in ``known`` (rows of ``point_rows`` computed elsewhere) not
    again: the numbers depend neither on the threads nor on ``known``."""
    import os
    import time
    t0, c0 = time.perf_counter(), time.process_time()
    names = [p.name for p in parameters]
    points = sample_points(parameters, n, seed)
    keys = point_keys(points)
    distinct = list(dict.fromkeys(keys))
    known = known or {}
    n_threads = n_threads or os.cpu_count() or 1
    seen = known | point_rows(result, names, [k for k in distinct if k not in known],
                              n_threads)
    rows = [seen[key] for key in keys]
    cost = dict(wall_s=time.perf_counter() - t0, cpu_s=time.process_time() - c0,
                n_distinct_points=len(distinct), n_threads=n_threads)
    return UncertaintyResult(
        parameters=tuple(parameters), n=n, seed=seed, points=points,
        vines_worst=np.array([r[0] for r in rows]), vines_regime=[r[1] for r in rows],
        tmd_worst=np.array([r[2] for r in rows]),
        nominal=dict(vines=result.worst_ratio, tmd=result.tmd.worst_ratio),
        design=dict(eta=result.eta, clearance_m=result.clearance_m, tmd_eta=result.tmd.eta),
        cost=cost)


def _checked(result, parameters, samples, seed, n_threads) -> tuple:
    """(parameters, n, seed, n_threads) of ``uncertainty``'s arguments, validated."""
    from .design import DesignResult
    if not isinstance(result, DesignResult):
        raise ParameterError("result", result, "must be the DesignResult of vines.design")
    pb = result.problem
    params = check_parameters(parameters, amplitudes_m=pb.amplitudes_m,
                              clearance_m=result.clearance_m, eta=result.eta)
    n = check_samples(samples)
    seed = check_int("uncertainty_seed", seed, lo=0, hi=2 ** 63 - 1)
    if n_threads is not None:
        n_threads = check_int("n_threads", n_threads, lo=1, hi=4096)
    return params, n, seed, n_threads


def uncertainty(result, parameters, *, samples: int = N_SAMPLES_DEFAULT, seed: int = 0,
                n_threads: int | None = None, known: dict | None = None) -> UncertaintyResult:
    """The design of ``result`` (``vines.design``'s DesignResult) with uncertain parts.

    parameters: a mapping name -> 'uniform:LO:HI' / 'normal:MEAN:SD' (or (DIST, A, B)), or
    'NAME=SPEC' strings; names and meanings in ``PARAMETERS`` (module docstring);
    samples: the Sobol base size n (a power of 2; n (k + 2) points for k parameters);
    seed: the scrambling's seed; known: the merged rows of ``uncertainty_part`` computed
    elsewhere (not run again; the same result). Raises ParameterError naming the bad
    argument."""
    params, n, seed, n_threads = _checked(result, parameters, samples, seed, n_threads)
    return evaluate(result, params, n, seed, n_threads, known)


def uncertainty_part(result, parameters, start: int, stop: int, *,
                     samples: int = N_SAMPLES_DEFAULT, seed: int = 0,
                     n_threads: int | None = None) -> dict:
    """The rows (``point_rows``) of the points [start, stop) (point order) of
    ``uncertainty(result, parameters, samples=samples, seed=seed)``: pass the merged dicts
    of all parts to it as ``known``."""
    params, n, seed, n_threads = _checked(result, parameters, samples, seed, n_threads)
    keys = point_keys(sample_points(params, n, seed))[start:stop]
    return point_rows(result, [p.name for p in params], keys, n_threads)
