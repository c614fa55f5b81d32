"""The Snakemake pipeline: config validation, datasets, chunking, dry-run plans and reruns.

The workflow is exercised on a copy of the repository's Snakefile/workflow/config in
tmp_path (with the sources of this checkout), so the tests never touch results/.
"""
import os
import re
import shutil
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from vines.core.measures import derived_measures, section_marks
from vines.core.params import D_DEFAULT
from vines.core.simulation import BATCH_FIELDS
from vines.data.builders import (
    grid_dataset,
    measures_dataset,
    merge_chunks,
    ragged_dataset,
    ragged_rows,
)
from vines.data.netcdf import read_dataset, write_dataset
from vines.data.provenance import provenance_attrs
from vines.pipeline.axes import (
    ConfigError,
    axis_values,
    chunk_key,
    chunk_map,
    grid_axes,
    grid_chunks,
)
from vines.pipeline.config import load_schema, validate_config
from vines.pipeline.parts import CHUNKED_STAGES, chunk_plan
from vines.pipeline.stages import compute_chunk, compute_sweep

ROOT = Path(__file__).resolve().parents[1]
#: the stages of `snakemake -c2 all` beyond the default target `paper`
BEYOND_PAPER = ("lyapunov", "robust_map", "basin_slice", "orbit_atlas", "design",
                "design_robust", "work_precision", "convergence", "shock", "model_ladder")
SCHEMA = ROOT / "src" / "vines" / "pipeline" / "config.schema.yaml"
SNAKEMAKE = shutil.which("snakemake")
needs_snakemake = pytest.mark.skipif(SNAKEMAKE is None, reason="snakemake not installed")

MODEL = {"r": 0.65, "d": D_DEFAULT}
SHORT = {"t_end": 300.0, "t_transient": 200.0}


def _validated(cfg):
    return validate_config(cfg, load_schema(SCHEMA))


# ------------------------------------------------------------------ config

def test_config_files_validate_and_fill_defaults():
    for name in ("config.yaml", "smoke.yaml"):
        cfg = _validated(yaml.safe_load((ROOT / "config" / name).read_text()))
        assert cfg["simulation"]["t_end"] > cfg["simulation"]["t_transient"]
        assert cfg["model"]["r"] == 0.65
    full = _validated(yaml.safe_load((ROOT / "config" / "config.yaml").read_text()))
    assert full["simulation"] == {"t_end": 7000.0, "t_transient": 4000.0, "v_stick": 1e-6,
                                  "max_impacts": 2000000, "root_tol": 1e-13,
                                  "periodic_shortcut": True}
    ax = grid_axes(full["grids"]["fig7_W1"])
    assert 0.3077 in ax["F"].tolist() and 0.4 in ax["F"].tolist()
    assert ax["eta"].max() == 1.0 and ax["F"].max() == 0.5
    w12 = grid_axes(full["grids"]["fig12_F0.3077"])["omega"]
    assert w12.size == 150 and np.min(np.abs(w12 - 0.909396)) < 1e-6
    for s in ("fig3", "fig14_F0.2", "fig15"):
        assert full["sweeps"][s]["directions"] == ["up", "down"]


@pytest.mark.parametrize("patch,key", [
    ({"simulation": {"t_end": "long"}}, "simulation.t_end"),
    ({"model": {"r": 1.5}}, "model.r"),
    ({"chunk_size": 0}, "chunk_size"),
    ({"grids": {"g": {"axes": {"eta": {"start": 0.1, "stop": 0.2, "num": 0}},
                      "fixed": {"omega": 1.0, "F": 0.1}}}}, "grids.g.axes.eta"),
    ({"grids": {"g": {"axes": {"eta": [0.1]}, "fixed": {"omega": 1.0}}}}, "grids.g.fixed.F"),
    ({"grids": {"g": {"axes": {"eta": [0.1, 0.2]}, "fixed": {"omega": 1.0, "F": 0.1},
                      "sections": {"eta": [0.15]}}}}, "grids.g.sections.eta"),
    ({"simulation": {"t_end": 100.0, "t_transient": 200.0}}, "simulation.t_transient"),
    ({"unknown_key": 1}, "<top level>"),
    ({"work_precision": {"cases": {"c": {"eta": 0.1, "omega": 1.0, "F": 0.1, "t_end": 50.0,
                                         "t_transient": 60.0}}}},
     "work_precision.cases.c.t_transient"),
    ({"work_precision": {"rk_methods": ["Euler"]}}, "work_precision.rk_methods.0"),
])
def test_config_error_names_the_key(patch, key):
    with pytest.raises(ConfigError) as ei:
        _validated(patch)
    assert ei.value.key == key
    assert f"'{key}'" in str(ei.value)


