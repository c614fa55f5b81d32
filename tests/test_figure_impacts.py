"""Direction of motion before each impact, reconstructed by the figures from a time-history
dataset (which stores w'_i, not v_m and v_b), against the solver's own pre-impact velocities."""
import numpy as np
import pytest
import xarray as xr

from vines.core.measures import time_histories
from vines.plotting.impacts import (
    SAME_WAY,
    TOWARDS,
    UNKNOWN,
    impact_direction,
    pre_impact_velocities,
)
from vines.solvers import simulate

SIM = {"t_end": 300.0, "t_transient": 150.0}
R = 0.65


def _dataset(points, window_samples_per_period):
    th = time_histories(points, model={"r": R}, simulation=SIM, n_periods=3,
                        samples_per_period=20, window_samples_per_period=window_samples_per_period)
    coords = {k: ("point", [p[k] for p in points]) for k in ("eta", "omega", "F")}
    data = {k: (("point", "sample"), v) for k, v in th.items()
            if k in ("t", "z_m", "v_m", "z_b", "v_b")}
    data.update({k: (("point", "window_sample"), v) for k, v in th.items()
                 if k.startswith("window_")})
    data.update({k: ("impact", v) for k, v in th.items() if k.startswith("impact_")})
    data["row_size"] = ("point", th["row_size"])
    return xr.Dataset(data, coords=coords, attrs={"solver_r": R})


# a 1:1 orbit (Fig 4a), a 2:2 orbit (Fig 9a: impacts in both directions), chatter (Fig 9c)
POINTS = [{"eta": 0.05, "omega": 1.0, "F": 0.05}, {"eta": 0.2, "omega": 0.8, "F": 0.4},
          {"eta": 0.2, "omega": 0.9, "F": 0.4}]


@pytest.mark.parametrize("per_period", [10, 0])
def test_pre_impact_velocities_match_the_solver(per_period):
    ds = _dataset(POINTS, per_period)
    for i, p in enumerate(POINTS):
        res = simulate(p["eta"], p["omega"], p["F"], r=R, **SIM)
        sel = res.impacts["t"] >= SIM["t_transient"]
        vm, vb = pre_impact_velocities(ds, i)
        known = ~np.isnan(vb)
        # with the whole window sampled every impact is known; with the last periods only,
        # those before the first sample are not (never guessed)
        first = ds["window_t"].values[i, 0] if per_period else ds["t"].values[i, 0]
        assert np.array_equal(known, res.impacts["t"][sel] > first), p
        scale = max(1.0, float(np.max(np.abs(res.impacts["v_b"][sel]))))
        # sampled v_b (a sample after the previous impact) or carried by the impact law
        ref_b, ref_m = res.impacts["v_b"][sel][known], res.impacts["v_m"][sel][known]
        assert np.allclose(vb[known], ref_b, rtol=0, atol=1e-9 * scale), p
        assert np.allclose(vm[known], ref_m, rtol=0, atol=1e-9 * scale), p
        want = np.where(res.impacts["v_m"][sel] * res.impacts["v_b"][sel] > 0, SAME_WAY,
                        TOWARDS)
        assert np.array_equal(impact_direction(ds, i), np.where(known, want, UNKNOWN)), p


def test_both_directions_occur_on_the_2to2_orbit():
    ds = _dataset(POINTS[1:2], 10)
    d = impact_direction(ds, 0)
    assert (d == SAME_WAY).any() and (d == TOWARDS).any()


# ------------------------------------------------------------------ basin-fraction intervals

def test_wilson_interval_matches_published_values():
    from vines.plotting.uncertainty import wilson_interval, wilson_width
    # Newcombe (1998), Stat. Med. 17, 857, Table I: 81/263 -> 0.2553 ... 0.3662 (95 %);
    # 0/10 -> 0 ... 0.2775; 1/29 -> 0.0061 ... 0.1718
    for k, n, lo, hi in ((81, 263, 0.2553, 0.3662), (0, 10, 0.0, 0.2775),
                         (1, 29, 0.0061, 0.1718)):
        a, b = wilson_interval(k / n, n)
        assert abs(a - lo) < 5e-5 and abs(b - hi) < 5e-5, (k, n, a, b)
    # symmetric about 1/2, widest there, and narrower with more states
    w = wilson_width(np.array([0.0, 0.25, 0.5, 0.75, 1.0]), 32)
    assert np.allclose(w, w[::-1]) and np.argmax(w) == 2
    assert wilson_width(0.5, 128) < wilson_width(0.5, 32)
