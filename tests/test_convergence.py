"""vines.studies.convergence: run length / window, v_stick and grid-resolution studies;
their datasets (vines.data.builders) and the contour geometry (vines.studies.contours).

Small sizes (a few seconds in all). Physical facts used as oracles, not values from the code:
* a stable periodic attractor reached well before t = 4000 (1:1 at eta 0.05, W 1, F 0.05)
  has the same time averages over any whole number of forcing periods, wherever the window
  starts;
* in periodic chatter the threshold v_stick only cuts off micro-bounces with relative speed
  below v_stick, so the measures agree to O(v_stick^2), a larger threshold sticks earlier
  (more time stuck) and leaves fewer impacts.
"""
import math
import runpy
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

import vines
from vines.data.builders import convergence_dataset
from vines.data.netcdf import read_dataset, write_dataset
from vines.studies import contours as G
from vines.studies import convergence as C

ROOT = Path(__file__).resolve().parents[1]
ONE_ONE = dict(eta=0.05, omega=1.0, F=0.05)          # stable 1:1 (Fig 4a)
CHATTER = dict(eta=0.2, omega=0.9, F=0.4)            # periodic chatter with sticking (Fig 9b)
GRID = dict(eta_range=(0.1, 0.6), omega_range=(0.9, 1.3), F=0.4, resolutions=(3, 5, 9),
            level=0.6)


@pytest.fixture(scope="module")
def window_res():
    return C.window_convergence([ONE_ONE], t_ends=(7000.0, 28000.0), n_threads=2)


@pytest.fixture(scope="module")
def vstick_res():
    return C.vstick_convergence([CHATTER], v_sticks=(1e-3, 1e-5, 1e-7, 1e-9), n_threads=2)


@pytest.fixture(scope="module")
def grid_res():
    return C.grid_convergence(**GRID, n_threads=2)


@pytest.fixture(scope="module")
def window_ds(window_res):
    return convergence_dataset("window", window_res)


@pytest.fixture(scope="module")
def vstick_ds(vstick_res):
    return convergence_dataset("vstick", vstick_res)


@pytest.fixture(scope="module")
def grid_ds(grid_res):
    return convergence_dataset("grid", grid_res)


def _assert_cf(ds):
    for name, var in ds.variables.items():
        assert var.attrs.get("long_name"), name
        assert "units" in var.attrs, name
    for dim in ds.dims:
        assert dim in ds.coords, f"dimension {dim} has no coordinate"
    assert ds.attrs["Conventions"] == "CF-1.10"
    for name, var in ds.variables.items():          # CF 3.5: flag_values of the var's type
        if "flag_values" in var.attrs:
            assert np.asarray(var.attrs["flag_values"]).dtype == var.dtype == np.int8, name


def _assert_plain(result):
    """A study result holds numbers, numpy arrays, lists and dicts of them: no xarray."""
    def walk(x):
        assert not isinstance(x, (xr.Dataset, xr.DataArray, xr.Variable)), type(x)
        for v in (x.values() if isinstance(x, dict) else
                  x if isinstance(x, (list, tuple)) else ()):
            walk(v)
    for v in vars(result).values():
        walk(v)


# ------------------------------------------------------------------ results and datasets

def test_results_are_plain_and_datasets_hold_them(window_res, window_ds, vstick_res,
                                                  vstick_ds, grid_res, grid_ds):
    for res in (window_res, vstick_res, grid_res):
        _assert_plain(res)
    for name, arr in {**window_res.measures, **window_res.differences}.items():
        np.testing.assert_array_equal(window_ds[name].values, arr)
    np.testing.assert_array_equal(window_ds["t_transient"].values, window_res.t_transient)
    assert window_ds["converged"].dtype == np.int8
    assert window_res.differences["converged"].dtype == bool
    np.testing.assert_array_equal(window_ds["xmax_m"].values,
                                  window_res.measures["xmax"] * vines.core.params.L_HALF_M)
    assert window_ds.attrs["solver_v_stick"] == window_res.solver["v_stick"] == 1e-6
    np.testing.assert_array_equal(vstick_ds["run_time"].values, vstick_res.run_time)
    np.testing.assert_array_equal(vstick_ds["v_stick"].values, vstick_res.v_stick)
    for name, arr in grid_res.per_resolution.items():
        np.testing.assert_array_equal(grid_ds[name].values, arr)
    np.testing.assert_array_equal(grid_ds["ke_ratio"].values, grid_res.fields["ke_ratio"])
    # the caller's attributes (provenance) go over the study's own
    ds = convergence_dataset("grid", grid_res, {"title": "t", "extra": 1})
    assert ds.attrs["title"] == "t" and ds.attrs["extra"] == 1 and ds.attrs["level"] == 0.6
    with pytest.raises(ValueError, match="unknown convergence study"):
        convergence_dataset("walls", grid_res)


