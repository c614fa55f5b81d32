"""
A stability boundary
====================

``stability_map`` classifies the 1:1 orbit over a grid of (eta, omega) at fixed F: no
admissible orbit, stable symmetric, stable asymmetric, or unstable; the edges of these
classes are the bifurcation curves that ``boundaries`` traces exactly (Fig 16 of the
paper). A 20 x 20 grid here; the paper's is finer.
"""
import matplotlib.pyplot as plt
import numpy as np

from vines.orbits import stability_map

eta = np.linspace(0.1, 0.5, 20)
omega = np.linspace(0.8, 1.3, 20)
m = stability_map(eta, omega, F=0.3077)
labels = ["no admissible 1:1", "stable symmetric", "stable asymmetric", "unstable"]
fig, ax = plt.subplots(figsize=(6, 4.5))
cmap = plt.get_cmap("viridis", 4)
im = ax.pcolormesh(omega, eta, m["cls"], cmap=cmap, vmin=-0.5, vmax=3.5, shading="nearest")
bar = fig.colorbar(im, ticks=range(4))
bar.ax.set_yticklabels(labels, fontsize=8)
ax.set_xlabel("frequency ratio omega")
ax.set_ylabel("mass ratio eta")
ax.set_title("the 1:1 orbit over (eta, omega) at F = 0.3077")
fig.tight_layout()
