"""Command-line contract of `vines periodic` and `vines continue` (spec section 7)."""
import json
import pathlib

import pytest
from conftest import run_vines

ROOT = pathlib.Path(__file__).resolve().parents[1]
SRC = ROOT / "src"

SOLUTION_KEYS = {"symmetric", "admissible", "stable", "lambda_max", "eigenvalues", "dw_L",
                 "dw_R", "phase_L", "phase_R", "flight_times"}
POINT_KEYS = {"eta", "omega", "F", "lambda_max", "stable", "symmetric", "admissible", "dw_L"}
EVENT_TYPES = {"fold", "flip", "neimark-sacker", "admissibility-loss", "symmetry-breaking"}


def test_periodic_json():
    proc = run_vines("periodic", "--eta", "0.05", "--omega", "1", "--F", "0.05", "--json")
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    sols = out["solutions"]
    assert sols and all(set(s) >= SOLUTION_KEYS for s in sols)
    best = sols[0]
    assert best["stable"] and best["admissible"] and best["symmetric"]
    assert 0.9 < best["lambda_max"] < 1.0
    assert len(best["eigenvalues"]) == 4 and all(len(e) == 2 for e in best["eigenvalues"])
    assert len(best["flight_times"]) == 2
    assert best["dw_L"] > 0 > best["dw_R"]
    assert any(not s["admissible"] for s in sols)     # non-admissible roots are reported


def test_periodic_text():
    proc = run_vines("periodic", "--eta", "0.55", "--omega", "1", "--F", "0.4")
    assert proc.returncode == 0, proc.stderr
    assert "stable" in proc.stdout and "lambda_max" in proc.stdout


def test_continue_json():
    proc = run_vines("continue", "--param", "eta", "--start", "0.05", "--stop", "0.03",
                     "--step", "0.005", "--omega", "1", "--F", "0.05", "--method", "natural", "--json")
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert {"branch", "events"} <= set(out)
    br = out["branch"]
    assert len(br) == 5 and all(set(p) >= POINT_KEYS for p in br)
    assert br[0]["eta"] == pytest.approx(0.05) and br[-1]["eta"] == pytest.approx(0.03)
    assert all(p["omega"] == 1.0 and p["F"] == 0.05 for p in br)
    assert br[0]["stable"] and not br[-1]["stable"]
    assert out["events"] and all(e["type"] in EVENT_TYPES for e in out["events"])
    assert all(0.03 <= e["at"] <= 0.05 for e in out["events"])


def test_continue_in_omega_and_F():
    for args in (["--param", "omega", "--start", "1.1", "--stop", "1.0", "--eta", "0.3",
                  "--F", "0.3077"],
                 ["--param", "F", "--start", "0.3", "--stop", "0.35", "--eta", "0.3",
                  "--omega", "1.1", "--step", "0.01"]):
        proc = run_vines("continue", *args, "--json")
        assert proc.returncode == 0, proc.stderr
        assert len(json.loads(proc.stdout)["branch"]) >= 2


@pytest.mark.parametrize("cmd, args, fragments", [
    ("periodic", ["--eta", "-1", "--omega", "1", "--F", "0.05"], ["--eta", "-1", "> 0"]),
    ("periodic", ["--eta", "0.1", "--omega", "abc", "--F", "0.05"], ["--omega", "abc"]),
    ("periodic", ["--eta", "0.1", "--omega", "1"], ["--F"]),
    ("periodic", ["--eta", "0.1", "--omega", "1", "--F", "0.1", "--r", "2"], ["--r", "2"]),
    ("periodic", ["--eta", "0.1", "--omega", "1", "--F", "0.1", "--bogus"], ["--bogus"]),
    ("continue", ["--param", "eta", "--start", "-1", "--stop", "0.1", "--omega", "1",
                  "--F", "0.1"], ["--start", "-1", "> 0"]),
    ("continue", ["--param", "eta", "--start", "0.1", "--stop", "0.2", "--F", "0.1"],
     ["--omega"]),
    ("continue", ["--param", "xi", "--start", "0.1", "--stop", "0.2", "--omega", "1",
                  "--F", "0.1"], ["--param", "xi"]),
    ("continue", ["--param", "F", "--start", "0.1", "--stop", "0.2", "--omega", "1",
                  "--eta", "0.1", "--step", "0"], ["--step", "0", "> 0"]),
    ("continue", ["--param", "omega", "--start", "1", "--stop", "nan", "--eta", "0.1",
                  "--F", "0.1"], ["--stop", "nan"]),
    ("continue", ["--param", "F", "--start", "0.1", "--stop", "0.2", "--omega", "1"],
     ["--eta"]),
])
def test_bad_input_exits_2_with_one_line(cmd, args, fragments):
    proc = run_vines(cmd, *args, "--json")
    assert proc.returncode == 2, proc.stderr
    assert proc.stdout == ""
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith(f"vines {cmd}: error: "), lines[0]
    for frag in fragments:
        assert frag in lines[0], (frag, lines[0])


def test_continue_through_the_fold_and_asymmetric_branch():
    """Issue 14 acceptance through the CLI: fold passing, asymmetric branch ending on the
    symmetric one, switching."""
    proc = run_vines("continue", "--param", "F", "--start", "0.3", "--stop", "0.01",
                     "--eta", "0.2", "--omega", "1", "--json")
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    fold = [e for e in out["events"] if e["type"] == "fold"]
    # the quoted values' last digit (0.01199, 0.821) bounds the error, not the solver (the
    # fold is solved to ~1e-12; test_arclength checks it independently to 1e-6 relative)
    assert len(fold) == 1 and abs(fold[0]["at"] - 0.01199) < 1e-4
    assert max(p["F"] for p in out["branch"][fold[0]["index"]:]) > 0.05
    proc = run_vines("continue", "--param", "eta", "--start", "0.12", "--stop", "0.3",
                     "--omega", "1.1", "--F", "0.3077", "--branch", "asymmetric", "--json")
    out = json.loads(proc.stdout)
    assert out["family"] == "asymmetric"
    assert out["branch"][0]["lambda_max"] == pytest.approx(0.821, abs=5e-4)
    assert out["events"][-1]["type"] == "symmetry-breaking"
    assert out["events"][-1]["connects"] == "symmetric" == out["events"][-1]["meets"]
    assert abs(out["events"][-1]["at"] - 0.1496) < 1e-4
    proc = run_vines("continue", "--param", "eta", "--start", "0.12", "--stop", "0.3",
                     "--omega", "1.1", "--F", "0.3077", "--switch")
    assert proc.returncode == 0, proc.stderr
    assert "meets the asymmetric branch" in proc.stdout and "asymmetric branch" in proc.stdout


@pytest.mark.parametrize("extra, fragments", [
    (["--branch", "both"], ["--branch", "both"]),
    (["--method", "secant"], ["--method", "secant"]),
    (["--max-inadmissible", "0"], ["--max-inadmissible", "0", ">= 1"]),
    (["--switch", "--method", "natural"], ["--switch", "natural"]),
    (["--switch", "--branch", "asymmetric"], ["--switch", "asymmetric"]),
])
def test_continue_new_options_refused(extra, fragments):
    proc = run_vines("continue", "--param", "eta", "--start", "0.1", "--stop", "0.2",
                     "--omega", "1", "--F", "0.1", *extra)
    assert proc.returncode == 2 and proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert all(f in lines[0] for f in fragments), lines[0]