# ------------------------------------------------------------------ run length and window

def test_window_dataset_layout_and_reference(window_ds, tmp_path):
    ds = window_ds
    _assert_cf(ds)
    assert ds["ke_ratio"].dims == ("point", "window", "t_end")
    assert ds["t_end"].values.tolist() == [7000.0, 28000.0]
    assert ds["window_rule"].values.tolist() == ["length", "fraction"]
    # windows: [t_end - 3000, t_end] and [t_end / 2, t_end]
    np.testing.assert_array_equal(ds["t_transient"].values[0],
                                  [[4000.0, 25000.0], [3500.0, 14000.0]])
    # reference: the longest run's widest window, difference zero there only by definition
    assert ds["reference_t_transient"].values[0] == 14000.0
    assert ds["d_ke"].values[0, 1, -1] == 0.0
    assert ds["rel_d_xmax"].values[0, 1, -1] == 0.0
    assert ds["converged"].values[0, 1, -1] == 1
    assert ds.attrs["tested_t_end"] == 7000.0 and ds.attrs["tested_t_transient"] == 4000.0
    assert ds["tested_d_ke"].values[0] == ds["d_ke"].values[0, ds.attrs["tested_window"], 0]
    back = read_dataset(write_dataset(ds, tmp_path / "w.nc"))
    xr.testing.assert_identical(back.drop_vars(["label", "window_rule", "regime", "status"]),
                                ds.drop_vars(["label", "window_rule", "regime", "status"]))
    assert back["regime"].values.tolist() == ds["regime"].values.tolist()


def test_window_tested_setting_is_added():
    res = C.window_convergence([ONE_ONE], t_ends=(8000.0,), window_lengths=(2000.0,),
                               window_fractions=(), n_threads=1)
    assert res.t_end.tolist() == [7000.0, 8000.0]
    assert res.rules == [("length", 2000.0), ("length", 3000.0)]
    assert (res.tested_window, res.tested_t_end_index) == (1, 0)
    ds = convergence_dataset("window", res)
    assert ds["t_end"].values.tolist() == [7000.0, 8000.0]
    assert ds["window_length"].values.tolist() == [2000.0, 3000.0]


def test_stable_1to1_converged_at_7000_4000(window_ds):
    # the paper's window holds 477.46 forcing periods: the partial period biases the
    # average by at most ~ (T / window) times the relative spread of v^2 (<= 2 for a
    # harmonic motion), i.e. 2 T / 3000 = 4.2e-3; x_max is a max over whole periods
    ds = window_ds
    assert ds["regime"].values[0, 0, 0] == "1:1"
    assert abs(ds["tested_d_ke"].values[0]) <= 2 * 2 * math.pi / 3000
    assert abs(ds["tested_rel_d_xmax"].values[0]) <= 1e-9
    assert ds["tested_converged"].values[0] == 1 and ds["tested_regime_same"].values[0] == 1
    # over whole forcing periods, averages of the periodic attractor are the same for the
    # 7000/4000 run and the 28000 runs (window 3000 or 14000)
    whole = convergence_dataset("window", C.window_convergence(
        [ONE_ONE], t_ends=(7000.0, 28000.0), whole_periods=True, n_threads=2))
    assert np.all(np.abs(whole["d_ke"].values) <= 1e-6)
    assert np.all(np.abs(whole["rel_d_xmax"].values) <= 1e-6)
    T = 2 * math.pi
    win = whole["t_end"].values - whole["t_transient"].values[0]
    np.testing.assert_allclose(win / T, np.round(win / T), rtol=0, atol=1e-9)


