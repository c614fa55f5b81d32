"""Bad configs stop before any job: one ConfigError naming the key, the value and the rule."""
import copy
import math
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml

from vines.pipeline.axes import ConfigError
from vines.pipeline.config import load_schema, load_yaml, validate_config

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = load_schema()
SMOKE = yaml.safe_load((ROOT / "config" / "smoke.yaml").read_text())


def _first(section):
    return sorted(SMOKE[section])[0]


SW, BR, SM, TH = _first("sweeps"), _first("branches"), _first("stability_maps"), _first("timehistories")
WP = sorted(SMOKE["work_precision"]["cases"])[0]
GR, BD = _first("grids"), _first("boundaries")
DZ, OA, SH = _first("designs"), _first("orbit_atlases"), _first("shocks")
ML = _first("model_ladders")
DR, UN = _first("design_robust"), _first("uncertainty")

BAD = [  # (path to set, keys joined by '/', value, expected key in the message, expected words)
    ("simulation/t_end", math.nan, "t_end", "finite"),
    ("simulation/t_end", math.inf, "t_end", "finite"),
    ("simulation/t_end", 1e300, "simulation.t_end", "limits.max_t_end"),
    (f"sweeps/{SW}/values", [0.0, 0.1], f"sweeps.{SW}.values", "eta"),
    (f"sweeps/{SW}/outer_values", [-0.2], f"sweeps.{SW}.outer_values", "F"),
    (f"branches/{BR}/start", 0.0, f"branches.{BR}.start", ""),
    (f"branches/{BR}/stop", -1.0, f"branches.{BR}.stop", ""),
    (f"branches/{BR}/step", 1e-300, f"branches.{BR}.step", "max_branch_points"),
    (f"stability_maps/{SM}/eta", [0.0, 0.5], f"stability_maps.{SM}.eta", "eta"),
    (f"stability_maps/{SM}/omega", {"start": -1.0, "stop": 1.0, "num": 3},
     f"stability_maps.{SM}.omega", "omega"),
    (f"stability_maps/{SM}/F", -0.1, f"stability_maps.{SM}.F", "F"),
    (f"timehistories/{TH}/points", [{"eta": 0.05, "omega": 0.0, "F": 0.1}],
     f"timehistories.{TH}.points.0.omega", "omega"),
    (f"work_precision/cases/{WP}/F", -1.0, f"work_precision.cases.{WP}.F", "F"),
    ("grids/big", {"axes": {"eta": {"start": 0.01, "stop": 1, "num": 1000},
                            "omega": {"start": 0.5, "stop": 1.5, "num": 1000}},
                   "fixed": {"F": 0.1}}, "grids.big", "limits.max_grid_points"),
    ("model/r", 1.5, "model.r", ""),
    # nonsense that used to plan every job (issue: bad input never escapes)
    (f"grids/{GR}/axes/eta", [0.1, 0.2, 0.1], f"grids.{GR}.axes.eta", "more than once"),
    (f"grids/{GR}/sections", {"F": [0.05]}, f"grids.{GR}.sections.F", "fixed"),
    (f"sweeps/{SW}/n_record", 10**9, f"sweeps.{SW}.n_record", "do not fit"),
    (f"sweeps/{SW}/t_settle", 1e300, f"sweeps.{SW}.t_settle", "limits.max_t_end"),
    (f"boundaries/{BD}/omega_range", [0.1, 1.4], f"boundaries.{BD}.omega_range", "outside"),
    (f"boundaries/{BD}/walls", "LLRR", f"boundaries.{BD}.stability_map", "1:1 curves only"),
    ("boundaries/seq", {"F": 0.4, "walls": "LXR", "eta_range": [0.1, 0.3],
                        "omega_range": [0.7, 0.9]}, "boundaries.seq.walls", ""),
    ("boundaries/seq", {"F": 0.4, "walls": "LLRR", "periods": 0, "eta_range": [0.1, 0.3],
                        "omega_range": [0.7, 0.9]}, "boundaries.seq.periods", ""),
    ("boundaries/seq", {"F": 0.4, "walls": "LLRR\n", "eta_range": [0.1, 0.3],
                        "omega_range": [0.7, 0.9]}, "boundaries.seq.walls", ""),
    (f"timehistories/{TH}/n_periods", 10**6, f"timehistories.{TH}.n_periods", "exceed the run"),
    (f"timehistories/{TH}/window_samples_per_period", 10**9,
     f"timehistories.{TH}.window_samples_per_period", "limits.max_samples"),
    ("work_precision/rk_methods", [], "work_precision.rk_methods", ""),
    ("work_precision/rtols", [], "work_precision.rtols", ""),
    ("convergence/window/window_lengths", [1500.0], "convergence.window.window_lengths",
     "shorter than every run"),
    ("convergence/grid/resolutions", [9, 5, 17], "convergence.grid.resolutions", "nest"),
    ("convergence/grid/resolutions", [5, 8, 17], "convergence.grid.resolutions", "nest"),
    ("convergence/grid/eta_range", [1.0, 0.01], "convergence.grid.eta_range", "lo < hi"),
    # designs: the validators of vines.design, named by the config key
    (f"designs/{DZ}/amplitudes_m", [0.003, -1.0], f"designs.{DZ}.amplitudes_m", ""),
    (f"designs/{DZ}/omega_band", [1.2, 0.8], f"designs.{DZ}.omega_band", ""),
    (f"designs/{DZ}/eta", 0.1, f"designs.{DZ}.eta_max", "do not give eta"),
    (f"designs/{DZ}/clearance_range_m", [0.1, 0.01], f"designs.{DZ}.clearance_range_m", ""),
    ("designs/both", {"amplitudes_m": [0.003], "eta_max": 0.1, "c_Ns_per_m": 2.0, "d": 0.01},
     "designs.both.d", "not both"),
    (f"designs/{DZ}/c_Ns_per_m", 1e9, f"designs.{DZ}.c_Ns_per_m", ""),
    (f"designs/{DZ}/t_transient", 1e9, f"designs.{DZ}.t_transient", ""),
    (f"designs/{DZ}/n_eta", 10**6, f"designs.{DZ}.n_eta", ""),
    (f"designs/{DZ}/census_n", 10**6, f"designs.{DZ}", "limits.max_grid_points"),
    # design_robust: the design's checks, then the mistuning's
    (f"design_robust/{DR}/mistuning", -0.1, f"design_robust.{DR}.mistuning", "-0.1"),
    (f"design_robust/{DR}/n_delta", 4, f"design_robust.{DR}.n_delta", "odd"),
    (f"design_robust/{DR}/omega_band", [1.2, 0.8], f"design_robust.{DR}.omega_band", ""),
    (f"design_robust/{DR}/eta", 0.1, f"design_robust.{DR}.eta_max", "do not give eta"),
    # uncertainty: its design as a designs entry, its parts and samples by their validators
    (f"uncertainty/{UN}/parameters/r", ["uniform", 0.8, 0.5], f"uncertainty.{UN}.parameters",
     "empty"),
    (f"uncertainty/{UN}/parameters/frequency", ["normal", 0.0, -0.1],
     f"uncertainty.{UN}.parameters", "standard deviation"),
    (f"uncertainty/{UN}/samples", 6, f"uncertainty.{UN}.samples", "power of 2"),
    (f"uncertainty/{UN}/design/amplitudes_m", [-0.003], f"uncertainty.{UN}.design.amplitudes_m",
     ""),
    (f"uncertainty/{UN}/samples", 2 ** 16, f"uncertainty.{UN}", "limits.max_grid_points"),
    # orbit atlases: a stability map that exists, or a whole grid the model accepts
    ("orbit_atlases/ref", {"stability_map": "nope"}, "orbit_atlases.ref.stability_map",
     "not a stability_maps entry"),
    (f"orbit_atlases/{OA}/stability_map", SM, f"orbit_atlases.{OA}.eta", "not both"),
    ("orbit_atlases/own", {"eta": [0.1], "omega": [1.0]}, "orbit_atlases.own.F", "missing"),
    ("orbit_atlases/own", {"eta": [0.0, 0.1], "omega": [1.0], "F": 0.2},
     "orbit_atlases.own.eta", "eta"),
    ("orbit_atlases/own", {"eta": {"start": 0.01, "stop": 1, "num": 1000},
                           "omega": {"start": 0.5, "stop": 1.5, "num": 1000}, "F": 0.2},
     "orbit_atlases.own", "limits.max_grid_points"),
    (f"orbit_atlases/{OA}/sim_t_end", 1e300, f"orbit_atlases.{OA}.sim_t_end",
     "limits.max_t_end"),
    # shocks: the validators of studies.shock, named by the config key
    (f"shocks/{SH}/eta", 0.0, f"shocks.{SH}.eta", ""),
    (f"shocks/{SH}/clearance_m", -0.01, f"shocks.{SH}.clearance_m", ""),
    (f"shocks/{SH}/energy_range_J", [10.0, 1.0], f"shocks.{SH}.energy_range_J", ""),
    (f"shocks/{SH}/n_energies", 10**6, f"shocks.{SH}.n_energies", "<= 10000"),
    (f"shocks/{SH}/history_energies_J", [1.0, -2.0], f"shocks.{SH}.history_energies_J[1]",
     ""),
    ("shocks/both", {"eta": 0.1, "clearance_m": 0.01, "history_energies_J": [1.0],
                     "c_Ns_per_m": 2.0, "d": 0.01}, "shocks.both.d", "not both"),
    (f"shocks/{SH}/omega_band", [1.2, 0.8], f"shocks.{SH}.omega_band", ""),
    (f"shocks/{SH}/periods", 1e9, f"shocks.{SH}.periods", "<= 10000"),
    # model ladders: the slow flow's and the exact solver's validators
    (f"model_ladders/{ML}/etas", [0.05, 0.6], f"model_ladders.{ML}.etas", "slow flow"),
    (f"model_ladders/{ML}/sigma_range", [-20.0, 3.0], f"model_ladders.{ML}.sigma_range",
     "omega must be > 0"),
    (f"model_ladders/{ML}/f", -1.0, f"model_ladders.{ML}.f", ""),
    (f"model_ladders/{ML}/t_transient", 1e6, f"model_ladders.{ML}.t_transient", ""),
    (f"model_ladders/{ML}/continuation_step", 2.0, f"model_ladders.{ML}.continuation_step",
     ""),
    # numbers YAML reads as text, and 16.0 for an integer: how to write them
    ("simulation/t_end", yaml.safe_load("x: 1e4")["x"], "simulation.t_end",
     "YAML reads 1e4 as text: write 10000.0"),
    ("simulation/t_end", yaml.safe_load("x: 2.5e3")["x"], "simulation.t_end",
     "write 2500.0"),
    ("chunk_size", yaml.safe_load("x: 1e3")["x"], "chunk_size", "write 1000)"),
    ("chunk_size", 16.0, "chunk_size", "16.0 is not of type 'integer' (write 16)"),
]


