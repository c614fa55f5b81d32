"""Compile the numba kernels once per install, before the jobs of a run start.

numba compiles a kernel on its first call and keeps the machine code in the package's
``__pycache__`` (``cache=True``). Without a warm cache every job that starts before the cache
exists compiles the kernels it calls (15-30 s a job, the same kernels in parallel jobs).
The workflow's ``onstart`` hook (workflow/rules/warmup.smk) runs ``python -m
vines.pipeline.warmup`` once before the first job: it calls every stage's numerics on one
tiny case (``TASKS``: core kernel and shortcut, 1:1 seeds, the shooting systems' jets,
branches, stability map columns and boundaries, attractor census, Lyapunov tangents,
period-n atlas, the jet chain of the other families' curves), spread over the run's cores (a task that reuses another's kernels starts
once those are cached), with the run's model and simulation settings (the same argument
types as the jobs), and writes a stamp.
The stamp holds the hash of the compiled subpackages' sources (``vines._numba_cache``) and
the numba version and CPU: while they match, the warm-up costs one file read; an edit of
core/ or orbits/ deletes the cache (``_numba_cache.refresh``) and the next run compiles again.
A kernel a tiny case does not reach is compiled by the first job that calls it, as before.
"""
from __future__ import annotations

import argparse
import contextlib
import ctypes
import json
import os
import signal
import sys
import tempfile
import threading
import time
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
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
    "lyapunov": {"sweep": "warm-up", "t_window": 100.0, "n_batches": 8},
    "orbit_atlas": {"eta": [0.3077], "omega": [0.9, 1.1], "F": 0.3077, "sim_t_end": 600.0},
}
_LABEL = {"code": "warm-up", "title": "warm-up"}
#: Linux prctl option: the signal a process gets when its parent dies
PR_SET_PDEATHSIG = 1
#: how often a worker checks that the warm-up is still there [s]
POLL_S = 0.2


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


def _core(model: dict, simulation: dict) -> None:
    """The event-driven kernel and the periodic shortcut (simulate_grid, sweeps, time
    histories, basin slices; the single runs of convergence and work_precision)."""
    from ..core.params import ModelParams, SolverSettings
    from ..core.simulation import simulate_exact
    from . import stages
    stages.compute_chunk({"eta": [POINT["eta"]], "omega": [POINT["omega"]], "F": [POINT["F"]]},
                         model=model, simulation=simulation)
    stages.compute_sweep({**TINY["sweep"], "v_stick": simulation["v_stick"]}, model=model,
                         periodic_shortcut=simulation["periodic_shortcut"])
    stages.timehistory(TINY["timehistory"], model=model, simulation=simulation, **_LABEL)
    stages.basin_slice(TINY["basin_slice"], model=model, simulation=simulation, **_LABEL)
    # a single run that takes the periodic shortcut (Fig 4a settles at t = 1663): the
    # kernels the shortcut calls from Python (convergence, work_precision, design)
    st = SolverSettings(t_end=7000.0, t_transient=4000.0,
                        **{k: simulation[k] for k in ("v_stick", "max_impacts", "root_tol")})
    simulate_exact(ModelParams(eta=0.05, omega=1.0, F=0.05, **model), st)


def _robust(model: dict, simulation: dict) -> None:
    """The attractor census (robust_map, design)."""
    from . import stages
    stages.robust_map(TINY["robust_map"], model=model, simulation=simulation, **_LABEL)


def _lyapunov(model: dict, simulation: dict) -> None:
    """The variational (tangent) kernels (lyapunov)."""
    from . import stages
    sweep = {**TINY["sweep"], "v_stick": simulation["v_stick"]}
    stages.lyapunov(TINY["lyapunov"], sweep, model=model,
                    periodic_shortcut=simulation["periodic_shortcut"], **_LABEL)


def _seeds(model: dict, simulation: dict) -> None:
    """The 1:1 maps, seeds and orbit solver that branches and boundaries share."""
    from ..orbits.family.periodic import find_1to1
    find_1to1(**POINT, **model, simulation=False)


def _shooting(model: dict, simulation: dict) -> None:
    """The jet kernel of the 1:1 shooting systems (``kernels.codim1``: continuation
    and boundaries), on its own: it shares no kernel with the others."""
    from ..orbits.jets import shooting
    shooting.residual_jacobian(shooting.Model(model["r"], model["d"]), "symmetric",
                               [0.5, 0.1, 0.0, 0.0], POINT, free=("eta",))


def _branches(model: dict, simulation: dict) -> None:
    """The 1:1 continuation (map_solve) from its seeds."""
    from . import stages
    stages.map_solve(TINY["branch"], model=model, **_LABEL)


def _boundaries(model: dict, simulation: dict) -> None:
    """The stability-map column kernel and the curve tracing (boundaries)."""
    from . import stages
    stages.boundaries(TINY["boundaries"], model=model, **_LABEL)


def _stability_map(model: dict, simulation: dict) -> None:
    """The column kernel of the stability maps."""
    from . import stages
    stages.stability_map(TINY["stability_map"], model=model, **_LABEL)


def _atlas(model: dict, simulation: dict) -> None:
    """The period-n sequence kernels (orbit_atlas)."""
    from . import stages
    stages.orbit_atlas(TINY["orbit_atlas"], sim_t_end=TINY["orbit_atlas"]["sim_t_end"],
                       model=model, **_LABEL)


