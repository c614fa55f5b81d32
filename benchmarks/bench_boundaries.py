"""Time the boundary curves of Fig 16 (``orbits.curves.boundaries``) per F, with a profile.

Usage: python benchmarks/bench_boundaries.py [--configfile config/config.yaml]
                                             [--only NAME ...] [--repeat N] [--no-profile]

For every entry of the config's ``boundaries`` section: its stability map (the
``stability_maps`` entry it names; computed here, not timed), then ``boundaries`` with the
map's class changes as the pipeline runs it, ``--repeat`` times (best wall time and CPU
time kept), then one run under cProfile whose time is split by where it goes (compiled
shooting derivatives, Newton corrector / tracer, orbit classification on the maps, numpy
linear algebra, parameter checks, the rest). First, one augmented-system evaluation
compiled vs with the pure-Python jets it replaced, side by side. Target (issue 13): <= ~8 s per F at the full
config on one idle core. The load average is printed next to every timing.
"""
import argparse
import cProfile
import os
import pstats
import time

import numpy as np
import yaml

from vines.core.params import D_DEFAULT
from vines.orbits.atlas.stability_map import stability_map
from vines.orbits.curves.boundaries import boundaries
from vines.pipeline.axes import axis_values
from vines.pipeline.config import load_schema, validate_config

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
# where the time goes: (label, substrings of "file:function" of the profile's entries)
GROUPS = (("compiled shooting derivatives (shooting_kernels)", ("shooting_kernels",)),
          ("Newton corrector, tangents, steps (arclength)", ("arclength.py",)),
          ("orbit classification on the maps (branches, periodic, maps)",
           ("branches.py", "periodic.py", "maps.py", "continuation.py")),
          ("numpy (linalg, array helpers)", ("numpy",)),
          ("parameter checks (core.params)", ("params.py",)),
          ("boundaries, augmented, shooting (Python glue)",
           ("boundaries.py", "augmented.py", "shooting.py", "tape.py")))


def _run(spec, model, class_map):
    kw = {k: spec[k] for k in ("n_scan", "step", "max_points", "n_map") if k in spec}
    return boundaries(float(spec["F"]), spec["eta_range"], spec["omega_range"],
                      r=model["r"], d=model["d"], class_map=class_map, **kw)


def _profile(spec, model, class_map):
    """Seconds of self time per GROUPS label (and 'other') of one profiled run."""
    prof = cProfile.Profile()
    prof.enable()
    _run(spec, model, class_map)
    prof.disable()
    out = {label: 0.0 for label, _ in GROUPS}
    out["other"] = 0.0
    for (path, _, func), row in pstats.Stats(prof).stats.items():
        where = f"{path}:{func}"
        label = next((lab for lab, keys in GROUPS if any(k in where for k in keys)), "other")
        out[label] += row[2]
    return out


def _per_evaluation(model):
    """Compiled vs pure-Python jets, one augmented-system evaluation (G, G_z) each, side by
    side in this process (same load): prints microseconds per call and the ratio."""
    from vines.orbits.family import augmented as ag
    from vines.orbits.family.periodic import find_1to1
    from vines.orbits.jets import shooting as sh
    m = sh.Model(model["r"], model["d"])
    orbits = find_1to1(0.12, 1.1, 0.3077, r=model["r"], d=model["d"], simulation=False)
    for family in sh.ORBIT_KINDS:
        o = next(o for o in orbits if o.symmetric == (family == "symmetric"))
        system = ag.Codim1System(m, family, "neimark-sacker", ("eta", "omega"), {"F": 0.3077})
        z = np.array(list(o.x_L) + ([] if o.symmetric else [o.flight_times[0]]) + [0.12, 1.1])
        times = {}
        for label, fun, n in (("compiled", system, 2000), ("jets", system.evaluate_jets, 50)):
            w0 = time.perf_counter()
            for _ in range(n):
                fun(z)
            times[label] = (time.perf_counter() - w0) / n * 1e6
        print(f"{family} neimark-sacker system: compiled {times['compiled']:.0f} us, "
              f"Python jets {times['jets']:.0f} us per evaluation "
              f"({times['jets'] / times['compiled']:.0f}x)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--configfile", default=os.path.join(ROOT, "config", "config.yaml"))
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--no-profile", action="store_true")
    args = ap.parse_args()
    with open(args.configfile) as f:
        cfg = yaml.safe_load(f)
    # the schema's defaults, as the pipeline reads the config
    validate_config(cfg, load_schema())
    model = {"r": cfg["model"]["r"],
             "d": D_DEFAULT if cfg["model"]["d"] is None else cfg["model"]["d"]}
    t0 = time.perf_counter()
    _run({"F": 0.3077, "eta_range": [0.1, 0.2], "omega_range": [1.0, 1.1], "n_scan": 1,
          "n_map": 0}, model, None)
    print(f"warm-up (numba cache load or compile): {time.perf_counter() - t0:.1f} s")
    _per_evaluation(model)
    for name, spec in cfg["boundaries"].items():
        if args.only and name not in args.only:
            continue
        smap = cfg["stability_maps"][spec["stability_map"]]
        eta, omega = axis_values(smap["eta"]), axis_values(smap["omega"])
        cls = stability_map(eta, omega, float(smap["F"]), r=model["r"], d=model["d"])["cls"]
        class_map = (eta, omega, cls)
        best_wall = best_cpu = np.inf
        for _ in range(args.repeat):
            w0, c0 = time.perf_counter(), time.process_time()
            res = _run(spec, model, class_map)
            best_wall = min(best_wall, time.perf_counter() - w0)
            best_cpu = min(best_cpu, time.process_time() - c0)
        print(f"{name}: {best_wall:.2f} s wall, {best_cpu:.2f} s CPU (best of {args.repeat}), "
              f"{len(res.curves)} curves, {sum(len(c.points) for c in res.curves)} points, "
              f"load {os.getloadavg()[0]:.2f}", flush=True)
        if not args.no_profile:
            parts = _profile(spec, model, class_map)
            total = sum(parts.values())
            for label, sec in sorted(parts.items(), key=lambda kv: -kv[1]):
                print(f"    {100 * sec / total:5.1f} %  {label}")


if __name__ == "__main__":
    main()