def _set(cfg, path, value):
    keys = path.split("/")
    node = cfg
    for k in keys[:-1]:
        node = node.setdefault(k, {})
    node[keys[-1]] = value


@pytest.mark.parametrize("path,value,key,words", BAD, ids=[b[0] + "=" + repr(b[1])[:20] for b in BAD])
def test_bad_value_is_refused_naming_its_key(path, value, key, words):
    cfg = copy.deepcopy(SMOKE)
    _set(cfg, path, value)
    t0 = time.perf_counter()
    with pytest.raises(ConfigError) as exc:
        validate_config(cfg, SCHEMA)
    assert time.perf_counter() - t0 < 30
    msg = str(exc.value)
    assert "\n" not in msg and key in msg and words in msg, msg


def test_the_shipped_configs_pass():
    for name in ("config.yaml", "smoke.yaml"):
        validate_config(yaml.safe_load((ROOT / "config" / name).read_text()), SCHEMA)


def test_limits_can_be_raised():
    cfg = copy.deepcopy(SMOKE)
    cfg["simulation"]["t_end"] = 2e6
    for section in ("robust_maps", "basin_slices"):     # their t_max must exceed t_end
        for entry in cfg[section].values():
            entry.pop("t_max", None)
    with pytest.raises(ConfigError, match="max_t_end"):
        validate_config(copy.deepcopy(cfg), SCHEMA)
    cfg["limits"] = {"max_t_end": 3e6, "max_samples": 10**8}   # the time histories grow too
    validate_config(cfg, SCHEMA)


