"""Validation of ModelParams / SolverSettings and the Table 1 conversions."""
import dataclasses
import math

import pytest

from vines.core.params import (
    C_DAMP_NS_PER_M,
    D_DEFAULT,
    K_SPRING_N_PER_M,
    L_HALF_M,
    M_LO_KG,
    MAX_IMPACTS_DEFAULT,
    R_DEFAULT,
    T_END_DEFAULT,
    T_TRANSIENT_DEFAULT,
    V_STICK_DEFAULT,
    W0_RAD_S,
    ModelParams,
    ParameterError,
    SolverSettings,
)

GOOD = dict(eta=0.05, omega=1.0, F=0.05)


def _assert_names(err: ParameterError, name: str, value) -> None:
    msg = str(err)
    assert err.name == name
    assert name in msg
    assert repr(value) in msg
    assert "\n" not in msg


# ---------------------------------------------------------------- ModelParams

def test_model_params_defaults():
    p = ModelParams(**GOOD)
    assert p.r == R_DEFAULT == 0.65
    assert p.d == D_DEFAULT
    assert p.phi == 0.0
    assert p.as_dict() == dict(eta=0.05, omega=1.0, F=0.05, r=0.65, d=D_DEFAULT, phi=0.0)


def test_model_params_accepts_numeric_strings_and_ints():
    p = ModelParams(eta="0.05", omega=1, F="5e-2", r="1", d=0, phi="-1e-3")
    assert (p.eta, p.omega, p.F, p.r, p.d, p.phi) == (0.05, 1.0, 0.05, 1.0, 0.0, -1e-3)
    assert all(isinstance(v, float) for v in p.as_dict().values())


def test_model_params_boundaries_allowed():
    ModelParams(eta=1e-12, omega=1e-12, F=0.0, r=0.0, d=0.0)
    ModelParams(eta=10.0, omega=5.0, F=2.0, r=1.0, d=3.0, phi=-7.0)


@pytest.mark.parametrize("name, value", [
    ("eta", 0.0), ("eta", -1.0), ("eta", "abc"), ("eta", float("nan")), ("eta", float("inf")),
    ("eta", True), ("eta", None),
    ("omega", 0.0), ("omega", -0.5), ("omega", float("-inf")),
    ("F", -0.1), ("F", "x"),
    ("r", -0.01), ("r", 1.5),
    ("d", -1e-3), ("d", float("nan")),
    ("phi", float("nan")), ("phi", "pi"),
])
def test_model_params_invalid(name, value):
    kwargs = {**GOOD, name: value}
    with pytest.raises(ParameterError) as exc:
        ModelParams(**kwargs)
    _assert_names(exc.value, name, value)
    assert isinstance(exc.value, ValueError)


def test_model_params_upper_bounds_allowed():
    """The largest allowed values (far beyond the tested extremes eta 50, W 8, F 20, d 3)."""
    from vines.core.params import D_MAX, ETA_MAX, F_MAX, OMEGA_MAX, PHI_MAX
    assert (ETA_MAX, OMEGA_MAX, F_MAX, D_MAX, PHI_MAX) == (1e3, 1e3, 1e4, 1e3, 1e3)
    p = ModelParams(eta=ETA_MAX, omega=OMEGA_MAX, F=F_MAX, r=1.0, d=D_MAX, phi=-PHI_MAX)
    assert (p.eta, p.omega, p.F, p.d, p.phi) == (1e3, 1e3, 1e4, 1e3, -1e3)
    ModelParams(eta=50.0, omega=8.0, F=20.0, d=2.5, phi=PHI_MAX)


@pytest.mark.parametrize("name, value, bound", [
    ("eta", 1000.5, "<= 1000"), ("eta", 1e308, "<= 1000"),
    ("omega", 1e160, "<= 1000"), ("omega", 1e308, "<= 1000"), ("omega", "1e308", "<= 1000"),
    ("F", 10000.5, "<= 10000"), ("F", 1e308, "<= 10000"),
    ("d", 1e308, "<= 1000"), ("d", 1000.5, "<= 1000"),
    ("phi", 1e308, "<= 1000"), ("phi", -1e308, ">= -1000"),
])
def test_model_params_above_the_maximum(name, value, bound):
    with pytest.raises(ParameterError) as exc:
        ModelParams(**{**GOOD, name: value})
    _assert_names(exc.value, name, value)
    assert bound in str(exc.value)


