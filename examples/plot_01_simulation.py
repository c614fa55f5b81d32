"""
One simulation and its time history
===================================

A run from rest at one parameter point (dimensionless time; the model is in
:doc:`/model`). ``vines.simulate`` integrates it exactly, event by event, and measures the
energy transfer over the window [t_transient, t_end]; ``state_at`` samples the motion at
any instants. Short run here: the paper's runs go to t = 7000.
"""
import matplotlib.pyplot as plt
import numpy as np

import vines

res = vines.simulate(eta=0.05, omega=1.0, F=0.05, t_end=600.0, t_transient=400.0)
print(f"regime {res.regime}, KE ratio {res.ke_ratio:.3f}, x_max {res.xmax_m * 1e3:.2f} mm, "
      f"{res.n_impacts} impacts")

t = np.linspace(0.0, 600.0, 6001)
z_m, v_m, z_b, v_b = res.state_at(t)
fig, (ax0, ax1) = plt.subplots(2, 1, sharex=True, figsize=(7, 4.5))
ax0.plot(t, z_m, lw=0.8)
ax0.set_ylabel("LO displacement $z_m$ (units of L)")
ax1.plot(t, z_m - z_b, lw=0.8, color="C1")
ax1.axhline(1, color="k", lw=0.5)
ax1.axhline(-1, color="k", lw=0.5)
ax1.plot(res.impacts["t"], res.impacts["z_m"] - res.impacts["z_b"], ".", ms=2, color="C3")
ax1.set_ylabel("ball in the cavity $w$")
ax1.set_xlabel("dimensionless time t")
ax0.axvspan(400, 600, color="0.9")
ax0.set_title("from rest; the window is shaded, the impacts are dots")
fig.tight_layout()