# ------------------------------------------------------------------ axes and chunks

def test_axis_values():
    assert axis_values(0.5).tolist() == [0.5]
    assert axis_values([0.3, 0.1]).tolist() == [0.1, 0.3]
    with pytest.raises(ConfigError, match="more than once"):
        axis_values([0.3, 0.1, 0.3], key="grids.g.axes.eta")
    assert axis_values({"start": 0.0, "stop": 1.0, "num": 3, "include": [0.5]}).size == 3
    a = axis_values({"start": 0.0, "stop": 1.0, "num": 5, "include": [0.3077]})
    assert a.tolist() == [0.0, 0.25, 0.3077, 0.5, 0.75, 1.0]
    # linspace(0.01, 1, 100)[9] is 0.09999999999999999: the included 0.1 replaces it (one
    # row at eta = 0.1, not two rows 1.4e-17 apart)
    a = axis_values({"start": 0.01, "stop": 1.0, "num": 100, "include": [0.1, 0.3077, 0.5]})
    assert a.size == 101 and a[9] == 0.1 and np.all(np.diff(a) > 1e-3)


def test_chunks_cover_the_grid_and_are_keyed_by_values():
    axes = {"eta": np.linspace(0.1, 1, 7), "omega": np.linspace(0.5, 1.5, 5), "F": np.array([0.2])}
    for size in (1, 3, 5, 6, 11, 35, 1000):
        chunks = grid_chunks(axes, size)
        pts = [(e, w, f) for c in chunks for e in c["eta"] for w in c["omega"] for f in c["F"]]
        assert len(pts) == 35 == len(set(pts))
        assert all(len(c["eta"]) * len(c["omega"]) * len(c["F"]) <= size for c in chunks)
    # extending the slowest axis keeps the finished full chunks (same names); only the last,
    # partial one is recomputed with the new values
    old = list(chunk_map(axes, 10))
    more = dict(axes, eta=np.concatenate([axes["eta"], [1.2, 1.4]]))
    assert len(old) == 4 and set(old[:-1]) <= set(chunk_map(more, 10))
    assert old[-1] not in chunk_map(more, 10)
    # the key depends on the values only
    c = grid_chunks(axes, 10)[0]
    assert chunk_key(c) == chunk_key({k: list(v) for k, v in c.items()})
    assert chunk_key(c) != chunk_key(dict(c, F=[0.2000000001]))


# ------------------------------------------------------------------ invariance of the numbers

def _grid(chunk_size, n_workers=1, block_size=4):
    axes = {"eta": np.linspace(0.05, 0.5, 4), "omega": np.array([0.9, 1.0, 1.1]),
            "F": np.array([0.1, 0.3077])}
    parts = []
    for c in grid_chunks(axes, chunk_size):
        f = compute_chunk(c, model=MODEL, simulation=SHORT, n_workers=n_workers,
                          block_size=block_size)
        parts.append(grid_dataset(c, f, {}))
    return merge_chunks(parts, axes)