def test_from_xi_bounds_d():
    with pytest.raises(ParameterError) as exc:
        ModelParams.from_xi(eta=0.5, omega=1.0, F=0.1, xi=1e308)
    _assert_names(exc.value, "xi", 1e308)
    assert "<= 2000" in str(exc.value)


def test_model_params_frozen():
    p = ModelParams(**GOOD)
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.eta = 0.1


def test_period_and_omega_s():
    p = ModelParams(eta=0.2, omega=0.8, F=0.4)
    assert p.period == pytest.approx(2 * math.pi / 0.8)
    assert p.omega_s == pytest.approx(1 / math.sqrt(1.2))


# ---------------------------------------------------------------- Table 1 conversions

def test_table1_constants():
    assert (M_LO_KG, L_HALF_M, R_DEFAULT, K_SPRING_N_PER_M, C_DAMP_NS_PER_M) == \
        (3.807, 0.015, 0.65, 11680.0, 2.53)
    # hand-computed from Table 1: w0 = sqrt(11680/3.807), d = 2.53/(3.807 w0)
    assert round(W0_RAD_S, 3) == 55.390
    assert round(W0_RAD_S / (2 * math.pi), 3) == 8.816
    assert round(D_DEFAULT, 6) == 0.011998


def test_from_dimensional_reproduces_table1():
    eta = 0.05
    p = ModelParams.from_dimensional(m_ball_kg=eta * 3.807, omega_rad_s=55.390, A_m=0.00075)
    assert p.eta == pytest.approx(eta, rel=1e-12)
    assert round(p.d, 6) == 0.011998
    # 55.390 is w0 = sqrt(k/M) = 55.39032.. rounded to 3 decimals: |omega - 1| <= 5e-4 / w0
    # (9.0e-6) by that rounding alone; the conversion itself is a division (round-off)
    assert abs(p.omega - 1.0) <= 5e-4 / W0_RAD_S
    assert p.omega == pytest.approx(55.390 / W0_RAD_S, rel=4e-16)
    assert pytest.approx(0.05, rel=1e-12) == p.F
    assert p.r == 0.65


def test_from_dimensional_d_independent_of_ball_mass():
    ds = {ModelParams.from_dimensional(m_ball_kg=m, omega_rad_s=50.0, A_m=1e-3).d
          for m in (0.01, 0.2, 1.0, 3.0)}
    assert len(ds) == 1
    assert round(ds.pop(), 6) == 0.011998


@pytest.mark.parametrize("name, value", [
    ("m_ball_kg", 0.0), ("omega_rad_s", -1.0), ("A_m", -1e-3), ("M_kg", 0.0),
    ("k_N_per_m", "stiff"), ("L_m", -0.015), ("c_Ns_per_m", -2.53),
])
def test_from_dimensional_invalid(name, value):
    kwargs = dict(m_ball_kg=0.2, omega_rad_s=55.0, A_m=1e-3)
    kwargs[name] = value
    with pytest.raises(ParameterError) as exc:
        ModelParams.from_dimensional(**kwargs)
    _assert_names(exc.value, name, value)


@pytest.mark.parametrize("eta, xi", [(0.05, 0.24), (0.5, 0.02), (1.0, 0.0)])
def test_from_xi(eta, xi):
    p = ModelParams.from_xi(eta=eta, omega=1.0, F=0.1, xi=xi)
    assert p.d == pytest.approx(eta * xi, rel=1e-15, abs=0.0)
    assert p.eta == eta


def test_from_xi_matches_fixed_d_at_one_eta():
    eta = 0.05
    p = ModelParams.from_xi(eta=eta, omega=1.0, F=0.05, xi=D_DEFAULT / eta)
    assert p.d == pytest.approx(D_DEFAULT, rel=1e-14)


@pytest.mark.parametrize("name, value", [("xi", -0.1), ("xi", "abc"), ("eta", 0.0)])
def test_from_xi_invalid(name, value):
    kwargs = dict(eta=0.05, omega=1.0, F=0.05, xi=0.2)
    kwargs[name] = value
    with pytest.raises(ParameterError) as exc:
        ModelParams.from_xi(**kwargs)
    _assert_names(exc.value, name, value)


