"""Periodic shortcut: the same measures with and without it, and the speed-up.

Run: PYTHONPATH=src python benchmarks/shortcut_check.py [--n 1000] [--threads 2] [--quick]
                                                          [--overhead]
                                                          [--config-sweeps [NAME ...]]

Compares ``periodic_shortcut=True`` (default) with ``False`` on
  1. every grid point of config/smoke.yaml (with its simulation settings),
  2. ``--n`` random points, eta in [0.01, 1], omega in [0.5, 1.5], F in [0.01, 0.5]
     (seed 0, the default run 7000 / window 4000), also timed (simulate_batch),
  3. every line of the bifurcation sweeps of config/smoke.yaml (and, with
     ``--config-sweeps``, of the named sweeps of config/config.yaml), up and down.
Acceptance (the issue): |KE ratio difference| <= 1e-9, relative x_max difference <= 1e-9,
|impacts per period difference| <= 1e-9 and the same regime at every point.
Sweeps: a point starts from the previous point's final state, which the shortcut reproduces
to the detection tolerance (~1e-10); a chaotic point amplifies that difference, and so do
the points after it. So every point of a sweep line (as run with the shortcut) is also run
without it from the same start: where the shortcut was taken the measures of the recorded
periods must pass the grid check (and w' of the impacts is reported), elsewhere the points
must be bit-identical. The two independent chains are compared too (``chain_*``:
information only). Prints a summary; exit status 1 if a
check fails.
"""
import argparse
import math
import os
import sys
import time

import numpy as np
import yaml

import vines
from vines.core.params import ModelParams
from vines.core.simulation import window_measures as _measures
from vines.core.sweep import bifurcation_sweep, sweep_point
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
        "xmax_whole_run_rel": float(np.max(np.abs(a["xmax_whole_run"] - b["xmax_whole_run"])
                                           / np.maximum(b["xmax_whole_run"], 1e-300),
                                           initial=0.0)),
        "n_impacts_mismatch": int(np.sum(a["n_impacts"] != b["n_impacts"])),
        "t_stuck": float(np.max(np.abs(a["t_stuck"] - b["t_stuck"]), initial=0.0)),
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
    """(with, without, (wall, CPU) seconds with, (wall, CPU) seconds without); CPU time
    of the process (all threads) is less sensitive to other jobs on the machine."""
    out, secs = [], []
    for flag in (True, False):
        t, c = time.perf_counter(), time.process_time()
        out.append(vines.simulate_batch(e, w, f, n_threads=threads, periodic_shortcut=flag,
                                        **kw))
        secs.append((time.perf_counter() - t, time.process_time() - c))
    return out[0], out[1], secs[0], secs[1]


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
    c.update(wall_seconds_with=ta[0], wall_seconds_without=tb[0], speedup_wall=tb[0] / ta[0],
             cpu_seconds_with=ta[1], cpu_seconds_without=tb[1], speedup_cpu=tb[1] / ta[1])
    taken = np.isfinite(a["shortcut_time"])
    c["shortcut_time_median"] = float(np.median(a["shortcut_time"][taken])) if taken.any() else None
    regimes = {}
    for r in np.unique(b["regime"]):
        sel = b["regime"] == r
        regimes[str(r)] = (int(sel.sum()), int(np.sum(taken & sel)))
    c["regimes (points, shortcut)"] = regimes
    return c


def overhead(n, repeat=5) -> dict:
    """Cost of the detection on the random points that never settle: thread CPU time of
    each such point with and without the shortcut (best of ``repeat``): the total, and the
    median and 90th percentile of the per-point ratio (single points stay noisy)."""
    from vines.core.params import D_DEFAULT, R_DEFAULT, SolverSettings
    from vines.core.simulation import _batch_point
    rng = np.random.default_rng(0)
    e, w, f = rng.uniform(0.01, 1.0, n), rng.uniform(0.5, 1.5, n), rng.uniform(0.01, 0.5, n)
    st = SolverSettings()
    idx = np.flatnonzero(np.isnan(vines.simulate_batch(e, w, f)["shortcut_time"]))
    best = np.full((idx.size, 2), math.inf)
    for k, i in enumerate(idx):
        for _ in range(repeat):
            for j, flag in enumerate((False, True)):
                t = time.thread_time()
                _batch_point(e[i], w[i], f[i], R_DEFAULT, D_DEFAULT, 0.0, st, flag)
                best[k, j] = min(best[k, j], time.thread_time() - t)
    ratio = best[:, 1] / best[:, 0]
    return dict(points=int(idx.size), cpu_seconds_without=float(best[:, 0].sum()),
                cpu_seconds_with=float(best[:, 1].sum()),
                overhead=float(best[:, 1].sum() / best[:, 0].sum() - 1.0),
                median_point_overhead=float(np.median(ratio) - 1.0),
                p90_point_overhead=float(np.percentile(ratio, 90) - 1.0))


def _dw(raw):
    return raw.impacts["v_m"] - raw.impacts["v_b"]


