"""Cost of the Lyapunov spectrum per impact, relative to ``simulate`` in the same process.

Run: python benchmarks/bench_lyapunov.py [--repeat N]
CPU times, best of N. Both integrate the same trajectory to t_end (``simulate`` with periodic_shortcut=False, the
spectrum's exact run with the Benettin frame and the window's regime): the ratio of the
times is the ratio per impact. Goal of the issue: <= 3x. Prints the load average too.
"""
import argparse
import os
import time

import vines
from vines.attractors.lyapunov import spectrum
from vines.core.params import ModelParams, SolverSettings

#: (label, eta, omega, F, state0): a 1:1 orbit, the irregular transient from rest at the
#: Fig 16 point, chatter with sticking
POINTS = (("1:1 (Fig 4a)", 0.05, 1.0, 0.05, (0.0, 0.0, 0.0, 0.0)),
          ("irregular (Fig 16 point, from rest)", 0.5, 0.9, 0.3077, (0.0, 0.0, 0.0, 0.0)),
          ("chatter/sticking", 0.2, 0.9, 0.4, (0.0, 0.0, 0.0, 0.0)))


def best_of(fn, repeat):
    """Smallest CPU time of ``repeat`` calls (single-threaded: robust to other processes
    sharing the machine, unlike the wall time) and the last result."""
    best, out = float("inf"), None
    for _ in range(repeat):
        t = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t)
    return best, out


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--t-end", type=float, default=7000.0)
    args = ap.parse_args()
    t_end, t_tr = args.t_end, args.t_end * 4.0 / 7.0
    st = SolverSettings(t_end=t_end, t_transient=t_tr)
    vines.lyapunov(eta=0.05, omega=1.0, F=0.05, t_end=60.0, t_transient=10.0, n_batches=2)
    print(f"load average before: {os.getloadavg()}")
    print(f"t_end = {t_end:g}, window from {t_tr:g}; best of {args.repeat}")
    for label, eta, omega, F, s0 in POINTS:
        p = ModelParams(eta=eta, omega=omega, F=F)
        sim_kw = dict(t_end=t_end, t_transient=t_tr, state0=s0, periodic_shortcut=False)
        t_sim, sim = best_of(lambda p=p, kw=sim_kw: vines.simulate(p.eta, p.omega, p.F, **kw),
                             args.repeat)
        t_lya, lya = best_of(lambda p=p, s0=s0: spectrum(p, st, s0), args.repeat)
        n = sim.n_impacts
        print(f"{label}: {n} impacts ({sim.regime}; spectrum {lya.regime}, "
              f"{lya.n_sticks} sticks in the window)")
        print(f"  simulate : {t_sim * 1e3:8.2f} ms ({t_sim / max(n, 1) * 1e6:6.2f} us/impact)")
        print(f"  lyapunov : {t_lya * 1e3:8.2f} ms ({t_lya / max(n, 1) * 1e6:6.2f} us/impact)")
        print(f"  ratio    : {t_lya / t_sim:6.2f}x   exponents {lya.exponents}")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
