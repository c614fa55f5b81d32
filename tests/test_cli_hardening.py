"""Hardening of the `vines` command and the API against out-of-range numbers.

Every refusal is one line on stderr (exit status 2, naming the parameter, the value and what
is allowed), no traceback, no output, and comes back well within 30 s:

1. huge omega / d / eta / F used to overflow inside the closed form (OverflowError traceback);
2. `vines continue` with a vanishing step or a huge stop ran for minutes;
3. `vines continue --param eta --eta 0.05` silently ignored --eta;
4. a run that stops at max_impacts was labelled "chatter" (now regime "unfinished");
5. every numeric option has a finite range.
"""
import json
import math
import types

import numpy as np
import pytest
from conftest import run_vines

import vines
from vines.core import params as P
from vines.core.simulation import window_measures
from vines.orbits.atlas.stability_map import stability_map
from vines.orbits.continuation.one_to_one import continue_branch
from vines.orbits.family.periodic import find_1to1

TIMEOUT = 30
BASE = ["--eta", "0.05", "--omega", "1", "--F", "0.05"]
CONT = ["--param", "eta", "--start", "0.01", "--stop", "0.2", "--omega", "1", "--F", "0.05"]


def refused(cmd, *args):
    """Run ``vines cmd args --json``; assert a one-line refusal and return that line."""
    proc = run_vines(cmd, *args, "--json", timeout=TIMEOUT)
    assert proc.returncode == 2, (proc.returncode, proc.stdout[:300], proc.stderr[-2000:])
    assert proc.stdout == ""
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith(f"vines {cmd}: error: "), lines[0]
    return lines[0]


def check(line, *fragments):
    for frag in fragments:
        assert frag in line, (frag, line)


# ------------------------------------------------------------------ 1. overflow -> refusal

@pytest.mark.parametrize("cmd, args, fragments", [
    ("simulate", ["--eta", "0.05", "--omega", "1e308", "--F", "0.05"],
     ["--omega", "1e308", "<= 1000"]),
    ("simulate", ["--eta", "0.05", "--omega", "1e160", "--F", "0.05"],
     ["--omega", "1e160", "<= 1000"]),
    ("simulate", BASE + ["--d", "1e308"], ["--d", "1e308", "<= 1000"]),
    ("simulate", ["--eta", "1e308", "--omega", "1", "--F", "0.05"], ["--eta", "1e308", "<= 1000"]),
    ("simulate", ["--eta", "0.05", "--omega", "1", "--F", "1e308"], ["--F", "1e308", "<= 10000"]),
    ("periodic", ["--eta", "0.05", "--omega", "1e308", "--F", "0.05"],
     ["--omega", "1e308", "<= 1000"]),
    ("periodic", BASE + ["--d", "1e308"], ["--d", "1e308", "<= 1000"]),
    ("periodic", ["--eta", "0.05", "--omega", "1", "--F", "1e300"], ["--F", "1e300", "<= 10000"]),
    ("continue", ["--param", "eta", "--start", "0.01", "--stop", "0.2", "--omega", "1e308",
                  "--F", "0.05"], ["--omega", "1e308", "<= 1000"]),
    ("continue", CONT + ["--d", "1e308"], ["--d", "1e308", "<= 1000"]),
])
def test_overflowing_values_are_refused(cmd, args, fragments):
    check(refused(cmd, *args), *fragments)


@pytest.mark.parametrize("name, value", [("omega", 1e308), ("omega", 1e160), ("d", 1e308),
                                         ("eta", 1e308), ("F", 1e308), ("phi", 1e308),
                                         ("omega", math.inf)])
def test_api_refuses_overflowing_values(name, value):
    kw = dict(eta=0.05, omega=1.0, F=0.05)
    kw[name] = value
    with pytest.raises(vines.ParameterError, match=name) as err:
        vines.simulate(**kw, t_end=10.0, t_transient=5.0)
    assert err.value.name == name and "\n" not in str(err.value)
    with pytest.raises(vines.ParameterError, match=name):
        find_1to1(**kw)


def test_api_batch_and_map_refuse_before_any_work():
    with pytest.raises(vines.ParameterError, match="omega"):
        vines.simulate_batch([0.05, 0.05], [1.0, 1e308], 0.05, t_end=10.0, t_transient=5.0)
    with pytest.raises(vines.ParameterError, match="F"):
        vines.simulate_batch(0.05, 1.0, [0.05, 2e4], t_end=10.0, t_transient=5.0)
    with pytest.raises(vines.ParameterError, match="eta"):
        stability_map([0.05, 1e308], [1.0], 0.05)
    with pytest.raises(vines.ParameterError, match="d"):
        stability_map([0.05], [1.0], 0.05, d=1e308)


# ------------------------------------------------------------------ 2. continuation that never ends

