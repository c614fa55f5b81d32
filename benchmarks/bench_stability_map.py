"""Time a 150 x 150 stability map (paper Fig. 16 grid) on 1 and 2 threads.

Usage: python benchmarks/bench_stability_map.py [n_eta n_omega [repeats [F]]]
Targets: 2 threads >= 1.8 x faster than 1 thread and <= 2 s for 150 x 150 at F = 0.3077 on
2 free cores, with identical arrays for 1 and 2 threads.

The runs alternate 1 and 2 threads ``repeats`` times (default 3) and the best wall time of
each is compared, which filters out most interference from other jobs. Also printed: the
CPU time of the process (which other jobs hardly change), CPU time / wall time (the cores
the map actually got), the cores other processes used meanwhile (from /proc/stat) and the
load average: a 2-thread run can only be ~2x faster when the others left a core free.
"""
import os
import sys
import time

import numpy as np

from vines.orbits.atlas.stability_map import stability_map

KEYS = ("lambda_max", "cls", "dw_L", "symmetric")


def _busy_seconds():
    """CPU seconds all processes of the machine have used so far (Linux; else nan)."""
    try:
        with open("/proc/stat") as f:
            ticks = [int(v) for v in f.readline().split()[1:]]
    except (OSError, ValueError):
        return float("nan")
    idle = ticks[3] + (ticks[4] if len(ticks) > 4 else 0)
    return (sum(ticks[:8]) - idle) / os.sysconf("SC_CLK_TCK")


def _run(eta, omega, F, nt):
    """(result, wall s, CPU s of this process, cores used meanwhile by other processes)."""
    b0, w0, c0 = _busy_seconds(), time.perf_counter(), time.process_time()
    res = stability_map(eta, omega, F, n_threads=nt)
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    return res, wall, cpu, max(0.0, (_busy_seconds() - b0 - cpu) / wall)


def main():
    n_eta = int(sys.argv[1]) if len(sys.argv) > 1 else 150
    n_om = int(sys.argv[2]) if len(sys.argv) > 2 else 150
    repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    F = float(sys.argv[4]) if len(sys.argv) > 4 else 0.3077
    eta = np.linspace(0.01, 1.0, n_eta)
    omega = np.linspace(0.5, 1.5, n_om)
    stability_map(eta[:3], omega[:3], F, n_threads=2)     # JIT compile or cache load
    print(f"{n_eta} x {n_om} map, F = {F}, cores: {os.cpu_count()}, "
          f"load average before: {os.getloadavg()[0]:.2f}")
    best = {1: (np.inf, np.inf), 2: (np.inf, np.inf)}
    results = {}
    for rep in range(repeats):
        for nt in (1, 2):
            results[nt], wall, cpu, others = _run(eta, omega, F, nt)
            print(f"  run {rep + 1}, {nt} thread(s): {wall:.2f} s wall, {cpu:.2f} s CPU "
                  f"({cpu / wall:.2f} cores; other processes meanwhile {others:.2f} cores), "
                  f"load {os.getloadavg()[0]:.2f}", flush=True)
            best[nt] = min(best[nt], (wall, cpu))
    for nt in (1, 2):
        wall, cpu = best[nt]
        print(f"best, {nt} thread(s): {wall:.2f} s ({1e3 * wall / (n_eta * n_om):.3f} ms per "
              f"point), CPU {cpu:.2f} s")
    print(f"ratio 1 thread / 2 threads (best wall times): {best[1][0] / best[2][0]:.2f}")
    same = all(np.array_equal(results[1][k], results[2][k], equal_nan=True) for k in KEYS)
    print(f"identical results on 1 and 2 threads: {same}")
    cls = results[1]["cls"]
    print("classes (0 none, 1 sym stable, 2 asym stable, 3 unstable):",
          {int(c): int((cls == c).sum()) for c in np.unique(cls)})
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
