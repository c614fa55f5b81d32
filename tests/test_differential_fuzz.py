"""Differential fuzzing of the numerics: the exact solver against the independent references
over the documented domain (issue 41 item 3).

hypothesis draws (eta, omega, F, r, d, phi, start state) over the whole domain, edges
included (``_differential.draws``); every draw runs the exact solver, checks its
invariants (|w| <= 1, momentum and restitution at impacts, the energy balance of the
window) and compares its impacts with a reference within a bound from the reference's
tolerance and the draw's conditioning, or classes the draw as one where the reference
cannot be trusted (``_differential.CLASSES``: sensitive, grazing, chatter, refused,
ref_failed, each with its reason). A split no class explains fails.

Fast suite: derandomized, a fixed number of examples. Long run (slow):

    VINES_FUZZ_EXAMPLES=2000 VINES_FUZZ_SEED=1 VINES_FUZZ_REPORT=fuzz.json \\
        pytest -m slow tests/test_differential_fuzz.py

prints (and writes to VINES_FUZZ_REPORT, if set) the classes with their counts and
reasons.
"""
import collections
import json
import os

import pytest
from _differential import CLASSES, compare, draws
from hypothesis import HealthCheck, given, seed, settings

N_FAST = {"rk": 60, "mp": 30}          # examples of the fast suite per reference
T_END = {"rk": 60.0, "mp": 20.0}       # horizons: the 40-digit reference on short runs
MIN_AGREE = 0.4     # fraction of the draws both solvers run that agree over the whole horizon


def _fuzz(reference: str, n: int, seed_=None) -> collections.Counter:
    """Run ``n`` draws against ``reference``; the classes counted, with reasons kept."""
    counts = collections.Counter()
    reasons = collections.defaultdict(list)
    worst = [0.0]

    @settings(max_examples=n, derandomize=seed_ is None, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(draws(T_END[reference]))
    def run(dr):
        out = compare(dr, reference)
        assert out.cls in CLASSES
        counts[out.cls] += 1
        worst[0] = max(worst[0], out.worst_ratio)
        if out.cls != "agree":
            reasons[out.cls].append(f"{out.reason}: {dr}")

    (run if seed_ is None else seed(seed_)(run))()
    counts["_worst_ratio"] = worst[0]
    counts.reasons = reasons
    return counts


@pytest.mark.parametrize("reference", sorted(N_FAST))
def test_exact_solver_agrees_with_reference_or_draw_is_classed(reference):
    counts = _fuzz(reference, N_FAST[reference])
    _assert_mostly_compared(counts)
    assert counts["_worst_ratio"] <= 1.0


def _assert_mostly_compared(counts):
    """Not a test that classes everything away: of the draws both solvers accept, at least
    MIN_AGREE are compared to the end."""
    run = sum(counts[k] for k in CLASSES if k not in ("refused", "ref_failed"))
    assert run >= 10 and counts["agree"] >= MIN_AGREE * run, dict(counts)


@pytest.mark.slow
@pytest.mark.parametrize("reference", sorted(N_FAST))
def test_long_differential_run(reference):
    """Thousands of draws (VINES_FUZZ_EXAMPLES, default 2000; seed VINES_FUZZ_SEED)."""
    n = int(os.environ.get("VINES_FUZZ_EXAMPLES", "2000"))
    seed_ = int(os.environ.get("VINES_FUZZ_SEED", "0"))
    counts = _fuzz(reference, n, seed_)
    summary = {"reference": reference, "examples": n, "seed": seed_,
               "counts": {k: counts[k] for k in CLASSES},
               "worst_error_over_bound": counts["_worst_ratio"],
               "reasons": {k: v for k, v in counts.reasons.items()}}
    print(json.dumps({k: summary[k] for k in ("reference", "counts",
                                              "worst_error_over_bound")}))
    path = os.environ.get("VINES_FUZZ_REPORT")
    if path:
        with open(f"{path}.{reference}", "w") as fh:
            json.dump(summary, fh, indent=1)
    _assert_mostly_compared(counts)
