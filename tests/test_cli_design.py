"""``vines design`` (src/vines/cli/design.py): its defaults are the API's, its flags reach
``vines.design`` and bad values exit 2 with one line naming the flag."""
import argparse
import json
import subprocess
import sys

import pytest
from conftest import run_vines

from vines import ParameterError
from vines.cli import design as cmd
from vines.cli.common import VinesArgumentParser
from vines.studies import design as api
from vines.studies.design_checks import VIEW_NAMES


def _parse(argv):
    parser = argparse.ArgumentParser(prog="vines")
    cmd.add_parser(parser.add_subparsers(dest="command", parser_class=VinesArgumentParser))
    return parser.parse_args(["design", *argv])


def test_defaults_are_the_apis():
    """The CLI shows and passes the API's defaults (one home: ``design_checks``), and its
    --help does not load the simulation."""
    import inspect
    defaults = {k: v.default for k, v in inspect.signature(api.design).parameters.items()}
    args = _parse([])
    assert args.omega_band == list(defaults["omega_band"]) == [0.8, 1.2]
    assert (args.n_omega, args.n_eta, args.n_clearance, args.census_n) == (
        defaults["n_omega"], defaults["n_eta"], defaults["n_clearance"], defaults["census_n"])
    assert args.amplitude == list(defaults["amplitudes_m"])
    assert set(api.VIEWS) == set(VIEW_NAMES)
    loaded = subprocess.run([sys.executable, "-c", "import sys; import vines.cli.design; "
                             "print(' '.join(sys.modules))"], check=True, capture_output=True,
                            text=True).stdout.split()
    assert "numba" not in loaded and "vines.studies.design" not in loaded


def test_run_evaluates_a_design():
    args = _parse(["--omega-band", "0.95", "1.05", "--n-omega", "3", "--amplitude", "0.001",
                   "--eta", "0.05", "--clearance", "0.02", "--census-n", "2", "--t-end", "2000",
                   "--t-transient", "1500", "--threads", "1", "--d", "0.02", "--json"])
    d = cmd.compute(args)
    json.dumps(d, allow_nan=False)
    assert d["inputs"]["d"] == 0.02 and d["vines"]["eta"] == 0.05
    assert d["curves"]["omega"] == [0.95, 1.0, 1.05]
    assert "LO alone" in cmd.text(d)


@pytest.mark.parametrize("argv, flag", [
    (["--eta", "0.1"], "--clearance"),
    (["--eta-max", "0.1", "--clearance-range", "0.02", "0.01"], "--clearance-range"),
    (["--eta", "0.1", "--clearance", "0.01", "--amplitude", "0.001", "-1"], "--amplitude"),
    (["--eta", "0.1", "--clearance", "0.01", "--n-omega", "x"], "--n-omega"),
    (["--eta", "0.1", "--clearance", "0.01", "--threads", "0"], "--threads"),
    (["--eta-max", "0.1", "--r-range", "0.8", "0"], "--r-range"),
    (["--eta-max", "0.1", "--r-range", "0", "nan"], "--r-range"),
    (["--eta-max", "0.1", "--r-range", "0", "0.8", "--n-r", "1"], "--n-r"),
])
def test_bad_values_name_the_flag(argv, flag):
    with pytest.raises(ParameterError) as err:
        cmd.compute(_parse(argv))
    assert cmd.FLAG_OF[err.value.name] == flag


def test_r_trade_and_r_range_in_the_json():
    """An optimised design's JSON holds r_trade (r = 0 ... 0.8, the clearance re-optimised);
    --no-r-trade skips it; --r-range searches r (no r_trade, r in the search)."""
    small = ["--omega-band", "0.95", "1.05", "--n-omega", "3", "--amplitude", "0.0015",
             "--eta-max", "0.1", "--n-eta", "1", "--n-clearance", "3", "--census-n", "0",
             "--t-end", "1000", "--t-transient", "600", "--threads", "1"]
    d = cmd.compute(_parse(small))
    t = d["r_trade"]
    assert t["r"] == [0.0, 0.3, 0.5, 0.65, 0.8] and len(t["worst_ratio"]) == 5
    assert t["eta"] == d["vines"]["eta"] and "clearance alone" in t["reoptimised"]
    i = t["r"].index(0.65)      # the design's own r: never worse than the optimum
    assert t["worst_ratio"][i] <= d["vines"]["worst_ratio"]
    assert "against restitution" in cmd.text(d)
    assert "r_trade" not in cmd.compute(_parse([*small, "--no-r-trade"]))
    d = cmd.compute(_parse([*small, "--r-range", "0", "0.8", "--n-r", "2"]))
    assert "r_trade" not in d and d["search"]["r"] == [0.0, 0.8]
    assert d["inputs"]["r_range"] == [0.0, 0.8] and 0.0 <= d["vines"]["r"] <= 0.8


def test_c_and_d_are_exclusive():
    with pytest.raises(SystemExit):
        _parse(["--c", "2", "--d", "0.01", "--eta", "0.1", "--clearance", "0.01"])


def test_command_line():
    """Through ``vines``: one JSON object on stdout, the text summary, one-line errors."""
    small = ["--omega-band", "0.95", "1.05", "--n-omega", "3", "--amplitude", "0.001",
             "--eta", "0.05", "--clearance", "0.02", "--census-n", "0", "--t-end", "2000",
             "--t-transient", "1500", "--threads", "1"]
    proc = run_vines("design", *small, "--json")
    assert proc.returncode == 0, proc.stderr
    d = json.loads(proc.stdout)
    assert d["curves"]["omega"] == [0.95, 1.0, 1.05] and d["vines"]["clearance_m"] == 0.02
    proc = run_vines("design", *small)
    assert proc.returncode == 0 and "LO alone" in proc.stdout
    proc = run_vines("design", *small[:-2], "--threads", "0")
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.splitlines() == [proc.stderr.strip()]
    assert proc.stderr.startswith("vines design: error: argument --threads: ")
    proc = run_vines("design", "--eta", "0.05")        # half of a design
    assert proc.returncode == 2 and proc.stderr.strip() == (
        "vines design: error: missing required option --clearance: give eta and clearance "
        "(evaluate a design) or eta_max (optimise one)")


def test_text_counts_the_whole_cost_and_explains_the_host_frequencies():
    d = {"cost": {"wall_s": 9.5, "n_runs_from_rest": 10, "n_runs_census": 0},
         "mistuning": {"cost": {"wall_s": 70.5}}}
    line = cmd._cost_text(d)
    assert "9.5 s for the design" in line and "mistuning 70.5 s" in line
    assert "80.0 s in all" in line
    m = {"D": 0.1, "delta": [-0.1, -0.0375, -0.05, 0.0, 0.025, 0.0375, 0.05, 0.075, 0.1],
         "n_delta": 7, "robust": None,
         "worst": {"lo_alone": 90.0, "tmd": 6.8, "vines": 48.0, "vines_any_attractor": None},
         "design": {"tmd": {"frequency_ratio": 0.9}, "vines": {"eta": 0.1,
                                                              "clearance_m": 0.04}}}
    head = cmd.mistuning_text(m)[0]
    assert "9 host frequencies: a grid of 7 and 2 added" in head