def test_window_arguments_are_checked():
    with pytest.raises(ValueError, match="fractions"):
        C.window_convergence([ONE_ONE], window_fractions=(1.5,))
    with pytest.raises(ValueError, match="t_transient"):
        C.window_convergence([ONE_ONE], t_end=3000.0, t_transient=4000.0)
    with pytest.raises(ValueError, match="needs numbers eta, omega, F"):
        C.window_convergence([{"eta": 0.1, "omega": 1.0}])


# ------------------------------------------------------------------ v_stick

def test_vstick_dataset_and_convergence_in_chatter(vstick_ds):
    ds = vstick_ds
    _assert_cf(ds)
    vs = ds["v_stick"].values
    assert vs.tolist() == [1e-9, 1e-7, 1e-6, 1e-5, 1e-3]      # tested 1e-6 added, increasing
    assert ds["run_time"].attrs["units"] == "s" and np.all(ds["run_time"].values > 0)
    assert set(ds["regime"].values[0]) == {"chatter"}
    assert ds["d_ke"].values[0, 0] == 0.0 and ds["rel_d_xmax"].values[0, 0] == 0.0
    # the cut-off micro-bounces have relative speed <= v_stick <= 1e-3: their share of the
    # kinetic energy and of x_max is O(v_stick^2) <= 1e-6
    assert np.all(np.abs(ds["d_ke"].values) <= 1e-6)
    assert np.all(np.abs(ds["rel_d_xmax"].values) <= 1e-6)
    assert ds["converged_below"].values[0] == vs[-1]
    # smaller threshold: later sticking (less time stuck) and more impacts; near the
    # kernel's round-off floor of bounce speeds (~1e-7) t_stuck may move by round-off
    assert np.all(np.diff(ds["t_stuck"].values[0]) >= -1e-6)
    assert np.all(np.diff(ds["impacts_per_period"].values[0]) <= 0)
    assert ds["t_stuck"].values[0, -1] > ds["t_stuck"].values[0, 0]


# ------------------------------------------------------------------ grid resolution

def test_grid_dataset_nested_and_finest_distance_zero(grid_ds):
    ds = grid_ds
    _assert_cf(ds)
    res = ds["resolution"].values
    assert res.tolist() == [3, 5, 9] and ds.sizes["eta"] == ds.sizes["omega"] == 9
    for n, s in zip(res, ds["stride"].values, strict=False):
        for dim, (lo, hi) in (("eta", GRID["eta_range"]), ("omega", GRID["omega_range"])):
            sub = ds[dim].values[::s]
            assert sub.size == n and sub[0] == lo and sub[-1] == hi
            assert set(sub.tolist()) <= set(ds[dim].values.tolist())      # nested, exactly
            np.testing.assert_allclose(sub, np.linspace(lo, hi, n), rtol=0, atol=1e-15)
    for name in ("contour_dist_mean", "contour_dist_max", "contour_hausdorff",
                 "d_area_fraction"):
        assert ds[name].values[-1] == 0.0                  # the finest grid to itself
    assert np.all(ds["contour_dist_mean"].values[:-1] > 0)  # coarse contours do differ
    assert np.all(ds["contour_dist_max"].values >= ds["contour_dist_mean"].values)
    assert np.all(ds["contour_hausdorff"].values >= ds["contour_dist_max"].values)
    assert np.all((ds["area_fraction"].values > 0) & (ds["area_fraction"].values < 1))


def test_grid_coarse_values_equal_an_own_coarse_run(grid_ds):
    s = int(grid_ds["stride"].values[0])
    eta, om = grid_ds["eta"].values[::s], grid_ds["omega"].values[::s]
    E, W = np.meshgrid(eta, om, indexing="ij")
    own = vines.simulate_batch(E, W, GRID["F"], n_threads=1)
    np.testing.assert_array_equal(grid_ds["ke_ratio"].values[::s, ::s], own["ke_ratio"])


def test_grid_arguments_are_checked():
    with pytest.raises(ValueError, match="not nested"):
        C.grid_convergence(resolutions=(11, 20))
    with pytest.raises(ValueError, match="not nested"):
        G.nested_axis(0.0, 1.0, 81, 30)


