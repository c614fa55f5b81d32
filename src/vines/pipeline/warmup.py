"""Compile the numba kernels once per install, before the jobs of a run start.

numba compiles a kernel on its first call and keeps the machine code in the package's
``__pycache__`` (``cache=True``). Without a warm cache every job that starts before the cache
exists compiles the kernels it calls (15-30 s a job, the same kernels in parallel jobs).
The workflow's ``onstart`` hook (workflow/rules/warmup.smk) runs ``python -m
vines.pipeline.warmup`` once before the first job: it calls every stage's numerics on one
tiny case, in two processes (core and attractor kernels; orbit kernels), with the run's
model and simulation settings (the same argument types as the jobs), and writes a stamp.
The stamp holds the hash of the compiled subpackages' sources (``vines._numba_cache``) and
the numba version and CPU: while they match, the warm-up costs one file read; an edit of
core/ or orbits/ deletes the cache (``_numba_cache.refresh``) and the next run compiles again.
A kernel a tiny case does not reach is compiled by the first job that calls it, as before.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

PKG_DIR = Path(__file__).resolve().parents[1]
STAMP = PKG_DIR / "__pycache__" / "numba-warm.txt"

#: one tiny case per stage (the smoke config's shapes, one point each)
POINT = {"eta": 0.2, "omega": 0.9, "F": 0.4}
TINY = {
    "sweep": {"param": "eta", "values": [0.05, 0.1], "outer": "F", "outer_values": [0.05],
              "directions": ["up"], "fixed": {"omega": 1.0}, "t_settle": 400.0,
              "t_step": 100.0, "n_record": 5},
    "timehistory": {"points": [POINT], "n_periods": 2, "samples_per_period": 20,
                    "window_samples_per_period": 10},
    "branch": {"param": "eta", "start": 0.01, "stop": 0.06, "step": 0.05,
               "fixed": {"omega": 1.0, "F": 0.05}},
    "stability_map": {"eta": [0.1, 0.5], "omega": [0.9, 1.1], "F": 0.3077},
    "boundaries": {"F": 0.3077, "eta_range": [0.05, 1.0], "omega_range": [0.7, 1.4],
                   "n_scan": 1},
    "robust_map": {"eta": [0.1], "omega": [0.8], "F": 0.2, "n": 2, "seed": 0,
                   "threshold": 0.7},
    "basin_slice": {"eta": 0.1, "omega": 0.8, "F": 0.2, "z_m0": [0.0, 0.5], "v_m0": [0.0]},
}
_LABEL = {"code": "warm-up", "title": "warm-up"}


def warm_stamp() -> str:
    """What a warm cache was compiled for: sources of the compiled subpackages, numba, CPU
    (cheap: reads the sources and asks llvmlite for the CPU, does not import numba)."""
    from importlib.metadata import version

    from llvmlite import binding

    from .._numba_cache import sources_hash
    return (f"{sources_hash(PKG_DIR)} numba {version('numba')} "
            f"cpu {binding.get_host_cpu_name()}\n")


def is_warm() -> bool:
    """True if the cache was warmed for these sources, this numba and this CPU."""
    try:
        return STAMP.read_text() == warm_stamp()
    except OSError:
        return False


def _core_and_attractors(model: dict, simulation: dict) -> None:
    from . import stages
    stages.compute_chunk({"eta": [POINT["eta"]], "omega": [POINT["omega"]], "F": [POINT["F"]]},
                         model=model, simulation=simulation)
    stages.compute_sweep({**TINY["sweep"], "v_stick": simulation["v_stick"]}, model=model,
                         periodic_shortcut=simulation["periodic_shortcut"])
    stages.timehistory(TINY["timehistory"], model=model, simulation=simulation, **_LABEL)
    stages.robust_map(TINY["robust_map"], model=model, simulation=simulation, **_LABEL)
    stages.basin_slice(TINY["basin_slice"], model=model, simulation=simulation, **_LABEL)


def _orbits(model: dict, simulation: dict) -> None:
    from . import stages
    stages.map_solve(TINY["branch"], model=model, **_LABEL)
    stages.stability_map(TINY["stability_map"], model=model, **_LABEL)
    stages.boundaries(TINY["boundaries"], model=model, **_LABEL)


GROUPS = (_core_and_attractors, _orbits)


def warm(model: dict, simulation: dict, n_workers: int = 2) -> float:
    """Compile the kernels (``GROUPS`` in ``n_workers`` processes), write the stamp; seconds."""
    t0 = time.perf_counter()
    if n_workers > 1:
        with ProcessPoolExecutor(min(n_workers, len(GROUPS))) as pool:
            for f in [pool.submit(g, model, simulation) for g in GROUPS]:
                f.result()
    else:
        for g in GROUPS:
            g(model, simulation)
    STAMP.parent.mkdir(exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=STAMP.parent, prefix=f".{STAMP.name}.")
    with os.fdopen(fd, "w") as fh:
        fh.write(warm_stamp())
    os.replace(tmp, STAMP)
    return time.perf_counter() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m vines.pipeline.warmup",
                                 description="Compile vines' numba kernels into the cache.")
    ap.add_argument("--model", required=True, help="the run's model section (JSON)")
    ap.add_argument("--simulation", required=True, help="the run's simulation section (JSON)")
    ap.add_argument("-j", "--jobs", type=int, default=2, help="processes (default 2)")
    args = ap.parse_args(argv)
    if is_warm():
        return 0
    print("vines: compiling the numba kernels once for this install (about a minute on "
          "2 cores; later runs reuse them)...", file=sys.stderr, flush=True)
    seconds = warm(json.loads(args.model), json.loads(args.simulation), max(1, args.jobs))
    print(f"vines: kernels compiled in {seconds:.0f} s", file=sys.stderr, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
