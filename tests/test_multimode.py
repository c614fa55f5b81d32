"""The general host with absorbers (``vines.multimode``): the engine against today's 1-DOF
kernel, against closed forms, its invariants, and the model's validation."""
import math

import numpy as np
import pytest

from vines.core.exact import run_exact
from vines.core.params import ModelParams, ParameterError, SolverSettings
from vines.multimode import (
    Absorber,
    HarmonicBase,
    Host,
    HostModel,
    ModelSettings,
    model_from_dict,
    simulate_model,
)


def _exact_1dof(eta, omega, F, t_end, t_tr, r=0.65, d=None, phi=0.0):
    kw = {} if d is None else {"d": d}
    p = ModelParams(eta=eta, omega=omega, F=F, r=r, phi=phi, **kw)
    raw = run_exact(p, SolverSettings(t_end=t_end, t_transient=t_tr), periodic_shortcut=False)
    from vines.core.simulation import window_measures
    return raw, window_measures(p, SolverSettings(t_end=t_end, t_transient=t_tr), raw)


def _run(model, t_end, t_tr, **kw):
    return simulate_model(model, ModelSettings(t_end=t_end, t_transient=t_tr, n_record=100_000,
                                               **kw), record_from=0.0)


# --------------------------------------------------------------------------- the ladder
@pytest.mark.parametrize("point", [(0.05, 1.0, 0.05, 0.65, 300.0), (0.1, 1.2, 0.3, 0.4, 300.0),
                                   (0.2, 0.8, 0.5, 0.9, 50.0), (0.3, 0.7, 1.0, 0.5, 80.0)])
def test_one_dof_host_with_one_ball_equals_the_kernel(point):
    """Impact for impact over horizons where the motion from rest does not amplify
    round-off beyond 1e-12 (transients from rest are often chaotic)."""
    eta, omega, F, r, t_end = point
    t_tr = t_end / 2
    raw, meas = _exact_1dof(eta, omega, F, t_end, t_tr, r=r)
    res = _run(HostModel.one_dof(eta, omega, F, r=r), t_end, t_tr)
    ti = raw.impacts["t"]
    assert ti.size > 10 and res.impacts["t"].size == ti.size
    assert np.abs(res.impacts["t"] - ti).max() <= 1e-12 * t_end
    assert np.array_equal(res.impacts["wall"], raw.impacts["wall"])
    assert abs(res.x_max[0] - meas["xmax"]) <= 1e-10 * meas["xmax"]
    assert abs(res.ke_ratio[0] - meas["ke_ratio"]) <= 1e-10


# --------------------------------------------------------------------------- invariants
def _mixed_model(r=(0.6, 0.7), damping=True, A=0.3):
    c = 1.0 if damping else 0.0
    host = Host([[1.0, 0.1], [0.1, 1.0]], [[2.0, -1.0], [-1.0, 2.0]],
                [[0.03 * c, -0.01 * c], [-0.01 * c, 0.02 * c]], [1.0, 1.0])
    ab = (Absorber(0, 0.05, 0.0, 0.0, 0.5, r[0]),
          Absorber(1, 0.04, 0.03, 0.002 * c, 0.8, r[1]),
          Absorber(1, 0.03, 0.02, 0.001 * c))
    return HostModel(host, ab, HarmonicBase(A, 1.1, 0.2))


def test_energy_balance_of_every_part():
    res = _run(_mixed_model(), 120.0, 60.0)
    eb = res.energy_balance
    scale = eb["forcing_work"] + eb["E_start"]
    assert res.status == "ok" and res.impacts["t"].size > 20
    assert abs(eb["residual"]) <= 1e-9 * scale
    assert (eb["dissipated_impacts"][:2] > 0).all() and eb["dissipated_impacts"][2] == 0.0
    # restitution of every impact that did not end in sticking
    free = res.impacts["stuck"] == 0
    r = np.array([a.restitution for a in res.model.absorbers])[res.impacts["absorber"]]
    assert np.allclose(res.impacts["dw_after"][free], -r[free] * res.impacts["dw_before"][free],
                       rtol=1e-12, atol=1e-14)


def test_pair_impulse_conserves_momentum_and_sets_restitution():
    from vines.multimode import kernel as K
    from vines.multimode.system import pack
    model = _mixed_model()
    pk = pack(model)
    rng = np.random.default_rng(3)
    N = model.n_dof
    Mf = np.zeros((5, 5))
    Mf[:2, :2] = model.host.mass
    for i, a in enumerate(model.absorbers):
        Mf[2 + i, 2 + i] = a.mass
    for stuck_l in (0, 1):
        walls = np.zeros(3, np.int64)
        V = rng.normal(size=5)
        if stuck_l:
            walls[2] = 1 if V[1] > V[4] else -1     # absorber 2 stuck, to be pushed on
            V[4] = V[1]
        before = V.copy()
        wd = V[0] - V[2]
        K._pair_impulse(0, 1, 0.6, pk.ab, N, pk.minv, walls, V, np.zeros(5), 0.0)
        assert np.isclose((Mf @ V).sum(), (Mf @ before).sum(), rtol=0, atol=1e-13)
        assert np.isclose(V[0] - V[2], -0.6 * wd, rtol=1e-13)
        if walls[2] != 0:
            assert V[4] == V[1]


