"""Issue 27 item 1: a progress bar on a terminal's stderr for a 256-state census, none when
stderr is not a terminal or with --quiet; stdout stays the answer alone (with --json one
JSON object, the same as without a terminal); -v logs progress lines instead."""
import json
import re

from conftest import run_on_terminal, run_vines

CENSUS = ["attractors", "--eta", "0.13", "--omega", "1", "--F", "0.1", "--n", "256",
          "--t-end", "1000", "--t-transient", "500", "--threads", "2"]


#: a census long enough (about a second) for the bar to be redrawn before it closes: tqdm
#: redraws at most every 0.1 s, and 256 states can finish within that on a fast idle machine
LONG_CENSUS = [*CENSUS[:CENSUS.index("--n") + 1], "4096", *CENSUS[CENSUS.index("--n") + 2:]]


def test_census_shows_a_bar_on_a_terminal():
    code, out, term = run_on_terminal(*LONG_CENSUS, "--json")
    assert code == 0, term
    assert "census:" in term and "/4096 [" in term and "%|" in term     # tqdm's bar
    assert re.search(r"census: +\d+%\|[^|]*\| *[1-9]\d*/4096 \[", term)   # it advanced
    assert "Traceback" not in term
    json.loads(out)                        # stdout: the answer alone


def test_no_bar_without_a_terminal_and_the_same_json():
    plain = run_vines(*CENSUS, "--json")
    assert plain.returncode == 0, plain.stderr
    assert plain.stderr == ""
    obj = json.loads(plain.stdout)         # exactly one JSON object on stdout
    assert plain.stdout.count("\n") == 1 and isinstance(obj, dict)
    code, out, term = run_on_terminal(*CENSUS, "--json")
    assert code == 0 and json.loads(out) == obj


def test_quiet_shows_no_bar():
    code, out, term = run_on_terminal(*CENSUS, "--quiet")
    assert code == 0, term
    assert "%|" not in term and "census" not in term
    assert out.startswith("eta = 0.13, omega = 1, F = 0.1: ")


def test_verbose_logs_progress_lines_without_a_terminal():
    proc = run_vines(*CENSUS, "--json", "-v")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stderr.splitlines()
    assert "vines attractors: census: started (256 states)" in lines
    assert "vines attractors: census 128/256 states (50 %)" in lines
    assert lines[-1].startswith("vines attractors: done in ")
    json.loads(proc.stdout)
