"""
The slow flow against the exact orbits
======================================

At small mass ratio the averaged slow flow predicts the symmetric two-impact response in
closed form (:doc:`/slowflow`). ``model_ladder.ladder`` puts it beside the exact models on
one frequency grid: the 1:1 orbits of the impact maps, their continuation in omega and the
simulation from rest, with the wall time of each (the pipeline's ``model_ladder`` stage,
here on 5 frequencies and short runs).
"""
import matplotlib.pyplot as plt
import numpy as np

from vines import D_DEFAULT
from vines.studies.model_ladder import ladder

eta, F = 0.02, 0.02
omegas = np.linspace(0.9, 1.1, 5)
lad = ladder(eta, F, omegas, r=0.65, d=D_DEFAULT, t_end=500.0, t_transient=300.0,
             n_dense=50, continuation_step=0.05)
for model, seconds in lad.seconds.items():
    print(f"{model:13s} {seconds * 1e3:9.2f} ms")

fig, ax = plt.subplots(figsize=(6.5, 4))
dense = lad.dense
for stable, marker in ((True, "o"), (False, "x")):
    rows = np.asarray(dense["stable"]) == stable
    ax.plot(np.asarray(dense["omega"])[rows], np.asarray(dense["amplitude"])[rows], marker,
            ms=3, color="C0", label=f"slow flow, {'stable' if stable else 'unstable'}")
cont = lad.continuation
ax.plot(cont["omega"], cont["amplitude"], ".", ms=1, color="C2", label="exact, continued")
exact = lad.exact
ax.plot(exact["omega"], exact["amplitude"], "s", mfc="none", color="C3",
        label="exact 1:1 orbits (map solve)")
ax.plot(lad.omega, lad.simulation["xmax"], "^", color="k", ms=5, label="simulation from rest")
ax.set_xlabel("frequency ratio omega")
ax.set_ylabel("LO amplitude max |z_m| (units of L)")
ax.set_title(f"eta = {eta}, F = {F}; activation threshold xi_min = {lad.xi_min:.3f}")
ax.legend(fontsize=8)
fig.tight_layout()