def test_elastic_impacts_without_damping_conserve_energy():
    host = Host([[1.0, 0.0], [0.0, 1.5]], [[2.0, -1.0], [-1.0, 1.5]], [[0.0, 0.0], [0.0, 0.0]])
    ab = (Absorber(0, 0.1, 0.0, 0.0, 0.3, 1.0), Absorber(1, 0.2, 0.05, 0.0, 0.4, 1.0))
    model = HostModel(host, ab, HarmonicBase(0.0, 1.0))
    res = simulate_model(model, ModelSettings(t_end=200.0, t_transient=100.0, v_stick=0.0),
                         state0={"v": [1.0, -0.5]})
    eb = res.energy_balance
    assert res.n_impacts_whole_run.sum() > 50
    assert abs(eb["E_end"] - eb["E_start"]) <= 1e-9 * eb["E_start"]
    assert np.abs(eb["dissipated_impacts"]).max() <= 1e-12 * eb["E_start"]


def test_tmd_without_stops_reaches_the_linear_steady_state():
    A, W = 0.2, 0.9
    M = np.array([[1.0, 0.0], [0.0, 1.0]])
    K = np.array([[2.0, -1.0], [-1.0, 2.0]])
    C = np.array([[0.2, 0.0], [0.0, 0.2]])
    m, k, c = 0.1, 0.07, 0.03
    model = HostModel(Host(M, K, C, [1.0, 1.0]), (Absorber(1, m, k, c),), HarmonicBase(A, W))
    # the 3-DOF linear system in closed form (absolute coordinates)
    Mf = np.diag([1.0, 1.0, m])
    Kf = np.zeros((3, 3))
    Kf[:2, :2] = K
    Cf = np.zeros((3, 3))
    Cf[:2, :2] = C
    for Af, v in ((Kf, k), (Cf, c)):
        Af[1, 1] += v
        Af[2, 2] += v
        Af[1, 2] -= v
        Af[2, 1] -= v
    rhs = np.zeros(3, complex)
    rhs[:2] = A * (W * C @ [1.0, 1.0] - 1j * K @ [1.0, 1.0])
    Z = np.linalg.solve(Kf - W * W * Mf + 1j * W * Cf, rhs)
    res = simulate_model(model, ModelSettings(t_end=900.0, t_transient=600.0))
    assert np.allclose(res.x_max, np.abs(Z[:2]), rtol=1e-8, atol=0)
    assert np.isclose(res.travel[0], abs(Z[1] - Z[2]), rtol=1e-8)
    th = W * res.final_state["t"]
    assert np.allclose(res.final_state["P"], (Z * np.exp(1j * th)).real, rtol=0, atol=1e-8 * abs(Z).max())


def test_a_tmd_whose_stops_are_never_reached_is_the_tmd():
    host = Host([[1.0]], [[1.0]], [[0.05]])
    f = HarmonicBase(0.1, 1.0)
    free = simulate_model(HostModel(host, (Absorber(0, 0.05, 0.045, 0.01),), f),
                          ModelSettings(t_end=300.0, t_transient=150.0))
    wide = simulate_model(HostModel(host, (Absorber(0, 0.05, 0.045, 0.01,
                                                    gap=2.0 * free.travel_whole_run[0]),), f),
                          ModelSettings(t_end=300.0, t_transient=150.0))
    assert wide.n_impacts_whole_run[0] == 0
    for name in ("x_max", "travel", "ke_ratio", "dissipated_damper"):
        assert np.allclose(getattr(wide, name), getattr(free, name), rtol=1e-12, atol=0)


def test_two_uncoupled_hosts_are_two_one_dof_runs():
    d1, d2 = 0.02, 0.05
    # the second host in units where its mass and stiffness are 1: time scale 1/w2
    w2, m2 = 1.3, 2.0
    host = Host([[1.0, 0.0], [0.0, m2]], [[1.0, 0.0], [0.0, m2 * w2 ** 2]],
                [[d1, 0.0], [0.0, m2 * w2 * d2]])
    W, A = 1.1, 0.2
    model = HostModel(host, (Absorber(0, 0.05, gap=1.0, restitution=0.6),
                             Absorber(1, 0.1 * m2, gap=1.0, restitution=0.7)),
                      HarmonicBase(A, W))
    res = _run(model, 200.0, 100.0)
    raw1, _ = _exact_1dof(0.05, W, A, 200.0, 100.0, r=0.6, d=d1)
    raw2, _ = _exact_1dof(0.1, W / w2, A, 200.0 * w2, 100.0 * w2, r=0.7, d=d2)
    for i, raw, scale in ((0, raw1, 1.0), (1, raw2, w2)):
        sel = res.impacts["absorber"] == i
        t = res.impacts["t"][sel]
        assert t.size == raw.impacts["t"].size > 5
        assert np.abs(t * scale - raw.impacts["t"]).max() <= 1e-11 * 200.0 * scale


