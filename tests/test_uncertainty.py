"""Uncertain parts (``vines.studies.uncertainty``, ``vines design --uncertainty``): the Sobol
machinery against the Ishigami function's known indices, zero-width ranges against the
nominal design, fixed deviations against the deviated structure built independently, and
bad input refused in one line."""
import json
import math

import numpy as np
import pytest
from conftest import run_vines

import vines
from vines import ParameterError
from vines.studies import uncertainty as unc
from vines.studies.uncertainty_checks import Uncertain, check_parameters

SMALL = dict(amplitudes_m=[0.00075, 0.003], omega_band=(0.9, 1.1), n_omega=5, census_n=0,
             t_end=2000.0, t_transient=1500.0)


@pytest.fixture(scope="module")
def nominal():
    return vines.design(eta=0.1, clearance_m=0.0424, n_threads=2, **SMALL)


# --------------------------------------------------------------------------- Sobol machinery

#: Ishigami function sin x1 + 7 sin^2 x2 + 0.1 x3^4 sin x1, x_i ~ U(-pi, pi): its exact
#: first-order indices (0.3139, 0.4424, 0) and total ones (0.5576, 0.4424, 0.2437)
ISHIGAMI_FIRST = (0.31391, 0.44241, 0.0)
ISHIGAMI_TOTAL = (0.55758, 0.44241, 0.24368)


def _ishigami_indices(n, seed, a=7.0):
    params = [Uncertain(f"x{i}", "uniform", -math.pi, math.pi) for i in range(3)]
    units = unc.pick_freeze_points(*unc.sobol_blocks(3, n, seed))
    x = np.stack([p.ppf(units[i]) for i, p in enumerate(params)])
    y = np.sin(x[0]) + a * np.sin(x[1]) ** 2 + 0.1 * x[2] ** 4 * np.sin(x[0])
    return unc.sobol_analysis(y, 3, n, seed, ["x1", "x2", "x3"], n_bootstrap=199)


def _ishigami_exact(a=7.0, b=0.1):
    """Closed-form first-order and total indices of the Ishigami function."""
    pi = math.pi
    v1 = 0.5 * (1 + b * pi ** 4 / 5) ** 2
    v2 = a * a / 8
    v13 = b * b * pi ** 8 * (1 / 18 - 1 / 50)
    v = v1 + v2 + v13
    return (v1 / v, v2 / v, 0.0), ((v1 + v13) / v, v2 / v, v13 / v)


def test_ishigami_closed_form_is_the_published_one():
    first, total = _ishigami_exact()
    assert np.allclose(first, ISHIGAMI_FIRST, atol=1e-5)
    assert np.allclose(total, ISHIGAMI_TOTAL, atol=1e-5)


def test_sobol_machinery_reproduces_ishigami_indices():
    """Our seeded Sobol blocks, pick-freeze points and scipy's estimators: every exact index
    inside its 95 % bootstrap interval, each interval narrower than CI_WIDTH_MAX (the
    estimator's own error at n = 4096 sets the tolerance)."""
    s = _ishigami_indices(4096, seed=0)
    first, total = _ishigami_exact()
    for i, name in enumerate(("x1", "x2", "x3")):
        v = s[name]
        assert v["first_order_ci"][0] <= first[i] <= v["first_order_ci"][1], (name, v)
        assert v["total_order_ci"][0] <= total[i] <= v["total_order_ci"][1], (name, v)
        assert v["reliable"]


def test_sobol_machinery_detects_a_wrong_function():
    """The same check fails for another function (a = 5): it can fail."""
    s = _ishigami_indices(4096, seed=0, a=5.0)
    first, _ = _ishigami_exact()
    assert not s["x2"]["first_order_ci"][0] <= first[1] <= s["x2"]["first_order_ci"][1]


def test_small_samples_are_flagged_unreliable_and_no_effect_is_exactly_zero():
    s = _ishigami_indices(32, seed=0)
    assert not all(v["reliable"] for v in s.values())
    n = 64
    units = unc.pick_freeze_points(*unc.sobol_blocks(2, n, 1))
    y = np.sin(units[0] * 6)              # x2 has no effect at all
    s = unc.sobol_analysis(y, 2, n, 1, ["x1", "x2"], n_bootstrap=99)
    assert s["x2"]["first_order"] == s["x2"]["total_order"] == 0.0
    assert unc.sobol_analysis(np.ones(4 * n), 2, n, 1, ["x1", "x2"]) is None


