"""Mistuning (vines.studies.mistuning): delta = 0 is ``vines design`` exactly; the detuned
host's closed forms against an independent integration and the VI NES's limits written in
the physical (stiffness k (1 + delta)^2) form; the robust TMD; bad input."""
import json

import numpy as np
import pytest
from conftest import run_vines
from scipy.integrate import solve_ivp

import vines
from vines import ParameterError
from vines.core.params import D_DEFAULT
from vines.studies import mistuning as mis

SHORT = dict(t_end=2000.0, t_transient=1500.0)


def detuned_lo(w, d, s):
    """|X/Y| of the LO of stiffness k s^2 in the nominal scale, written out directly."""
    return np.hypot(s * s, d * w) / np.hypot(s * s - w * w, d * w)


def detuned_stuck(w, eta, d, s):
    """LO and ball as one body of mass 1 + eta on the spring k s^2."""
    return np.hypot(s * s, d * w) / np.hypot(s * s - (1 + eta) * w * w, d * w)


def test_delta_zero_reproduces_vines_design_exactly():
    res = vines.design(eta=0.1, clearance_m=0.015, amplitudes_m=[0.00075, 0.003],
                       omega_band=(0.95, 1.05), n_omega=3, census_n=2, **SHORT)
    d = res.to_dict()
    c = mis.curves(res.problem, res.tmd.eta, res.tmd.frequency_ratio, res.tmd.damping_ratio,
                   res.eta, res.clearance_m, 0.05, n_delta=3)
    k = list(c.delta).index(0.0)
    assert c.vines[k] == d["vines"]["worst_ratio"]
    assert c.vines_any_attractor[k] == d["vines"]["worst_ratio_any_attractor"]
    assert c.tmd[k] == d["tmd"]["worst_ratio"]
    assert c.lo_alone[k] == d["lo_alone"]["worst_ratio"]
    # D = 0: one host frequency, the nominal one
    c0 = mis.curves(res.problem, res.tmd.eta, res.tmd.frequency_ratio,
                    res.tmd.damping_ratio, res.eta, res.clearance_m, 0.0, n_delta=3)
    assert c0.delta.tolist() == [0.0] and c0.worst["vines"] == d["vines"]["worst_ratio"]


def _lo_tmd_steady_amplitude(w, d, mu, f, zeta, s):
    """|X|/A of the LO (stiffness s^2, damping d, base y = sin(w t)) carrying a TMD (mass
    mu, spring mu f^2, damper 2 mu zeta f), by DOP853 from rest until every free mode has
    decayed below 1e-11 (rates from the eigenvalues), then a least-squares harmonic fit."""
    K = np.array([[s * s + mu * f * f, -mu * f * f], [-f * f, f * f]])
    C = np.array([[d + 2 * mu * zeta * f, -2 * mu * zeta * f], [-2 * zeta * f, 2 * zeta * f]])
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-K, -C]])
    rate = -np.linalg.eigvals(A).real.max()
    T = 2 * np.pi / w
    t_end = T * np.ceil(26.0 / rate / T)

    def rhs(t, u):
        y, yd = np.sin(w * t), w * np.cos(w * t)
        x, xa, v, va = u
        fa = mu * (f * f * (xa - x) + 2 * zeta * f * (va - v))
        return [v, va, -d * (v - yd) - s * s * (x - y) + fa,
                -(f * f * (xa - x) + 2 * zeta * f * (va - v))]

    t = np.linspace(t_end - 4 * T, t_end, 801)
    sol = solve_ivp(rhs, (0, t_end), [0, 0, 0, 0], method="DOP853", rtol=1e-12, atol=1e-13,
                    t_eval=t)
    basis = np.stack([np.sin(w * t), np.cos(w * t)], axis=1)
    coef = np.linalg.lstsq(basis, sol.y[0], rcond=None)[0]
    return float(np.hypot(*coef))


@pytest.mark.parametrize("delta, w", [(-0.1, 0.88), (0.1, 1.02), (0.07, 1.13)])
def test_detuned_tmd_closed_form_against_dop853(delta, w):
    mu, f, zeta = 0.1, 0.9067, 0.1864
    closed = float(mis.tmd_ratio(w, D_DEFAULT, mu, f, zeta, delta))
    direct = _lo_tmd_steady_amplitude(w, D_DEFAULT, mu, f, zeta, 1 + delta)
    assert closed == pytest.approx(direct, rel=1e-6)


@pytest.mark.parametrize("delta", [-0.08, 0.06])
def test_detuned_vines_limits_in_physical_form(delta):
    s = 1 + delta
    # huge clearance (F = 1e-4): the detuned LO alone
    A = 0.001
    res = vines.design(eta=0.1, clearance_m=A * 1e4, amplitudes_m=[A],
                       omega_band=(0.9, 1.1), n_omega=5, census_n=0)
    ev = mis.detuned(res.problem, delta)
    w = np.asarray(res.problem.omega)
    from vines.studies.design import Evaluator
    r = Evaluator(ev).responses([(0.1, A * 1e4)])[0]
    np.testing.assert_allclose(r.curves[0], detuned_lo(w, D_DEFAULT, s), rtol=1e-6)
    # vanishing clearance: the stuck body of mass 1 + eta on the detuned spring
    res = vines.design(eta=0.1, clearance_m=1e-3 * A, amplitudes_m=[A],
                       omega_band=(0.91, 1.01), n_omega=5, census_n=0)
    r = Evaluator(mis.detuned(res.problem, delta)).responses([(0.1, 1e-3 * A)])[0]
    w = np.asarray(res.problem.omega)
    np.testing.assert_allclose(r.curves[0], detuned_stuck(w, 0.1, D_DEFAULT, s), rtol=1e-2)
    # the window keeps its length in seconds
    assert ev.settings.t_end == s * res.problem.settings.t_end