def test_yaml_syntax_error_names_file_and_line(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("run: x\nsimulation:\n  t_end: [1, 2\n")
    with pytest.raises(ConfigError) as exc:
        load_yaml(bad)
    assert f"{bad}:" in str(exc.value) and "YAML syntax error" in str(exc.value)
    r = subprocess.run([sys.executable, "-m", "vines.pipeline.config", str(bad)],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and str(bad) in r.stderr


def test_convergence_points_can_name_a_time_history_point():
    """A figure's point is written once: {timehistory: NAME, index: I} in the convergence
    studies is replaced by that point of the time-history entry (and its label)."""
    cfg = copy.deepcopy(SMOKE)
    th = sorted(cfg["timehistories"])[0]
    cfg["convergence"]["vstick"]["points"] = [{"timehistory": th, "index": 0, "label": "x"}]
    validate_config(cfg, SCHEMA)
    want = {k: SMOKE["timehistories"][th]["points"][0][k] for k in ("eta", "omega", "F")}
    assert cfg["convergence"]["vstick"]["points"] == [{**want, "label": "x"}]
    for study, bad, key in (("window", {"timehistory": "nope", "index": 0}, "timehistory"),
                            ("vstick", {"timehistory": th, "index": 99}, "index")):
        cfg = copy.deepcopy(SMOKE)
        cfg["convergence"][study]["points"] = [bad]
        with pytest.raises(ConfigError, match=rf"convergence\.{study}\.points\[0\]\.{key}"):
            validate_config(cfg, SCHEMA)


def test_shipped_convergence_studies_name_the_figure_points_they_share():
    """No copy of a time-history point in the shipped configs' convergence studies."""
    for name in ("config.yaml", "smoke.yaml"):
        cfg = yaml.safe_load((ROOT / "config" / name).read_text())
        histories = {(p["eta"], p["omega"], p["F"]) for th in cfg["timehistories"].values()
                     for p in th["points"]}
        for study in ("window", "vstick"):
            for p in cfg["convergence"][study]["points"]:
                if "timehistory" not in p:
                    assert (p["eta"], p["omega"], p["F"]) not in histories, (name, study, p)
def test_an_atlas_may_name_a_stability_map():
    from vines.pipeline.config_checks import atlas_grid
    cfg = copy.deepcopy(SMOKE)
    cfg["orbit_atlases"] = {"ref": {"stability_map": SM}}
    validate_config(cfg, SCHEMA)
    sm = cfg["stability_maps"][SM]
    assert atlas_grid(cfg, "ref") == {k: sm[k] for k in ("eta", "omega", "F")}
    assert cfg["orbit_atlases"]["ref"]["sim_t_end"] == 600.0