def test_our_estimators_are_scipys_default():
    """The estimators the bootstrap uses are those of scipy's default method."""
    from scipy.stats import sobol_indices
    rng = np.random.default_rng(5)
    f = dict(f_A=rng.normal(3, 1, (1, 64)), f_B=rng.normal(3, 1, (1, 64)),
             f_AB=rng.normal(3, 1, (3, 1, 64)))
    ours = sobol_indices(func=f, n=64, method=unc.pick_freeze_estimators)
    theirs = sobol_indices(func=f, n=64)
    assert np.allclose(ours.first_order, theirs.first_order, rtol=0, atol=1e-12)
    assert np.allclose(ours.total_order, theirs.total_order, rtol=0, atol=1e-12)


def test_sampling_is_seeded_and_within_the_support():
    a1, b1 = unc.sobol_blocks(2, 16, 3)
    a2, b2 = unc.sobol_blocks(2, 16, 3)
    assert np.array_equal(a1, a2) and np.array_equal(b1, b2)
    assert not np.array_equal(a1, unc.sobol_blocks(2, 16, 4)[0])
    u = Uncertain("r", "normal", 0.6, 0.05)
    x = u.ppf(np.linspace(1e-9, 1 - 1e-9, 101))
    assert u.support == pytest.approx((0.45, 0.75))
    assert x.min() >= 0.45 - 1e-12 and x.max() <= 0.75 + 1e-12


def test_regime_groups():
    assert [unc.regime_group(x) for x in ("no-impact", "1:1", "2:1", "period-3", "chatter",
                                          "irregular", "max_impacts")] == [
        "no-impact", "1:1", "other periodic", "other periodic", "chatter", "irregular",
        "irregular"]


# --------------------------------------------------------------------------- design

def test_zero_width_ranges_are_the_nominal_design(nominal):
    """Every part known exactly: every point is the nominal design, bit for bit."""
    zero = {"frequency": "uniform:0:0", "clearance": "normal:0:0", "mass": "uniform:0:0",
            "r": f"uniform:{nominal.problem.model.r}:{nominal.problem.model.r}"}
    res = unc.uncertainty(nominal, zero, samples=2, n_threads=2)
    assert res.points.shape == (4, 12)
    assert np.all(res.vines_worst == nominal.worst_ratio)
    assert np.all(res.tmd_worst == nominal.tmd.worst_ratio)
    d = res.to_dict()
    assert d["vines"]["mean"] == d["vines"]["q95"] == nominal.worst_ratio
    assert d["sensitivity"] == {"vines": None, "tmd": None}
    assert res.cost["n_distinct_points"] == 1
    json.dumps(d, allow_nan=False)


def _tmd_si(res, band, k_host, mass_factor, n=20001):
    """Worst |X/Y| over the band (absolute frequency, nominal w0) of the LO (M, k_host, c)
    carrying the built TMD (its k_a, c_a; mass m_a * mass_factor): the 2-DOF frequency
    response in SI units, on a dense grid."""
    pb, t = res.problem, res.to_dict()["tmd"]
    M, c = pb.M_kg, pb.c_Ns_per_m
    m, ka, ca = t["mass_kg"] * mass_factor, t["stiffness_N_per_m"], t["damping_Ns_per_m"]
    w = np.linspace(band[0], band[1], n) * pb.w0_rad_s
    iw = 1j * w
    a11 = -M * w ** 2 + c * iw + k_host + ca * iw + ka
    a12 = -(ca * iw + ka)
    a22 = -m * w ** 2 + ca * iw + ka
    x = (c * iw + k_host) * a22 / (a11 * a22 - a12 * a12)
    return np.abs(x).max()


@pytest.mark.parametrize("delta, e_L, r, e_m", [(0.04, -0.1, 0.5, 0.05),
                                                (-0.03, 0.2, 0.8, -0.05)])
