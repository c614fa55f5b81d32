# Config validation (with defaults), grid chunks and code version, all at parse time so
# the DAG is static. Helpers live in vines.pipeline.stages (tested without snakemake).
import importlib.util
import os
import sys

# Use the vines of this checkout (src layout) whatever copy happens to be installed, here
# and in every job (workflow/scripts/_checkout.py): the code version below is the hash of
# exactly the sources that run.
_SRC = os.path.join(workflow.basedir, "src")
if os.path.isdir(os.path.join(_SRC, "vines")):
    sys.path.insert(0, _SRC)

from vines.core.params import D_DEFAULT
from vines.pipeline.stages import (NON_COMPUTE_SOURCES, STUDY_SOURCES, ConfigError, chunk_map,
                            code_version, grid_axes, load_schema, validate_config)

try:
    validate_config(config, load_schema(workflow.source_path("../schemas/config.schema.yaml")))
except ConfigError as err:
    sys.exit(f"vines pipeline: {err}")


RES = f"results/{config['run']}"
# d = null means the Table 1 value c/(M w0) to full precision (not a rounded 0.011998)
MODEL = {"r": config["model"]["r"],
         "d": D_DEFAULT if config["model"]["d"] is None else config["model"]["d"]}
SIMULATION = dict(config["simulation"])
# sha256 of the vines sources used by the computations: a param of every compute rule, so
# a change of the numerics reruns them (Snakemake does not track imported modules).
CODE = code_version(exclude=NON_COMPUTE_SOURCES + STUDY_SOURCES)
# the solver studies (work-precision, convergence) also use the RK reference and hiprec
CODE_STUDY = code_version(exclude=tuple(set(NON_COMPUTE_SOURCES) - {"reference.py"}))

GRIDS = config["grids"]
AXES = {name: grid_axes(g, key=f"grids.{name}") for name, g in GRIDS.items()}
CHUNKS = {name: chunk_map(AXES[name], config["chunk_size"]) for name in GRIDS}
SWEEPS = config["sweeps"]
BRANCHES = config["branches"]
SMAPS = config["stability_maps"]
THIST = config["timehistories"]
WPREC = config["work_precision"]
WPREC_SETTINGS = {k: v for k, v in WPREC.items() if k != "cases"}
CONV = config["convergence"]


def _have(module):
    try:
        return importlib.util.find_spec(module) is not None
    except ImportError:
        return False


# map-solve / stability-map call vines.orbits.continuation / vines.orbits.stability_map; until those
# modules exist their outputs are left out of `all` (with a warning), not faked.
HAVE_CONTINUATION = _have("vines.orbits.continuation")
HAVE_STABILITY_MAP = _have("vines.orbits.stability_map")
if BRANCHES and not HAVE_CONTINUATION:
    print("vines pipeline: warning: vines.orbits.continuation not available, map-solve outputs "
          "are not requested", file=sys.stderr)
if SMAPS and not HAVE_STABILITY_MAP:
    print("vines pipeline: warning: vines.orbits.stability_map not available, stability-map "
          "outputs are not requested", file=sys.stderr)


wildcard_constraints:
    grid="[A-Za-z0-9_.-]+",
    key="[0-9a-f]{16}",
    sweep="[A-Za-z0-9_.-]+",
    branch="[A-Za-z0-9_.-]+",
    smap="[A-Za-z0-9_.-]+",
    th="[A-Za-z0-9_.-]+",


def chunk_files(wildcards):
    return [f"{RES}/grid/{wildcards.grid}/chunk_{k}.nc" for k in CHUNKS[wildcards.grid]]


def all_datasets():
    out = [f"{RES}/measures/{g}.nc" for g in GRIDS]
    out += [f"{RES}/sweeps/{s}.nc" for s in SWEEPS]
    if HAVE_CONTINUATION:
        out += [f"{RES}/branches/{b}.nc" for b in BRANCHES]
    if HAVE_STABILITY_MAP:
        out += [f"{RES}/stability/{m}.nc" for m in SMAPS]
    out += [f"{RES}/timehistories/{t}.nc" for t in THIST]
    out += [f"{RES}/workprecision/{c}.nc" for c in WPREC["cases"]]
    out += [f"{RES}/convergence/{s}.nc" for s in CONV]
    return out
