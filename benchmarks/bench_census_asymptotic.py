"""Cost of the census's asymptotic view (``census(t_max=...)``) against its t_end view.

Run: python benchmarks/bench_census_asymptotic.py [--n 256] [--t-max 1e5] [--threads 2]
For each point: wall and CPU time (all threads) of the t_end view alone and with t_max,
measured in this process, and the machine's load average (CPU time is the robust number on
a shared machine). Points: the Fig 16 point (irregular transient), (0.13, 1, 0.1)
(chatter transient) and a point of lasting chaos (the most expensive case: every state
runs to t_max).
"""
import argparse
import os
import time

from vines.attractors import census

POINTS = ((0.5, 0.9, 0.3077), (0.13, 1.0, 0.1), (0.2026, 0.917, 0.1345))


def timed(fn):
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return time.perf_counter() - w, time.process_time() - c, out


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--t-max", type=float, default=1e5)
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    census(0.5, 0.9, 0.3077, n=2, t_max=8000.0)           # compile / load the caches
    for pt in POINTS:
        load = os.getloadavg()[0]
        w0, c0, _ = timed(lambda pt=pt: census(*pt, n=args.n, n_threads=args.threads))
        w1, c1, c = timed(lambda pt=pt: census(*pt, n=args.n, n_threads=args.threads,
                                         t_max=args.t_max))
        print(f"{pt}: t_end view {w0:.1f} s wall / {c0:.1f} s CPU; with t_max = "
              f"{args.t_max:g}: {w1:.1f} s wall / {c1:.1f} s CPU (load {load:.1f} -> "
              f"{os.getloadavg()[0]:.1f})")
        for i, a in enumerate(c.to_dict()["attractors"]):
            life = a.get("lifetime") or {}
            print(f"  {i}: {a['regime']:10s} {a['basin_fraction']:.3f} -> "
                  f"{a['basin_fraction_asymptotic']:.3f} {a['status']:10s} "
                  f"lambda_1 {a['lyapunov_max']:+.4f} lifetime {life.get('mean', '')} "
                  f"{life.get('ci', '')} escaped {life.get('escaped', '')} "
                  f"censored {life.get('censored', '')} to {a.get('escape_to', '')}")


if __name__ == "__main__":
    main()