# ---------------------------------------------------------------- SolverSettings

def test_solver_settings_defaults():
    s = SolverSettings()
    assert (s.t_end, s.t_transient) == (T_END_DEFAULT, T_TRANSIENT_DEFAULT) == (7000.0, 4000.0)
    assert s.v_stick == V_STICK_DEFAULT
    assert s.max_impacts == MAX_IMPACTS_DEFAULT
    assert s.state0 == (0.0, 0.0, 0.0, 0.0)
    d = s.as_dict()
    assert d["state0"] == [0.0, 0.0, 0.0, 0.0]
    assert {"t_end", "t_transient", "v_stick", "max_impacts", "root_tol"} <= set(d)


def test_solver_settings_accepts_strings():
    s = SolverSettings(t_end="300", t_transient="100", v_stick="0", max_impacts="10")
    assert (s.t_end, s.t_transient, s.v_stick, s.max_impacts) == (300.0, 100.0, 0.0, 10)
    assert isinstance(s.max_impacts, int)


@pytest.mark.parametrize("name, value", [
    ("t_end", 0.0), ("t_end", -5.0), ("t_end", "long"), ("t_end", float("inf")),
    ("t_transient", -1.0), ("t_transient", 7000.0), ("t_transient", 8000.0),
    ("t_transient", float("nan")),
    ("v_stick", -1e-6), ("v_stick", "tiny"),
    ("max_impacts", 0), ("max_impacts", 1.5), ("max_impacts", "many"), ("max_impacts", True),
    ("root_tol", 0.0), ("root_tol", 1e-2),
])
def test_solver_settings_invalid(name, value):
    with pytest.raises(ParameterError) as exc:
        SolverSettings(**{name: value})
    _assert_names(exc.value, name, value)


def test_solver_settings_upper_bounds():
    from vines.core.params import MAX_IMPACTS_MAX, T_END_MAX, V_STICK_MAX
    s = SolverSettings(t_end=T_END_MAX, t_transient=0.0, v_stick=V_STICK_MAX,
                       max_impacts=MAX_IMPACTS_MAX, state0=(1e12, -1e12, 1e12, 1e12))
    assert (s.t_end, s.v_stick, s.max_impacts) == (1e9, 1.0, 100_000_000)
    assert SolverSettings(max_impacts="2e6").max_impacts == 2_000_000


@pytest.mark.parametrize("name, value, bound", [
    ("t_end", 1e308, "<= 1e+09"), ("t_end", 1.5e9, "<= 1e+09"),
    ("v_stick", 1e308, "<= 1"), ("v_stick", 1.5, "<= 1"),
    ("max_impacts", 10 ** 8 + 1, "<= 100000000"), ("max_impacts", 1e300, "<= 100000000"),
    ("max_impacts", float("inf"), "integer"),
])
def test_solver_settings_above_the_maximum(name, value, bound):
    with pytest.raises(ParameterError) as exc:
        SolverSettings(**{name: value})
    _assert_names(exc.value, name, value)
    assert bound in str(exc.value)


@pytest.mark.parametrize("state0", [(1e300, 0.0, 1e300, 0.0), (0.0, 1e13, 0.0, 0.0)])
def test_solver_settings_state0_bounded(state0):
    with pytest.raises(ParameterError) as exc:
        SolverSettings(state0=state0)
    assert "<= 1e+12" in str(exc.value)


def test_t_transient_message_states_t_end():
    with pytest.raises(ParameterError) as exc:
        SolverSettings(t_end=300.0, t_transient=300.0)
    assert "t_end = 300" in str(exc.value)


@pytest.mark.parametrize("state0", [(0.0, 0.0, 0.0), "abcd", 5, (0.0, 0.0, 1.5, 0.0),
                                    (0.0, float("nan"), 0.0, 0.0)])
def test_solver_settings_invalid_state0(state0):
    with pytest.raises(ParameterError):
        SolverSettings(state0=state0)


def test_solver_settings_state0_on_wall_allowed():
    s = SolverSettings(state0=(0.5, 0.0, -0.5, 0.0))
    assert s.state0 == (0.5, 0.0, -0.5, 0.0)
