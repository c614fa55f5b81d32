"""The lyapunov stage (exponents along a sweep), the both-view census maps and the split of
irregular sweep points by the exponent."""
import numpy as np
import pytest

from vines.attractors.lyapunov_sweep import sweep_exponents
from vines.core.sweep import SweepLine, bifurcation_sweep
from vines.pipeline import stages
from vines.pipeline.axes import ConfigError
from vines.pipeline.config_checks import check_attractor_maps, check_lyapunov_sweeps

SWEEP = {"param": "eta", "values": {"start": 0.01, "stop": 0.2, "num": 3}, "outer": "F",
         "outer_values": [0.1], "fixed": {"omega": 1.0}, "directions": ["up", "down"],
         "t_settle": 300.0, "t_step": 100.0, "n_record": 4, "v_stick": 1e-6}
MODEL = {"r": 0.65, "d": 0.011997966952746818}


def test_sweep_exponents_walk_the_sweeps_chain():
    """Same states as the sweep (same phase per point, bit for bit); a stick-free window has
    four finite exponents, descending, inside their intervals' span."""
    vals = np.linspace(0.01, 0.2, 3)
    kw = dict(omega=1.0, F=0.1, t_settle=300.0, t_step=100.0, n_record=4)
    sw = bifurcation_sweep("eta", vals, **kw)
    ex = sweep_exponents(SweepLine("eta", vals, **kw), t_window=100.0, n_batches=4)
    assert np.array_equal(sw["phi"], ex["phi"])
    lam = ex["exponents"]
    assert lam.shape == (3, 4) and ex["ci"].shape == (3, 4, 2)
    finite = ex["n_sticks"] == 0
    assert np.all(np.diff(lam[finite], axis=1) <= 0)
    # the flow contracts phase volume (damping d > 0 between impacts, r < 1 at impacts)
    assert np.all(lam[finite].sum(axis=1) < 0)


def test_t_window_longer_than_a_point_refused():
    with pytest.raises(Exception, match="t_window"):
        sweep_exponents(SweepLine("eta", [0.05], omega=1.0, F=0.1, t_settle=300.0,
                                  t_step=100.0, n_record=4), t_window=150.0)


def test_lyapunov_dataset_cf_and_order():
    spec = {"sweep": "s", "t_window": 100.0, "n_batches": 4}
    ds = stages.lyapunov(spec, SWEEP, model=MODEL, code="x", title="t")
    assert ds.sizes["point"] == 6
    for v in ds.variables.values():
        assert "long_name" in v.attrs and "units" in v.attrs
    assert list(ds["direction"].values) == [1, 1, 1, -1, -1, -1]
    assert np.array_equal(ds["lambda_1"].values, ds["exponents"].values[:, 0])
    assert ds.attrs["sweep"] == "s"


def _config(**ly):
    return {"sweeps": {"s": SWEEP}, "lyapunov_sweeps": {"a": {"sweep": "s", "t_window": 100.0,
                                                              "n_batches": 4, **ly}}}


def test_config_checks():
    check_lyapunov_sweeps(_config(), MODEL, {})
    with pytest.raises(ConfigError, match="lyapunov_sweeps.a.sweep"):
        check_lyapunov_sweeps(_config(sweep="nope"), MODEL, {})
    with pytest.raises(ConfigError, match="lyapunov_sweeps.a.t_window"):
        check_lyapunov_sweeps(_config(t_window=101.0), MODEL, {})
    bad = {"robust_maps": {}, "simulation": {"t_end": 1000.0},
           "basin_slices": {"b": {"eta": 0.1, "omega": 0.8, "F": 0.2, "z_m0": [0.0, 1.0],
                                  "v_m0": [0.0, 1.0], "t_max": 500.0}}}
    with pytest.raises(ConfigError, match="basin_slices.b.t_max"):
        check_attractor_maps(bad, MODEL, {"max_grid_points": 10**6})


def test_robust_point_both_views_fig16_point():
    """At the Fig 16 point the window view counts transient irregular/chatter states; at t_max
    every state is on the 1:1 orbit (the issue's finding): the window fields are those of the
    plain census, the asymptotic ones differ."""
    from vines.attractors.census_maps import robust_point
    kw = dict(n=4, seed=0, t_end=1000.0, t_transient=600.0, threshold=0.7, n_threads=1)
    plain = robust_point(0.5, 0.9, 0.3077, **kw)
    both = robust_point(0.5, 0.9, 0.3077, t_max=2e4, **kw)
    assert {k: both[k] for k in plain} == plain
    assert both["stable_1to1_fraction_asymptotic"] == 1.0
    assert both["escaped_fraction"] == 1.0 - plain["stable_1to1_fraction"]


def test_split_irregular():
    import xarray as xr

    from vines.plotting.sweep_regimes import (
        REGIME_CHAOTIC,
        REGIME_IRREGULAR,
        REGIME_PERIODIC,
        REGIME_QUASIPERIODIC,
        split_irregular,
    )
    ci = np.zeros((4, 4, 2))
    ci[:, 0] = [[0.01, 0.02], [-0.01, 0.01], [-0.03, -0.02], [0.01, 0.02]]
    ly = xr.Dataset({"exponents_ci": (("point", "exponent", "bound"), ci)})
    codes = np.array([REGIME_IRREGULAR] * 3 + [REGIME_PERIODIC])
    assert list(split_irregular(codes, ly)) == [REGIME_CHAOTIC, REGIME_QUASIPERIODIC,
                                                REGIME_IRREGULAR, REGIME_PERIODIC]
