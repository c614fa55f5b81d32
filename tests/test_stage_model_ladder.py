"""The model_ladder stage: the exact orbits' amplitudes against the simulation from rest
where it settles on them, the slow flow's rows against its own one-point answer, the error
and band rules on hand-made rows, and the figure."""

import numpy as np
import pytest
from _figures import run_figure

from vines.core.params import D_DEFAULT
from vines.data.netcdf import write_dataset
from vines.pipeline import stages
from vines.studies import model_ladder as ml

MODEL = {"r": 0.65, "d": D_DEFAULT}
#: omega 0.99, 1.0, 1.01 at eta = F = 0.05: the simulation from rest settles on the stable
#: symmetric 1:1 orbit there
SPEC = {"etas": [0.05], "f": 1.0, "sigma_range": [-0.2, 0.2], "n_omega": 3, "n_dense": 30,
        "continuation_step": 0.05, "t_end": 3000.0, "t_transient": 2000.0}


@pytest.fixture(scope="module")
def ds():
    return stages.model_ladder(SPEC, model=MODEL, code="test", title="t")


def test_exact_orbits_are_where_the_simulation_settles(ds):
    p = ds.isel(eta=0)
    settled = np.flatnonzero(p["simulation_regime"].values == "1:1")
    assert settled.size >= 2
    for i in settled:
        stable = p["exact_amplitude"].values[i][p["exact_stable"].values[i] == 1]
        assert stable.size == 1
        assert stable[0] == pytest.approx(float(p["simulation_xmax"][i]), rel=1e-6)


def test_slow_flow_rows_and_errors_are_those_of_its_one_point_answer(ds):
    from vines.slowflow import response
    p = ds.isel(eta=0)
    for i, w in enumerate(p["omega"].values):
        one = sorted(o.amplitude for o in response(0.05, w, 0.05, **MODEL).orbits)
        rows = p["slowflow_amplitude"].values[i]
        np.testing.assert_allclose(sorted(rows[np.isfinite(rows)]), one, rtol=1e-12)
        ex = p["exact_amplitude"].values[i]
        ex = np.sort(ex[np.isfinite(ex)])
        if ex.size == len(one):       # the error is against the exact orbits, sorted
            want = np.max(np.abs(np.array(one) - ex) / ex)
            assert float(p["error_max"][i]) == pytest.approx(want, rel=1e-12)
    assert np.all(ds["seconds"].values > 0)


def test_error_and_band_rules():
    sf = {"index": np.array([0, 0, 1, 3]), "amplitude": np.array([1.0, 2.0, 1.1, 5.0])}
    ex = {"index": np.array([0, 0, 1, 1, 3]), "amplitude": np.array([2.2, 1.01, 1.0, 3.0, 5.0])}
    err, nearest = ml.errors(4, sf, ex)
    # omega 0: pairs (1.0, 1.01), (2.0, 2.2); 1: counts differ; 2: no orbit; 3: exact
    np.testing.assert_allclose(err, [0.2 / 2.2, np.nan, 0.0, 0.0], rtol=1e-12)
    np.testing.assert_allclose(nearest, [0.01 / 1.01, 0.2 / 2.2, 0.1, 0.0], rtol=1e-12)
    W = np.array([0.9, 1.0, 1.1, 1.2, 1.3])
    assert ml.band(W, np.array([0.001, np.nan, 0.002, 0.003, 0.02]), 0.01) == (1.1, 1.2, 0.6)
    lo, hi, share = ml.band(W, np.full(5, 0.5), 0.01)
    assert np.isnan(lo) and np.isnan(hi) and share == 0.0


def test_model_ladder_figure_from_the_stage_dataset(ds, tmp_path):
    path = write_dataset(ds, tmp_path / "model_ladder.nc")
    png, log = run_figure("model_ladder", tmp_path, "model_ladder", colormap=None,
                          ladders=[str(path)])
    assert png.read_bytes()[:4] == b"\x89PNG"
    assert "eta = 0.05, F = 0.05: within 1%:" in log
