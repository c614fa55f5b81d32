"""``vines periodic --walls SEQ --periods N`` and ``vines continue --walls SEQ --periods N``:
the JSON keys, the 1:1 numbers for ``--walls LR --periods 1``, one-line errors."""
import json

import pytest
from conftest import json_paths, run_vines

from vines import ParameterError
from vines.cli import periodic as cmd
from vines.orbits.family import family as sequence
from vines.orbits.family.periodic import find_1to1

SOLUTION_KEYS = {"walls", "periods", "dw", "phases", "eigenvalues", "lambda_max",
                 "admissible", "stable"}


def _json(*args):
    proc = run_vines(*args, "--json")
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def test_limits_are_the_solvers():
    assert (cmd.MAX_IMPACTS_PER_ORBIT, cmd.MAX_PERIODS) == (
        sequence.MAX_IMPACTS_PER_ORBIT, sequence.MAX_PERIODS)


def test_periodic_walls_json_and_text():
    point = ["--eta", "0.2", "--omega", "0.8", "--F", "0.4"]
    d = _json("periodic", *point, "--walls", "LLRR", "--periods", "1")
    assert d["family"] == "LLRR/1" and d["solutions"]
    assert all(set(s) >= SOLUTION_KEYS and len(s["dw"]) == 4 for s in d["solutions"])
    assert d["solutions"][0]["stable"]
    text = run_vines("periodic", *point, "--walls", "LLRR", "--periods", "1").stdout
    assert "LLRR/1" in text and "solution(s)" in text


def test_walls_lr_gives_the_1to1_numbers():
    point = ["--eta", "0.55", "--omega", "1", "--F", "0.4"]
    one = _json("periodic", *point, "--walls", "lr", "--periods", "1")
    ref = find_1to1(0.55, 1.0, 0.4)
    assert [s["lambda_max"] for s in one["solutions"]] == [o.lambda_max for o in ref]
    assert [s["dw"] for s in one["solutions"]] == [[o.dw_L, o.dw_R] for o in ref]
    whole = _json("periodic", *point)
    plain = whole["solutions"]
    assert [s["lambda_max"] for s in plain] == [s["lambda_max"] for s in one["solutions"]]
    assert [[s["dw_L"], s["dw_R"]] for s in plain] == [s["dw"] for s in one["solutions"]]
    # one JSON shape: the same keys, the old 1:1 keys equal to the new ones
    assert json_paths(whole) == json_paths(one) and whole["family"] == "LR/1"
    for d in (whole, one):
        for s in d["solutions"]:
            assert [s["phase_L"], s["phase_R"]] == s["phases"]
            assert [s["dw_L"], s["dw_R"]] == s["dw"]


def test_continue_walls():
    args = ("continue", "--param", "omega", "--start", "0.75", "--stop", "0.77",
            "--eta", "0.142", "--F", "0.2", "--branch", "asymmetric", "--step", "0.001",
            "--max-points", "20")
    d = _json(*args, "--walls", "LR", "--periods", "1")
    plain = _json(*args)
    # one JSON shape: `--walls LR --periods 1` prints the keys of the 1:1 output
    assert json_paths(d) == json_paths(plain), json_paths(d) ^ json_paths(plain)
    for p in d["branch"] + plain["branch"]:
        assert p["dw_L"] == p["dw"][0]
    assert d["walls"] == "LR" and d["periods"] == 1 and d["param"] == "omega"
    assert 1 < len(d["branch"]) <= 20
    assert all({"dw", "phases", "flight_times", "lambda_max"} <= set(p) for p in d["branch"])
    omegas = [p["omega"] for p in d["branch"]]
    assert omegas[0] == pytest.approx(0.75) and max(omegas) <= 0.77


@pytest.mark.parametrize("cmd_, extra, fragment", [
    ("periodic", ["--walls", "LQ"], "argument --walls: invalid walls = 'LQ'"),
    ("periodic", ["--walls", "LR", "--periods", "0"], "argument --periods: invalid periods"),
    ("periodic", ["--walls", "LR", "--periods", "2.5"], "argument --periods: invalid periods"),
    ("continue", ["--walls", "LR", "--method", "natural", "--switch"], "argument --switch: "),
    ("continue", ["--walls", "X"], "argument --walls: "),
    ("periodic", ["--walls", ""], "argument --walls: invalid walls = ''"),
    ("boundaries", ["--walls", ""], "argument --walls: invalid walls = ''"),
])
def test_bad_walls_exit_2_with_one_line(cmd_, extra, fragment):
    point = {"periodic": ["--eta", "0.2", "--omega", "0.8", "--F", "0.4"],
             "boundaries": ["--F", "0.4"],
             "continue": ["--param", "omega", "--start", "0.8", "--stop", "0.9", "--eta", "0.2",
                          "--F", "0.4"]}[cmd_]
    proc = run_vines(cmd_, *point, *extra, "--json")
    assert proc.returncode == 2 and proc.stdout == "" and "Traceback" not in proc.stderr
    assert len(proc.stderr.splitlines()) == 1 and fragment in proc.stderr, proc.stderr


def test_run_walls_refuses_bad_model_values():
    import argparse
    args = argparse.Namespace(eta="-1", omega="0.8", F="0.4", r=0.6, d=0.01, walls="LR",
                              periods="1")
    with pytest.raises(ParameterError, match="eta"):
        cmd.run_walls(args)
