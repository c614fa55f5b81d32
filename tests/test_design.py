"""vines.design: limits with known answers, the TMD against the classical optimum and an
independent time integration, the optimiser against brute force, views, threads, input."""
import json
import math

import numpy as np
import pytest

import vines
from vines import ParameterError
from vines.core.params import D_DEFAULT
from vines.studies import tmd
from vines.studies.design import N_REFINE, search_grid

#: short runs where the limit does not need the default window
SHORT = dict(t_end=2000.0, t_transient=1500.0)


def lo_alone(w, d):
    """|X/Y| of the LO alone under base excitation, written out independently."""
    return np.sqrt(1 + (d * w) ** 2) / np.sqrt((1 - w ** 2) ** 2 + (d * w) ** 2)


def stuck(w, eta, d):
    """|X/Y| of LO and ball moving as one body of mass 1 + eta (paper Eq. 28)."""
    return np.sqrt(1 + (d * w) ** 2) / np.sqrt((1 - (1 + eta) * w ** 2) ** 2 + (d * w) ** 2)


def test_huge_clearance_is_the_lo_alone():
    # F = A/L = 1e-4: the LO moves at most 83 F << 1, the ball never hits
    A = 0.001
    res = vines.design(eta=0.1, clearance_m=A * 1e4, amplitudes_m=[A], omega_band=(0.9, 1.1),
                       n_omega=9, census_n=0)
    w = np.asarray(res.problem.omega)
    np.testing.assert_allclose(res.rest.curves[0], lo_alone(w, D_DEFAULT), rtol=1e-6)
    # the refined peak is the curve at the omega where it was found, and near the true peak
    np.testing.assert_allclose(res.rest.peak, lo_alone(res.rest.peak_omega, D_DEFAULT),
                               rtol=1e-6)
    true_peak = lo_alone(np.linspace(0.99, 1.01, 200001), D_DEFAULT).max()
    assert res.worst_ratio <= true_peak * (1 + 1e-9)
    assert res.worst_ratio >= 0.99 * true_peak
    d = res.to_dict()
    assert d["lo_alone"]["worst_ratio"] == pytest.approx(true_peak, rel=1e-8)


def test_vanishing_clearance_is_the_stuck_system():
    A, eta = 0.002, 0.1
    res = vines.design(eta=eta, clearance_m=1e-3 * A, amplitudes_m=[A],
                       omega_band=(0.91, 1.01), n_omega=5, census_n=0)
    w = np.asarray(res.problem.omega)
    np.testing.assert_allclose(res.rest.curves[0], stuck(w, eta, D_DEFAULT), rtol=1e-2)
    # the band holds the stuck resonance 1/sqrt(1 + eta) = 0.9535: the refined worst case
    # finds its peak although no grid point is within 0.006 of it
    peak = stuck(np.linspace(0.94, 0.97, 300001), eta, D_DEFAULT).max()
    assert res.worst_ratio == pytest.approx(peak, rel=1e-2)
    assert res.rest.curves.max() < 0.8 * peak


def test_tmd_formula_against_time_integration():
    """The closed-form 2-DOF transmissibility against scipy's integration of
    x'' + d (x' - y') + (x - y) + mu (2 zeta f (x' - x_a') + f^2 (x - x_a)) = 0,
    x_a'' + 2 zeta f (x_a' - x') + f^2 (x_a - x) = 0, y = sin(omega t)."""
    from scipy.integrate import solve_ivp
    mu, f, zeta, d, w = 0.1, 0.92, 0.12, 0.05, 1.07

    def rhs(t, s):
        x, v, xa, va = s
        y, yd = math.sin(w * t), w * math.cos(w * t)
        fa = 2 * zeta * f * (va - v) + f * f * (xa - x)
        return [v, -d * (v - yd) - (x - y) + mu * fa, va, -fa]

    T = 2 * math.pi / w
    t_end = 400 * T
    sol = solve_ivp(rhs, (0, t_end), [0, 0, 0, 0], method="DOP853", rtol=1e-11, atol=1e-12,
                    t_eval=np.linspace(t_end - 5 * T, t_end, 20001))
    amp = np.abs(sol.y[0]).max()
    assert tmd.tmd_ratio(w, d, mu, f, zeta) == pytest.approx(amp, rel=1e-5)


def _peaks(t: tmd.TunedMassDamper, d, band):
    w = np.linspace(band[0], band[1], 400001)
    y = t.ratio(w, d)
    i = np.flatnonzero((y[1:-1] > y[:-2]) & (y[1:-1] > y[2:])) + 1
    return y[i]


