"""Issue 30 item 3: integer options take what people type for an integer, and Ctrl-C ends a
command with one line on stderr, exit status 130 and nothing on stdout, also in the middle
of a long census, boundary scan, continuation or design."""
import json
import os
import queue
import re
import signal
import subprocess
import sys
import threading
import time

import pytest
from conftest import ROOT, SRC, run_on_terminal, run_vines

POINT = ["--eta", "0.13", "--omega", "1", "--F", "0.1"]


@pytest.fixture(autouse=True)
def _sigint_reaches_children():
    """The commands started here get Ctrl-C's default handling even when pytest itself runs
    with SIGINT ignored (a background job of a script), which they would inherit."""
    old = signal.getsignal(signal.SIGINT)
    if old == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, old)


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
    """Ctrl-C on a terminal once the continuation's bar shows (its loop has started; a
    fixed wait raced with the run's end): the bar is cleared and one line stays."""
    code, out, term = run_on_terminal(
        "continue", "--param", "F", "--start", "0.3", "--stop", "0.01", "--eta", "0.2",
        "--omega", "1", "--step", "1e-5", "--max-points", "1e6", "--json", timeout=120,
        interrupt_on="branch in F: ")
    assert code == 130, term
    assert out == "" and "Traceback" not in term
    # what stays on the terminal: every line but the bar's frames ("... [00:01, ...]")
    shown = [ln for ln in re.split(r"[\r\n]+", term) if ln.strip()
             and not re.search(r"\[\d\d:\d\d", ln)]
    assert shown == ["vines continue: interrupted (Ctrl-C); no output written"], term


INTERRUPTED = "interrupted (Ctrl-C); no output written"
LONG_RUNS = {
    "attractors": ["attractors", *POINT, "--n", "16384", "--t-end", "20000"],
    "continue": ["continue", "--param", "F", "--start", "0.3", "--stop", "0.01", "--eta",
                 "0.2", "--omega", "1", "--step", "1e-5", "--max-points", "1e6"],
    "boundaries": ["boundaries", "--F", "0.2"],
    "design": ["design", "--eta", "0.05", "--clearance", "0.015"],
}


def _lines(stream, q):
    for line in stream:
        q.put(line)
    q.put(None)


@pytest.mark.parametrize("command", sorted(LONG_RUNS))
def test_ctrl_c_inside_a_long_loop(command):
    """SIGINT once the command's loop has started (its -v progress line says so): the
    loop stops at its next item, pending work is dropped, exit 130 without a traceback."""
    env = dict(os.environ, PYTHONPATH=str(SRC))
    proc = subprocess.Popen([sys.executable, "-m", "vines", *LONG_RUNS[command], "--json",
                             "-v"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env=env, cwd=ROOT)
    q, err = queue.Queue(), []
    threading.Thread(target=_lines, args=(proc.stderr, q), daemon=True).start()
    try:
        while not any(": started (" in line for line in err):
            line = q.get(timeout=300)
            assert line is not None, "".join(err)      # ended before its loop started
            err.append(line)
        proc.send_signal(signal.SIGINT)
        t_sent = time.monotonic()
        out = proc.stdout.read()
        proc.wait(timeout=60)
        waited = time.monotonic() - t_sent
    finally:
        if proc.poll() is None:
            proc.kill()
    while (line := q.get(timeout=10)) is not None:
        err.append(line)
    text = "".join(err)
    assert proc.returncode == 130, text
    assert out == "" and "Traceback" not in text
    assert err[-1].rstrip("\n") == f"vines {command}: {INTERRUPTED}"
    assert text.count(INTERRUPTED) == 1
    assert waited < 30, waited        # a hang detector; measured: about 1 s
