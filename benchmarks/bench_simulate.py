"""Speed of the exact solver against the DOP853 event loop, and thread scaling of batches.

Run: python benchmarks/bench_simulate.py [--quick]
Prints ratios measured in this process (no timing assertions anywhere in the tests).
Every run integrates to t_end (periodic_shortcut=False): this measures the integrator; the
shortcut's speed-up is measured by benchmarks/shortcut_check.py.
"""
import argparse
import os
import time

import numpy as np

import vines

POINT = dict(eta=0.05, omega=1.0, F=0.05)     # 1:1 orbit of Fig 4(a)


#: points of the batch-scaling measurement
N_BATCH = 512


def best_of(fn, repeat):
    best = float("inf")
    out = None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="shorter DOP853 run (1000 units)")
    args = ap.parse_args()
    t_end = 1000.0 if args.quick else 7000.0
    t_tr = t_end * 4.0 / 7.0
    vines.simulate(**POINT, t_end=50.0, t_transient=10.0)      # compile / load cache
    t_ex, r_ex = best_of(lambda: vines.simulate(**POINT, t_end=t_end, t_transient=t_tr,
                                                periodic_shortcut=False), 5)
    t_rk, r_rk = best_of(lambda: vines.simulate(**POINT, t_end=t_end, t_transient=t_tr,
                                                solver="rk", rtol=1e-12), 1)
    n = r_ex.n_impacts
    print(f"1:1 run eta=0.05 W=1 F=0.05, t_end={t_end:g}: {n} impacts")
    print(f"  exact   : {t_ex * 1e3:9.2f} ms  ({t_ex / n * 1e6:6.2f} us/impact)")
    print(f"  DOP853  : {t_rk * 1e3:9.2f} ms  ({t_rk / r_rk.n_impacts * 1e6:6.0f} us/impact, rtol 1e-12)")
    print(f"  ratio DOP853/exact: {t_rk / t_ex:8.0f}x")
    print(f"  |KE ratio difference| = {abs(r_ex.ke_ratio - r_rk.ke_ratio):.2e}")

    # batch scaling: the same N_BATCH points on 1 and 2 threads (64 points took ~0.2 s:
    # too short for thread start-up and the load of other processes not to dominate)
    rng = np.random.default_rng(0)
    eta = rng.uniform(0.02, 1.0, N_BATCH)
    omega = rng.uniform(0.6, 1.4, N_BATCH)
    F = rng.uniform(0.05, 0.5, N_BATCH)
    kw = dict(t_end=7000.0, t_transient=4000.0, periodic_shortcut=False)
    vines.simulate_batch(eta[:2], omega[:2], F[:2], n_threads=2, **kw)
    t1, b1 = best_of(lambda: vines.simulate_batch(eta, omega, F, n_threads=1, **kw), 3)
    t2, b2 = best_of(lambda: vines.simulate_batch(eta, omega, F, n_threads=2, **kw), 3)
    same = all(np.array_equal(b1[k], b2[k], equal_nan=b1[k].dtype.kind == "f") for k in b1)
    print(f"batch of {N_BATCH} points (7000 units each) on {os.cpu_count()} cores "
          f"(load average {os.getloadavg()[0]:.2f}):")
    print(f"  1 thread : {t1:7.3f} s ({t1 / N_BATCH * 1e3:.1f} ms/point)")
    print(f"  2 threads: {t2:7.3f} s   speed-up {t1 / t2:.2f}x   identical results: {same}")


if __name__ == "__main__":
    main()