def test_fixed_deviations_are_the_deviated_structure(nominal, delta, e_L, r, e_m):
    """Zero-width ranges away from the nominal: the VI NES equals ``vines.design`` of the
    structure built with those parts (stiffness k (1 + delta)^2, band in the new w0's
    units, eta (1 + e_m), L (1 + e_L), r); the TMD the 2-DOF response in SI units."""
    spec = {"frequency": f"uniform:{delta}:{delta}", "clearance": f"uniform:{e_L}:{e_L}",
            "r": f"normal:{r}:0", "mass": f"uniform:{e_m}:{e_m}"}
    res = unc.uncertainty(nominal, spec, samples=2, n_threads=2)
    pb, g = nominal.problem, 1.0 + delta
    band = (SMALL["omega_band"][0] / g, SMALL["omega_band"][1] / g)
    kw = dict(SMALL, omega_band=band)
    direct = vines.design(eta=0.1 * (1 + e_m), clearance_m=0.0424 * (1 + e_L), r=r,
                          M_kg=pb.M_kg, k_N_per_m=pb.k_N_per_m * g * g,
                          c_Ns_per_m=pb.c_Ns_per_m, n_threads=2, **kw)
    assert res.vines_worst[0] == pytest.approx(direct.worst_ratio, rel=1e-6)
    tmd = _tmd_si(nominal, SMALL["omega_band"], pb.k_N_per_m * g * g, 1 + e_m)
    assert res.tmd_worst[0] == pytest.approx(tmd, rel=1e-6)
    assert res.tmd_worst[0] > nominal.tmd.worst_ratio      # detuned: worse


def test_same_numbers_on_one_or_two_threads(nominal):
    spec = {"frequency": "uniform:-0.05:0.05", "r": "uniform:0.5:0.8"}
    one = unc.uncertainty(nominal, spec, samples=2, n_threads=1).to_dict()
    two = unc.uncertainty(nominal, spec, samples=2, n_threads=2).to_dict()
    one.pop("cost"), two.pop("cost")
    assert [k for k in one if json.dumps(one[k]) != json.dumps(two[k])] == []
    assert json.dumps(one) == json.dumps(two)
    assert one["n_points"] == 8 and len(one["vines"]["regime"]) == 8
    assert sum(one["vines"]["regime_shares"].values()) == pytest.approx(1.0)


# --------------------------------------------------------------------------- bad input

@pytest.mark.parametrize("spec, words", [
    ({"r": "uniform:0.8:0.5"}, "empty"),
    ({"clearance": "uniform:0.1:-0.1"}, "empty"),
    ({"mass": "normal:0:-0.1"}, "standard deviation"),
    ({"r": "uniform:0.5:1.2"}, "[0, 1]"),
    ({"frequency": "uniform:-0.9:0"}, "[-0.5, 1]"),
    ({"frequency": "uniform:nan:0"}, "finite"),
    ({"stiffness": "uniform:0:1"}, "one of"),
    ({"r": "beta:1:2"}, "distribution"),
    ({"r": "0.5"}, "NAME=uniform"),
    ({}, "at least one"),
    (["r=uniform:0.5:0.6", "r=uniform:0.5:0.6"], "twice"),
])
def test_bad_specifications_name_the_argument(spec, words):
    with pytest.raises(ParameterError) as err:
        check_parameters(spec)
    assert err.value.name == "uncertainty" and words in str(err.value)


def test_context_checks_and_samples(nominal):
    with pytest.raises(ParameterError, match="A_max"):
        unc.uncertainty(nominal, {"clearance": "uniform:-0.999999:0"})
    for n in (3, 1, "x", 2 ** 20):
        with pytest.raises(ParameterError) as err:
            unc.uncertainty(nominal, {"r": "uniform:0.5:0.6"}, samples=n)
        assert err.value.name == "samples"


def test_cli_refuses_an_empty_range_in_one_line():
    p = run_vines("design", "--eta", "0.1", "--clearance", "0.0424", "--uncertainty",
                  "r=uniform:0.8:0.5", "clearance=uniform:-0.1:0.1")
    assert p.returncode == 2 and p.stdout == ""
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "--uncertainty" in lines[0] and "empty" in lines[0]
