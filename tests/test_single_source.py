"""One source of truth: the config schema's defaults and choices equal the API's."""
import inspect
from pathlib import Path

import vines
from vines import cli
from vines.core import params as P
from vines.core.measures import time_histories
from vines.core.simulation import simulate_batch
from vines.core.sweep import bifurcation_sweep
from vines.core.walls import WALL_L, WALL_R, impact_velocities
from vines.pipeline.config import load_schema
from vines.reference.hiprec import DPS_DEFAULT, H_SAMPLE_DEFAULT
from vines.reference.rk import METHODS
from vines.solvers import RK_METHODS, SOLVERS, simulate

SCHEMA = load_schema()
PROPS = SCHEMA["properties"]


def _defaults(fn):
    return {k: v.default for k, v in inspect.signature(fn).parameters.items()
            if v.default is not inspect.Parameter.empty}


def test_simulation_defaults_equal_the_api():
    sim = PROPS["simulation"]["properties"]
    api = _defaults(simulate)
    for key in ("t_end", "t_transient", "v_stick", "max_impacts", "root_tol"):
        assert sim[key]["default"] == api[key], key
    assert _defaults(simulate_batch)["t_end"] == api["t_end"]
    assert PROPS["model"]["properties"]["r"]["default"] == P.R_DEFAULT == api["r"]
    assert PROPS["model"]["properties"]["d"]["default"] is None   # None -> P.D_DEFAULT
    assert api["d"] == P.D_DEFAULT


def test_sweep_defaults_equal_the_api():
    sw = PROPS["sweeps"]["additionalProperties"]["properties"]
    api = _defaults(bifurcation_sweep)
    for key in ("t_settle", "t_step", "n_record", "v_stick"):
        assert sw[key]["default"] == api[key], key


def test_timehistory_defaults_equal_the_api():
    th = PROPS["timehistories"]["additionalProperties"]["properties"]
    api = _defaults(time_histories)
    assert th["window_samples_per_period"]["default"] == api["window_samples_per_period"]


def test_boundaries_defaults_equal_the_api():
    from vines.orbits.curves.boundaries import boundaries
    bd = PROPS["boundaries"]["additionalProperties"]["properties"]
    api = _defaults(boundaries)
    for key in ("n_scan", "step", "max_points", "n_map"):
        assert bd[key]["default"] == api[key], key


def test_work_precision_defaults_equal_the_api():
    wp = PROPS["work_precision"]["properties"]
    assert wp["dps"]["default"] == DPS_DEFAULT
    assert wp["h_sample"]["default"] == H_SAMPLE_DEFAULT


def test_choices_come_from_one_registry():
    assert SCHEMA["definitions"]["param_name"]["enum"] == list(P.PARAM_NAMES)
    rk_enum = PROPS["work_precision"]["properties"]["rk_methods"]["items"]["enum"]
    assert set(rk_enum) == set(RK_METHODS) == set(METHODS)
    parser, _ = cli.build_parser()
    sim_parser = parser._subparsers._group_actions[0].choices["simulate"]
    solver = next(a for a in sim_parser._actions if a.dest == "solver")
    assert tuple(solver.choices) == tuple(SOLVERS) == ("exact", "rk")
    assert all(callable(f) for f in SOLVERS.values())


def test_walls_and_impact_law_in_one_place():
    assert (WALL_L, WALL_R) == (1, -1)
    eta, r, vm, vb = 0.2, 0.65, 0.7, -0.4
    vm_p, vb_p = impact_velocities(eta, r, vm, vb)
    # + - * / only (correctly rounded IEEE, the same on every CPU): each side carries a few
    # roundings of terms <= |v_m| + |v_b| = 1.1, k u 1.1 with k <= 8 is 1e-15 (measured 1.1e-16
    # and 2.2e-16)
    assert abs((vm_p + eta * vb_p) - (vm + eta * vb)) < 1e-15      # momentum
    assert abs((vm_p - vb_p) + r * (vm - vb)) < 1e-15               # restitution
    assert vines.core.result.WALL_L is WALL_L


def _schema_keys(node, path, defs):
    if "$ref" in node:
        node = defs[node["$ref"].split("/")[-1]]
    if node.get("type") != "object":
        yield path
        return
    for k, v in node.get("properties", {}).items():
        yield from _schema_keys(v, f"{path}.{k}" if path else k, defs)
    if isinstance(node.get("additionalProperties"), dict):
        yield from _schema_keys(node["additionalProperties"], f"{path}.<name>", defs)


def test_config_readme_lists_every_key():
    """config/README.md names every leaf key of the schema (braces and `.a`, `.b` lists
    expand to several keys)."""
    import re
    text = (Path(__file__).resolve().parents[1] / "config" / "README.md").read_text()
    listed, listed_base = set(), ""
    for cell in re.findall(r"^\| (`[^|]+) \|", text, re.M):
        for key in re.findall(r"`([^`]+)`", cell):
            full = key if not key.startswith(".") else listed_base + key
            listed_base = key.rsplit(".", 1)[0] if not key.startswith(".") else listed_base
            m = re.match(r"(.*)\{(.*)\}$", full)
            listed |= {m.group(1) + x for x in m.group(2).split(",")} if m else {full}
    missing = set(_schema_keys(SCHEMA, "", SCHEMA["definitions"])) - listed
    assert not missing, f"config/README.md lacks {sorted(missing)}"


def test_api_defaults_are_not_copied_into_the_schema_file():
    """The schema file leaves the API's defaults out; loading fills them in from
    ``core.params`` (one source), and a default written in the file is refused."""
    from importlib.resources import files

    import pytest
    import yaml

    from vines.pipeline.config import _fill_defaults, api_defaults
    raw = yaml.safe_load(files("vines.pipeline").joinpath("config.schema.yaml").read_text())
    for path, value in api_defaults().items():
        node, loaded = raw, SCHEMA
        for part in path.split("."):
            key = "additionalProperties" if part == "*" else None
            node = node[key] if key else node["properties"][part]
            loaded = loaded[key] if key else loaded["properties"][part]
        assert "default" not in node, path
        assert loaded["default"] == value and type(loaded["default"]) is type(value), path
    raw["properties"]["model"]["properties"]["r"]["default"] = 0.5
    with pytest.raises(ValueError, match="model.r"):
        _fill_defaults(raw)


def test_design_map_defaults_equal_the_api():
    from vines.studies.design_map import check_map
    dm = PROPS["design_maps"]["additionalProperties"]["properties"]
    api = _defaults(check_map)
    for key, prop in dm.items():
        if "default" in prop:
            want = api[key]
            assert prop["default"] == (list(want) if isinstance(want, tuple) else want), key
