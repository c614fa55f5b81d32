"""``vines slowflow`` and ``vines design --model`` (the slow flow's design): JSON keys, the
numbers are the API's, bad input exits 2 with one line naming the flag."""
import argparse
import json

import pytest
from conftest import run_vines

from vines import ParameterError
from vines.cli import design as design_cmd
from vines.cli import slowflow as cmd
from vines.cli.common import VinesArgumentParser
from vines.slowflow import frc, response


def _parse(module, argv):
    parser = argparse.ArgumentParser(prog="vines")
    module.add_parser(parser.add_subparsers(dest="command", parser_class=VinesArgumentParser))
    if module is design_cmd:
        return parser.parse_args(["design", *argv])
    return parser.parse_args([module.NAME, *argv])


def test_one_point():
    d = cmd.compute(_parse(cmd, ["--eta", "0.02", "--omega", "1", "--F", "0.02"]))
    json.dumps(d, allow_nan=False)
    assert {"rho", "xi_min", "orbits", "regime", "smr", "warnings"} <= set(d)
    assert {"amplitude", "ball_amplitude", "phase", "stable"} <= set(d["orbits"][0])
    assert d == response(0.02, 1.0, 0.02).to_dict()
    assert d["regime"] == "two-impact" and "regime two-impact" in cmd.text(d)


def test_omega_range_is_the_frc():
    d = cmd.compute(_parse(cmd, ["--eta", "0.02", "--omega-range", "0.9", "1.1", "21",
                                 "--F", "0.03", "--r", "0.7", "--d", "0.01"]))
    ref = frc(0.02, [0.9 + 0.01 * k for k in range(21)], 0.03, r=0.7, d=0.01)
    assert [p["amplitude"] for p in d["frc"]] == pytest.approx(ref.amplitude.tolist())
    assert len(d["regimes"]) == 21 and d["params"]["n_omega"] == 21
    assert "fixed points over 21 frequencies" in cmd.text(d)


@pytest.mark.parametrize("argv, flag", [
    (["--eta", "0.02", "--omega-range", "1.1", "0.9", "5", "--F", "0.03"], "--omega-range"),
    (["--eta", "0.02", "--omega-range", "0.9", "1.1", "1", "--F", "0.03"], "--omega-range"),
    (["--eta", "0.7", "--omega", "1", "--F", "0.03"], "--eta"),
    (["--eta", "0.02", "--omega", "1", "--F", "0.03", "--r", "1"], "--r"),
])
def test_bad_values_name_the_flag(argv, flag, capsys):
    from vines.cli import main
    with pytest.raises(SystemExit) as err:
        main(["slowflow", *argv])
    out = capsys.readouterr()
    assert err.value.code == 2 and out.out == ""
    assert len(out.err.splitlines()) == 1 and flag in out.err


def test_command_line():
    """One process: the answer on stdout, exit 0; a bad value: one line, exit 2."""
    proc = run_vines("slowflow", "--eta", "0.05", "--omega", "1", "--F", "0.02", "--json")
    assert proc.returncode == 0 and json.loads(proc.stdout)["regime"] == "SMR"
    proc = run_vines("slowflow", "--eta", "0.05", "--omega", "x", "--F", "0.02")
    assert proc.returncode == 2 and len(proc.stderr.splitlines()) == 1


def test_design_model_slowflow_and_both():
    """--model slowflow is the slow flow's design; both adds it and the difference to the
    exact object, whose numbers do not change."""
    common = ["--omega-band", "0.95", "1.05", "--n-omega", "3", "--amplitude", "0.001",
              "--eta", "0.05", "--clearance", "0.02", "--census-n", "0", "--t-end", "1500",
              "--t-transient", "1000", "--threads", "1"]
    slow = design_cmd.with_model(_parse(design_cmd, [*common, "--model", "slowflow"]),
                                 lambda: pytest.fail("the exact design ran"))
    assert slow["model"] == "slowflow" and slow["vines"]["clearance_m"] == 0.02
    assert slow["optimal"]["worst_ratio"] <= slow["vines"]["worst_ratio"] + 1e-12
    args = _parse(design_cmd, [*common, "--model", "both"])
    both = design_cmd.with_model(args, lambda: design_cmd.compute(args))
    exact = design_cmd.compute(_parse(design_cmd, common))
    assert {k: v for k, v in both.items() if k not in ("slowflow", "difference")
            } | {"cost": None} == exact | {"cost": None}
    assert both["difference"]["worst_ratio"] == pytest.approx(
        both["slowflow"]["vines"]["worst_ratio"] - exact["vines"]["worst_ratio"])
    assert "slow flow minus exact" in design_cmd.text(both)
    assert "slow flow, band" in design_cmd.text(slow)
    with pytest.raises(ParameterError) as err:
        design_cmd.with_model(_parse(design_cmd, ["--model", "slowflow", "--eta", "0.02"]),
                              None)
    assert err.value.name == "clearance"