@pytest.mark.parametrize("mu", [0.02, 0.1])
def test_tmd_on_undamped_lo_is_the_classical_optimum(mu):
    band = (0.5, 1.5)
    t = tmd.optimal_tmd(mu, 0.0, band)
    f_dh, z_dh, peak_dh = tmd.den_hartog(mu)
    # the minimax optimum: two equal peaks ...
    p = _peaks(t, 0.0, band)
    assert len(p) == 2 and p[0] == pytest.approx(p[1], rel=1e-5)
    assert t.worst_ratio == pytest.approx(p.max(), rel=1e-6)
    # ... no lower than the fixed points' common height sqrt(1 + 2/mu) (any tuning has one
    # fixed point at least that high), and lower than Den Hartog's own tuning's peak
    dh_design = tmd.TunedMassDamper(mu, f_dh, z_dh, math.nan, math.nan, math.nan)
    assert peak_dh * (1 - 1e-9) <= t.worst_ratio < _peaks(dh_design, 0.0, band).max()
    # measured differences from Den Hartog's formulas (docs/design.md), mu 0.02 / 0.1:
    # frequency ratio -0.0002 % / -0.004 %, peak +0.03 % / +0.14 %, damping ratio
    # +2.1 % / +10.5 % (his damping averages the optima at the two fixed points)
    assert t.frequency_ratio == pytest.approx(f_dh, rel=1e-3)
    assert t.worst_ratio == pytest.approx(peak_dh, rel=3e-3)
    assert 0 < t.damping_ratio / z_dh - 1 < 1.2 * mu


def test_tmd_beats_lo_alone_and_respects_the_band():
    band = (0.8, 1.2)
    t = tmd.optimal_tmd(0.05, D_DEFAULT, band)
    w = np.linspace(*band, 100001)
    dense = t.ratio(w, D_DEFAULT).max()
    assert t.worst_ratio == pytest.approx(dense, rel=1e-7)
    assert t.worst_ratio < 0.1 * lo_alone(w, D_DEFAULT).max()
    # detuning either way is worse: a local minimum of the worst case
    for df, dz in ((1.01, 1), (0.99, 1), (1, 1.05), (1, 0.95)):
        other = tmd.tmd_ratio(w, D_DEFAULT, 0.05, t.frequency_ratio * df,
                              t.damping_ratio * dz).max()
        assert other > t.worst_ratio


def _small_optimisation(**kw):
    base = dict(eta_max=0.1, amplitudes_m=[0.0015], omega_band=(0.9, 1.1), n_omega=5,
                n_eta=2, n_clearance=4, clearance_range_m=(0.0075, 0.06), census_n=0, **SHORT)
    return vines.design(**(base | kw))


def test_optimiser_never_worse_than_brute_force_grid_nor_lo_alone():
    res = _small_optimisation()
    d = res.to_dict()
    etas, Ls = search_grid(0.1, (0.0075, 0.06), 2, 4)
    brute = [vines.design(eta=e, clearance_m=L, amplitudes_m=[0.0015], omega_band=(0.9, 1.1),
                          n_omega=5, census_n=0, **SHORT).worst_ratio
             for e in etas for L in Ls]
    np.testing.assert_allclose(np.ravel(d["search"]["worst_ratio"]), brute, rtol=0)
    assert res.worst_ratio <= min(brute)
    assert res.worst_ratio <= d["lo_alone"]["worst_ratio"]
    assert 0 < res.eta <= 0.1 and 0.0075 <= res.clearance_m <= 0.06
    assert d["cost"]["n_designs"] >= len(brute)


def test_same_numbers_on_one_or_two_threads():
    kw = dict(eta=0.1, clearance_m=0.015, amplitudes_m=[0.00075, 0.003],
              omega_band=(0.95, 1.05), n_omega=3, census_n=4, **SHORT)
    one = vines.design(n_threads=1, **kw).to_dict()
    two = vines.design(n_threads=2, **kw).to_dict()
    one.pop("cost"), two.pop("cost")
    assert json.dumps(one) == json.dumps(two)


