# Config validation (with defaults), grid chunks and code versions, all at parse time so
# the DAG is static. Helpers live in vines.pipeline (tested without snakemake).
import glob
import os
import re
import sys

# The vines of this checkout (src layout) runs, whatever copy is installed: first on
# sys.path here and, through PYTHONPATH (ahead of site-packages), in every job, so the
# code versions below are hashes of exactly the sources that run.
_SRC = os.path.join(workflow.basedir, "src")
sys.path.insert(0, _SRC)
os.environ.update(
    PYTHONPATH=os.pathsep.join(
        [_SRC]
        + [
            p
            for p in os.environ.get("PYTHONPATH", "").split(os.pathsep)
            if p and p != _SRC
        ]
    )
)

from vines.core.params import D_DEFAULT
from vines.data.netcdf import unreadable_datasets, unwritable_folder
from vines.pipeline.axes import chunk_map, grid_axes
from vines.pipeline.codeversion import (
    ATTRACTORS,
    COMPUTE,
    DESIGN,
    FIGURES,
    MODELS,
    STUDIES,
    code_version,
    script_version,
)
from vines.pipeline.config import (
    ConfigError,
    load_schema,
    load_yaml,
    move_chunk_size,
    validate_config,
)
from vines.pipeline.parts import CHUNKED_STAGES, chunk_plan
from vines.pipeline.config_checks import atlas_grid, boundary_family

try:
    # Snakemake's YAML reading keeps the last of a key given twice: refuse that first
    for _path in workflow.config_settings.configfiles or ["config/config.yaml"]:
        load_yaml(_path)
    _NOTE = move_chunk_size(config)
    if _NOTE:
        print(_NOTE, file=sys.stderr)
    validate_config(config, load_schema())
except ConfigError as err:
    sys.exit(f"vines pipeline: {err}")


RES = f"results/{config['run']}"
# d = null means the Table 1 value c/(M w0) to full precision (not a rounded 0.011998)
MODEL = {
    "r": config["model"]["r"],
    "d": D_DEFAULT if config["model"]["d"] is None else config["model"]["d"],
}
SIMULATION = dict(config["simulation"])
# Code versions (sha256 of the vines subpackages each kind of rule depends on) are params
# of the rules, so editing a subpackage reruns exactly the rules that depend on it
# (Snakemake does not track imported modules).
CODE = code_version(COMPUTE)
CODE_STUDY = code_version(STUDIES)
CODE_ATTRACTORS = code_version(ATTRACTORS)
CODE_DESIGN = code_version(DESIGN)
CODE_FIGURES = code_version(FIGURES)
CODE_MODELS = code_version(MODELS)
SCRIPTS = os.path.join(workflow.basedir, "workflow", "scripts")


def script_of(script):
    """A rule's script param: the hash of the contents of workflow/scripts/<script>, so that
    an edit reruns its jobs and a touch or checkout does not (the profile's rerun-triggers
    leave out Snakemake's script-mtime check; docs/pipeline.md)."""
    return script_version(os.path.join(SCRIPTS, script))


GRIDS = config["grids"]
AXES = {name: grid_axes(g, key=f"grids.{name}") for name, g in GRIDS.items()}
CHUNKS = {
    name: chunk_map(AXES[name], config["chunks"]["simulate_grid"]) for name in GRIDS
}
SWEEPS = config["sweeps"]
LYAPUNOV_SWEEPS = config["lyapunov_sweeps"]
BRANCHES = config["branches"]
STABILITY_MAPS = config["stability_maps"]
BOUNDARIES = config["boundaries"]
TIMEHISTORIES = config["timehistories"]
ROBUST_MAPS = config["robust_maps"]
BASIN_SLICES = config["basin_slices"]
WORK_PRECISION = config["work_precision"]
WORK_PRECISION_SETTINGS = {k: v for k, v in WORK_PRECISION.items() if k != "cases"}
CONVERGENCE = config["convergence"]
DESIGNS = config["designs"]
DESIGN_ROBUST = config["design_robust"]
UNCERTAINTY = config["uncertainty"]
ORBIT_ATLASES = config["orbit_atlases"]
SHOCKS = config["shocks"]
MODEL_LADDERS = config["model_ladders"]
DESIGN_MAPS = config["design_maps"]

# A results folder that cannot be written (permissions, a read-only disk, a file in the
# way) would fail every job: stop before any job, in one line.
_UNWRITABLE = unwritable_folder(RES)
if _UNWRITABLE:
    sys.exit(
        f"vines pipeline: cannot write the results folder {RES}: {_UNWRITABLE}; make it "
        "writable (or move what is in the way), then run the same command again"
    )

# A damaged dataset (a truncated chunk, a disk error) would look finished to Snakemake:
# stop before any job, naming the file and the command that recomputes it.
_DAMAGED = unreadable_datasets(sorted(glob.glob(f"{RES}/**/*.nc", recursive=True)))
if _DAMAGED:
    path, reason = _DAMAGED[0]
    sys.exit(
        f"vines pipeline: {path} cannot be read {reason} ({len(_DAMAGED)} damaged "
        f"file(s)); remove it to recompute it: rm {' '.join(p for p, _ in _DAMAGED)}"
    )


