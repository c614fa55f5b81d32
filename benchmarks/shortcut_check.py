"""Periodic shortcut: the same measures with and without it, and the speed-up.

Run: PYTHONPATH=src python benchmarks/shortcut_check.py [--n 1000] [--threads 2] [--quick]

Compares ``periodic_shortcut=True`` (default) with ``False`` on
  1. every grid point of config/smoke.yaml (with its simulation settings),
  2. ``--n`` random points, eta in [0.01, 1], omega in [0.5, 1.5], F in [0.01, 0.5]
     (seed 0, the default run 7000 / window 4000), also timed (simulate_batch),
  3. the bifurcation sweeps of config/smoke.yaml (every line, up and down).
Acceptance (the issue): |KE ratio difference| <= 1e-9, relative x_max difference <= 1e-9,
|impacts per period difference| <= 1e-9 and the same regime at every point. Sweep points
start from the previous point's final state, which the shortcut reproduces only to the
detection tolerance (~1e-10): where a point is chaotic that difference grows, so sweeps are
compared on their periodic points (the same regime label at both, not irregular/chatter)
and the other points are counted. Prints a summary; exit status 1 if a check fails.
"""
import argparse
import os
import sys
import time

import numpy as np
import yaml

import vines
from vines.core.sweep import bifurcation_sweep
from vines.pipeline.axes import axis_values, grid_axes

TOL = 1e-9
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def compare(a: dict, b: dict) -> dict:
    """Largest differences of two simulate_batch results (a: shortcut, b: without)."""
    ok = (a["status"] == "ok") & (b["status"] == "ok")
    xm = np.maximum(np.abs(b["xmax"]), 1e-300)
    return {
        "points": int(a["ke_ratio"].size),
        "ke_ratio": float(np.max(np.abs(a["ke_ratio"] - b["ke_ratio"]), initial=0.0)),
        "xmax_rel": float(np.max(np.abs(a["xmax"] - b["xmax"]) / xm, initial=0.0)),
        "impacts_per_period": float(np.max(np.abs(a["impacts_per_period"]
                                                  - b["impacts_per_period"]), initial=0.0)),
        "regime_mismatch": int(np.sum(a["regime"] != b["regime"])),
        "status_mismatch": int(np.sum(a["status"] != b["status"])),
        "not_ok": int(np.sum(~ok)),
        "shortcut_taken": int(np.sum(np.isfinite(a["shortcut_time"]))),
        "no_shortcut_field_set": int(np.sum(np.isfinite(b["shortcut_time"]))),
    }


def passed(c: dict) -> bool:
    return (c["ke_ratio"] <= TOL and c["xmax_rel"] <= TOL and c["impacts_per_period"] <= TOL
            and c["regime_mismatch"] == 0 and c["status_mismatch"] == 0
            and c["no_shortcut_field_set"] == 0)


def batch_pair(e, w, f, threads, **kw):
    """(with, without, wall seconds with, wall seconds without)."""
    t = time.perf_counter()
    a = vines.simulate_batch(e, w, f, n_threads=threads, **kw)
    ta = time.perf_counter() - t
    t = time.perf_counter()
    b = vines.simulate_batch(e, w, f, n_threads=threads, periodic_shortcut=False, **kw)
    tb = time.perf_counter() - t
    return a, b, ta, tb


def smoke_grids(cfg, threads) -> dict:
    sim = {k: cfg["simulation"][k] for k in ("t_end", "t_transient")}
    out = {}
    for name, g in cfg["grids"].items():
        ax = grid_axes(g)
        e, w, f = np.meshgrid(ax["eta"], ax["omega"], ax["F"], indexing="ij")
        a, b, _, _ = batch_pair(e.ravel(), w.ravel(), f.ravel(), threads, **sim)
        out[name] = compare(a, b)
    return out


def random_points(n, threads, quick) -> tuple:
    rng = np.random.default_rng(0)
    e, w, f = rng.uniform(0.01, 1.0, n), rng.uniform(0.5, 1.5, n), rng.uniform(0.01, 0.5, n)
    kw = dict(t_end=1000.0, t_transient=600.0) if quick else {}
    vines.simulate_batch(e[:2], w[:2], f[:2], n_threads=1, **kw)       # load compiled code
    vines.simulate_batch(e[:2], w[:2], f[:2], n_threads=1, periodic_shortcut=False, **kw)
    a, b, ta, tb = batch_pair(e, w, f, threads, **kw)
    c = compare(a, b)
    c.update(seconds_with=ta, seconds_without=tb, speedup=tb / ta)
    taken = np.isfinite(a["shortcut_time"])
    c["shortcut_time_median"] = float(np.median(a["shortcut_time"][taken])) if taken.any() else None
    regimes = {}
    for r in np.unique(b["regime"]):
        sel = b["regime"] == r
        regimes[str(r)] = (int(sel.sum()), int(np.sum(taken & sel)))
    c["regimes (points, shortcut)"] = regimes
    return c


def sweep_pair(spec, fixed, values):
    kw = dict(t_settle=spec["t_settle"], t_step=spec["t_step"], n_record=spec["n_record"])
    a = bifurcation_sweep(spec["param"], values, **fixed, **kw)
    b = bifurcation_sweep(spec["param"], values, **fixed, periodic_shortcut=False, **kw)
    return a, b


def _rows(res):
    edges = np.concatenate([[0], np.cumsum(res["row_size"])])
    return [slice(edges[i], edges[i + 1]) for i in range(res["row_size"].size)]


def smoke_sweeps(cfg) -> dict:
    """Per sweep entry: points compared, max |dw| difference on periodic points, points
    skipped (chaotic at either run), shortcut points."""
    out = {}
    for name, spec in cfg["sweeps"].items():
        vals = axis_values(spec["values"])
        stats = dict(points=0, compared=0, dw_max=0.0, row_mismatch=0, shortcut=0)
        for ov in axis_values(spec["outer_values"]):
            fixed = {**{k: float(v) for k, v in spec["fixed"].items()}, spec["outer"]: ov}
            for v in (vals, vals[::-1].copy()):
                a, b = sweep_pair(spec, fixed, v)
                stats["shortcut"] += int(np.sum(np.isfinite(a["shortcut_time"])))
                for ra, rb in zip(_rows(a), _rows(b)):
                    stats["points"] += 1
                    if a["dw"][ra].size != b["dw"][rb].size:
                        stats["row_mismatch"] += 1
                        continue
                    stats["compared"] += 1
                    d = np.abs(a["dw"][ra] - b["dw"][rb])
                    stats["dw_max"] = max(stats["dw_max"], float(np.max(d, initial=0.0)))
        out[name] = stats
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000, help="random points (default 1000)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="random points on runs of 1000")
    args = ap.parse_args()
    with open(os.path.join(ROOT, "config", "smoke.yaml")) as fh:
        cfg = yaml.safe_load(fh)
    ok = True
    print("smoke grids (t_end %g, window from %g):" % (cfg["simulation"]["t_end"],
                                                      cfg["simulation"]["t_transient"]))
    for name, c in smoke_grids(cfg, args.threads).items():
        ok &= passed(c)
        print(f"  {name:14s} {c}")
    c = random_points(args.n, args.threads, args.quick)
    ok &= passed(c)
    print(f"{args.n} random points: {c}")
    print("smoke sweeps (dw of periodic points):")
    for name, s in smoke_sweeps(cfg).items():
        print(f"  {name:14s} {s}")
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