@pytest.mark.parametrize("args, fragments", [
    (CONT + ["--step", "1e-308"], ["--step", "1e-308", "--max-points = 100000"]),
    (CONT + ["--step", "1e-7"], ["--step", "1e-7", "--max-points = 100000"]),
    (["--param", "eta", "--start", "0.01", "--stop", "1e308", "--omega", "1", "--F", "0.05"],
     ["--stop", "1e308", "<= 1000"]),
    (["--param", "eta", "--start", "1e308", "--stop", "0.2", "--omega", "1", "--F", "0.05"],
     ["--start", "1e308", "<= 1000"]),
    (["--param", "omega", "--start", "1", "--stop", "1e200", "--eta", "0.1", "--F", "0.1"],
     ["--stop", "1e200", "<= 1000"]),
    (["--param", "F", "--start", "0.1", "--stop", "-1", "--eta", "0.1", "--omega", "1"],
     ["--stop", "-1", ">= 0"]),
    (["--param", "F", "--start", "0.1", "--stop", "inf", "--eta", "0.1", "--omega", "1"],
     ["--stop", "inf", "finite"]),
    (CONT + ["--step", "0.01", "--max-points", "5"], ["--step", "0.01", "--max-points = 5"]),
    (CONT + ["--max-points", "0"], ["--max-points", "0", ">= 1"]),
    (CONT + ["--max-points", "1e300"], ["--max-points", "1e300", "<= 10000000"]),
    (CONT + ["--max-points", "abc"], ["--max-points", "abc", "integer"]),
    (CONT + ["--step", "nan"], ["--step", "nan", "finite"]),
    (CONT + ["--step", "-0.01"], ["--step", "-0.01", "> 0"]),
])
def test_continue_ranges(args, fragments):
    check(refused("continue", *args), *fragments)


