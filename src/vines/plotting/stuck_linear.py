"""Fig 11 (vines.core.linear on a figure): x_max of the VINES against the stuck linear
system Eq. 28 (its amplitude on a fine omega grid and its exact peak), and the LO
displacement of the VINES against Eq. 28's steady state at the points of a time-history
dataset."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ..core.linear import stuck_amplitude, stuck_peak, stuck_steady_state
from ..core.params import L_HALF_M
from . import palette
from .checks import FigureInputError, fixed_value
from .draw import C_BALL, LABELS, fmt, metres, panel_label, th_title

#: points of the fine omega grid on which the Eq. 28 curve is drawn
FINE_POINTS = 4001


def stuck_curve(W, eta, F, d):
    """Eq. 28 amplitude (m) on a fine omega grid (FINE_POINTS over the grid's range, plus the
    exact peak) and the exact peak (omega, x_max in m)."""
    w_pk, a_pk = stuck_peak(eta, F, d)
    fine = np.linspace(W.min(), W.max(), FINE_POINTS)
    if W.min() < w_pk < W.max():
        fine = np.sort(np.append(fine, w_pk))
    return fine, stuck_amplitude(eta, fine, F, d) * L_HALF_M, float(w_pk), float(a_pk) * L_HALF_M


def xmax_panel(ax, s, F, d, i):
    """x_max (m, log axis) vs omega of the VINES (grid) and Eq. 28 (fine grid, exact peak)."""
    eta, W = float(s["eta"]), s["omega"].values
    on_grid = stuck_amplitude(eta, W, F, d) * L_HALF_M
    if not np.allclose(on_grid, s["xmax_stuck_linear_m"].values, rtol=1e-9, atol=0):
        raise FigureInputError("xmax_stuck_linear_m of the grid differs from Eq. 28 with "
                               f"the grid's d = {d} (eta = {eta})")
    fine, amp, w_pk, a_pk = stuck_curve(W, eta, F, d)
    kv = int(np.argmax(s["xmax_m"].values))
    ax.semilogy(W, s["xmax_m"].values, "-", color=C_BALL, lw=1.3, label="VINES, Eqs. (5)-(6)")
    ax.semilogy(fine, amp, "-", color="black", lw=1.0, label="stuck linear, Eq. (28)")
    ax.plot([W[kv]], [s["xmax_m"].values[kv]], "o", color=C_BALL, ms=4)
    ax.plot([w_pk], [a_pk], "o", color="black", ms=4)
    ax.axvline(1.0, color="0.6", lw=0.6, ls=":")
    ax.axvline(1 / np.sqrt(1 + eta), color=palette.OKABE_ITO["reddish purple"], lw=0.9, ls="--",
               label=r"$\Omega = 1/\sqrt{1+\eta}$")
    ax.set_xlabel(LABELS["omega"])
    ax.set_ylabel(LABELS["xmax_m"])
    ax.set_xlim(W.min(), W.max())
    panel_label(ax, i, rf"$\eta$ = {fmt(eta)}, $F$ = {fmt(F)}")
    ax.text(0.02, 0.03, f"peaks: VINES {1e3 * s['xmax_m'].values[kv]:.0f} mm at "
            rf"$\Omega$ = {W[kv]:.4f} (grid)" "\n"
            f"Eq. (28) {1e3 * a_pk:.0f} mm at " rf"$\Omega$ = {w_pk:.4f} (exact)",
            transform=ax.transAxes, fontsize=7, va="bottom")
    print(f"eta = {eta}: VINES peak {s['xmax_m'].values[kv]:.6g} m at omega {W[kv]:.6g}; "
          f"Eq. 28 peak {a_pk:.6g} m at omega {w_pk:.8f}")
    ax.legend(fontsize=7, loc="upper right")


def damping(ds) -> float:
    """The damping d of a dataset's runs (global attribute solver_d)."""
    d = ds.attrs.get("solver_d")
    if d is None or not np.isfinite(float(d)):
        raise FigureInputError(f"{ds.attrs.get('_path')}: global attribute solver_d (damping d) is missing")
    return float(d)


def stuck_linear_figure(ds, th):
    """Fig 11: (a, b, ...) ``xmax_panel`` per eta of the grid ``ds``; under them, per point
    of the time histories ``th``, the LO displacement of the VINES and Eq. 28's steady
    state (closed form with the dataset's damping)."""
    d_grid, d = damping(ds), damping(th)
    ne, nt = ds.sizes["eta"], th.sizes["point"]
    fig = plt.figure(figsize=(max(3.6 * nt, 4.5 * ne), 6.4), constrained_layout=True)
    gs = fig.add_gridspec(2, ne * nt)
    F = fixed_value(ds, "F")
    for i in range(ne):
        ax = fig.add_subplot(gs[0, i * nt:(i + 1) * nt])
        xmax_panel(ax, ds.isel(eta=i, F=0), F, d_grid, i)
    for k in range(nt):
        ax = fig.add_subplot(gs[1, k * (ne * nt) // nt:(k + 1) * (ne * nt) // nt])
        t, zm = th["t"].values[k], th["z_m"].values[k]
        eta, om, Fk = (float(th[v].values[k]) for v in ("eta", "omega", "F"))
        ax.plot(t, metres(zm), color=C_BALL, lw=1.0, label="VINES")
        ax.plot(t, metres(stuck_steady_state(t, eta, om, Fk, d)), color="black", lw=1.0,
                label="Eq. (28)")
        ax.set_xlim(t[0], t[-1])
        ax.set_xlabel(LABELS["t"])
        ax.set_ylabel(r"$x_m$ (m)")
        panel_label(ax, ne + k, th_title(th, k))
        if k == 0:
            ax.legend(fontsize=7, loc="upper right")
    return fig
