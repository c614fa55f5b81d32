# Config validation (with defaults), grid chunks and code versions, all at parse time so
# the DAG is static. Helpers live in vines.pipeline (tested without snakemake).
import glob
import os
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
from vines.data.netcdf import unreadable_datasets
from vines.pipeline.axes import chunk_map, grid_axes
from vines.pipeline.codeversion import (
    ATTRACTORS,
    COMPUTE,
    FIGURES,
    STUDIES,
    code_version,
)
from vines.pipeline.config import ConfigError, load_schema, validate_config

try:
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
CODE_FIGURES = code_version(FIGURES)

GRIDS = config["grids"]
AXES = {name: grid_axes(g, key=f"grids.{name}") for name, g in GRIDS.items()}
CHUNKS = {name: chunk_map(AXES[name], config["chunk_size"]) for name in GRIDS}
SWEEPS = config["sweeps"]
BRANCHES = config["branches"]
SMAPS = config["stability_maps"]
BOUNDARIES = config["boundaries"]
THIST = config["timehistories"]
ROBUST = config["robust_maps"]
SLICES = config["basin_slices"]
WPREC = config["work_precision"]
WPREC_SETTINGS = {k: v for k, v in WPREC.items() if k != "cases"}
CONV = config["convergence"]

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
    sweep="[A-Za-z0-9_.-]+",
    branch="[A-Za-z0-9_.-]+",
    smap="[A-Za-z0-9_.-]+",
    bnd="[A-Za-z0-9_.-]+",
    th="[A-Za-z0-9_.-]+",
    rmap="[A-Za-z0-9_.-]+",
    bslice="[A-Za-z0-9_.-]+",


def chunk_files(wildcards):
    return [f"{RES}/grid/{wildcards.grid}/chunk_{k}.nc" for k in CHUNKS[wildcards.grid]]


def boundaries_seed_map(wildcards):
    """The stability map whose class changes seed the boundary curves (key stability_map)."""
    name = BOUNDARIES[wildcards.bnd].get("stability_map")
    return [f"{RES}/stability/{name}.nc"] if name else []


def all_datasets():
    out = [f"{RES}/measures/{g}.nc" for g in GRIDS]
    out += [f"{RES}/sweeps/{s}.nc" for s in SWEEPS]
    out += [f"{RES}/branches/{b}.nc" for b in BRANCHES]
    out += [f"{RES}/stability/{m}.nc" for m in SMAPS]
    out += [f"{RES}/boundaries/{b}.nc" for b in BOUNDARIES]
    out += [f"{RES}/timehistories/{t}.nc" for t in THIST]
    out += [f"{RES}/robust/{m}.nc" for m in ROBUST]
    out += [f"{RES}/basins/{s}.nc" for s in SLICES]
    out += [f"{RES}/workprecision/{c}.nc" for c in WPREC["cases"]]
    out += [f"{RES}/convergence/{s}.nc" for s in CONV]
    return out