def sweep_line(spec, fixed, values) -> dict:
    """One sweep line as ``bifurcation_sweep`` runs it (with the shortcut), where every point
    is also run without the shortcut from the same start (state and forcing phase).

    At the points where the shortcut was taken, the measures of the recorded periods are
    compared as for grid points (``compare``; KE ratio, x_max, impacts per period, regime),
    with the largest difference of the impacts' w' and of the state handed to the next
    point; every other point must be bit-identical (only the detection ran there)."""
    param, n_rec = spec["param"], spec["n_record"]
    st = dict(points=int(values.size), shortcut=0, dw_max_shortcut=0.0, bitwise_other=True,
              next_state_max=0.0, seconds_with=0.0, seconds_without=0.0)
    ma, mb = [], []
    state, theta = (0.0, 0.0, 0.0, 0.0), 0.0
    for k, val in enumerate(values):
        kw = {**fixed, param: float(val)}
        p = ModelParams(eta=kw["eta"], omega=kw["omega"], F=kw["F"],
                        phi=math.fmod(theta, 2.0 * math.pi))
        t_run = (spec["t_settle"] if k == 0 else spec["t_step"]) + n_rec * p.period
        t = time.perf_counter()
        a, sa, nxt, theta_a = sweep_point(p, state, t_run, n_rec, 1e-6, 400, True)
        st["seconds_with"] += time.perf_counter() - t
        t = time.perf_counter()
        b, sb, nxt_b, _ = sweep_point(p, state, t_run, n_rec, 1e-6, 400, False)
        st["seconds_without"] += time.perf_counter() - t
        if np.isfinite(a.shortcut_time):
            st["shortcut"] += 1
            ma.append({**_measures(p, sa, a), "status": a.status,
                       "shortcut_time": a.shortcut_time})
            mb.append({**_measures(p, sb, b), "status": b.status, "shortcut_time": math.nan})
            if a.impacts.size == b.impacts.size:
                st["dw_max_shortcut"] = max(st["dw_max_shortcut"], float(np.max(
                    np.abs(_dw(a) - _dw(b)), initial=0.0)))
            else:
                st["dw_max_shortcut"] = math.inf
        else:
            st["bitwise_other"] &= bool(np.array_equal(a.impacts, b.impacts)
                                        and np.array_equal(nxt, nxt_b))
        st["next_state_max"] = max(st["next_state_max"],
                                   float(np.max(np.abs(np.subtract(nxt, nxt_b)))))
        state, theta = nxt, theta_a
    if ma:
        cat = {key: np.array([m[key] for m in ma]) for key in ma[0]}
        cbt = {key: np.array([m[key] for m in mb]) for key in mb[0]}
        st["measures"] = compare(cat, cbt)
    return st


def sweep_chain(spec, fixed, values) -> dict:
    """The whole sweep line with and without the shortcut (each carrying its own states):
    points whose impacts agree to 1e-8 and where the first disagreement starts."""
    kw = dict(t_settle=spec["t_settle"], t_step=spec["t_step"], n_record=spec["n_record"])
    a = bifurcation_sweep(spec["param"], values, **fixed, **kw)
    b = bifurcation_sweep(spec["param"], values, **fixed, periodic_shortcut=False, **kw)
    ea, eb = (np.concatenate([[0], np.cumsum(r["row_size"])]) for r in (a, b))
    agree = 0
    first = None
    for i in range(values.size):
        da, db = a["dw"][ea[i]:ea[i + 1]], b["dw"][eb[i]:eb[i + 1]]
        ok = da.size == db.size and np.all(np.abs(da - db) <= 1e-8)
        agree += bool(ok)
        if not ok and first is None:
            first = round(float(values[i]), 5)
    return dict(chain_agree=agree, chain_first_difference=first)


def sweeps(cfg, names=None) -> dict:
    """sweep_line over every line (outer value, up and down) of the named config sweeps."""
    out = {}
    for name, spec in cfg["sweeps"].items():
        if names and name not in names:
            continue
        vals = axis_values(spec["values"])
        for ov in axis_values(spec["outer_values"]):
            fixed = {**{k: float(v) for k, v in spec["fixed"].items()}, spec["outer"]: ov}
            for direction, v in (("up", vals), ("down", vals[::-1].copy())):
                out[f"{name} {spec['outer']}={ov:g} {direction}"] = {
                    **sweep_line(spec, fixed, v), **sweep_chain(spec, fixed, v)}
    return out


def sweep_passed(st: dict) -> bool:
    return st["bitwise_other"] and ("measures" not in st or passed(st["measures"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000, help="random points (default 1000)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="random points on runs of 1000")
    ap.add_argument("--overhead", action="store_true",
                    help="also time the random points that never settle (best of 3)")
    ap.add_argument("--config-sweeps", nargs="*", default=None, metavar="NAME",
                    help="also compare these sweeps of config/config.yaml (paper settings)")
    args = ap.parse_args()
    with open(os.path.join(ROOT, "config", "smoke.yaml")) as fh:
        cfg = yaml.safe_load(fh)
    ok = True
    print(f"smoke grids (t_end {cfg['simulation']['t_end']:g}, "
          f"window from {cfg['simulation']['t_transient']:g}):")
    for name, c in smoke_grids(cfg, args.threads).items():
        ok &= passed(c)
        print(f"  {name:14s} {c}")
    c = random_points(args.n, args.threads, args.quick)
    ok &= passed(c)
    print(f"{args.n} random points: {c}")
    if args.overhead:
        print(f"points that never settle: {overhead(args.n)}")
    print("smoke sweeps:")
    for name, st in sweeps(cfg).items():
        ok &= sweep_passed(st)
        print(f"  {name:24s} {st}")
    if args.config_sweeps is not None:
        with open(os.path.join(ROOT, "config", "config.yaml")) as fh:
            full = yaml.safe_load(fh)
        print("config.yaml sweeps:")
        for name, st in sweeps(full, args.config_sweeps).items():
            ok &= sweep_passed(st)
            print(f"  {name:24s} {st}")
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