def test_contour_tools_on_analytic_fields():
    # circles of radius 1 and 1.1: distance 0.1 everywhere; a set of lines to itself: 0
    th = np.linspace(0, 2 * np.pi, 2001)
    c1 = [np.c_[np.cos(th), np.sin(th)]]
    c2 = [1.1 * c1[0]]
    mean, mx = G.contour_distance(c1, c2, 1e-3)
    assert mean == pytest.approx(0.1, abs=1e-5) and mx == pytest.approx(0.1, abs=1e-5)
    assert max(G.contour_distance(c2, c2, 1e-3)) <= 1e-12
    assert G.contour_distance([], c2, 1e-3) == (pytest.approx(np.nan, nan_ok=True),) * 2
    # contour of r = 0.5 from a grid: within O(h^2) of the circle; area above the level
    x = np.linspace(-1, 1, 101)
    z = np.hypot(*np.meshgrid(x, x))
    lines = G.contour_lines(x, x, z, 0.5)
    r = np.hypot(*np.concatenate(lines).T)
    # marching squares interpolates r linearly along a cell edge: the vertex is off the
    # circle by <= h^2/8 max|r''| <= h^2/8 / 0.48 = 0.26 h^2 (h = 0.02; measured 0.18 h^2)
    np.testing.assert_allclose(r, 0.5, atol=(x[1] - x[0]) ** 2)
    # chords c <= sqrt(2) h fall short of their arcs by c^2/(24 r^2) <= 1.3e-4 (relative), the
    # vertices' offset changes the length by <= 1.04e-4/r = 2.1e-4: 3.4e-4 in all
    assert G.line_length(lines) == pytest.approx(np.pi, rel=1e-3)   # circumference 2 pi r
    # area error <= perimeter x (vertex offset 1.04e-4 + 2/3 sagitta c^2/(8 r) = 1.3e-4)
    # = 7.5e-4 (measured 2.6e-4)
    assert G.area_above(x, x, z, 0.5) == pytest.approx(4 - np.pi * 0.25, abs=2e-3)
    assert G.area_above(x, x, z, 5.0) == 0.0


# ------------------------------------------------------------------ threads, figure

def test_results_do_not_depend_on_n_threads(window_ds, vstick_ds, grid_ds):
    w1 = C.window_convergence([ONE_ONE], t_ends=(7000.0, 28000.0), n_threads=1)
    xr.testing.assert_identical(convergence_dataset("window", w1), window_ds)
    v1 = C.vstick_convergence([CHATTER], v_sticks=(1e-3, 1e-5, 1e-7, 1e-9), n_threads=1)
    xr.testing.assert_identical(convergence_dataset("vstick", v1).drop_vars("run_time"),
                                vstick_ds.drop_vars("run_time"))
    g1 = C.grid_convergence(**GRID, n_threads=1)
    xr.testing.assert_identical(convergence_dataset("grid", g1), grid_ds)


def test_figure_script_draws_the_datasets(window_ds, vstick_ds, grid_ds, tmp_path,
                                          monkeypatch):
    paths = {k: write_dataset(ds, tmp_path / f"{k}.nc")
             for k, ds in (("window", window_ds), ("vstick", vstick_ds), ("grid", grid_ds))}
    sm = SimpleNamespace(input=SimpleNamespace(**{k: str(p) for k, p in paths.items()}),
                         output=SimpleNamespace(pdf=str(tmp_path / "c.pdf"),
                                                png=str(tmp_path / "c.png")),
                         log=[str(tmp_path / "c.log")], wildcards={},
                         params=SimpleNamespace(colormap="viridis"), rule="figure_convergence")
    scripts = ROOT / "workflow" / "scripts" / "figures"
    monkeypatch.syspath_prepend(str(scripts))
    runpy.run_path(str(scripts / "convergence.py"), init_globals={"snakemake": sm})
    assert (tmp_path / "c.pdf").stat().st_size > 0 and (tmp_path / "c.png").stat().st_size > 0
    # a dataset without its variables fails with a clear message, no figure
    bad = window_ds.drop_vars("d_ke")
    write_dataset(bad, paths["window"])
    (tmp_path / "c.png").unlink()
    with pytest.raises(SystemExit):
        runpy.run_path(str(scripts / "convergence.py"), init_globals={"snakemake": sm})
    assert "expected variable 'd_ke' is missing" in (tmp_path / "c.log").read_text()
    assert not (tmp_path / "c.png").exists()
