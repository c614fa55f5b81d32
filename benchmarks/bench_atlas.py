"""Cost of one orbit-atlas point (``vines.orbits.atlas.atlas``): a coarse (eta, omega) grid per F,
swept as the stage would (omega rows with neighbour seeds), with and without the shared
simulation from rest. Prints ms per point and the load of the machine.

    python benchmarks/bench_atlas.py [n_eta n_omega]
"""
from __future__ import annotations

import os
import sys
import time

import numpy as np

from vines.core.params import ModelParams
from vines.orbits.atlas.atlas import atlas_arrays, atlas_point


def main(n_eta=10, n_omega=15):
    atlas_point(ModelParams(eta=0.2, omega=0.8, F=0.4))        # compile / load the cache
    eta = np.linspace(0.01, 1.0, n_eta)
    omega = np.linspace(0.45, 1.5, n_omega)
    print(f"load {os.getloadavg()[0]:.2f}, grid {n_eta} x {n_omega}")
    for F in (0.2, 0.3077, 0.4):
        for sim in (True, False):
            t0 = time.perf_counter()
            cpu0 = time.process_time()
            atlas_arrays(eta, omega, F, simulation=sim)
            wall = time.perf_counter() - t0
            cpu = time.process_time() - cpu0
            n = eta.size * omega.size
            print(f"F = {F}: simulation {sim!s:5s}  {1e3 * wall / n:6.1f} ms/point wall, "
                  f"{1e3 * cpu / n:6.1f} ms/point CPU; 100 x 190 grid: {cpu / n * 19000:5.0f} s CPU")
    print(f"load {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main(*map(int, sys.argv[1:3]))
