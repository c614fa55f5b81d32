"""Command-line contract (spec section 7): error paths and the --json success path."""
import json
import math
import pathlib
import tomllib

import pytest
from conftest import run_vines

ROOT = pathlib.Path(__file__).resolve().parents[1]
SRC = ROOT / "src"

SIMULATE_KEYS = {"ke_ratio", "xmax_m", "xmax", "xmax_whole_run_m", "n_impacts",
                 "impacts_per_period", "regime", "t_stuck", "solver", "params"}
BASE = ["--eta", "0.05", "--omega", "1", "--F", "0.05"]


def assert_one_line_error(proc, *fragments):
    assert proc.returncode == 2, proc.stderr
    assert proc.stdout == ""
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("vines simulate: error: "), lines[0]
    for frag in fragments:
        assert frag in lines[0], (frag, lines[0])


@pytest.mark.parametrize("args, fragments", [
    (["--eta", "-1", "--omega", "1", "--F", "0.05"], ["--eta", "-1", "> 0"]),
    (["--eta", "abc", "--omega", "1", "--F", "0.05"], ["--eta", "abc", "number"]),
    (BASE + ["--r", "1.5"], ["--r", "1.5", "<= 1"]),
    (["--eta", "0.05", "--omega", "0", "--F", "0.05"], ["--omega", "0", "> 0"]),
    (BASE + ["--t-transient", "8000"], ["--t-transient", "8000", "t_end = 7000"]),
    (BASE + ["--foo"], ["--foo", "--eta"]),
    (BASE + ["--foo", "3"], ["--foo"]),
    (["--eta", "0.05", "--omega", "1"], ["--F", ">= 0"]),
    (BASE + ["--solver", "bogus"], ["--solver", "bogus", "exact", "rk"]),
    (BASE + ["--F", "nan"], ["--F", "nan", "finite"]),
    (BASE + ["--phi", "-inf"], ["--phi", "-inf", "finite"]),
    (BASE + ["--d", "-1e-3"], ["--d", "-1e-3", ">= 0"]),
    (BASE + ["--v-stick", "-1"], ["--v-stick", "-1", ">= 0"]),
    (BASE + ["--max-impacts", "0"], ["--max-impacts", "0", ">= 1"]),
    (BASE + ["--max-impacts", "2.5"], ["--max-impacts", "2.5", "integer"]),
    (BASE + ["--rtol", "0"], ["--rtol", "0", ">= 1e-14"]),     # the range of vines.simulate
    (BASE + ["--t-end", "-7"], ["--t-end", "-7", "> 0"]),
    (BASE + ["--eta"], ["--eta"]),
    (BASE + ["--omeg", "1"], ["--omeg"]),   # no silent abbreviations
])
def test_simulate_bad_input(args, fragments):
    proc = run_vines("simulate", *args, "--json")
    assert_one_line_error(proc, *fragments)


def test_no_subcommand_prints_help_and_exits_2():
    proc = run_vines()
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert "simulate" in proc.stderr and "usage" in proc.stderr.lower()


def test_unknown_command():
    proc = run_vines("simulat")
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert len(proc.stderr.splitlines()) == 1
    assert "simulat" in proc.stderr


def test_version():
    proc = run_vines("--version")
    assert proc.returncode == 0
    import vines
    assert proc.stdout.strip() == f"vines {vines.__version__}"
    meta = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert meta["project"]["version"] == vines.__version__


def test_simulate_help_lists_every_flag():
    proc = run_vines("simulate", "--help")
    assert proc.returncode == 0
    for flag in ("--eta", "--omega", "--F", "--r", "--d", "--phi", "--t-end", "--t-transient",
                 "--solver", "--rtol", "--v-stick", "--max-impacts", "--json"):
        assert flag in proc.stdout


def test_simulate_json_success():
    proc = run_vines("simulate", "--eta", "0.05", "--omega", "1", "--F", "0.05",
                     "--t-end", "300", "--t-transient", "100", "--json")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert len(lines) == 1, proc.stdout            # exactly one JSON object, nothing else
    out = json.loads(lines[0], parse_constant=lambda c: pytest.fail(f"non-JSON constant {c}"))
    assert isinstance(out, dict)
    assert set(out) >= SIMULATE_KEYS, SIMULATE_KEYS - set(out)
    assert out["solver"] == "exact"
    params = out["params"]
    expected = {"eta": 0.05, "omega": 1.0, "F": 0.05, "r": 0.65, "phi": 0.0,
                "t_end": 300.0, "t_transient": 100.0}
    for key, value in expected.items():
        assert key in params, key
        assert params[key] == pytest.approx(value), key
    for key in ("d", "v_stick", "max_impacts"):
        assert key in params, key
    assert round(params["d"], 6) == 0.011998
    ke = out["ke_ratio"]
    assert ke is None or 0.0 <= ke <= 1.0
    assert out["xmax_m"] is None or math.isclose(out["xmax_m"], out["xmax"] * 0.015,
                                                  rel_tol=1e-12)