def test_attractor_view_at_least_from_rest_and_sometimes_more():
    # eta 0.1, F = 0.05 at omega 0.96: the start from rest settles on a small motion while
    # other initial states reach a larger attractor
    res = vines.design(eta=0.1, clearance_m=0.015, amplitudes_m=[0.00075],
                       omega_band=(0.96, 1.0), n_omega=3, census_n=16)
    d = res.to_dict()
    any_ = np.array(d["curves"]["vines_any_attractor"])
    rest = np.array(d["curves"]["vines"])
    assert np.all(any_ >= rest)
    assert d["vines"]["worst_ratio_any_attractor"] >= d["vines"]["worst_ratio"]
    assert np.any(any_ > 1.05 * rest)
    assert d["vines"]["view"] == "t_end"


def test_json_keys_of_the_issue():
    res = vines.design(eta=0.05, clearance_m=0.02, amplitudes_m=[0.001], omega_band=(0.9, 1.1),
                       n_omega=3, census_n=2, **SHORT)
    d = json.loads(json.dumps(res.to_dict(), allow_nan=False))
    assert set(d["curves"]) >= {"omega", "lo_alone", "tmd", "vines"}
    assert len(d["curves"]["vines"]) == 1 and len(d["curves"]["vines"][0]) == 3
    assert set(d["lo_alone"]) >= {"worst_ratio"}
    assert set(d["tmd"]) >= {"eta", "frequency_ratio", "damping_ratio", "worst_ratio"}
    assert set(d["vines"]) >= {"eta", "clearance_m", "worst_ratio", "worst_ratio_any_attractor"}
    assert d["tmd"]["eta"] == 0.05 and d["vines"]["clearance_m"] == 0.02
    assert d["inputs"]["mode"] == "evaluate" and d["search"] is None
    assert {"wall_s", "n_runs_from_rest", "n_runs_census"} <= set(d["cost"])
    # 3 grid runs, then per refinement round one or two runs (a side outside the band
    # is skipped)
    assert 3 + N_REFINE <= d["cost"]["n_runs_from_rest"] <= 3 + 2 * N_REFINE


@pytest.mark.parametrize("kw, name", [
    (dict(eta=0.1), "clearance"),
    (dict(clearance_m=0.01), "eta"),
    (dict(eta=0.1, clearance_m=0.01, eta_max=0.1), "eta_max"),
    (dict(eta=0.1, clearance_m=0.01, clearance_range_m=(0.01, 0.02)), "clearance_range"),
    (dict(eta_max=0.1, clearance_range_m=(0.02, 0.01)), "clearance_range"),
    (dict(eta=0.1, clearance_m=-1.0), "clearance"),
    (dict(eta=0.0, clearance_m=0.01), "eta"),
    (dict(eta=0.1, clearance_m=0.01, omega_band=(1.2, 0.8)), "omega_band"),
    (dict(eta=0.1, clearance_m=0.01, omega_band=(0.8,)), "omega_band"),
    (dict(eta=0.1, clearance_m=0.01, amplitudes_m=[]), "amplitude"),
    (dict(eta=0.1, clearance_m=0.01, amplitudes_m=[0.001, "x"]), "amplitude"),
    (dict(eta=0.1, clearance_m=0.01, c_Ns_per_m=2.0, d=0.01), "d"),
    (dict(eta=0.1, clearance_m=0.01, M_kg=0.0), "M"),
    (dict(eta=0.1, clearance_m=0.01, n_omega=1), "n_omega"),
    (dict(eta=0.1, clearance_m=0.01, view="asymptotic-typo"), "view"),
    (dict(eta=0.1, clearance_m=0.01, basin_min=2), "basin_min"),
    (dict(eta=0.1, clearance_m=0.01, n_threads=0), "n_threads"),
    (dict(eta=0.1, clearance_m=0.01, t_transient=8000), "t_transient"),
])
def test_bad_input_names_the_argument(kw, name):
    with pytest.raises(ParameterError) as err:
        vines.design(**kw)
    assert err.value.name == name
    assert "\n" not in str(err.value)


@pytest.mark.slow
def test_default_design_beats_lo_alone_and_loses_to_tmd():
    """The issue's default design (band 0.8-1.2, amplitudes 0.75-6 mm, eta_max 0.1):
    the optimal VI NES lowers the worst case below the LO alone's, the TMD of the same mass
    lowers it much further (measured: docs/design.md)."""
    d = vines.design(eta_max=0.1, census_n=16).to_dict()
    lo, t, v = d["lo_alone"]["worst_ratio"], d["tmd"]["worst_ratio"], d["vines"]
    assert v["worst_ratio"] < lo
    assert v["worst_ratio_any_attractor"] >= v["worst_ratio"]
    assert t < v["worst_ratio"]
    assert min(np.ravel(d["search"]["worst_ratio"])) >= v["worst_ratio"]
