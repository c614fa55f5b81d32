"""Periodic shortcut: the same measures with and without it, and the speed-up.

Run: PYTHONPATH=src python benchmarks/shortcut_check.py [--n 1000] [--threads 2] [--quick]
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
without it from the same start: where the shortcut was taken the impacts must agree (same
count and walls, |dw| within 1e-8), elsewhere be bit-identical. The two independent chains
are compared too (``chain_*``: information only). Prints a summary; exit status 1 if a
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


def _dw(raw):
    return raw.impacts["v_m"] - raw.impacts["v_b"]


def sweep_line(spec, fixed, values) -> dict:
    """One sweep line as ``bifurcation_sweep`` runs it (with the shortcut), where every point
    is also run without the shortcut from the same start (state and forcing phase).

    Returns: points, points where the shortcut was taken, the largest |dw| difference at
    those points and whether their impacts (count, walls) were the same, the largest
    difference of the states handed to the next point, and the largest |dw| difference at
    the other points (chaotic points need not agree: none was skipped there, only the
    periodic checks of ``run_exact`` ran, so they must agree to round-off)."""
    param, n_rec = spec["param"], spec["n_record"]
    st = dict(points=int(values.size), shortcut=0, same_impacts=True, dw_max_shortcut=0.0,
              dw_max_other=0.0, next_state_max=0.0, seconds_with=0.0, seconds_without=0.0)
    state, theta = (0.0, 0.0, 0.0, 0.0), 0.0
    for k, val in enumerate(values):
        kw = {**fixed, param: float(val)}
        p = ModelParams(eta=kw["eta"], omega=kw["omega"], F=kw["F"],
                        phi=math.fmod(theta, 2.0 * math.pi))
        t_run = (spec["t_settle"] if k == 0 else spec["t_step"]) + n_rec * p.period
        t = time.perf_counter()
        a, nxt, theta_a = sweep_point(p, state, t_run, n_rec, 1e-6, 400, True)
        st["seconds_with"] += time.perf_counter() - t
        t = time.perf_counter()
        b, nxt_b, theta_b = sweep_point(p, state, t_run, n_rec, 1e-6, 400, False)
        st["seconds_without"] += time.perf_counter() - t
        taken = bool(np.isfinite(a.shortcut_time))
        same = a.impacts.size == b.impacts.size and np.array_equal(a.impacts["wall"],
                                                                  b.impacts["wall"])
        d = float(np.max(np.abs(_dw(a) - _dw(b)), initial=0.0)) if same else math.inf
        st["shortcut"] += taken
        key = "dw_max_shortcut" if taken else "dw_max_other"
        st[key] = max(st[key], d)
        st["same_impacts"] &= same or not taken
        st["next_state_max"] = max(st["next_state_max"],
                                   float(np.max(np.abs(np.subtract(nxt, nxt_b)))))
        state, theta = nxt, theta_a
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
    return st["same_impacts"] and st["dw_max_shortcut"] <= 1e-8 and st["dw_max_other"] == 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000, help="random points (default 1000)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="random points on runs of 1000")
    ap.add_argument("--config-sweeps", nargs="*", default=None, metavar="NAME",
                    help="also compare these sweeps of config/config.yaml (paper settings)")
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
