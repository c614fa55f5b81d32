"""Issue 30 item 3: integer options take what people type for an integer, and Ctrl-C ends a
command with one line on stderr, exit status 130 and nothing on stdout."""
import json
import os
import signal
import subprocess
import sys
import time

import pytest
from conftest import ROOT, SRC, run_vines

POINT = ["--eta", "0.13", "--omega", "1", "--F", "0.1"]


def test_integer_forms_give_the_same_census():
    outs = []
    for n, seed in (("4", "1000"), ("4.0", "1e3"), ("4e0", "1_000")):
        proc = run_vines("attractors", *POINT, "--n", n, "--seed", seed, "--threads", "1",
                         "--json")
        assert proc.returncode == 0, proc.stderr
        outs.append(json.loads(proc.stdout))
    assert outs[0] == outs[1] == outs[2] and outs[0]["seed"] == 1000


@pytest.mark.parametrize("flag, value", [("--seed", "1e3.5"), ("--seed", "1.5"),
                                         ("--n", "x"), ("--threads", "2.5")])
def test_non_integers_are_refused_in_one_line(flag, value):
    proc = run_vines("attractors", *POINT, flag, value, "--json")
    assert proc.returncode == 2 and proc.stdout == "" and "Traceback" not in proc.stderr
    assert len(proc.stderr.splitlines()) == 1
    assert f"argument {flag}: invalid" in proc.stderr and value in proc.stderr


def test_ctrl_c_on_continue():
    env = dict(os.environ, PYTHONPATH=str(SRC))
    proc = subprocess.Popen([sys.executable, "-m", "vines", "continue", "--param", "F",
                             "--start", "0.3", "--stop", "0.01", "--eta", "0.2", "--omega", "1",
                             "--step", "1e-5", "--max-points", "1e6", "--json"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                            cwd=ROOT)
    time.sleep(8)                       # imports done, inside the continuation
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert out == "" and "Traceback" not in err
    assert err.splitlines() == ["vines continue: interrupted (Ctrl-C); no output written"]