def test_max_points_is_configurable():
    """4 steps of 0.005 from 0.05 to 0.03: refused with --max-points 3, run with 4."""
    args = ["--param", "eta", "--start", "0.05", "--stop", "0.03", "--step", "0.005",
            "--omega", "1", "--F", "0.05", "--method", "natural"]
    check(refused("continue", *args, "--max-points", "3"), "--step", "--max-points = 3")
    proc = run_vines("continue", *args, "--max-points", "4", "--json", timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert len(json.loads(proc.stdout)["branch"]) == 5


@pytest.mark.parametrize("kwargs, name", [
    (dict(step=1e-308), "step"),
    (dict(step=0.01, max_points=5), "step"),
    (dict(stop=1e308), "stop"),
    (dict(start=1e308), "eta"),
    (dict(max_points=0), "max_points"),
    (dict(max_points=10 ** 9), "max_points"),
    (dict(min_step=0.0), "min_step"),
    (dict(event_tol=0.0), "event_tol"),
    (dict(fixed={"omega": 1.0, "F": 0.05, "eta": 0.05}), "eta"),
    (dict(fixed={"omega": 1e308, "F": 0.05}), "omega"),
])
def test_api_continue_refuses_before_any_work(kwargs, name):
    kw = dict(param="eta", start=0.01, stop=0.2, step=None, fixed={"omega": 1.0, "F": 0.05})
    kw.update(kwargs)
    with pytest.raises(vines.ParameterError) as err:
        continue_branch(**kw)
    assert err.value.name == name, str(err.value)
    assert "\n" not in str(err.value)


# ------------------------------------------------------------------ 3. continued parameter fixed too

@pytest.mark.parametrize("param, extra, others", [
    ("eta", ["--eta", "0.05", "--omega", "1", "--F", "0.05"], "--omega and --F"),
    ("omega", ["--omega", "1", "--eta", "0.1", "--F", "0.1"], "--eta and --F"),
    ("F", ["--F", "0.1", "--eta", "0.1", "--omega", "1"], "--eta and --omega"),
])
def test_continued_parameter_given_as_fixed_is_refused(param, extra, others):
    line = refused("continue", "--param", param, "--start", "0.5", "--stop", "0.6", *extra)
    value = extra[extra.index(f"--{param}") + 1]
    check(line, f"--{param}", repr(value), f"--param {param}", others)


# ------------------------------------------------------------------ 4. max_impacts is not chatter

def test_run_stopped_at_max_impacts_is_unfinished_cli():
    proc = run_vines("simulate", *BASE, "--t-end", "1e9", "--max-impacts", "1000", "--json",
                     timeout=TIMEOUT)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["status"] == "max_impacts"
    assert out["regime"] == "unfinished"
    assert out["n_impacts"] == 1000


def test_run_stopped_at_max_impacts_is_unfinished_api():
    res = vines.simulate(0.2, 0.9, 0.4, t_end=1e9, max_impacts=500)     # a chatter point
    assert res.status == "max_impacts" and res.regime == "unfinished"
    rk = vines.simulate(0.05, 1.0, 0.05, t_end=300.0, t_transient=100.0, solver="rk",
                        max_impacts=20)
    assert rk.status == "max_impacts" and rk.regime == "unfinished"
    # a finished run keeps its classification (chatter with sticking, Fig 9)
    ok = vines.simulate(0.2, 0.9, 0.4, t_end=600.0, t_transient=300.0)
    assert ok.status == "ok" and ok.regime == "chatter"


@pytest.mark.parametrize("status, regime", [("max_impacts", "unfinished"), ("zeno", "chatter"),
                                            ("stalled", "failed")])
def test_regime_of_runs_that_stop_early(status, regime):
    p = P.ModelParams(eta=0.05, omega=1.0, F=0.05)
    st = P.SolverSettings(t_end=100.0, t_transient=50.0)
    impacts = np.zeros(0, dtype=[("t", "f8"), ("wall", "i1")])
    raw = types.SimpleNamespace(int_vm2=1.0, int_vb2=1.0, impacts=impacts, impact_tally=None,
                                status=status,
                                xmax_window=0.5, xmax_whole_run=0.5, n_impacts=0,
                                t_stuck_window=0.0, t_stuck_total=0.0, n_sticks=0,
                                shortcut_time=float("nan"), shortcut_period=0)
    m = window_measures(p, st, raw)
    assert m["regime"] == regime and m["period"] == 0


# ------------------------------------------------------------------ 5. every numeric option

@pytest.mark.parametrize("args, fragments", [
    (["--t-end", "1e308"], ["--t-end", "1e308", "<= 1e+09"]),
    (["--t-end", "2e9"], ["--t-end", "2e9", "<= 1e+09"]),
    (["--t-end", "inf"], ["--t-end", "inf", "finite"]),
    (["--t-transient", "1e308"], ["--t-transient", "1e308", "< t_end"]),
    (["--t-transient", "-1"], ["--t-transient", "-1", ">= 0"]),
    (["--max-impacts", "1e300"], ["--max-impacts", "1e300", "<= 100000000"]),
    (["--max-impacts", "100000001"], ["--max-impacts", "100000001", "<= 100000000"]),
    (["--max-impacts", "inf"], ["--max-impacts", "inf", "integer"]),
    (["--rtol", "1e308"], ["--rtol", "1e308", "<= 0.01"]),
    (["--rtol", "0.5"], ["--rtol", "0.5", "<= 0.01"]),
    (["--rtol", "1e-300"], ["--rtol", "1e-300", ">= 1e-14"]),
    (["--v-stick", "1e308"], ["--v-stick", "1e308", "<= 1"]),
    (["--v-stick", "2"], ["--v-stick", "2", "<= 1"]),
    (["--phi", "1e308"], ["--phi", "1e308", "<= 1000"]),
    (["--phi", "-1e308"], ["--phi", "-1e308", ">= -1000"]),
    (["--r", "1e308"], ["--r", "1e308", "<= 1"]),
    (["--d", "inf"], ["--d", "inf", "finite"]),
])
def test_simulate_option_ranges(args, fragments):
    check(refused("simulate", *BASE, *args), *fragments)


@pytest.mark.parametrize("cmd, args, fragments", [
    ("periodic", ["--eta", "0.05", "--omega", "1", "--F", "0.05", "--r", "-1e308"],
     ["--r", "-1e308", ">= 0"]),
    ("periodic", ["--eta", "2000", "--omega", "1", "--F", "0.05"], ["--eta", "2000", "<= 1000"]),
    ("periodic", ["--eta", "0.05", "--omega", "-1e308", "--F", "0.05"],
     ["--omega", "-1e308", "> 0"]),
    ("continue", CONT + ["--r", "1e308"], ["--r", "1e308", "<= 1"]),
    ("continue", ["--param", "F", "--start", "0.1", "--stop", "0.2", "--eta", "1e308",
                  "--omega", "1"], ["--eta", "1e308", "<= 1000"]),
])
def test_periodic_and_continue_option_ranges(cmd, args, fragments):
    check(refused(cmd, *args), *fragments)


def test_help_states_the_ranges():
    proc = run_vines("simulate", "--help", timeout=TIMEOUT)
    assert proc.returncode == 0
    text = " ".join(proc.stdout.split())
    for frag in ("<= 1000", "<= 10000", "<= 1e+09", "<= 100000000"):
        assert frag in text, frag
    proc = run_vines("continue", "--help", timeout=TIMEOUT)
    assert proc.returncode == 0 and "--max-points" in proc.stdout


def test_upper_bounds_still_run():
    """The largest allowed values run to the end without overflow (status ok, finite)."""
    res = vines.simulate(P.ETA_MAX, P.OMEGA_MAX, P.F_MAX, d=P.D_MAX, phi=-P.PHI_MAX,
                         t_end=20.0, t_transient=10.0)
    assert res.status == "ok"
    assert all(math.isfinite(x) for x in (res.ke_ratio, res.xmax, res.xmax_whole_run))
    res = vines.simulate(0.05, 1.0, P.F_MAX, d=0.0, t_end=50.0, t_transient=25.0,
                         v_stick=P.V_STICK_MAX)
    assert res.status == "ok" and math.isfinite(res.xmax)
