"""The census's asymptotic view (``census(t_max=...)``, ``attractors.asymptotic``)."""
import math

import numpy as np
import pytest

from vines.attractors import census
from vines.attractors.asymptotic import lifetime
from vines.core.params import ParameterError

FIG16 = (0.5, 0.9, 0.3077)
CHAOTIC = (0.2026, 0.917, 0.1345)
NEW_KEYS = {"basin_fraction_asymptotic", "ci_asymptotic", "status", "lyapunov_max",
            "lyapunov_max_ci", "lyapunov_window", "lifetime", "escape_to", "horizon",
            "regime_asymptotic", "modulation"}


def _t_end_view(d: dict, n_attractors: int) -> dict:
    out = {k: v for k, v in d.items() if k not in ("t_max", "from_rest_asymptotic",
                                                   "attractors")}
    out["attractors"] = [{k: v for k, v in a.items() if k not in NEW_KEYS}
                         for a in d["attractors"][:n_attractors]]
    return out


def test_t_end_view_unchanged_and_thread_independent():
    """With t_max the t_end view is the same object as without (no new key without t_max);
    the asymptotic view is the same on 1 and 2 threads."""
    kw = dict(n=32, seed=0)
    plain = census(*FIG16, **kw, n_threads=2).to_dict()
    assert "t_max" not in plain and all(NEW_KEYS.isdisjoint(a) for a in plain["attractors"])
    one = census(*FIG16, **kw, t_max=30000.0, n_threads=1).to_dict()
    two = census(*FIG16, **kw, t_max=30000.0, n_threads=2).to_dict()
    assert one == two
    assert _t_end_view(one, len(plain["attractors"])) == plain
    fr = [a["basin_fraction_asymptotic"] for a in one["attractors"]]
    assert sum(fr) + one["unsettled_fraction"] == pytest.approx(1.0, abs=1e-12)


def test_fig16_point_irregular_class_is_transient_fast():
    """At (0.5, 0.9, 0.3077) the states that are irregular at t = 7000 all end on the 1:1
    orbit: the class is transient, with a lifetime, and its states escape to the 1:1."""
    c = census(*FIG16, n=32, seed=0, t_max=30000.0).to_dict()
    irr = [a for a in c["attractors"] if a["regime"] == "irregular"]
    assert irr and irr[0]["basin_fraction"] > 0.0
    a = irr[0]
    one = next(j for j, b in enumerate(c["attractors"]) if b["regime"] == "1:1")
    assert a["status"] == "transient" and a["basin_fraction_asymptotic"] == 0.0
    assert a["escape_to"] == {str(one): a["count"]}
    life = a["lifetime"]
    assert life["escaped"] == a["count"] and life["censored"] == 0
    assert life["ci"][0] < life["mean"] < life["ci"][1] < 30000.0
    assert a["lyapunov_max"] > 0.0          # transient chaos in the window
    assert c["attractors"][one]["status"] == "persistent"
    assert c["attractors"][one]["lyapunov_max"] < 0.0


@pytest.mark.slow
def test_fig16_point_irregular_class_is_transient_256_states():
    c = census(*FIG16, n=256, seed=0, t_max=1e5).to_dict()
    irr = next(a for a in c["attractors"] if a["regime"] == "irregular")
    assert irr["basin_fraction"] > 0.1 and irr["status"] == "transient"
    assert irr["basin_fraction_asymptotic"] == 0.0
    assert irr["lifetime"]["ci"][1] < 1e4


def test_persistent_chaos_is_persistent():
    """At a chaotic point no state escapes by t_max and lambda_1 > 0 over [t_end, t_max]."""
    c = census(*CHAOTIC, n=4, seed=0, t_max=20000.0).to_dict()
    irr = [a for a in c["attractors"] if a["regime"] == "irregular"]
    assert irr
    for a in irr:
        assert a["status"] == "persistent" and a["lifetime"]["escaped"] == 0
        assert a["lyapunov_max"] > 0.0 and a["lyapunov_max_ci"][0] > 0.0
        assert a["lyapunov_window"] == [7000.0, 20000.0]
        assert a["basin_fraction_asymptotic"] == a["basin_fraction"]


def test_lifetime_estimate_by_hand_and_coverage():
    life = lifetime([1.0, 2.0, 3.0, 10.0], [True, True, True, False])
    assert life["mean"] == pytest.approx(16.0 / 3.0)
    assert (life["escaped"], life["censored"]) == (3, 1)
    assert life["km_median_residual"] == 2.0
    none = lifetime([5.0, 5.0], [False, False])
    assert none["mean"] == math.inf and none["ci"][1] == math.inf and none["ci"][0] > 0.0
    # coverage of the 95 % interval: exponential lifetimes (mean 100) censored at 150
    rng = np.random.default_rng(0)
    hits = 0
    for _ in range(400):
        tau = rng.exponential(100.0, 40)
        life = lifetime(np.minimum(tau, 150.0), tau < 150.0)
        hits += life["ci"][0] <= 100.0 <= life["ci"][1]
    assert 0.92 <= hits / 400 <= 0.98


def test_bad_t_max():
    with pytest.raises(ParameterError, match="t_max"):
        census(*FIG16, n=2, t_max=5000.0)
    with pytest.raises(ParameterError, match="t_max"):
        census(*FIG16, n=2, t_max="soon")