wildcard_constraints:
    grid="[A-Za-z0-9_.-]+",
    key="[0-9a-f]{16}",
    name="[A-Za-z0-9_.-]+",
    k="[0-9]+",


# Result paths: every stage writes results/<run>/<rule>/<entry>.nc (the folder is named
# after the rule), its log to logs/<rule>/ and its benchmark to benchmarks/<rule>/; the
# entry is the wildcard {name} (the config entry's name) unless given.
def dataset(stage, name="{name}"):
    return f"{RES}/{stage}/{name}.nc"


def job_log(stage, name="{name}"):
    return f"{RES}/logs/{stage}/{name}.log"


def job_benchmark(stage, name="{name}"):
    return f"{RES}/benchmarks/{stage}/{name}.tsv"


# Resources of a compute job (`resources: mem_mb=..., runtime=...` in each stage rule, the
# one place they are set): memory in MB and wall time in minutes, the full study's peaks
# (the jobs' benchmark files) with a margin, remade by benchmarks/rule_resources.py
# (docs/performance.md). Each retry of a job gets them once more (a job a cluster killed
# for running over its memory or time would fail the same way again).
def per_attempt(value):
    return lambda wildcards, attempt: value * attempt


# Threads of a compute job: the config's `threads`, a number or `max` (every core of
# `-c N`, read per job as work_precision does: commands without a core count give 1).
def job_threads(wildcards):
    if config["threads"] == "max":
        return workflow.resource_settings.cores or 1
    return config["threads"]


def chunk_files(wildcards):
    return [
        dataset("simulate_grid", f"{wildcards.name}/chunk_{k}")
        for k in CHUNKS[wildcards.name]
    ]


def boundaries_seed_map(wildcards):
    """The stability map whose class changes seed the boundary curves (key stability_map)."""
    name = BOUNDARIES[wildcards.name].get("stability_map")
    return [dataset("stability_map", name)] if name else []


#: stage -> the config entries it makes one dataset of
STAGE_ENTRIES = {
    "extract_measures": GRIDS,
    "bifurcation_sweep": SWEEPS,
    "lyapunov": LYAPUNOV_SWEEPS,
    "map_solve": BRANCHES,
    "stability_map": STABILITY_MAPS,
    "boundaries": BOUNDARIES,
    "timehistory": TIMEHISTORIES,
    "robust_map": ROBUST_MAPS,
    "basin_slice": BASIN_SLICES,
    "work_precision": WORK_PRECISION["cases"],
    "convergence": CONVERGENCE,
    "design": DESIGNS,
    "design_robust": DESIGN_ROBUST,
    "uncertainty": UNCERTAINTY,
    "orbit_atlas": ORBIT_ATLASES,
    "shock": SHOCKS,
    "model_ladder": MODEL_LADDERS,
    "design_map": DESIGN_MAPS,
}


#: the stages behind the paper's figures (rule `paper`, the default target); the others
#: (Lyapunov exponents, attractor censuses, solver studies, design, design_robust,
#: uncertainty, orbit atlas, shock, model ladder) go beyond the paper and run with rule `all`
PAPER_STAGES = (
    "extract_measures",
    "bifurcation_sweep",
    "map_solve",
    "stability_map",
    "boundaries",
    "timehistory",
)


def all_datasets(stages=tuple(STAGE_ENTRIES)):
    """Every configured dataset of ``stages`` (grid chunks with extract_measures)."""
    # the chunks too: a chunk removed (the remedy for a damaged one) is then recomputed
    # by the same command, and the measures after it
    chunks = []
    if "extract_measures" in stages:
        chunks = [
            dataset("simulate_grid", f"{g}/chunk_{k}") for g in GRIDS for k in CHUNKS[g]
        ]
    return chunks + [
        dataset(stage, n) for stage in stages for n in STAGE_ENTRIES[stage]
    ]


# The chunked stages (vines.pipeline.parts): the item ranges of every entry's chunk jobs
# (config `chunks`), each job writing results/<run>/<stage>/<entry>/chunk_<k>.pkl (a
# temporary file, removed once the stage's gather job has written the entry's dataset).
PARTS = {
    stage: {name: chunk_plan(stage, name, config) for name in STAGE_ENTRIES[stage]}
    for stage in CHUNKED_STAGES
}


def part_file(stage, name="{name}", k="{k}"):
    return f"{RES}/{stage}/{name}/chunk_{k}.pkl"


def part_files(stage):
    """Input function of a gather: the part files of the entry's chunk jobs, in order."""
    return lambda w: [
        part_file(stage, w.name, k) for k in range(len(PARTS[stage][w.name]))
    ]


def part_range(stage):
    """Param function of a chunk job: its (start, stop) items of the entry."""
    return lambda w: PARTS[stage][w.name][int(w.k)]
