"""Every command's --help: exit 0, on stdout, no doubled percent sign (argparse formats help
strings but prints descriptions as written)."""
import pytest
from conftest import run_vines

from vines.cli import build_parser

COMMANDS = sorted(build_parser()[1])


def test_every_registered_command_is_listed():
    assert {"simulate", "periodic", "continue", "boundaries", "attractors",
            "design"} <= set(COMMANDS)


@pytest.mark.parametrize("command", COMMANDS)
def test_help_has_no_doubled_percent(command):
    proc = run_vines(command, "--help")
    assert proc.returncode == 0, proc.stderr
    assert "usage: vines " + command in proc.stdout
    assert "%%" not in proc.stdout


def test_switched_branch_header_names_where_it_is_born():
    from vines.cli.continue_ import _text
    pt = {"eta": 0.0, "lambda_max": 0.5, "stable": True, "symmetric": False,
          "admissible": True, "dw": [1.0, -1.0]}
    sw = {"param": "eta", "family": "asymmetric", "events": [], "stopped": "done",
          "switched": [], "branch": [dict(pt, eta=0.1496), dict(pt, eta=0.12)]}
    d = dict(sw, family="symmetric", switched=[sw], branch=[dict(pt, eta=0.12)])
    lines = _text(d, {"start": 0.12, "stop": 0.3}).splitlines()
    assert lines[0].startswith("symmetric branch in eta from 0.12 towards 0.3")
    head = [ln for ln in lines if "asymmetric branch" in ln][0]
    assert "born at eta = 0.1496, followed down to 0.12" in head


def test_continue_text_is_a_summary_unless_all():
    args = ["continue", "--param", "F", "--start", "0.3", "--stop", "0.01", "--eta", "0.2",
            "--omega", "1"]
    short, full = run_vines(*args), run_vines(*args, "--all")
    assert short.returncode == full.returncode == 0
    n_short, n_full = len(short.stdout.splitlines()), len(full.stdout.splitlines())
    assert n_short <= 40 < n_full
    events = [ln for ln in full.stdout.splitlines() if "event " in ln]
    assert events and all(ev in short.stdout for ev in events)


@pytest.mark.parametrize("command", COMMANDS)
def test_help_points_to_the_docs_not_the_readme(command):
    text = run_vines(command, "--help").stdout
    assert "README" not in text
    if command == "simulate":        # the JSON keys: docs/usage.md, linked from docs/cli.md
        assert "docs/usage.md" in " ".join(text.split()) and "docs/cli.md" in text
    if command == "design":          # --view: the one view it offers, said in words
        assert "the only one is t_end" in " ".join(text.split())


def test_top_level_help_names_the_reference():
    text = " ".join(run_vines("--help").stdout.split())
    assert "docs/cli.md" in text and "docs/usage.md" in text


def test_usage_and_readme_name_every_command_and_no_count():
    """docs/usage.md names every subcommand and states no count of them (it said "seven"
    beside nine); the README's command block has a line for each."""
    import re

    from conftest import ROOT
    usage = (ROOT / "docs" / "usage.md").read_text()
    readme = (ROOT / "README.md").read_text()
    for command in COMMANDS:
        assert f"`{command}`" in usage, command
        assert re.search(rf"^vines {command} ", readme, re.M), command
    numbers = "two|three|four|five|six|seven|eight|nine|ten|eleven|twelve|[0-9]+"
    assert not re.search(rf"\b({numbers}) (sub)?commands\b", usage + readme)


def test_continue_text_has_no_nested_brackets():
    """The reason a branch ended may hold brackets itself ("admissibility lost for good
    (1000 points)"): the header gives it after "ended:", not inside brackets."""
    from vines.cli.continue_ import _text
    d = {"param": "F", "family": "symmetric", "events": [], "switched": [], "branch": [],
         "stopped": "admissibility lost for good (1000 points)"}
    head = _text(d, {"start": 0.3, "stop": 0.01}).splitlines()[0]
    assert head.endswith("0 points; ended: admissibility lost for good (1000 points)"), head


def test_attractors_text_names_where_states_escape():
    """``escape_to`` (JSON: attractor index -> count) reads as text, not as a raw dict."""
    from vines.cli.attractors import _text
    from vines.core.params import ModelParams
    a0 = {"regime": "1:1", "basin_fraction": 0.98, "ci": [0.95, 0.99], "ke_ratio": 0.79,
          "xmax_m": 0.002, "status": "persistent", "basin_fraction_asymptotic": 1.0,
          "ci_asymptotic": [0.98, 1.0], "lifetime": None, "escape_to": {}}
    a1 = dict(a0, regime="chatter", status="transient", basin_fraction_asymptotic=0.0,
              lifetime={"mean": 3220.0, "ci": [1380.0, 9900.0]}, escape_to={"0": 36})
    d = {"attractors": [a0, a1], "n": 256, "unsettled_fraction": 0.0, "from_rest": 0,
         "t_max": 1e5, "from_rest_asymptotic": 0}
    text = _text(d, ModelParams(eta=0.13, omega=1.0, F=0.1))
    assert "{" not in text and "'" not in text, text
    assert "states escaped: 36 to attractor 0 (1:1)" in text
    assert "mean lifetime 3.22e+03 [1.38e+03, 9.9e+03] time units" in text
    assert text.endswith("from rest at t_max: attractor 0 (1:1)")