def test_chunk_split_workers_and_blocks_give_identical_numbers():
    ref = _grid(5000)
    for kw in ({"chunk_size": 500 // 100}, {"chunk_size": 2, "n_workers": 2},
               {"chunk_size": 7, "n_workers": 2, "block_size": 1}):
        other = _grid(**kw)
        for k in BATCH_FIELDS:
            np.testing.assert_array_equal(other[k], ref[k], err_msg=k)
    assert set(np.unique(ref["status"])) == {"ok"}


def test_sweep_directions_and_thread_invariance():
    spec = {"param": "eta", "values": {"start": 0.05, "stop": 0.2, "num": 3}, "outer": "F",
            "outer_values": [0.05, 0.1], "fixed": {"omega": 1.0}, "directions": ["up", "down"],
            "t_settle": 200.0, "t_step": 50.0, "n_record": 3, "v_stick": 1e-6}
    a = compute_sweep(spec, model=MODEL, n_workers=1)
    b = compute_sweep(spec, model=MODEL, n_workers=2)
    for k in a:
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)
    assert a["value"].size == 12 and a["row_size"].sum() == a["dw"].size
    assert a["direction"].tolist() == [1] * 3 + [-1] * 3 + [1] * 3 + [-1] * 3
    assert a["value"][3:6].tolist() == a["value"][:3][::-1].tolist()


# ------------------------------------------------------------------ datasets

def _measures_dataset():
    axes = {"eta": [0.05, 0.1], "omega": [1.0], "F": [0.05, 0.3077]}
    f = compute_chunk(axes, model=MODEL, simulation=SHORT)
    attrs = provenance_attrs(title="test", config_subset={"axes": axes}, settings=SHORT,
                             code_version="abc", commit="0" * 40)
    fields = merge_chunks([grid_dataset(axes, f, {})], axes)
    derived = derived_measures(fields, axes["eta"], axes["omega"], axes["F"], D_DEFAULT)
    marks = {"F": section_marks(axes["F"], [0.3077], "F")}
    return measures_dataset(grid_dataset(axes, fields, attrs), derived, marks)


def test_dataset_round_trip_cf_attrs_and_byte_identical_rewrite(tmp_path):
    ds = _measures_dataset()
    p1, p2 = tmp_path / "a.nc", tmp_path / "sub" / "b.nc"
    write_dataset(ds, p1)
    write_dataset(read_dataset(p1), p2)
    write_dataset(ds, tmp_path / "c.nc")
    assert (tmp_path / "c.nc").read_bytes() == p1.read_bytes()
    back = read_dataset(p1)
    for name, var in back.variables.items():
        assert "long_name" in var.attrs and "units" in var.attrs, name
    assert back.attrs["Conventions"].startswith("CF-1.")
    for k in ("vines_version", "git_commit", "config_sha256", "code_version", "solver_t_end"):
        assert k in back.attrs
    assert not any(re.search(r"\d{4}-\d\d-\d\dT", str(v)) for v in back.attrs.values())
    assert tuple(back["ke_ratio"].dims) == ("eta", "omega", "F")
    assert back["regime"].dtype.kind in "OU" and back["regime"].values.ravel()[0] != ""
    assert back["section_F"].values.tolist() == [0, 1]
    enc = back["ke_ratio"].encoding
    assert enc.get("zlib") and enc.get("chunksizes")
    for k in BATCH_FIELDS:
        np.testing.assert_array_equal(back[k].values, ds[k].values)
    # no temp file left behind; permissions of an ordinary new file (umask), not mkstemp's 0600
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.nc", "c.nc", "sub"]
    mask = os.umask(0)
    os.umask(mask)
    assert p1.stat().st_mode & 0o777 == 0o666 & ~mask


def test_write_removes_the_temporary_of_a_killed_write(tmp_path):
    """A write killed by SIGKILL leaves its temporary (.x.nc.<random>.tmp): the next write of
    that dataset removes it; another dataset's temporary is not touched."""
    stale, other = tmp_path / ".x.nc.k1l2e3d4.tmp", tmp_path / ".x.nc2.k1l2e3d4.tmp"
    for p in (stale, other):
        p.write_bytes(b"half a dataset")
    ds = xr.Dataset({"x": ("n", [1.0], {"long_name": "x", "units": "1"})})
    write_dataset(ds, tmp_path / "x.nc")
    assert sorted(p.name for p in tmp_path.iterdir()) == [other.name, "x.nc"]


