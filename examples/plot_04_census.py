"""
An attractor census
===================

From rest the system reaches one motion; a structure can start anywhere. ``census`` runs
scrambled Sobol initial states at one point and groups where they end: each attractor with
its basin fraction and a 95 % interval (:doc:`/attractors`). 64 states and short runs here
(the command line's default is 256 to t = 7000): what it finds is a finite-time answer.
"""
import matplotlib.pyplot as plt
import numpy as np

from vines.attractors import census

c = census(0.13, 1.0, 0.1, n=64, t_end=3000.0, t_transient=2000.0)
for i, a in enumerate(c.attractors):
    print(f"{i}: {a.regime:10s} basin {a.basin_fraction:.3f} {a.ci} KE ratio {a.ke_ratio:.3f}"
          + ("  <- from rest" if i == c.from_rest else ""))

names = [f"{i}: {a.regime}" for i, a in enumerate(c.attractors)]
frac = np.array([a.basin_fraction for a in c.attractors])
ci = np.array([a.ci for a in c.attractors])
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.bar(names, frac, yerr=[frac - ci[:, 0], ci[:, 1] - frac], capsize=4, color="C0")
ax.set_ylabel("basin fraction")
ax.set_ylim(0, 1.05)
ax.set_title(f"eta = 0.13, omega = 1, F = 0.1: {c.n} initial states, t <= 3000")
fig.tight_layout()
