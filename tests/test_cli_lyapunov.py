"""``vines lyapunov`` and ``vines attractors --t-max``: JSON keys, values checked against
independent expectations, and one-line refusals (exit 2) of bad input."""
import json
import math

import pytest
from conftest import run_vines

BASE = ["--eta", "0.05", "--omega", "1", "--F", "0.05"]


def refused(cmd, *args):
    proc = run_vines(cmd, *args, "--json", timeout=120)
    assert proc.returncode == 2, (proc.returncode, proc.stderr[-2000:])
    assert proc.stdout == "" and "Traceback" not in proc.stderr
    lines = proc.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"vines {cmd}: error: "), proc.stderr
    return lines[0]


def test_lyapunov_json_no_impacts_limit():
    """F = 0 from a state that never impacts: {0, 0, -d/2, -d/2} (the ball drifts freely,
    the LO decays) -- an expectation independent of the code."""
    d = 0.02
    proc = run_vines("lyapunov", "--eta", "0.05", "--omega", "1", "--F", "0", "--d", str(d),
                     "--t-end", "3000", "--t-transient", "1000", "--json")
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert {"exponents", "ci", "regime", "n_impacts", "n_sticks", "params",
            "settings"} <= set(out)
    assert len(out["exponents"]) == 4 and len(out["ci"]) == 4
    assert out["n_impacts"] == 0
    lam = sorted(out["exponents"], reverse=True)
    assert lam == out["exponents"]                        # descending
    assert abs(lam[0]) < 5e-3 and abs(lam[1]) < 5e-3
    assert lam[2] == pytest.approx(-d / 2, abs=1e-3)
    assert lam[3] == pytest.approx(-d / 2, abs=1e-3)
    assert out["settings"]["t_end"] == 3000.0


def test_lyapunov_text_lists_four_exponents():
    proc = run_vines("lyapunov", *BASE, "--t-end", "1500", "--t-transient", "1000")
    assert proc.returncode == 0, proc.stderr
    assert [ln.split("=")[0].strip() for ln in proc.stdout.splitlines()[1:]] == \
        ["lambda_1", "lambda_2", "lambda_3", "lambda_4"]


@pytest.mark.parametrize("args, fragments", [
    (["--eta", "-1", "--omega", "1", "--F", "0.05"], ["--eta", "-1", "> 0"]),
    (BASE + ["--state0", "0", "0", "3", "0"], ["--state0", "|z_m0 - z_b0| <= 1"]),
    (BASE + ["--state0", "0", "x", "0", "0"], ["state0"]),
    (BASE + ["--t-end", "100", "--t-transient", "200"], ["--t-transient", "200"]),
    (BASE + ["--t-end", "nan"], ["--t-end", "nan"]),
    (["--eta", "0.05", "--omega", "1"], ["--F"]),
    (BASE + ["--bogus", "1"], ["--bogus"]),
])
def test_lyapunov_refuses_bad_input(args, fragments):
    line = refused("lyapunov", *args)
    for frag in fragments:
        assert frag in line, (frag, line)


@pytest.mark.parametrize("t_max, fragments", [
    ("500", ["--t-max", "500", "> 1000"]),
    ("abc", ["--t-max", "abc"]),
    ("1e12", ["--t-max", "1e12"]),
])
def test_attractors_t_max_refused(t_max, fragments):
    line = refused("attractors", *BASE, "--n", "2", "--t-end", "1000", "--t-transient", "500",
                   "--t-max", t_max)
    for frag in fragments:
        assert frag in line, (frag, line)


def test_attractors_t_max_json_keys():
    """With --t-max every attractor carries the asymptotic view; without it, nothing new."""
    common = ["attractors", *BASE, "--n", "4", "--t-end", "1500", "--t-transient", "1000",
              "--json"]
    plain = json.loads(run_vines(*common).stdout)
    proc = run_vines(*common, "--t-max", "3000")
    assert proc.returncode == 0, proc.stderr
    asy = json.loads(proc.stdout)
    assert "t_max" not in plain and asy["t_max"] == 3000.0 and "from_rest_asymptotic" in asy
    for a in asy["attractors"]:
        assert {"basin_fraction_asymptotic", "ci_asymptotic", "status", "lyapunov_max"} <= set(a)
        assert a["status"] in {"persistent", "transient", "unresolved"}
    assert math.isclose(sum(a["basin_fraction_asymptotic"] for a in asy["attractors"]), 1.0)
    # the t_end view is unchanged by --t-max
    assert [a["basin_fraction"] for a in plain["attractors"]] == \
        [a["basin_fraction"] for a in asy["attractors"][:len(plain["attractors"])]]
