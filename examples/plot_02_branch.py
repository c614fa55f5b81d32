"""
A periodic orbit and its branch
===============================

``find_1to1`` solves the 1:1 orbits (one impact on each wall per forcing period) from the
impact maps; ``continue_branch`` follows the symmetric one in F by pseudo-arclength
continuation (folds are passed) and locates the events where its stability changes, here
symmetry breaking and Neimark-Sacker (:doc:`/bifurcation`). A coarse step keeps this
example short.
"""
import matplotlib.pyplot as plt
import numpy as np

from vines.orbits import continue_branch, find_1to1

eta, omega = 0.2, 1.0
for orbit in find_1to1(eta, omega, 0.3):
    print(f"1:1 orbit: stable {orbit.stable}, admissible {orbit.admissible}, "
          f"lambda_max {max(abs(orbit.eigenvalues)):.3f}")

br = continue_branch("F", 0.3, 0.05, step=0.02, fixed={"eta": eta, "omega": omega},
                     max_points=200)
lam = np.abs(np.array([max(abs(o.eigenvalues)) for o in br.orbits]))
stable = np.array([o.stable for o in br.orbits])
fig, ax = plt.subplots(figsize=(7, 4))
ax.plot(br.values, lam, color="0.6", lw=1, label="branch")
ax.plot(br.values[stable], lam[stable], "o", ms=3, color="C0", label="stable")
ax.plot(br.values[~stable], lam[~stable], "o", ms=3, mfc="none", color="C3",
        label="unstable or not admissible")
for ev in br.events:
    ax.axvline(ev["at"], color="k", lw=0.5, ls=":")
    ax.text(ev["at"], 50, ev["type"], rotation=90, va="top", ha="right", fontsize=8)
ax.axhline(1, color="k", lw=0.5)
ax.set_yscale("log")
ax.set_xlabel("forcing amplitude F")
ax.set_ylabel(r"largest Floquet multiplier $|\lambda|_{max}$")
ax.set_title(f"1:1 branch at eta = {eta}, omega = {omega} ({br.stopped})")
ax.legend(loc="center right", fontsize=8)
fig.tight_layout()