def test_against_the_rk_oracle_on_a_mixed_model():
    from vines.reference.rk_multimode import run_rk_model
    model = _mixed_model()
    res = _run(model, 40.0, 20.0)
    ref = run_rk_model(model, 40.0, t_transient=20.0)
    assert res.impacts["t"].size == ref["t"].size > 15
    assert np.abs(res.impacts["t"] - ref["t"]).max() <= 1e-6
    assert np.array_equal(res.impacts["absorber"], ref["absorber"])
    assert np.abs(res.final_state["P"] - ref["P"]).max() <= 1e-6
    eb = res.energy_balance
    assert np.allclose(eb["dissipated_impacts"], ref["dissipated_impacts"], rtol=1e-6, atol=1e-9)
    assert np.isclose(eb["forcing_work"], ref["forcing_work"], rtol=1e-8)


# --------------------------------------------------------------------------- the model
BASE = {"host": {"mass": [[1, 0], [0, 1]], "stiffness": [[2, -1], [-1, 2]],
                 "damping": [[0.02, 0], [0, 0.02]]},
        "absorbers": [{"dof": 0, "mass": 0.05, "gap": 1.0}],
        "forcing": {"amplitude": 0.1, "frequency": 1.0}}


def _with(path, value):
    import copy
    d = copy.deepcopy(BASE)
    node = d
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    return d


@pytest.mark.parametrize("path, value, name", [
    (("host", "stiffness"), [[2, -1], [-0.5, 2]], "host.stiffness"),
    (("host", "stiffness"), [[1, 2], [2, 1]], "host.stiffness"),
    (("host", "mass"), [[1, 0], [0, float("nan")]], "host.mass"),
    (("host", "damping"), [[0.02, 0], [0, 0.02], [0, 0]], "host.damping"),
    (("absorbers",), [{"dof": 2, "mass": 0.05, "gap": 1.0}], "absorbers[0].dof"),
    (("absorbers",), [{"dof": 0, "mass": -0.05, "gap": 1.0}], "absorbers[0].mass"),
    (("absorbers",), [{"dof": 0, "mass": 0.05, "gap": 0}], "absorbers[0].gap"),
    (("absorbers",), [{"dof": 0, "mass": 0.05}], "absorbers[0].stiffness"),
    (("absorbers",), [{"dof": 0, "mass": 0.05, "gap": 1, "colour": 1}], "absorbers[0].colour"),
    (("forcing", "frequency"), 0.0, "forcing.frequency"),
])
def test_bad_models_are_refused_naming_the_key(path, value, name):
    with pytest.raises(ParameterError) as err:
        model_from_dict(_with(path, value))
    assert err.value.name == name
    assert "\n" not in str(err.value)


def test_host_from_modes_has_those_modes():
    S = [[1.0, 1.0], [1.0, -1.0]]
    host = Host.from_modes([1.0, 2.5], [0.01, 0.02], S, [2.0, 1.0])
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(host.mass, host.stiffness)).real)
    assert np.allclose(np.sqrt(w2), [1.0, 2.5], rtol=1e-12)


def test_undamped_resonance_is_refused():
    with pytest.raises(ParameterError) as err:
        model_from_dict(_with(("host", "damping"), [[0, 0], [0, 0]]) | {
            "absorbers": [], "forcing": {"amplitude": 0.1, "frequency": 1.0}})
    assert err.value.name == "forcing.frequency"


# --------------------------------------------------------------------------- command line
def test_model_check_and_simulate_model_on_the_command_line(tmp_path, capsys):
    import json

    import yaml

    from vines.cli import main
    good = tmp_path / "m.yaml"
    good.write_text(yaml.safe_dump(BASE))
    assert main(["model", "check", str(good), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["valid"] and np.allclose(out["natural_frequencies"], [1.0, math.sqrt(3.0)])
    assert main(["simulate", "--model", str(good), "--t-end", "60", "--t-transient", "30",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["status"] == "ok" and len(out["absorbers"]) == 1 and len(out["host"]["x_max"]) == 2
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump(_with(("absorbers",), [{"dof": 0, "mass": 0.05, "gap": 0}])))
    with pytest.raises(SystemExit) as ex:
        main(["model", "check", str(bad)])
    assert ex.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["vines model: error: invalid absorbers[0].gap = 0: must be a finite number > 0"]
    with pytest.raises(SystemExit) as ex:
        main(["simulate", "--model", str(good), "--eta", "0.1"])
    assert ex.value.code == 2
