"""Time a 150 x 150 stability map (paper Fig. 16 grid) on 1 and 2 threads.

Usage: python benchmarks/bench_stability_map.py [n_eta n_omega]
Target: <= 60 s on 2 cores for 150 x 150 at F = 0.3077.
"""
import sys
import time

import numpy as np

from vines.orbits.stability_map import stability_map


def main():
    n_eta = int(sys.argv[1]) if len(sys.argv) > 1 else 150
    n_om = int(sys.argv[2]) if len(sys.argv) > 2 else 150
    eta = np.linspace(0.01, 1.0, n_eta)
    omega = np.linspace(0.5, 1.5, n_om)
    stability_map(eta[:3], omega[:3], 0.3077, n_threads=1)     # JIT warm-up
    times = {}
    results = {}
    for nt in (1, 2):
        t0 = time.perf_counter()
        results[nt] = stability_map(eta, omega, 0.3077, n_threads=nt)
        times[nt] = time.perf_counter() - t0
        print(f"{n_eta} x {n_om} map, F = 0.3077, {nt} thread(s): {times[nt]:.2f} s "
              f"({1e3 * times[nt] / (n_eta * n_om):.3f} ms per point)")
    print(f"ratio 1 thread / 2 threads: {times[1] / times[2]:.2f}")
    same = all(np.array_equal(results[1][k], results[2][k], equal_nan=True)
               for k in ("lambda_max", "cls", "dw_L", "symmetric"))
    print(f"identical results on 1 and 2 threads: {same}")
    cls = results[1]["cls"]
    print("classes (0 none, 1 sym stable, 2 asym stable, 3 unstable):",
          {int(c): int((cls == c).sum()) for c in np.unique(cls)})


if __name__ == "__main__":
    main()
