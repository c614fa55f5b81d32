"""The shock stage: its dataset against the LO's closed-form free decay, its energy
balance, its decays in time consistent with its curve, and its figure."""
import math

import numpy as np
import pytest
from _figures import run_figure

from vines.core.params import D_DEFAULT
from vines.data.netcdf import write_dataset
from vines.pipeline import stages

MODEL = {"r": 0.65, "d": D_DEFAULT}
#: the default design (activation ~10.7 J): 1 J below activation, 100 J above it
SPEC = {"eta": 0.1, "clearance_m": 0.0424, "energy_range_J": [1.0, 100.0], "n_energies": 3,
        "history_energies_J": [5.0, 100.0], "periods": 2.0, "omega_band": [0.8, 1.2],
        "M_kg": 3.807, "k_N_per_m": 11680.0, "c_Ns_per_m": None, "d": None, "starts": 3,
        "seed": 0}


def lo_energy_left(d: float, t):
    """E(t)/E0 of the free damped LO from x = 0, x' = 1 (closed form, d < 2)."""
    a = 0.5 * d
    wd = math.sqrt(1.0 - a * a)
    x = np.exp(-a * t) * np.sin(wd * t) / wd
    v = np.exp(-a * t) * (np.cos(wd * t) - a * np.sin(wd * t) / wd)
    return x * x + v * v


@pytest.fixture(scope="module")
def ds():
    return stages.shock(SPEC, model=MODEL, code="test", title="t")


def test_lo_alone_and_the_vines_below_activation_decay_as_the_closed_form(ds):
    d = ds.attrs["d"]
    t = 2.0 * math.pi * ds["time_periods"].values
    assert t[-1] == pytest.approx(2.0 * math.pi * SPEC["periods"], rel=1e-15)
    want = lo_energy_left(d, t)
    np.testing.assert_allclose(ds["lo_alone_remaining"].values, want, rtol=1e-10, atol=0)
    assert float(ds["lo_alone_dissipated_fraction"]) == pytest.approx(1 - want[-1], rel=1e-10)
    # 5 J and 1 J are below activation: no impact, the LO alone's decay (exact flow)
    assert ds["activation_energy"] > 5.0
    np.testing.assert_allclose(ds["vines_remaining"].values[0], want, rtol=1e-9, atol=0)
    assert ds["vines_history_n_impacts"].values[0].max() == 0
    assert int(ds["vines_n_impacts"][0]) == 0
    assert float(ds["vines_dissipated_fraction"][0]) == pytest.approx(1 - want[-1], rel=1e-9)


def test_energy_balance_and_history_agree_with_the_curve(ds):
    E = ds["energy"].values
    np.testing.assert_allclose(E, np.geomspace(1.0, 100.0, 3), rtol=1e-15)
    np.testing.assert_allclose(ds["velocity"].values, np.sqrt(2 * E / SPEC["M_kg"]),
                               rtol=1e-15)
    frac = ds["vines_dissipated_fraction"].values
    np.testing.assert_allclose(ds["vines_by_damping"] + ds["vines_by_impacts"], frac,
                               rtol=1e-9)
    tmd = float(ds["tmd_by_damping"] + ds["tmd_by_absorber"])
    assert tmd == pytest.approx(float(ds["tmd_dissipated_fraction"]), rel=1e-9)
    # the 100 J decay in time is the curve's last run: same end state, same impacts
    assert ds["history_energy"].values[-1] == E[-1]
    assert 1.0 - ds["vines_remaining"].values[-1, -1] == pytest.approx(frac[-1], rel=1e-12)
    assert ds["vines_history_n_impacts"].values[-1, -1] == ds["vines_n_impacts"].values[-1] > 0
    assert float(ds["optimal_dissipated_fraction"]) == frac.max()
    assert set(ds["vines_status"].values) == {"ok"}


def test_travel_and_ball_starts(ds):
    V = ds["velocity"].values
    L = SPEC["clearance_m"]
    assert float(ds["vines_stroke"]) == L
    # linear strokes grow like V0; the TMD of equal travel reaches L at the largest energy
    for name in ("tmd", "tmd_fastest", "tmd_equal_travel", "lo_alone"):
        key = f"{name}_x_max" if name == "lo_alone" else f"{name}_stroke"
        np.testing.assert_allclose(ds[key].values / V, ds[key].values[-1] / V[-1], rtol=1e-12)
    assert float(ds["tmd_equal_travel_stroke"][-1]) == pytest.approx(L, rel=1e-8)
    assert float(ds["tmd_stroke"][-1]) > L
    assert float(ds["tmd_fastest_decay_rate"]) > float(ds["tmd_equal_travel_decay_rate"])
    f = ds["vines_start_dissipated_fraction"].values
    q = ds["vines_start_quantile"].values
    assert f.shape == (3, 3) and q.shape == (3, 5)
    assert np.all((f.min(axis=1) <= q[:, 0]) & (q[:, -1] <= f.max(axis=1)))
    assert np.all(np.abs(ds["ball_position"].values) < 1)


def test_shock_figure_from_the_stage_dataset(ds, tmp_path):
    path = write_dataset(ds, tmp_path / "shock_x.nc")
    png, log = run_figure("shock", tmp_path, "shock", colormap=None, shocks=[str(path)])
    assert png.read_bytes()[:4] == b"\x89PNG"
    assert "eta = 0.1, L = 42.4 mm, 2 periods: VI NES best" in log