def test_write_refuses_variables_without_units(tmp_path):
    ds = xr.Dataset({"x": ("n", [1.0], {"long_name": "x"})})
    with pytest.raises(ValueError, match="long_name/units"):
        write_dataset(ds, tmp_path / "x.nc")
    assert list(tmp_path.iterdir()) == []


def test_ragged_round_trip(tmp_path):
    rs = [2, 0, 3]
    ds = ragged_dataset({"value": ([0.1, 0.2, 0.3], "v", "1")},
                        {"dw": (np.arange(5.0), "w", "1")}, rs, instance_dim="point",
                        sample_dim="impact", attrs={"Conventions": "CF-1.10"})
    write_dataset(ds, tmp_path / "r.nc")
    back = read_dataset(tmp_path / "r.nc")
    assert back["row_size"].attrs["sample_dimension"] == "impact"
    rows = ragged_rows(back, "dw")
    assert [r.tolist() for r in rows] == [[0.0, 1.0], [], [2.0, 3.0, 4.0]]


# ------------------------------------------------------------------ snakemake: plans and reruns

TINY = {
    "run": "tiny", "chunks": {"simulate_grid": 3}, "block_size": 2, "threads": 1,
    "simulation": {"t_end": 120.0, "t_transient": 60.0},
    "grids": {
        "gA": {"axes": {"eta": [0.05, 0.1, 0.2]}, "fixed": {"omega": 1.0, "F": 0.1}},
        "gB": {"axes": {"eta": [0.1, 0.3], "F": [0.2, 0.4]}, "fixed": {"omega": 1.0},
               "sections": {"F": [0.4]}},
    },
    "sweeps": {"sw": {"param": "eta", "values": [0.05, 0.1], "outer": "F", "outer_values": [0.1],
                      "fixed": {"omega": 1.0}, "t_settle": 60.0, "t_step": 20.0, "n_record": 2}},
    "timehistories": {"th": {"points": [{"eta": 0.05, "omega": 1.0, "F": 0.05}],
                             "n_periods": 2, "samples_per_period": 8}},
}