def test_linear_worst_over_delta_and_robust_tmd():
    band, d, mu = (0.8, 1.2), D_DEFAULT, 0.1
    from vines.studies.tmd import optimal_tmd
    t = optimal_tmd(mu, d, band)
    D = 0.1
    # the LO alone's worst over the band is its detuned peak, about s / d
    dense = np.linspace(-D, D, 201)
    lo = [mis.lo_worst(band, d, x) for x in dense]
    top, where = mis._sup(lambda x: mis.lo_worst(band, d, x), mis.delta_grid(D, 7), D)
    assert top >= max(lo) * (1 - 1e-12) and where == pytest.approx(D)
    w = np.linspace(1 + D - 0.01, 1 + D + 0.01, 200001)     # the peak, near s
    assert top == pytest.approx(detuned_lo(w, d, 1 + D).max(), rel=1e-7)
    # the re-tuned TMD: no better than the nominal optimum at delta = 0, better over the set
    f, z = mis.robust_tmd(mu, d, band, D, (t.frequency_ratio, t.damping_ratio))

    def over_set(f_, z_):
        return max(mis.tmd_worst(band, d, mu, f_, z_, x) for x in np.linspace(-D, D, 21))
    assert mis.tmd_worst(band, d, mu, f, z, 0.0) >= t.worst_ratio * (1 - 1e-9)
    assert over_set(f, z) < over_set(t.frequency_ratio, t.damping_ratio)


@pytest.mark.parametrize("kw, name", [
    (dict(D=-0.1), "mistuning"), (dict(D=float("nan")), "mistuning"),
    (dict(D=0.6), "mistuning"), (dict(D=0.1, n_delta=4), "n_delta"),
    (dict(D=0.1, n_delta=1), "n_delta"), (dict(D=0.1, n_search=2), "n_search"),
])
def test_bad_input_names_the_argument(kw, name):
    with pytest.raises(ParameterError) as err:
        mis.check_mistuning(**kw)
    assert err.value.name == name and "\n" not in str(err.value)


def test_command_line_refuses_bad_mistuning_in_one_line_and_reports_the_key():
    small = ["--omega-band", "0.95", "1.05", "--n-omega", "3", "--amplitude", "0.001",
             "--eta", "0.05", "--clearance", "0.02", "--census-n", "0", "--t-end", "1000",
             "--t-transient", "600", "--threads", "1"]
    proc = run_vines("design", *small, "--mistuning", "-0.1")
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.splitlines() == [proc.stderr.strip()]
    assert "--mistuning" in proc.stderr and "-0.1" in proc.stderr
    proc = run_vines("design", *small, "--mistuning", "0.1", "--robust")
    assert proc.returncode == 2 and "--robust" in proc.stderr and "--eta-max" in proc.stderr
    proc = run_vines("design", *small, "--mistuning", "0.05", "--n-delta", "3", "--json")
    assert proc.returncode == 0, proc.stderr
    m = json.loads(proc.stdout)["mistuning"]
    assert {"delta", "lo_alone", "tmd", "vines", "worst"} <= set(m)
    assert 3 <= len(m["delta"]) == len(m["vines"]) == len(m["tmd"]) <= 3 + 2 * mis.N_REFINE_DELTA
    assert m["worst"]["vines"] == max(m["vines"]) and m["robust"] is None
    assert m["worst"]["tmd"] >= max(m["tmd"]) and m["worst"]["lo_alone"] >= max(m["lo_alone"])


def test_design_robust_stage_and_figure(tmp_path):
    """The stage on a tiny entry: the robust VI NES is no worse than the nominal one over
    the robust search's host frequencies (it starts a compass search from it), the
    re-tuned TMD no worse over the drift; the figure script draws it."""
    import runpy
    from pathlib import Path
    from types import SimpleNamespace

    from vines.data.netcdf import write_dataset
    from vines.pipeline import stages
    spec = {"omega_band": [0.9, 1.1], "n_omega": 3, "amplitudes_m": [0.003], "eta_max": 0.1,
            "n_eta": 1, "n_clearance": 2, "census_n": 0, "t_end": 300.0,
            "t_transient": 200.0, "mistuning": 0.1, "n_delta": 3, "n_search": 3}
    ds = stages.design_robust(spec, model={"r": 0.65, "d": D_DEFAULT},
                              simulation={"v_stick": 1e-6, "max_impacts": 10**6,
                                          "root_tol": 1e-13}, code="t", title="t")
    searched = [-0.1, 0.0, 0.1]
    assert (ds["robust_vines"].sel(robust_delta=searched).max()
            <= ds["vines"].sel(delta=searched).max() + 1e-12)
    assert float(ds["robust_worst_tmd"]) < float(ds["worst_tmd"])
    assert "vines_any_attractor" not in ds and ds.attrs["mistuning"] == 0.1
    path = write_dataset(ds, tmp_path / "table1.nc")
    out = SimpleNamespace(pdf=str(tmp_path / "f.pdf"), png=str(tmp_path / "f.png"))
    sm = SimpleNamespace(input=SimpleNamespace(robust=[str(path)]), output=out,
                         log=[str(tmp_path / "f.log")], params=SimpleNamespace(),
                         rule="fig_design_robust", wildcards={})
    script = Path(__file__).resolve().parents[1] / "workflow/scripts/figures/design_robust.py"
    runpy.run_path(str(script), init_globals={"snakemake": sm})
    assert Path(out.png).read_bytes()[:4] == b"\x89PNG"