def _chain(model: dict, simulation: dict) -> None:
    """The jet chain of every other family's curves (``jets.chain``: the exact derivatives
    of ``boundaries`` with walls), on its own; the values are those of no orbit."""
    from ..core.walls import WALL_L, WALL_R
    from ..orbits.jets import chain
    jets = chain.model_of(model["r"], model["d"], 0.0)
    if jets is None:                    # d outside (0, 2): the curves use differences
        return
    par, x0, fl = (POINT["eta"], POINT["omega"], POINT["F"]), [0.5, 0.1, 0.0, 0.0], [3.0, 3.0]
    chain.residual_derivatives(jets, [WALL_L, WALL_R], False, 6.0, par, x0, fl, "fold")
    chain.grazing_derivatives(jets, [WALL_L, WALL_R, WALL_L], False, 6.0, par,
                              [*x0, *fl, 1.0], (0, 0))


#: warm-up tasks: name -> (function, tasks whose compiled kernels it reuses: it starts once
#: they are in the cache); ready tasks start in this order. Compile CPU measured cold, one
#: process, in this order: seeds ~13-16 s (1:1 maps, seeds, orbit solver), shooting ~13-18 s,
#: core ~17 s more (event kernel; the periodic shortcut reuses the orbit solver), stability
#: map ~7 s more (its column kernel), lyapunov ~4 s, chain ~13 s (its own jets); the rest
#: reuse these. On 2 workers:
#: seeds then core on one, shooting then the stability map on the other (~33 s).
TASKS = {
    "seeds": (_seeds, ()),
    "shooting": (_shooting, ()),
    "core": (_core, ("seeds",)),
    "stability_map": (_stability_map, ("seeds",)),
    "lyapunov": (_lyapunov, ("core",)),
    "branches": (_branches, ("seeds", "shooting", "core")),
    "robust": (_robust, ("core",)),
    "boundaries": (_boundaries, ("branches", "stability_map")),
    "atlas": (_atlas, ("branches",)),
    "chain": (_chain, ()),
}


def _exit_with_parent(parent: int) -> None:
    """End this process as soon as its parent is gone (else a killed warm-up leaves workers
    waiting for tasks forever): Linux's parent-death signal, and on every system a thread
    that polls the parent's pid every ``POLL_S``; ``parent``: the warm-up's pid."""
    start_parent = os.getppid()
    if sys.platform.startswith("linux"):
        with contextlib.suppress(OSError, AttributeError):
            ctypes.CDLL(None).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    if start_parent != parent and not _alive(parent):   # died before the signal was set
        os._exit(1)

    def watch():
        while os.getppid() == start_parent:
            time.sleep(POLL_S)
        os._exit(1)

    threading.Thread(target=watch, daemon=True, name="vines-exit-with-parent").start()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        pass
    return True


def _worker_start(parent: int) -> None:
    """Worker start: ends with the warm-up; the stages' progress lines (meant for job logs)
    are not shown."""
    _exit_with_parent(parent)
    sys.stdout = sys.stderr = open(os.devnull, "w")  # noqa: SIM115 (the worker's life)


def _run_tasks(model: dict, simulation: dict, n_workers: int) -> None:
    """Run ``TASKS`` on ``n_workers`` processes, each as soon as the tasks it reuses are done
    (ready tasks in ``TASKS`` order)."""
    if n_workers <= 1:
        with (open(os.devnull, "w") as devnull, contextlib.redirect_stderr(devnull),
              contextlib.redirect_stdout(devnull)):
            for fn, _ in TASKS.values():
                fn(model, simulation)
        return
    done: set[str] = set()
    todo = dict(TASKS)
    running = {}
    with ProcessPoolExecutor(n_workers, initializer=_worker_start,
                             initargs=(os.getpid(),)) as pool:
        while todo or running:
            for name in [n for n, (_, after) in todo.items() if done.issuperset(after)]:
                if len(running) >= n_workers:
                    break
                running[pool.submit(todo.pop(name)[0], model, simulation)] = name
            finished, _ = wait(running, return_when=FIRST_COMPLETED)
            for fut in finished:
                fut.result()
                done.add(running.pop(fut))


def warm(model: dict, simulation: dict, n_workers: int = 2) -> float:
    """Compile the kernels (``TASKS`` on ``n_workers`` processes), write the stamp; seconds."""
    from .._jit import check_cache
    from ..core.flow import fundamentals
    t0 = time.perf_counter()
    check_cache(fundamentals)      # damaged cache files: removed here, in one line (workers are quiet)
    _run_tasks(model, simulation, max(1, n_workers))
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
    print("vines: compiling the numba kernels once for this install (about 40 s on "
          "2 cores; later runs reuse them)...", file=sys.stderr, flush=True)
    try:
        seconds = warm(json.loads(args.model), json.loads(args.simulation), max(1, args.jobs))
    except BrokenProcessPool:
        print("vines: warm-up stopped: one of its worker processes died (killed, or out of "
              "memory); the jobs compile the kernels they need", file=sys.stderr, flush=True)
        return 1
    except KeyboardInterrupt:
        print("vines: warm-up interrupted; the jobs compile the kernels they need",
              file=sys.stderr, flush=True)
        return 130
    print(f"vines: kernels compiled in {seconds:.0f} s", file=sys.stderr, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