def _copy_workflow(dst: Path, with_src_copy=False):
    shutil.copy(ROOT / "Snakefile", dst / "Snakefile")
    shutil.copy(ROOT / "environment.yml", dst / "environment.yml")   # the rules' conda env
    shutil.copytree(ROOT / "profiles" / "default", dst / "profiles" / "default")  # read by every run
    shutil.copytree(ROOT / "workflow", dst / "workflow",
                    ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(ROOT / "config", dst / "config")
    shutil.copy(ROOT / "environment.yml", dst / "environment.yml")   # the rules' conda env
    if with_src_copy:   # a private copy of the sources (keeps the numba cache: copy2 mtimes)
        shutil.copytree(ROOT / "src", dst / "src", ignore=shutil.ignore_patterns("*.egg-info"))
    else:
        (dst / "src").symlink_to(ROOT / "src", target_is_directory=True)


def _smk(cwd, *args, cfg=None, check=True):
    cmd = [SNAKEMAKE, "-c2", "--directory", str(cwd), "--snakefile", str(cwd / "Snakefile"),
           *args]
    if cfg is not None:     # last: --configfile takes every file name that follows it
        (cwd / "cfg.yaml").write_text(yaml.safe_dump(cfg))
        cmd += ["--configfile", str(cwd / "cfg.yaml")]
    r = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, timeout=600)
    if check and r.returncode != 0:
        raise AssertionError(f"snakemake failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r


def _planned(r) -> dict:
    """{rule: count} from a dry-run's job stats table."""
    out = r.stdout + r.stderr
    if "Nothing to be done" in out:
        return {}
    m = re.search(r"Job stats:\n.*?\n-+\s+-+\n(.*?)\ntotal", out, re.S)
    assert m, out
    return {ln.split()[0]: int(ln.split()[1]) for ln in m.group(1).strip().splitlines()}


@needs_snakemake
def test_bad_config_stops_before_any_job(tmp_path):
    _copy_workflow(tmp_path)
    cfg = dict(TINY, simulation={"t_end": -5.0})
    r = _smk(tmp_path, "-n", cfg=cfg, check=False)
    assert r.returncode != 0
    assert "simulation.t_end" in r.stderr + r.stdout
    assert "Traceback" not in r.stderr
    assert not (tmp_path / "results").exists()


@needs_snakemake
def test_dry_run_plans_the_full_study_and_the_smoke_run(tmp_path):
    _copy_workflow(tmp_path)
    full = _planned(_smk(tmp_path, "-n"))
    cfg = _validated(yaml.safe_load((ROOT / "config" / "config.yaml").read_text()))
    size = cfg["chunks"]["simulate_grid"]
    n_chunks = sum(len(chunk_map(grid_axes(g), size)) for g in cfg["grids"].values())
    assert full["simulate_grid"] == n_chunks
    assert full["extract_measures"] == len(cfg["grids"])
    assert full["bifurcation_sweep"] == len(cfg["sweeps"])
    assert full["timehistory"] == len(cfg["timehistories"])
    assert full["map_solve"] == len(cfg["branches"])
    assert full["stability_map"] == len(cfg["stability_maps"])
    assert full["boundaries"] == len(cfg["boundaries"])
    assert all(len(c["eta"]) * len(c["omega"]) * len(c["F"]) <= size
               for g in cfg["grids"].values() for c in grid_chunks(grid_axes(g), size))
    smoke = _planned(_smk(tmp_path, "-n", "--configfile", str(tmp_path / "config" / "smoke.yaml")))
    assert set(smoke) == set(full)          # same DAG, tiny grids
    # the default target `paper`: Figs 2-16 and the stages behind them, nothing beyond
    assert {f"fig{n}" for n in range(2, 17)} <= set(full)
    beyond = set(BEYOND_PAPER)
    assert not beyond & set(full) and "all" not in full
    # `all`: every stage and figure besides
    everything = _planned(_smk(tmp_path, "-n", "all"))
    assert beyond <= set(everything)
    assert {"fig3_lyapunov", "fig14_regimes", "fig_robust_tet", "fig_atlas", "fig_design",
            "fig_design_robust", "fig_workprecision", "fig_convergence", "fig_basin_slices",
            "fig_shock", "fig_model_ladder"} <= set(everything)
    assert all(everything[rule] == n for rule, n in full.items() if rule != "paper")
    # the chunked stages: many jobs an entry (config chunks), one gather an entry
    for stage, section in CHUNKED_STAGES.items():
        jobs = sum(len(chunk_plan(stage, name, cfg)) for name in cfg[section])
        assert everything[f"{stage}_chunk"] == jobs > everything[stage], stage
        assert everything[stage] == len(cfg[section])


@needs_snakemake
def test_reruns_only_what_changed(tmp_path):
    _copy_workflow(tmp_path, with_src_copy=True)
    _smk(tmp_path, cfg=TINY)
    out = tmp_path / "results" / "tiny"
    ds = read_dataset(out / "extract_measures" / "gB.nc")
    assert ds["ke_ratio"].shape == (2, 1, 2) and ds["section_F"].values.tolist() == [0, 1]
    sw = read_dataset(out / "bifurcation_sweep" / "sw.nc")
    assert sw["row_size"].attrs["sample_dimension"] == "impact"
    assert _planned(_smk(tmp_path, "-n", cfg=TINY)) == {}

    # rerunning a job rewrites a byte-identical file
    chunk = sorted((out / "simulate_grid" / "gA").glob("chunk_*.nc"))[0]
    before = chunk.read_bytes()
    _smk(tmp_path, "--forcerun", "simulate_grid", "--until", "simulate_grid", cfg=TINY)
    assert chunk.read_bytes() == before

    # extend one grid: only its new chunk and its dependents
    cfg = yaml.safe_load(yaml.safe_dump(TINY))
    cfg["grids"]["gA"]["axes"]["eta"] = [0.05, 0.1, 0.2, 0.3]
    assert _planned(_smk(tmp_path, "-n", cfg=cfg)) == {
        "simulate_grid": 1, "extract_measures": 1, "paper": 1}

    # one config section: the simulation settings -> grid chunks, measures, time histories
    cfg = yaml.safe_load(yaml.safe_dump(TINY))
    cfg["simulation"]["v_stick"] = 2e-6
    plan = _planned(_smk(tmp_path, "-n", cfg=cfg))
    assert plan == {"simulate_grid": 3, "extract_measures": 2, "timehistory": 1, "paper": 1}
    # ...the sweep section -> only the sweep
    cfg = yaml.safe_load(yaml.safe_dump(TINY))
    cfg["sweeps"]["sw"]["n_record"] = 3
    assert _planned(_smk(tmp_path, "-n", cfg=cfg)) == {"bifurcation_sweep": 1, "paper": 1}
    # settings that do not change any number do not rerun anything
    cfg = yaml.safe_load(yaml.safe_dump(TINY))
    cfg.update(block_size=7, threads=2)
    assert _planned(_smk(tmp_path, "-n", cfg=cfg)) == {}

    # touching (or checking out) an unchanged script reruns nothing: scripts are tracked by
    # content (param `script`), not by Snakemake's mtime check (docs/pipeline.md)
    later = time.time() + 60
    for name in ("simulate_grid.py", "timehistory.py"):
        os.utime(tmp_path / "workflow" / "scripts" / name, (later, later))
    assert _planned(_smk(tmp_path, "-n", cfg=TINY)) == {}

    # editing one script reruns only its rule
    script = tmp_path / "workflow" / "scripts" / "timehistory.py"
    script.write_text(script.read_text() + "\n# edited\n")
    assert _planned(_smk(tmp_path, "-n", cfg=TINY)) == {"timehistory": 1, "paper": 1}
    _smk(tmp_path, cfg=TINY)

    # a change of the numerics (a vines.core source) reruns every computation
    flow = tmp_path / "src" / "vines" / "core" / "flow.py"
    original = flow.read_text()
    flow.write_text(original + "\n# edited\n")
    plan = _planned(_smk(tmp_path, "-n", cfg=TINY))
    assert plan == {"simulate_grid": 3, "extract_measures": 2, "bifurcation_sweep": 1,
                    "timehistory": 1, "paper": 1}
    flow.write_text(original)
    # ...a change of a non-computing source (CLI) does not

    cli = tmp_path / "src" / "vines" / "cli" / "common.py"
    cli.write_text(cli.read_text() + "\n# edited\n")
    assert _planned(_smk(tmp_path, "-n", cfg=TINY)) == {}


@pytest.mark.slow   # fast suite: test_reruns_only_what_changed plans one missing chunk alone;
@needs_snakemake    # CI: tests/fault_injection.py kills a real run 3 times
def test_killed_run_keeps_finished_chunks(tmp_path):
    """An interrupted run restarts with only the unfinished chunks (no partial files)."""
    _copy_workflow(tmp_path)
    cfg = dict(TINY, grids={"gA": TINY["grids"]["gA"]}, sweeps={}, timehistories={})
    _smk(tmp_path, "--until", "simulate_grid", cfg=cfg)
    done = sorted((tmp_path / "results" / "tiny" / "simulate_grid" / "gA").glob("chunk_*.nc"))
    done[0].unlink()          # as if that job had been killed (atomic writes: no partial file)
    assert _planned(_smk(tmp_path, "-n", cfg=cfg)) == {
        "simulate_grid": 1, "extract_measures": 1, "paper": 1}


def test_distributed_scheduler_gives_identical_numbers():
    distributed = pytest.importorskip("distributed")
    chunk = {"eta": [0.05, 0.2], "omega": [1.0], "F": [0.1, 0.3077]}
    ref = compute_chunk(chunk, model=MODEL, simulation=SHORT, n_workers=1, block_size=1)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster:
        got = compute_chunk(chunk, model=MODEL, simulation=SHORT, block_size=3,
                            scheduler=cluster.scheduler_address)
    for k in BATCH_FIELDS:
        np.testing.assert_array_equal(got[k], ref[k], err_msg=k)


@needs_snakemake
def test_damaged_chunk_is_named_and_recomputed_after_removal(tmp_path):
    _copy_workflow(tmp_path)
    cfg = {k: v for k, v in TINY.items() if k in ("run", "chunks", "block_size", "threads",
                                                   "simulation")}
    cfg["grids"] = {"gA": TINY["grids"]["gA"]}
    _smk(tmp_path, cfg=cfg)
    out = tmp_path / "results" / "tiny"
    measures = out / "extract_measures" / "gA.nc"
    before = read_dataset(measures)
    chunk = sorted((out / "simulate_grid" / "gA").glob("chunk_*.nc"))[0]
    data = chunk.read_bytes()
    chunk.write_bytes(data[: len(data) // 2])
    r = _smk(tmp_path, cfg=cfg, check=False)
    msg = r.stdout + r.stderr
    assert r.returncode != 0 and str(chunk.relative_to(tmp_path)) in msg and "rm " in msg
    assert "Traceback" not in msg
    assert measures.exists()                      # nothing valid was deleted
    chunk.unlink()        # the command the message gives, then the same command again
    _smk(tmp_path, cfg=cfg)
    assert read_dataset(chunk)["ke_ratio"].size == 3          # recomputed
    assert measures.stat().st_mtime > chunk.stat().st_mtime   # and the measures after it
    after = read_dataset(measures)
    for k in BATCH_FIELDS:
        np.testing.assert_array_equal(after[k].values, before[k].values)


def _datasets(out: Path) -> dict:
    """{relative path: {variable: values}} of every dataset of a results tree."""
    got = {}
    for p in sorted(out.rglob("*.nc")):
        with xr.open_dataset(p) as ds:
            got[str(p.relative_to(out))] = {k: ds[k].values.copy() for k in ds.variables}
    return got


@needs_snakemake
@pytest.mark.slow
def test_a_killed_run_completes_after_the_readme_steps(tmp_path):
    """SIGKILL mid-run, then the README's steps (`snakemake --unlock`, the same command
    again): a complete run with the numbers of an uninterrupted one."""
    import signal
    import time
    cfg = {k: v for k, v in TINY.items() if k != "timehistories"}
    cfg["simulation"] = {"t_end": 2000.0, "t_transient": 1000.0}
    ref, run = tmp_path / "ref", tmp_path / "run"
    for d in (ref, run):
        d.mkdir()
        _copy_workflow(d)
    _smk(ref, cfg=cfg)
    (run / "cfg.yaml").write_text(yaml.safe_dump(cfg))
    cmd = [SNAKEMAKE, "-c2", "--directory", str(run), "--snakefile", str(run / "Snakefile"),
           "--configfile", str(run / "cfg.yaml")]
    proc = subprocess.Popen(cmd, cwd=run, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    deadline = time.monotonic() + 300
    while not list((run / "results").rglob("*.nc")) and time.monotonic() < deadline:
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    _smk(run, "--unlock", cfg=cfg)
    _smk(run, cfg=cfg)
    a, b = _datasets(ref / "results" / "tiny"), _datasets(run / "results" / "tiny")
    assert a.keys() == b.keys()
    for name in a:
        for k in a[name]:
            np.testing.assert_array_equal(a[name][k], b[name][k], err_msg=f"{name}: {k}")
